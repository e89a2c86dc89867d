// The contracts of the header, enforced: each *_checked entry point refuses
// each kind of out-of-contract input with its SV_E_* code (and writes
// nothing), and accepts input exactly at every bound.
//
// Copyright (C) 2026 the shadowvol authors. LGPL-2.1-or-later.
#include "test_support.h"

#include <climits>
#include <set>

using namespace svtest;

namespace {
const sv_variant *paper() { return sv_variant_by_name("sse2_paper"); }
const sv_variant *ref() { return sv_variant_by_name("c_ref"); }
} // namespace

TEST(Contracts, VariantTableNamesAreUniqueAndComplete) {
    int n = 0;
    const sv_variant *all = sv_variants(&n);
    ASSERT_GE(n, 2);
    EXPECT_STREQ(all[0].name, "c_ref") << "the reference comes first";
    // Complete: exactly the variants this platform builds (the asm kernels
    // exist per platform, docs/PLATFORMS.md), in the table's order.
    std::vector<std::string> want, got;
    for (const char *name : {"c_ref", "c_branchless", "sse2_paper", "avx2", "avx512", "avx512vbmi"})
        if (variant_built_here(name)) want.push_back(name);
    for (int i = 0; i < n; i++) got.push_back(all[i].name);
    EXPECT_EQ(got, want);
    std::set<std::string> names;
    for (int i = 0; i < n; i++) {
        EXPECT_TRUE(names.insert(all[i].name).second) << all[i].name;
        EXPECT_EQ(sv_variant_by_name(all[i].name), &all[i]);
        EXPECT_TRUE(all[i].count_facing && all[i].count_facing_cull &&
                    all[i].create_sil_triangles && all[i].create_cap_triangles)
            << all[i].name;
    }
    EXPECT_EQ(sv_variant_by_name("no_such_variant"), nullptr);
    EXPECT_EQ(sv_variant_by_name(nullptr), nullptr);
}

TEST(Contracts, StatusStringsAreDistinct) {
    std::set<std::string> seen;
    for (int s = SV_OK; s >= SV_E_CULL_BITS; s--) {
        EXPECT_TRUE(seen.insert(sv_status_string(s)).second) << s;
    }
}

TEST(Contracts, CountFacingRefusesUnalignedNegativeAndNonBoolean) {
    SV_REQUIRE_SSE2_PAPER();
    const svtest::IsaLimitLifted lifted; // a named variant's contract
    alignas(16) uint8_t facing[33] = {0};
    facing[3] = 1;
    EXPECT_EQ(sv_count_facing_checked(paper(), facing, 32), 1);
    EXPECT_EQ(sv_count_facing_checked(paper(), facing + 1, 16), SV_E_ALIGNMENT);
    EXPECT_EQ(sv_count_facing_checked(ref(), facing + 1, 16), 1) << "c_ref needs no alignment";
    EXPECT_EQ(sv_count_facing_checked(paper(), facing, -1), SV_E_COUNT);
    EXPECT_EQ(sv_count_facing_checked(paper(), nullptr, 4), SV_E_NULL);
    EXPECT_EQ(sv_count_facing_checked(paper(), nullptr, 0), 0);
    EXPECT_EQ(sv_count_facing_checked(nullptr, facing, 4), SV_E_NULL);
    facing[7] = 2;
    EXPECT_EQ(sv_count_facing_checked(paper(), facing, 32), SV_E_FACING_NOT_BOOL);
}

TEST(Contracts, CountFacingCullRefusesIndicesOutOfRange) {
    SV_REQUIRE_SSE2_PAPER();
    const svtest::IsaLimitLifted lifted; // a named variant's contract
    uint8_t facing[2] = {0, 0};
    int indices[6] = {0, 1, 2, 1, 2, 3};
    uint8_t cull[4] = {1, 1, 1, 0};
    uint8_t before[2] = {0, 0};
    EXPECT_EQ(sv_count_facing_cull_checked(paper(), facing, 2, indices, cull, 3), SV_E_INDEX_RANGE);
    EXPECT_EQ(0, memcmp(facing, before, 2)) << "a refused call must not modify facing";
    indices[0] = -1;
    EXPECT_EQ(sv_count_facing_cull_checked(paper(), facing, 2, indices, cull, 4), SV_E_INDEX_RANGE);
    indices[0] = 0;
    EXPECT_EQ(sv_count_facing_cull_checked(paper(), facing, 2, indices, cull, 4), 1);
    EXPECT_EQ(facing[0], 1);
    EXPECT_EQ(sv_count_facing_cull_checked(paper(), facing, -2, indices, cull, 4), SV_E_COUNT);
    EXPECT_EQ(sv_count_facing_cull_checked(paper(), facing, INT_MAX, indices, cull, 4),
              SV_E_OVERFLOW)
        << "3 * numTriangles would overflow int";
}

SV_TIERED_TEST(Contracts, SilTrianglesCapacityIsExactlySixPerEdge) {
    Rng rng = rng_for("Contracts.SilCapacity");
    // every edge a silhouette edge: the output fills the bound exactly
    const int n = 37;
    std::vector<uint8_t> facing(n + 2);
    std::vector<SilEdge> edges(n);
    for (int i = 0; i <= n; i++) facing[(size_t)i] = (uint8_t)(i & 1);
    facing[(size_t)n + 1] = 1;
    for (int i = 0; i < n; i++) edges[(size_t)i] = {i, i + 1, 2 * i, 2 * i + 2};
    for (const sv_variant *v : runnable_variants()) {
        GuardedBuffer out((size_t)6 * n * sizeof(int), 0);
        EXPECT_EQ(sv_create_sil_triangles_checked(v, out.as<int>(), 6 * n - 1, facing.data(), n + 1,
                                                  edges.data(), n),
                  SV_E_CAPACITY)
            << v->name;
        EXPECT_EQ(sv_create_sil_triangles_checked(v, out.as<int>(), 6 * n, facing.data(), n + 1,
                                                  edges.data(), n),
                  6 * n)
            << v->name;
        EXPECT_TRUE(out.guards_intact()) << v->name;
    }
    (void)rng;
}

TEST(Contracts, SilTrianglesRefusesBadEdges) {
    SV_REQUIRE_SSE2_PAPER();
    const svtest::IsaLimitLifted lifted; // a named variant's contract
    uint8_t facing[3] = {0, 1, 1};
    alignas(16) int out[12];
    SilEdge good = {0, 2, 0, 2};
    EXPECT_EQ(sv_create_sil_triangles_checked(paper(), out, 6, facing, 2, &good, 1), 6);
    SilEdge odd = {0, 2, 1, 2};
    EXPECT_EQ(sv_create_sil_triangles_checked(paper(), out, 6, facing, 2, &odd, 1),
              SV_E_ODD_VERTEX);
    SilEdge far = {0, 3, 0, 2};
    EXPECT_EQ(sv_create_sil_triangles_checked(paper(), out, 6, facing, 2, &far, 1),
              SV_E_INDEX_RANGE);
    SilEdge neg = {-1, 1, 0, 2};
    EXPECT_EQ(sv_create_sil_triangles_checked(paper(), out, 6, facing, 2, &neg, 1),
              SV_E_INDEX_RANGE);
    uint8_t bad_facing[3] = {0, 1, 2};
    EXPECT_EQ(sv_create_sil_triangles_checked(paper(), out, 6, bad_facing, 2, &good, 1),
              SV_E_FACING_NOT_BOOL);
    EXPECT_EQ(sv_create_sil_triangles_checked(paper(), out, 6, facing, 2, &good, -1), SV_E_COUNT);
    EXPECT_EQ(sv_create_sil_triangles_checked(paper(), out, 6, facing, 2, &good, INT_MAX / 6 + 1),
              SV_E_OVERFLOW);
}

TEST(Contracts, CapTrianglesRefusesPartialTrianglesAndUnalignedIndices) {
    SV_REQUIRE_SSE2_PAPER();
    const svtest::IsaLimitLifted lifted; // a named variant's contract
    alignas(16) int indices[16] = {0, 1, 2, 2, 1, 3, 3, 1, 0, 0, 2, 3};
    uint8_t facing[4] = {0, 0, 1, 0};
    alignas(16) int out[32];
    EXPECT_EQ(sv_create_cap_triangles_checked(paper(), out, 24, facing, indices, 12, 4), 18);
    EXPECT_EQ(sv_create_cap_triangles_checked(paper(), out, 24, facing, indices, 13, 4),
              SV_E_COUNT);
    EXPECT_EQ(sv_create_cap_triangles_checked(paper(), out, 24, facing, indices + 1, 9, 4),
              SV_E_ALIGNMENT);
    EXPECT_EQ(sv_create_cap_triangles_checked(ref(), out, 24, facing, indices + 1, 9, 4), 12);
    EXPECT_EQ(sv_create_cap_triangles_checked(paper(), out, 23, facing, indices, 12, 4),
              SV_E_CAPACITY);
    EXPECT_EQ(sv_create_cap_triangles_checked(paper(), out, 24, facing, indices, 12, 3),
              SV_E_INDEX_RANGE);
    EXPECT_EQ(sv_create_cap_triangles_checked(paper(), out, 24, facing, indices, 12, (1 << 30) + 1),
              SV_E_INDEX_RANGE)
        << "doubled vertex numbers must fit in an int";
}

TEST(Contracts, ShadowVolumeCapacityAndOverflow) {
    EXPECT_EQ(sv_shadow_volume_capacity(0, 0), 0u);
    EXPECT_EQ(sv_shadow_volume_capacity(3 * 1344, 2016), 6u * 2016 + 6u * 1344);
    EXPECT_EQ(sv_shadow_volume_capacity(-3, 5), 0u);
    // 6 * INT_MAX + 2 * (INT_MAX - 1) fits a 64-bit size_t; a 32-bit one
    // (32-bit x86) gets SIZE_MAX, the documented overflow answer.
    const unsigned long long big = 6ull * INT_MAX + 2ull * (INT_MAX - 1);
    EXPECT_EQ(sv_shadow_volume_capacity(INT_MAX - 1, INT_MAX),
              big > (unsigned long long)SIZE_MAX ? SIZE_MAX : (size_t)big);
    EXPECT_EQ(sv_shadow_volume_capacity(0, (int)(SIZE_MAX / 6 < INT_MAX ? SIZE_MAX / 6 : 1000)),
              SIZE_MAX / 6 < INT_MAX ? SIZE_MAX / 6 * 6 : 6000u)
        << "the largest count whose capacity still fits size_t";
    int out[1];
    int indices[3] = {0, 1, 2};
    uint8_t facing[2] = {0, 1};
    SilEdge edge = {0, 1, 0, 2};
    // 6 * 400M edges does not fit the int the routine returns
    EXPECT_EQ(sv_create_shadow_volume_checked(ref(), out, SIZE_MAX, indices, 3, 3, &edge, 400000000,
                                              facing, nullptr),
              SV_E_OVERFLOW);
    EXPECT_EQ(sv_create_shadow_volume_checked(ref(), out, 11, indices, 3, 3, &edge, 1, facing,
                                              nullptr),
              SV_E_CAPACITY);
    alignas(16) int out12[12];
    EXPECT_EQ(sv_create_shadow_volume_checked(ref(), out12, 12, indices, 3, 3, &edge, 1, facing,
                                              nullptr),
              12);
    SilEdge beyond = {0, 1, 0, 6}; // vertex 3 of a 3-vertex mesh
    EXPECT_EQ(sv_create_shadow_volume_checked(ref(), out12, 12, indices, 3, 3, &beyond, 1, facing,
                                              nullptr),
              SV_E_INDEX_RANGE);
}

// Issue 17: numTriangles = INT_MAX made sv_create_sil_triangles_checked
// compute numTriangles + 1 (signed overflow; UBSan aborts, and in Release
// the wrapped count checked no facing byte at all). The bytes are now
// checked up to numTriangles and facing[numTriangles] apart: the bad byte
// at 1 is found long before the end of the (nominal) array.
SV_TIERED_TEST(Contracts, SilTrianglesAtIntMaxTrianglesDoesNotOverflow) {
    const svtest::IsaLimitLifted lifted;
    uint8_t facing[4] = {0, 2, 1, 1};
    alignas(16) int out[6];
    for (const sv_variant *v : runnable_variants()) {
        EXPECT_EQ(sv_create_sil_triangles_checked(v, out, 6, facing, INT_MAX, nullptr, 0),
                  SV_E_FACING_NOT_BOOL)
            << v->name;
    }
}

// Issue 17: facing[numTriangles] must be 1 (dangling edges point at it).
// One triangle with facing {0, 0} and its three dangling edges used to
// return 6 indices with status ok: an open volume.
SV_TIERED_TEST(Contracts, FacingSentinelMustBeOne) {
    const svtest::IsaLimitLifted lifted;
    alignas(16) int indices[4] = {0, 1, 2, 0};
    const SilEdge edges[3] = {{0, 1, 0, 2}, {0, 1, 2, 4}, {0, 1, 4, 0}};
    for (const sv_variant *v : runnable_variants()) {
        alignas(16) uint8_t facing[16] = {0, 0};
        alignas(16) int out[64];
        EXPECT_EQ(sv_create_sil_triangles_checked(v, out, 64, facing, 1, edges, 3),
                  SV_E_FACING_SENTINEL)
            << v->name;
        EXPECT_EQ(sv_create_shadow_volume_checked(v, out, 64, indices, 3, 3, edges, 3, facing,
                                                  nullptr),
                  SV_E_FACING_SENTINEL)
            << v->name;
        facing[1] = 1;
        EXPECT_EQ(sv_create_sil_triangles_checked(v, out, 64, facing, 1, edges, 3), 18) << v->name;
        EXPECT_EQ(sv_create_shadow_volume_checked(v, out, 64, indices, 3, 3, edges, 3, facing,
                                                  nullptr),
                  24)
            << v->name;
    }
}

// Issue 17 (erratum D-5): sse2_paper's CountFacingCull honours cull bits
// 0..6 only. Four triangles whose vertices all have cull byte 0x80: c_ref
// culls all four (count 4), sse2_paper none (0). Its checked entry points
// now refuse such cull bytes; the other variants take all 8 bits.
SV_TIERED_TEST(Contracts, Sse2PaperRefusesCullBitSeven) {
    const svtest::IsaLimitLifted lifted;
    alignas(16) int indices[12] = {0, 1, 2, 0, 2, 3, 0, 3, 1, 1, 3, 2};
    uint8_t cull[4] = {0x80, 0x80, 0x80, 0x80};
    for (const sv_variant *v : runnable_variants()) {
        alignas(16) uint8_t facing[16] = {0, 0, 0, 0, 1};
#if defined(SV_HAVE_ASM_SSE2)
        const bool paper_cull = v->count_facing_cull == sv_count_facing_cull_sse2_paper;
#else
        const bool paper_cull = false; // no sse2_paper built on this platform
#endif
        EXPECT_EQ(sv_count_facing_cull_checked(v, facing, 4, indices, cull, 4),
                  paper_cull ? SV_E_CULL_BITS : 4)
            << v->name;
        uint8_t facing2[16] = {0, 0, 0, 0, 1};
        alignas(16) int out[64];
        const SilEdge edge = {0, 1, 0, 2};
        const int r = sv_create_shadow_volume_checked(v, out, 64, indices, 12, 4, &edge, 1, facing2,
                                                      cull);
        EXPECT_EQ(r, paper_cull ? SV_E_CULL_BITS : 0) << v->name;
        uint8_t low[4] = {0x40, 0x40, 0x40, 0x41}; // bits 0..6: every variant takes them
        uint8_t facing3[16] = {0, 0, 0, 0, 1};
        EXPECT_EQ(sv_count_facing_cull_checked(v, facing3, 4, indices, low, 4), 4) << v->name;
    }
}
