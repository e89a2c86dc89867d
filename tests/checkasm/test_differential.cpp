// Differential tests: every variant against the paper's C (c_ref), on every
// count from 0 to 600 (every tail of the 256/16/4/1 loops of appendix C and
// of the 4/1 loops of D-F), at facing densities 0%, 50%, 100% and random,
// with random index arrays, at every alignment the variant allows. Every
// call goes through the ABI-checking trampoline with garbage in the upper
// half of each int argument, and every output buffer is sized exactly at
// the documented bound with guard bytes on both sides.
//
// Each test runs once per variant (Variants/Differential.<Test>/<variant>,
// test_support.h's VariantTest): --gtest_filter='*/avx2' runs one variant,
// and every case is an EXPECT, so a failing variant or case hides no other.
// The cases are the same for every variant (drawn from the test's name).
//
// Copyright (C) 2026 the shadowvol authors. LGPL-2.1-or-later.
#include "test_support.h"

#include <algorithm>

using namespace svtest;

namespace {

constexpr int kMaxCount = 600;

// Facing densities: fraction of bytes set; < 0 draws one at random per case.
constexpr double kDensities[] = {0.0, 0.5, 1.0, -1.0};

std::string density_name(double d) {
    return d < 0 ? std::string("random") : std::to_string((int)(d * 100)) + "%";
}

std::vector<uint8_t> random_facing(Rng &rng, int n, double density) {
    double p = density < 0 ? rng.unit() : density;
    std::vector<uint8_t> f((size_t)std::max(n, 0));
    for (auto &b : f) b = rng.chance(p) ? 1 : 0;
    return f;
}

// Offsets from a 64-byte boundary that satisfy `alignment` and exercise
// every position inside a 16-byte vector (or every aligned slot in a line).
std::vector<size_t> offsets_for(unsigned alignment, unsigned element_size) {
    std::vector<size_t> out;
    unsigned step = std::max(alignment, element_size);
    unsigned limit = step >= 16 ? 64 : 16;
    for (unsigned o = 0; o < limit; o += step) out.push_back(o);
    return out;
}

// Cull bytes using bits 0..6 only (bit 7 is the documented sse2_paper limit,
// pinned separately in test_errata.cpp). `sparsity` in [0, 1] thins the bits
// so some cases cull nearly nothing and some nearly everything.
std::vector<uint8_t> random_cull_bits(Rng &rng, int numVerts) {
    double p = rng.unit();
    std::vector<uint8_t> c((size_t)numVerts);
    for (auto &b : c) {
        uint8_t v = 0;
        for (int bit = 0; bit < 7; bit++)
            if (rng.chance(p)) v |= (uint8_t)(1u << bit);
        b = v;
    }
    return c;
}

} // namespace

class Differential : public VariantTest {};

INSTANTIATE_TEST_SUITE_P(Variants, Differential, ::testing::ValuesIn(variant_names()), param_name);

TEST_P(Differential, CountFacing) {
    SCOPED_TRACE(seed_trace());
    Rng rng = rng_for("Differential.CountFacing");
    for (int n = 0; n <= kMaxCount; n++) {
        if (stop_after_failures()) return;
        for (double density : kDensities) {
            std::vector<uint8_t> facing = random_facing(rng, n, density);
            const int expected = sv_count_facing_c_ref(facing.data(), n);
            for (size_t off : offsets_for(v->align_facing, 1)) {
                GuardedBuffer buf((size_t)n, off);
                std::copy(facing.begin(), facing.end(), buf.data());
                int got = checked_call(abi, v->count_facing, buf.data(), n);
                EXPECT_EQ(got, expected) << v->name << " n=" << n << " density "
                                         << density_name(density) << " offset " << off;
                EXPECT_TRUE(buf.guards_intact()) << v->name << " n=" << n;
                EXPECT_TRUE(std::equal(facing.begin(), facing.end(), buf.data()))
                    << v->name << " modified its const input, n=" << n;
            }
        }
    }
}

TEST_P(Differential, CountFacingCull) {
    SCOPED_TRACE(seed_trace());
    Rng rng = rng_for("Differential.CountFacingCull");
    for (int n = 0; n <= kMaxCount; n++) {
        if (stop_after_failures()) return;
        for (double density : kDensities) {
            std::vector<uint8_t> facing = random_facing(rng, n, density);
            const int numVerts = 1 + (int)rng.below((uint32_t)(3 * n + 1));
            std::vector<int> indices((size_t)3 * n);
            for (auto &i : indices) i = (int)rng.below((uint32_t)numVerts);
            std::vector<uint8_t> cull = random_cull_bits(rng, numVerts);

            std::vector<uint8_t> expected_facing = facing;
            const int expected = sv_count_facing_cull_c_ref(expected_facing.data(), n,
                                                            indices.data(), cull.data());
            // No alignment contract: every byte offset of facing, every
            // int offset of indices.
            for (size_t off : offsets_for(1, 1)) {
                GuardedBuffer fbuf((size_t)n, off);
                GuardedBuffer ibuf(indices.size() * sizeof(int), (off * 4) % 16);
                GuardedBuffer cbuf(cull.size(), off);
                std::copy(facing.begin(), facing.end(), fbuf.data());
                std::copy(indices.begin(), indices.end(), ibuf.as<int>());
                std::copy(cull.begin(), cull.end(), cbuf.data());
                int got = checked_call(abi, v->count_facing_cull, fbuf.data(), n, ibuf.as<int>(),
                                       cbuf.data());
                EXPECT_EQ(got, expected) << v->name << " n=" << n << " density "
                                         << density_name(density) << " offset " << off;
                EXPECT_TRUE(std::equal(expected_facing.begin(), expected_facing.end(), fbuf.data()))
                    << v->name << ": facing array differs, n=" << n << " offset " << off;
                EXPECT_TRUE(fbuf.guards_intact() && ibuf.guards_intact() && cbuf.guards_intact())
                    << v->name << " wrote out of bounds, n=" << n << " offset " << off;
            }
        }
    }
}

TEST_P(Differential, CreateSilTriangles) {
    SCOPED_TRACE(seed_trace());
    Rng rng = rng_for("Differential.CreateSilTriangles");
    for (int n = 0; n <= kMaxCount; n++) {
        if (stop_after_failures()) return;
        for (double density : kDensities) {
            const int numTriangles = (int)rng.below(2u * (uint32_t)n + 2);
            std::vector<uint8_t> facing = random_facing(rng, numTriangles + 1, density);
            facing[(size_t)numTriangles] = 1; // the dangling edges' byte
            const int numVerts = 1 + (int)rng.below(1u << 20);
            std::vector<SilEdge> edges((size_t)n);
            for (auto &e : edges) {
                e.p1 = (int)rng.below((uint32_t)numTriangles + 1);
                // some dangling edges, the rest between two triangles
                e.p2 = rng.chance(0.1) ? numTriangles : (int)rng.below((uint32_t)numTriangles + 1);
                e.v1 = 2 * (int)rng.below((uint32_t)numVerts);
                e.v2 = 2 * (int)rng.below((uint32_t)numVerts);
            }
            std::vector<int> expected((size_t)6 * n + 6);
            const int expected_count = sv_create_sil_triangles_c_ref(expected.data(), facing.data(),
                                                                     edges.data(), n);
            for (size_t out_off : offsets_for(v->align_shadow_indices, 4)) {
                GuardedBuffer out((size_t)6 * n * sizeof(int), out_off);
                GuardedBuffer ebuf(edges.size() * sizeof(SilEdge), (out_off * 3) % 16);
                std::copy(edges.begin(), edges.end(), ebuf.as<SilEdge>());
                int got = checked_call(abi, v->create_sil_triangles, out.as<int>(), facing.data(),
                                       ebuf.as<SilEdge>(), n);
                const std::string what = std::string(v->name) + " n=" + std::to_string(n) +
                                         " density " + density_name(density) + " offset " +
                                         std::to_string(out_off);
                EXPECT_EQ(got, expected_count) << what;
                EXPECT_TRUE(
                    std::equal(expected.begin(), expected.begin() + expected_count, out.as<int>()))
                    << what << ": indices differ";
                EXPECT_TRUE(out.guards_intact()) << what << ": wrote outside 6 * numSilEdges ints";
            }
        }
    }
}

TEST_P(Differential, CreateCapTriangles) {
    SCOPED_TRACE(seed_trace());
    Rng rng = rng_for("Differential.CreateCapTriangles");
    for (int n = 0; n <= kMaxCount; n++) {
        if (stop_after_failures()) return;
        for (double density : kDensities) {
            std::vector<uint8_t> facing = random_facing(rng, n, density);
            const int numVerts = 1 + (int)rng.below(1u << 29);
            std::vector<int> indices((size_t)3 * n);
            for (auto &i : indices) i = (int)rng.below((uint32_t)numVerts);
            std::vector<int> expected((size_t)6 * n + 6);
            const int expected_count = sv_create_cap_triangles_c_ref(expected.data(), facing.data(),
                                                                     indices.data(), 3 * n);
            // every input offset, each paired with one of the output's
            const std::vector<size_t> out_offsets = offsets_for(v->align_shadow_indices, 4);
            for (size_t in_off : offsets_for(v->align_indices, 4)) {
                size_t out_off = out_offsets[in_off / 4 % out_offsets.size()];
                GuardedBuffer ibuf(indices.size() * sizeof(int), in_off);
                GuardedBuffer out((size_t)6 * n * sizeof(int), out_off);
                std::copy(indices.begin(), indices.end(), ibuf.as<int>());
                int got = checked_call(abi, v->create_cap_triangles, out.as<int>(), facing.data(),
                                       ibuf.as<int>(), 3 * n);
                const std::string what = std::string(v->name) + " n=" + std::to_string(n) +
                                         " density " + density_name(density) + " offsets " +
                                         std::to_string(in_off) + "/" + std::to_string(out_off);
                EXPECT_EQ(got, expected_count) << what;
                EXPECT_TRUE(
                    std::equal(expected.begin(), expected.begin() + expected_count, out.as<int>()))
                    << what << ": indices differ";
                EXPECT_TRUE(out.guards_intact() && ibuf.guards_intact())
                    << what << ": wrote outside 6 * numTriangles ints";
            }
        }
    }
}

// The whole volume, with and without culling, on random connectivity: the
// four kernels of each variant glued by sv_create_shadow_volume.
TEST_P(Differential, CreateShadowVolume) {
    SCOPED_TRACE(seed_trace());
    Rng rng = rng_for("Differential.CreateShadowVolume");
    const sv_variant *ref = sv_variant_by_name("c_ref");
    ASSERT_NE(ref, nullptr);
    for (int numTriangles = 0; numTriangles <= 300; numTriangles++) {
        if (stop_after_failures()) return;
        for (double density : kDensities) {
            for (bool cull : {false, true}) {
                const int numIndices = 3 * numTriangles;
                const int numEdges = numTriangles * 3 / 2 + (int)rng.below(4);
                const int numVerts = 1 + (int)rng.below((uint32_t)numIndices + 1);
                std::vector<int> indices((size_t)numIndices);
                for (auto &i : indices) i = (int)rng.below((uint32_t)numVerts);
                std::vector<uint8_t> facing = random_facing(rng, numTriangles + 1, density);
                facing[(size_t)numTriangles] = 1;
                std::vector<SilEdge> edges((size_t)numEdges);
                for (auto &e : edges) {
                    e.p1 = (int)rng.below((uint32_t)numTriangles + 1);
                    e.p2 = (int)rng.below((uint32_t)numTriangles + 1);
                    e.v1 = 2 * (int)rng.below((uint32_t)numVerts);
                    e.v2 = 2 * (int)rng.below((uint32_t)numVerts);
                }
                std::vector<uint8_t> cullBits = random_cull_bits(rng, numVerts);
                const size_t cap = sv_shadow_volume_capacity(numIndices, numEdges);

                std::vector<int> expected(cap + 6);
                std::vector<uint8_t> expected_facing = facing;
                const int expected_count =
                    sv_create_shadow_volume(ref, expected.data(), indices.data(), numIndices,
                                            edges.data(), numEdges, expected_facing.data(),
                                            cull ? cullBits.data() : nullptr);

                GuardedBuffer out(cap * sizeof(int), 0);
                GuardedBuffer fbuf(facing.size(), 0);
                GuardedBuffer ibuf(indices.size() * sizeof(int), 0);
                std::copy(facing.begin(), facing.end(), fbuf.data());
                std::copy(indices.begin(), indices.end(), ibuf.as<int>());
                int got = sv_create_shadow_volume_checked(v, out.as<int>(), cap, ibuf.as<int>(),
                                                          numIndices, numVerts, edges.data(),
                                                          numEdges, fbuf.data(),
                                                          cull ? cullBits.data() : nullptr);
                const std::string what = std::string(v->name) +
                                         " triangles=" + std::to_string(numTriangles) +
                                         " cull=" + std::to_string(cull) + " density " +
                                         density_name(density);
                EXPECT_EQ(got, expected_count)
                    << what << ": " << (got < 0 ? sv_status_string(got) : "");
                EXPECT_TRUE(
                    std::equal(expected.begin(), expected.begin() + expected_count, out.as<int>()))
                    << what << ": indices differ";
                EXPECT_TRUE(std::equal(expected_facing.begin(), expected_facing.end(), fbuf.data()))
                    << what << ": facing differs";
                EXPECT_TRUE(out.guards_intact())
                    << what << ": wrote past sv_shadow_volume_capacity";
            }
        }
    }
}
