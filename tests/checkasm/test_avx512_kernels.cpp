// What the differential suite does not reach, written with the AVX-512
// kernels (asm/*_avx512.asm) in mind and run on every variant the CPU has:
//  - cull bytes with bit 7 (the differential tests stay in bits 0..6 for
//    sse2_paper's documented limit D-5; every other variant must cull on
//    any shared bit, as section 5's C does);
//  - counts far beyond 600, where the AVX-512 kernels change chunk or
//    block-accumulator (count_facing: 62 x 256 bytes; count_facing_cull:
//    960 triangles; create_sil_triangles: 448 edges);
//  - create_sil_triangles with triangle numbers around 2048, where the
//    AVX-512 kernel leaves its in-register facing bitmap (a chunk too wide
//    for it goes to the AVX2 kernel, and so does a call of over 3072
//    edges);
//  - every input array ending at an unmapped page, and starting right after
//    one: masked loads and tails must read nothing outside the arrays
//    (guard bytes only catch writes).
//
// Copyright (C) 2026 the shadowvol authors. LGPL-2.1-or-later.
#include "test_support.h"

#include "mman_compat.h"

#include <algorithm>

using namespace svtest;

namespace {

// `bytes` of memory between two unmapped pages, placed against the upper
// one (at_end) or the lower one: a read one byte outside faults.
class FencedBuffer {
public:
    FencedBuffer(size_t bytes, bool at_end) {
        page_ = (size_t)sysconf(_SC_PAGESIZE);
        const size_t pages = (bytes + page_ - 1) / page_ + 2;
        len_ = pages * page_;
        map_ = (uint8_t *)mmap(nullptr, len_, PROT_READ | PROT_WRITE, MAP_PRIVATE | MAP_ANONYMOUS,
                               -1, 0);
        EXPECT_NE((void *)map_, MAP_FAILED);
        EXPECT_EQ(mprotect(map_, page_, PROT_NONE), 0);
        EXPECT_EQ(mprotect(map_ + len_ - page_, page_, PROT_NONE), 0);
        data_ = at_end ? map_ + len_ - page_ - bytes : map_ + page_;
    }
    ~FencedBuffer() { munmap(map_, len_); }
    FencedBuffer(const FencedBuffer &) = delete;
    FencedBuffer &operator=(const FencedBuffer &) = delete;
    template <class T> T *as() { return reinterpret_cast<T *>(data_); }

private:
    size_t page_, len_;
    uint8_t *map_, *data_;
};

bool aligned(const void *p, unsigned alignment) {
    return (uintptr_t)p % std::max(alignment, 1u) == 0;
}

std::vector<uint8_t> random_facing(Rng &rng, int n) {
    const double p = rng.unit();
    std::vector<uint8_t> f((size_t)n);
    for (auto &b : f) b = rng.chance(p) ? 1 : 0;
    return f;
}

// Random cull bytes over all 8 bits; a fraction of them 0x80 exactly, so
// that many triangles share bit 7 and nothing else.
std::vector<uint8_t> cull_bytes_8bit(Rng &rng, int numVerts) {
    const double p = rng.unit();
    std::vector<uint8_t> c((size_t)numVerts);
    for (auto &b : c) {
        if (rng.chance(0.3)) {
            b = 0x80;
            continue;
        }
        uint8_t v = 0;
        for (int bit = 0; bit < 8; bit++)
            if (rng.chance(p)) v |= (uint8_t)(1u << bit);
        b = v;
    }
    return c;
}

std::vector<SilEdge> random_edges(Rng &rng, int n, int numTriangles, int numVerts) {
    std::vector<SilEdge> edges((size_t)n);
    for (auto &e : edges) {
        e.p1 = (int)rng.below((uint32_t)numTriangles + 1);
        e.p2 = rng.chance(0.1) ? numTriangles : (int)rng.below((uint32_t)numTriangles + 1);
        e.v1 = 2 * (int)rng.below((uint32_t)numVerts);
        e.v2 = 2 * (int)rng.below((uint32_t)numVerts);
    }
    return edges;
}

// V's CreateSilTriangles on FACING and EDGES, through the ABI-checking
// trampoline into a guarded output, against c_ref's: count, indices and
// the guards after the output.
::testing::AssertionResult sil_matches_reference(Rng &abi, const sv_variant *v,
                                                 const uint8_t *facing,
                                                 const std::vector<SilEdge> &edges) {
    const int n = (int)edges.size();
    std::vector<int> expected_out((size_t)6 * n + 6);
    const int expected = sv_create_sil_triangles_c_ref(expected_out.data(), facing, edges.data(),
                                                       n);
    GuardedBuffer out((size_t)6 * n * sizeof(int), 0);
    const int got = checked_call(abi, v->create_sil_triangles, out.as<int>(), facing, edges.data(),
                                 n);
    if (got != expected) {
        return ::testing::AssertionFailure() << "returned " << got << ", c_ref " << expected;
    }
    if (!std::equal(expected_out.begin(), expected_out.begin() + expected, out.as<int>())) {
        return ::testing::AssertionFailure() << "indices differ from c_ref's";
    }
    if (!out.guards_intact()) {
        return ::testing::AssertionFailure() << "wrote past its " << expected << " ints";
    }
    return ::testing::AssertionSuccess();
}

int check_count_facing(Rng &abi, const sv_variant *v, const std::vector<uint8_t> &facing,
                       uint8_t *buf) {
    std::copy(facing.begin(), facing.end(), buf);
    return checked_call(abi, v->count_facing, buf, (int)facing.size());
}

} // namespace

// One instance per variant of sv_variants(). A test that holds for only
// some of them is instantiated for those alone (a skip would make the
// whole ctest entry count as skipped: tests/support/test_conditions.h).
class Avx512Kernels : public VariantTest {};

INSTANTIATE_TEST_SUITE_P(Variants, Avx512Kernels, ::testing::ValuesIn(variant_names()), param_name);

std::vector<std::string> variant_names_but(std::initializer_list<const char *> left_out) {
    std::vector<std::string> out;
    for (const std::string &n : variant_names()) {
        bool keep = true;
        for (const char *l : left_out) keep = keep && n != l;
        if (keep) out.push_back(n);
    }
    return out;
}

// Every variant but sse2_paper, which keeps limit D-5 (bit 7 alone is not
// culled in its four-triangle loop): pinned by Errata.D5_*.
class Avx512KernelsBit7 : public VariantTest {};
INSTANTIATE_TEST_SUITE_P(Variants, Avx512KernelsBit7,
                         ::testing::ValuesIn(variant_names_but({"sse2_paper"})), param_name);

TEST_P(Avx512KernelsBit7, CullOnAnySharedBitBit7Included) {
    SCOPED_TRACE(seed_trace());
    Rng rng = rng_for("Avx512Kernels.CullBit7");
    for (int n = 0; n <= 300; n++) {
        if (stop_after_failures()) return;
        std::vector<uint8_t> facing = random_facing(rng, n);
        const int numVerts = 1 + (int)rng.below((uint32_t)(3 * n + 1));
        std::vector<int> indices((size_t)3 * n);
        for (auto &i : indices) i = (int)rng.below((uint32_t)numVerts);
        std::vector<uint8_t> cull = cull_bytes_8bit(rng, numVerts);
        std::vector<uint8_t> expected_facing = facing;
        const int expected = sv_count_facing_cull_c_ref(expected_facing.data(), n, indices.data(),
                                                        cull.data());
        GuardedBuffer fbuf((size_t)n, 0);
        std::copy(facing.begin(), facing.end(), fbuf.data());
        int got = checked_call(abi, v->count_facing_cull, fbuf.data(), n, indices.data(),
                               cull.data());
        EXPECT_EQ(got, expected) << v->name << " n=" << n;
        EXPECT_TRUE(std::equal(expected_facing.begin(), expected_facing.end(), fbuf.data()))
            << v->name << ": facing differs, n=" << n;
        EXPECT_TRUE(fbuf.guards_intact()) << v->name << " n=" << n;
    }
}

TEST_P(Avx512Kernels, LargeCounts) {
    SCOPED_TRACE(seed_trace());
    Rng rng = rng_for("Avx512Kernels.LargeCounts");
    // CountFacing: around one and two full chunks of 62 x 256 bytes,
    // and all ones (the largest lane sums).
    for (int n : {15871, 15872, 15873, 31744, 31745, 40000}) {
        for (bool all_ones : {false, true}) {
            std::vector<uint8_t> facing = random_facing(rng, n);
            if (all_ones) std::fill(facing.begin(), facing.end(), 1);
            GuardedBuffer buf((size_t)n, 0);
            EXPECT_EQ(check_count_facing(abi, v, facing, buf.data()),
                      sv_count_facing_c_ref(facing.data(), n))
                << v->name << " n=" << n;
        }
    }
    // CountFacingCull over several lists of 960; CapTriangles and
    // SilTriangles over many blocks and chunks.
    for (int n : {959, 960, 961, 1920, 5000}) {
        std::vector<uint8_t> facing = random_facing(rng, n);
        const int numVerts = 1 + (int)rng.below((uint32_t)(3 * n));
        std::vector<int> indices((size_t)3 * n);
        for (auto &i : indices) i = (int)rng.below((uint32_t)numVerts);
        std::vector<uint8_t> cull = cull_bytes_8bit(rng, numVerts);
        if (std::string(v->name) == "sse2_paper")
            for (auto &c : cull) c &= 0x7F; // limit D-5
        std::vector<uint8_t> expected_facing = facing;
        const int expected = sv_count_facing_cull_c_ref(expected_facing.data(), n, indices.data(),
                                                        cull.data());
        GuardedBuffer fbuf((size_t)n, 0);
        std::copy(facing.begin(), facing.end(), fbuf.data());
        EXPECT_EQ(checked_call(abi, v->count_facing_cull, fbuf.data(), n, indices.data(),
                               cull.data()),
                  expected)
            << v->name << " n=" << n;
        EXPECT_TRUE(std::equal(expected_facing.begin(), expected_facing.end(), fbuf.data()))
            << v->name << ": facing differs, n=" << n;
        EXPECT_TRUE(fbuf.guards_intact()) << v->name << " n=" << n;

        std::vector<int> expected_out((size_t)6 * n + 6);
        const int expected_caps = sv_create_cap_triangles_c_ref(expected_out.data(), facing.data(),
                                                                indices.data(), 3 * n);
        GuardedBuffer ibuf(indices.size() * sizeof(int), 0);
        std::copy(indices.begin(), indices.end(), ibuf.as<int>());
        GuardedBuffer out((size_t)6 * n * sizeof(int), 0);
        EXPECT_EQ(checked_call(abi, v->create_cap_triangles, out.as<int>(), facing.data(),
                               ibuf.as<int>(), 3 * n),
                  expected_caps)
            << v->name << " n=" << n;
        EXPECT_TRUE(
            std::equal(expected_out.begin(), expected_out.begin() + expected_caps, out.as<int>()))
            << v->name << ": cap indices differ, n=" << n;
        EXPECT_TRUE(out.guards_intact()) << v->name << " n=" << n;
    }
    for (int n : {447, 448, 449, 896, 5000}) {
        for (int numTriangles : {n / 2, 1500, 5000}) {
            std::vector<uint8_t> facing = random_facing(rng, numTriangles + 1);
            facing[(size_t)numTriangles] = 1;
            std::vector<SilEdge> edges = random_edges(rng, n, numTriangles, 1 << 20);
            EXPECT_TRUE(sil_matches_reference(abi, v, facing.data(), edges))
                << v->name << " n=" << n << " triangles=" << numTriangles;
        }
    }
}

// The largest triangle number M decides between the AVX-512 kernel's
// bitmap (M < 2048) and the AVX2 kernel it hands wider chunks to; the
// facing array has exactly M + 1 bytes and ends at an unmapped page.
TEST_P(Avx512Kernels, SilTriangleNumbersAroundTheBitmapLimit) {
    SCOPED_TRACE(seed_trace());
    Rng rng = rng_for("Avx512Kernels.SilBitmapLimit");
    for (int maxP : {0, 1, 63, 64, 2046, 2047, 2048, 2049, 4095, 100000}) {
        for (int n : {1, 15, 16, 17, 100, 449}) {
            std::vector<uint8_t> facing = random_facing(rng, maxP + 1);
            std::vector<SilEdge> edges = random_edges(rng, n, maxP, 1 << 20);
            edges[rng.below((uint32_t)n)].p2 = maxP; // M exactly
            FencedBuffer fbuf((size_t)maxP + 1, true);
            std::copy(facing.begin(), facing.end(), fbuf.as<uint8_t>());
            FencedBuffer ebuf(edges.size() * sizeof(SilEdge), true);
            std::copy(edges.begin(), edges.end(), ebuf.as<SilEdge>());
            std::vector<int> expected_out((size_t)6 * n + 6);
            const int expected = sv_create_sil_triangles_c_ref(expected_out.data(), facing.data(),
                                                               edges.data(), n);
            GuardedBuffer out((size_t)6 * n * sizeof(int), 0);
            EXPECT_EQ(checked_call(abi, v->create_sil_triangles, out.as<int>(), fbuf.as<uint8_t>(),
                                   ebuf.as<SilEdge>(), n),
                      expected)
                << v->name << " n=" << n << " M=" << maxP;
            EXPECT_TRUE(
                std::equal(expected_out.begin(), expected_out.begin() + expected, out.as<int>()))
                << v->name << ": indices differ, n=" << n << " M=" << maxP;
            EXPECT_TRUE(out.guards_intact()) << v->name << " n=" << n << " M=" << maxP;
        }
    }
}

// The AVX-512 kernel's chunks of 448 edges: a chunk whose triangle numbers
// span more than its 2048-bit window is handed to the AVX2 kernel by an
// ordinary call, and the next chunk must find its window (kept in
// zmm28-zmm31) and the output position as they were; whole calls above
// 3072 edges go to the AVX2 kernel at entry. The edges come sorted by p1
// over triangles 0..span, each p2 within 300 triangles of its p1 (behind
// or ahead), so with span 999 the next chunk often finds the window
// already covering it, and with 2600 or 2900 the window slides and
// extends across the chunks; one edge of chunk 0, 1 or 2 names triangle
// 5000, which makes that chunk too wide.
TEST_P(Avx512Kernels, SilWideChunkBetweenWindowedChunks) {
    SCOPED_TRACE(seed_trace());
    Rng rng = rng_for("Avx512Kernels.SilWideChunk");
    constexpr int kFar = 5000;
    for (int n : {3 * 448, 3 * 448 + 5, 3072, 3073, 6 * 448}) {
        for (int span : {999, 2600, 2900}) {
            for (int wideChunk : {0, 1, 2}) {
                std::vector<SilEdge> edges = random_edges(rng, n, span, 1 << 20);
                std::sort(edges.begin(), edges.end(),
                          [](const SilEdge &a, const SilEdge &b) { return a.p1 < b.p1; });
                for (SilEdge &e : edges) {
                    const int p2 = e.p1 + (int)rng.below(601) - 300;
                    e.p2 = std::min(std::max(p2, 0), span);
                }
                edges[(size_t)wideChunk * 448 + rng.below(448)].p2 = kFar;
                std::vector<uint8_t> facing = random_facing(rng, kFar + 1);
                EXPECT_TRUE(sil_matches_reference(abi, v, facing.data(), edges))
                    << v->name << " n=" << n << " span " << span << " wide chunk " << wideChunk;
            }
        }
    }
}

// The avx512vbmi CountFacingCull keeps cullBits[0 .. M] in sixteen 64-byte
// registers (M: the largest vertex number) and hands M >= 1024 to the list
// kernel. Around every register and pair boundary of that table, and around
// 64-triangle blocks: cullBits has exactly M + 1 bytes and ends at an
// unmapped page (a table load past cullBits[M] faults), the vertex numbers
// and the facing bytes end at one too (the tail block's masked loads).
TEST_P(Avx512Kernels, CullTableAroundItsRegisterBoundaries) {
    SCOPED_TRACE(seed_trace());
    Rng rng = rng_for("Avx512Kernels.CullTable");
    for (int maxV : {0,   1,   63,  64,  127, 128, 191, 192, 255, 256,  383,  384,  511, 512,
                     575, 576, 767, 831, 832, 895, 896, 959, 960, 1023, 1024, 1025, 5000}) {
        for (int n : {1, 2, 63, 64, 65, 127, 128, 191, 200, 1344}) {
            std::vector<uint8_t> facing = random_facing(rng, n);
            std::vector<int> indices((size_t)3 * n);
            for (auto &i : indices) i = (int)rng.below((uint32_t)maxV + 1);
            indices[rng.below((uint32_t)(3 * n))] = maxV; // M exactly
            std::vector<uint8_t> cull = cull_bytes_8bit(rng, maxV + 1);
            if (std::string(v->name) == "sse2_paper")
                for (auto &c : cull) c &= 0x7F; // limit D-5
            FencedBuffer fbuf((size_t)n, true), ibuf(indices.size() * sizeof(int), true),
                cbuf((size_t)maxV + 1, true);
            std::copy(facing.begin(), facing.end(), fbuf.as<uint8_t>());
            std::copy(indices.begin(), indices.end(), ibuf.as<int>());
            std::copy(cull.begin(), cull.end(), cbuf.as<uint8_t>());
            std::vector<uint8_t> expected_facing = facing;
            const int expected = sv_count_facing_cull_c_ref(expected_facing.data(), n,
                                                            indices.data(), cull.data());
            EXPECT_EQ(checked_call(abi, v->count_facing_cull, fbuf.as<uint8_t>(), n, ibuf.as<int>(),
                                   cbuf.as<uint8_t>()),
                      expected)
                << v->name << " n=" << n << " M=" << maxV;
            EXPECT_TRUE(
                std::equal(expected_facing.begin(), expected_facing.end(), fbuf.as<uint8_t>()))
                << v->name << ": facing differs, n=" << n << " M=" << maxV;
        }
    }
}

// "Writes only facing bytes that were 0" (the AVX2, AVX-512 and avx512vbmi
// kernels' contract; the C's too): every triangle facing and culled, the
// facing bytes in a read-only page. A store of the same 1 would fault.
// c_branchless and sse2_paper store every facing byte (branch-free): their
// contract does not promise the next test's property.
class Avx512KernelsStoreNoOne : public VariantTest {};
INSTANTIATE_TEST_SUITE_P(Variants, Avx512KernelsStoreNoOne,
                         ::testing::ValuesIn(variant_names_but({"c_branchless", "sse2_paper"})),
                         param_name);

TEST_P(Avx512KernelsStoreNoOne, CullWritesNoFacingByteThatWasOne) {
    SCOPED_TRACE(seed_trace());
    Rng rng = rng_for("Avx512Kernels.CullReadOnly");
    const size_t page = (size_t)sysconf(_SC_PAGESIZE);
    for (int n : {1, 63, 64, 65, 1344, 3000}) {
        for (int numVerts : {3, 700, 2000}) {
            std::vector<int> indices((size_t)3 * n);
            for (auto &i : indices) i = (int)rng.below((uint32_t)numVerts);
            std::vector<uint8_t> cull((size_t)numVerts, 0x21);
            const size_t len = ((size_t)n + page - 1) / page * page;
            uint8_t *facing = (uint8_t *)mmap(nullptr, len, PROT_READ | PROT_WRITE,
                                              MAP_PRIVATE | MAP_ANONYMOUS, -1, 0);
            ASSERT_NE((void *)facing, MAP_FAILED);
            std::fill(facing, facing + n, 1);
            ASSERT_EQ(mprotect(facing, len, PROT_READ), 0);
            EXPECT_EQ(checked_call(abi, v->count_facing_cull, facing, n, indices.data(),
                                   cull.data()),
                      n)
                << v->name << " n=" << n << " vertices=" << numVerts;
            munmap(facing, len);
        }
    }
}

// Every input array placed against an unmapped page, above it and below
// it: a read outside any array faults. Variants whose alignment needs the
// placement does not meet are skipped for that placement.
TEST_P(Avx512Kernels, InputsAtPageEdgesReadNothingOutside) {
    SCOPED_TRACE(seed_trace());
    Rng rng = rng_for("Avx512Kernels.PageEdges");
    std::vector<int> counts;
    for (int n = 0; n <= 80; n++) counts.push_back(n);
    for (int n : {127, 128, 129, 255, 256, 257, 1000, 1344}) counts.push_back(n);
    for (bool at_end : {true, false}) {
        for (int n : counts) {
            if (stop_after_failures()) return;
            std::vector<uint8_t> facing = random_facing(rng, n);
            const int numVerts = 1 + (int)rng.below((uint32_t)(3 * n + 1));
            std::vector<int> indices((size_t)3 * n);
            for (auto &i : indices) i = (int)rng.below((uint32_t)numVerts);
            if (n > 0) indices[rng.below((uint32_t)(3 * n))] = numVerts - 1;
            std::vector<uint8_t> cull = cull_bytes_8bit(rng, numVerts);
            for (auto &c : cull) c &= 0x7F; // every variant, sse2_paper included
            const int numTriangles = (int)rng.below(2u * (uint32_t)n + 2);
            std::vector<uint8_t> sil_facing = random_facing(rng, numTriangles + 1);
            sil_facing[(size_t)numTriangles] = 1;
            std::vector<SilEdge> edges = random_edges(rng, n, numTriangles, 1 << 20);

            FencedBuffer fbuf((size_t)n, at_end), ibuf(indices.size() * sizeof(int), at_end),
                cbuf((size_t)numVerts, at_end), sfbuf((size_t)numTriangles + 1, at_end),
                ebuf(edges.size() * sizeof(SilEdge), at_end);
            std::copy(indices.begin(), indices.end(), ibuf.as<int>());
            std::copy(cull.begin(), cull.end(), cbuf.as<uint8_t>());
            std::copy(sil_facing.begin(), sil_facing.end(), sfbuf.as<uint8_t>());
            std::copy(edges.begin(), edges.end(), ebuf.as<SilEdge>());

            std::vector<uint8_t> cull_facing = facing;
            const int expected_cull = sv_count_facing_cull_c_ref(cull_facing.data(), n,
                                                                 indices.data(), cull.data());
            std::vector<int> expected_caps((size_t)6 * n + 6), expected_sil((size_t)6 * n + 6);
            const int n_caps = sv_create_cap_triangles_c_ref(expected_caps.data(), facing.data(),
                                                             indices.data(), 3 * n);
            const int n_sil = sv_create_sil_triangles_c_ref(expected_sil.data(), sil_facing.data(),
                                                            edges.data(), n);

            const std::string where = std::string(v->name) + " n=" + std::to_string(n) +
                                      (at_end ? " (arrays end at a page)"
                                              : " (arrays start at a page)");
            if (aligned(fbuf.as<uint8_t>(), v->align_facing)) {
                EXPECT_EQ(check_count_facing(abi, v, facing, fbuf.as<uint8_t>()),
                          sv_count_facing_c_ref(facing.data(), n))
                    << where;
            }
            std::copy(facing.begin(), facing.end(), fbuf.as<uint8_t>());
            EXPECT_EQ(checked_call(abi, v->count_facing_cull, fbuf.as<uint8_t>(), n, ibuf.as<int>(),
                                   cbuf.as<uint8_t>()),
                      expected_cull)
                << where;
            EXPECT_TRUE(std::equal(cull_facing.begin(), cull_facing.end(), fbuf.as<uint8_t>()))
                << where;

            std::copy(facing.begin(), facing.end(), fbuf.as<uint8_t>());
            GuardedBuffer out((size_t)6 * n * sizeof(int), 0);
            if (aligned(ibuf.as<int>(), v->align_indices)) {
                EXPECT_EQ(checked_call(abi, v->create_cap_triangles, out.as<int>(),
                                       fbuf.as<uint8_t>(), ibuf.as<int>(), 3 * n),
                          n_caps)
                    << where;
                EXPECT_TRUE(std::equal(expected_caps.begin(), expected_caps.begin() + n_caps,
                                       out.as<int>()))
                    << where;
                EXPECT_TRUE(out.guards_intact()) << where;
            }
            EXPECT_EQ(checked_call(abi, v->create_sil_triangles, out.as<int>(), sfbuf.as<uint8_t>(),
                                   ebuf.as<SilEdge>(), n),
                      n_sil)
                << where;
            EXPECT_TRUE(
                std::equal(expected_sil.begin(), expected_sil.begin() + n_sil, out.as<int>()))
                << where;
            EXPECT_TRUE(out.guards_intact()) << where;
        }
    }
}
