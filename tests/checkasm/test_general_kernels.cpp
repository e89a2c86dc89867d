// The general rule's kernels (issue 27, shadowvol.h: sv_general_edges)
// against their C reference, checkasm-style: every variant of
// sv_general_variants() through the ABI-checking trampoline, into guarded
// output, at every tail length around the SIMD blocks (8, 16) and the
// list chunk (512 pairs), with the facing bytes at every offset from a
// 4-byte boundary; random bytes (0, 1, 2), all four classes of edges
// (the paper's with dangling ones, pairs, open edges, shared edges of 2
// to 5 triangles running either way); the caps likewise; inputs against
// unmapped pages (the gathers read only bytes of the array).
//
// Copyright (C) 2026 the shadowvol authors. LGPL-2.1-or-later.
#include "test_support.h"

#include "mman_compat.h"

#include <algorithm>

using namespace svtest;

namespace {

std::vector<std::string> general_variant_names() {
    int n = 0;
    const sv_general_variant *v = sv_general_variants(&n);
    std::vector<std::string> names;
    for (int i = 0; i < n; i++) names.push_back(v[i].name);
    return names;
}

class GeneralKernels : public ::testing::TestWithParam<std::string> {
protected:
    void SetUp() override {
        const ::testing::TestInfo *info = ::testing::UnitTest::GetInstance()->current_test_info();
        abi = rng_for((std::string(info->test_suite_name()) + "." + info->name()).c_str());
        v = sv_general_variant_by_name(GetParam().c_str());
        ASSERT_NE(v, nullptr);
        const std::string why = isa_missing(v->isa);
        if (!why.empty()) GTEST_SKIP() << "general variant " << GetParam() << ": " << why;
    }
    const sv_general_variant *v = nullptr;
    Rng abi{0};
};

/* A random table and its facing bytes. Triangles [0, paperTriangles) are
 * the paper's class (bytes 0 or 1), the rest general (0, 1, 2); the
 * sentinel facing[numTriangles] = 1. */
struct RandomTable {
    int numTriangles = 0, numVerts = 0;
    std::vector<uint8_t> facing;
    std::vector<SilEdge> paper, pairs, opens;
    std::vector<sv_shared_edge> shared;
    std::vector<int> uses;
    sv_general_edges view() const {
        sv_general_edges e{};
        e.paper = paper.data(), e.numPaper = (int)paper.size();
        e.pairs = pairs.data(), e.numPairs = (int)pairs.size();
        e.opens = opens.data(), e.numOpens = (int)opens.size();
        e.shared = shared.data(), e.numShared = (int)shared.size();
        e.sharedUses = uses.data(), e.numSharedUses = (int)uses.size();
        return e;
    }
};

RandomTable random_table(Rng &rng, int numPaper, int numPairs, int numOpens, int numShared) {
    RandomTable t;
    const int paperTriangles = 1 + (int)rng.below(64);
    t.numTriangles = paperTriangles + 1 + (int)rng.below(3000);
    t.numVerts = 1 + (int)rng.below(5000);
    t.facing.resize((size_t)t.numTriangles + 1);
    const double p0 = rng.unit(), p1 = rng.unit();
    for (int i = 0; i < t.numTriangles; i++) {
        const double u = rng.unit();
        const int b = u < p0 ? 0 : (u < p0 + (1 - p0) * p1 ? 1 : 2);
        t.facing[(size_t)i] = (uint8_t)(i < paperTriangles ? std::min(b, 1) : b);
    }
    t.facing[(size_t)t.numTriangles] = 1;
    auto vert = [&] { return 2 * (int)rng.below((uint32_t)t.numVerts); };
    auto general = [&] {
        return paperTriangles + (int)rng.below((uint32_t)(t.numTriangles - paperTriangles));
    };
    for (int i = 0; i < numPaper; i++) {
        const int p1 = (int)rng.below((uint32_t)paperTriangles);
        const int p2 = rng.chance(0.1) ? t.numTriangles : (int)rng.below((uint32_t)paperTriangles);
        t.paper.push_back({p1, p2, vert(), vert()});
    }
    for (int i = 0; i < numPairs; i++) t.pairs.push_back({general(), general(), vert(), vert()});
    for (int i = 0; i < numOpens; i++) {
        const int p = general();
        t.opens.push_back({p, p, vert(), vert()});
    }
    for (int i = 0; i < numShared; i++) {
        const int k = 2 + (int)rng.below(4);
        t.shared.push_back({vert(), vert(), (int)t.uses.size(), k});
        for (int j = 0; j < k; j++) t.uses.push_back(2 * general() + (int)rng.below(2));
    }
    return t;
}

/* V's silhouette list of T, its facing bytes copied OFFSET bytes after a
 * 64-byte boundary, into guarded output of exactly the bound, against
 * c_ref's. */
::testing::AssertionResult sil_matches(Rng &abi, const sv_general_variant *v, const RandomTable &t,
                                       size_t offset) {
    const sv_general_edges e = t.view();
    const size_t bound = sv_general_sil_capacity(&e);
    std::vector<int> want(bound + 1);
    const int expected = sv_create_general_sil_triangles_c_ref(want.data(), t.facing.data(), &e);
    GuardedBuffer facing(t.facing.size(), offset);
    std::copy(t.facing.begin(), t.facing.end(), facing.data());
    GuardedBuffer out(bound * sizeof(int), 0);
    const int got = checked_call(abi, v->create_general_sil_triangles, out.as<int>(),
                                 (const uint8_t *)facing.data(), &e);
    if (got != expected)
        return ::testing::AssertionFailure() << "returned " << got << ", c_ref " << expected;
    if (!std::equal(want.begin(), want.begin() + expected, out.as<int>()))
        return ::testing::AssertionFailure() << "indices differ from c_ref's";
    if (!out.guards_intact()) return ::testing::AssertionFailure() << "wrote past the bound";
    if (!facing.guards_intact()) return ::testing::AssertionFailure() << "wrote to facing";
    return ::testing::AssertionSuccess();
}

::testing::AssertionResult caps_match(Rng &abi, const sv_general_variant *v,
                                      const std::vector<uint8_t> &bytes,
                                      const std::vector<int> &indices, size_t offset) {
    const int n = (int)indices.size();
    std::vector<int> want(2 * (size_t)n + 1);
    const int expected = sv_create_general_cap_triangles_c_ref(want.data(), bytes.data(),
                                                               indices.data(), n);
    GuardedBuffer facing(bytes.size(), offset);
    std::copy(bytes.begin(), bytes.end(), facing.data());
    GuardedBuffer out(2 * (size_t)n * sizeof(int), 0);
    const int got = checked_call(abi, v->create_general_cap_triangles, out.as<int>(),
                                 (const uint8_t *)facing.data(), indices.data(), n);
    if (got != expected)
        return ::testing::AssertionFailure() << "returned " << got << ", c_ref " << expected;
    if (!std::equal(want.begin(), want.begin() + expected, out.as<int>()))
        return ::testing::AssertionFailure() << "indices differ from c_ref's";
    if (!out.guards_intact()) return ::testing::AssertionFailure() << "wrote past 2 * numIndices";
    return ::testing::AssertionSuccess();
}

/* Every count 0 .. 40, and around one and two list chunks. */
std::vector<int> tail_counts() {
    std::vector<int> n;
    for (int i = 0; i <= 40; i++) n.push_back(i);
    for (int i = 512 - 17; i <= 512 + 17; i++) n.push_back(i);
    n.push_back(2 * 512 + 9);
    return n;
}

} // namespace

TEST_P(GeneralKernels, SilEveryClassAtEveryTailLength) {
    SCOPED_TRACE(seed_trace());
    Rng rng = rng_for("GeneralKernels.Sil");
    for (int n : tail_counts()) {
        for (int rep = 0; rep < 3; rep++) {
            /* Each class alone at this count, then all of them. */
            const int shape = rep == 0 ? (int)rng.below(4) : 4;
            const int small = (int)rng.below(20);
            const RandomTable t = random_table(rng, shape == 0 || shape == 4 ? n : small,
                                               shape == 1 || shape == 4 ? n : small,
                                               shape == 2 || shape == 4 ? n : small,
                                               shape == 3 || shape == 4 ? n : small);
            EXPECT_TRUE(sil_matches(abi, v, t, (size_t)(rep + n) % 4))
                << v->name << " n=" << n << " shape " << shape;
            if (stop_after_failures()) return;
        }
    }
}

TEST_P(GeneralKernels, CapsAtEveryTailLength) {
    SCOPED_TRACE(seed_trace());
    Rng rng = rng_for("GeneralKernels.Caps");
    for (int n : tail_counts()) {
        const int numVerts = 1 + (int)rng.below(1u << 20);
        std::vector<int> indices(3 * (size_t)n);
        for (int &i : indices) i = (int)rng.below((uint32_t)numVerts);
        std::vector<uint8_t> bytes((size_t)n);
        const double p = rng.unit();
        for (uint8_t &b : bytes) b = (uint8_t)(rng.chance(p) ? rng.below(3) : 2);
        EXPECT_TRUE(caps_match(abi, v, bytes, indices, (size_t)n % 4)) << v->name << " n=" << n;
        if (stop_after_failures()) return;
    }
}

TEST_P(GeneralKernels, FacingAgainstUnmappedPagesReadsNothingOutsideItsWords) {
    /* Facing bytes ending at an unmapped page and starting right after
     * one: the words the gathers read (each ending at its byte) stay
     * inside. */
    SCOPED_TRACE(seed_trace());
    Rng rng = rng_for("GeneralKernels.Pages");
    const long page = sysconf(_SC_PAGESIZE);
    for (int n : {1, 5, 17, 63, 600}) {
        RandomTable t = random_table(rng, 0, 700, 30, 10);
        t.numTriangles = n;
        t.facing.resize((size_t)n + 1);
        t.facing[(size_t)n] = 1;
        /* Keep the table's triangles inside the smaller count. */
        for (SilEdge &e : t.pairs) e.p1 %= n, e.p2 %= n;
        for (SilEdge &e : t.opens) e.p1 %= n, e.p2 = e.p1;
        for (int &u : t.uses) u = 2 * ((u >> 1) % n) + (u & 1);
        for (uint8_t &b : t.facing) b = std::min<uint8_t>(b, 2);
        for (bool at_end : {true, false}) {
            const size_t bytes = t.facing.size();
            const size_t len = ((bytes + (size_t)page - 1) / (size_t)page + 2) * (size_t)page;
            auto *map = (uint8_t *)mmap(nullptr, len, PROT_READ | PROT_WRITE,
                                        MAP_PRIVATE | MAP_ANONYMOUS, -1, 0);
            ASSERT_NE((void *)map, MAP_FAILED);
            ASSERT_EQ(mprotect(map, (size_t)page, PROT_NONE), 0);
            ASSERT_EQ(mprotect(map + len - (size_t)page, (size_t)page, PROT_NONE), 0);
            uint8_t *f = at_end ? map + len - (size_t)page - bytes : map + page;
            std::copy(t.facing.begin(), t.facing.end(), f);
            const sv_general_edges e = t.view();
            std::vector<int> want(sv_general_sil_capacity(&e)), got(want.size());
            const int w = sv_create_general_sil_triangles_c_ref(want.data(), f, &e);
            const int g = checked_call(abi, v->create_general_sil_triangles, got.data(),
                                       (const uint8_t *)f, &e);
            EXPECT_EQ(g, w) << v->name << " n=" << n;
            EXPECT_TRUE(std::equal(want.begin(), want.begin() + w, got.begin()));
            munmap(map, len);
        }
    }
}

INSTANTIATE_TEST_SUITE_P(Variants, GeneralKernels, ::testing::ValuesIn(general_variant_names()),
                         param_name);
