// The self-test of `shadowvol check` can fail: the check library
// (src/check/routine_checks.h) is handed tables with deliberately broken
// variants beside good ones, and must report each broken one as FAILED for
// the right routine and variant, with the case and what broke, while the
// good rows (and the broken variant's other routines) stay ok. Without
// this, "52 ok" would mean nothing.
//
// Copyright (C) 2026 the shadowvol authors. LGPL-2.1-or-later.
#include <gtest/gtest.h>

#include <algorithm>
#include <cstdio>
#include <limits>
#include <string>
#include <vector>

#include "routine_checks.h"
#if defined(SV_HAVE_ABI_CHECKER)
#include "abi_check.h"
#endif

using svcheck::Result;
using svcheck::Routine;
using svcheck::Variant;

extern "C" {
#if defined(SV_HAVE_ABI_CHECKER)
// tests/checkasm/routine_checks_broken.asm: right counts, broken ABI.
int sv_broken_count_facing_clobber(const uint8_t *facing, int numTriangles);
int sv_broken_count_facing_dirty_ymm(const uint8_t *facing, int numTriangles);
#endif
}

namespace {

constexpr uint64_t kSeed = 20260416;
constexpr int kMiscountedSize = 37;

// CountFacing one too high for one count only: a tail a check that skips
// sizes would miss.
int miscount_one_size(const uint8_t *facing, int n) {
    return sv_count_facing_c_ref(facing, n) + (n == kMiscountedSize ? 1 : 0);
}

// CreateCapTriangles right, then one int written past the bound
// (2 * numIndices ints) that its contract gives it.
int cap_writes_past_bound(int *out, const uint8_t *facing, const int *indices, int numIndices) {
    const int r = sv_create_cap_triangles_c_ref(out, facing, indices, numIndices);
    if (numIndices > 0) out[2 * numIndices] = 0;
    return r;
}

// CalculateFacing right, then the byte after its numTriangles + 1 set.
void facing_writes_past_bound(const Plane *planes, int n, const Vec4 *light, uint8_t *facing) {
    sv_calculate_facing_c_ref(planes, n, light, facing);
    if (n >= 0) facing[n + 1] = 0;
}

// c_ref's kernels under another name, with one of them replaced.
Variant c_ref_with(const char *name, sv_count_facing_fn count, sv_create_cap_triangles_fn cap,
                   sv_calculate_facing_fn facing) {
    sv_variant k = *sv_variant_by_name("c_ref");
    k.name = name;
    if (count) k.count_facing = count;
    if (cap) k.create_cap_triangles = cap;
    Variant v = svcheck::make_variant(name, sv_facing_variant_by_name("c_ref"), &k);
    if (facing) {
        for (svcheck::Kernels &c : v.by_class) c.calculate_facing = facing;
    }
    return v;
}

const Result &row(const std::vector<Result> &rs, const std::string &variant) {
    for (const Result &r : rs)
        if (r.variant == variant) return r;
    static const Result none{};
    ADD_FAILURE() << "no row for " << variant;
    return none;
}

// The library's variants beside the broken ones: the good rows of every
// table below, which must stay ok (or skipped, where this CPU lacks them).
std::vector<Variant> with_good(const std::vector<Variant> &broken) {
    std::vector<Variant> t = svcheck::library_variants();
    for (const Variant &b : broken) t.push_back(b);
    return t;
}

// Runs ROUTINE over TABLE: VARIANT must come back FAILED with WHAT in its
// detail, and every other row ok (or skipped, where this CPU lacks it).
Result expect_reported(Routine routine, const std::vector<Variant> &table,
                       const std::string &variant, const std::string &what) {
    const std::vector<Result> rs = svcheck::check_routine(routine, table, kSeed);
    const Result bad = row(rs, variant);
    EXPECT_EQ(bad.status, Result::failed) << variant;
    EXPECT_EQ(bad.routine, routine);
    EXPECT_NE(bad.detail.find(what), std::string::npos) << bad.detail;
    int ok = 0;
    for (const Result &r : rs) {
        if (r.variant == variant) continue;
        EXPECT_NE(r.status, Result::failed) << r.variant << ": " << r.detail;
        ok += r.status == Result::ok;
    }
    // c_ref and planned run everywhere (the per-light call: planned only).
    EXPECT_GE(ok, routine == Routine::shadow_volume_for_light ? 1 : 2);
    return bad;
}

} // namespace

TEST(RoutineChecks, LibraryVariantsPassOrSkipWithAReason) {
    const std::vector<Variant> table = svcheck::library_variants();
    ASSERT_EQ(table.front().name, "c_ref");
    ASSERT_EQ(table.back().name, "planned");
    for (Routine r : svcheck::all_routines()) {
        const std::vector<Result> rs = svcheck::check_routine(r, table, kSeed);
        // (the per-light call has a plan: "planned" only; the general
        // rule's SIMD kernels are x86-64 only, so a 32-bit build has its
        // C alone: docs/PLATFORMS.md)
        const bool general = r == Routine::create_general_sil_triangles ||
                             r == Routine::create_general_cap_triangles;
        const bool one = r == Routine::shadow_volume_for_light || (general && sizeof(void *) < 8);
        EXPECT_GE(rs.size(), one ? 1u : 2u) << svcheck::routine_name(r);
        for (const Result &x : rs) {
            // The lines `shadowvol check` would print: the report of the
            // cross builds, which have no `shadowvol` program.
            std::printf("%-24s %-13s %s %s\n", svcheck::routine_name(r), x.variant.c_str(),
                        x.status == Result::ok        ? "ok"
                        : x.status == Result::skipped ? "skipped"
                                                      : "FAILED",
                        x.detail.c_str());
            EXPECT_NE(x.status, Result::failed)
                << svcheck::routine_name(r) << " " << x.variant << ": " << x.detail;
            if (x.status == Result::ok) {
                EXPECT_GT(x.cases, 300) << x.variant;
            } else if (x.status == Result::skipped) {
                EXPECT_FALSE(x.detail.empty()) << x.variant;
            }
        }
    }
}

TEST(RoutineChecks, ReportsAMiscountAtOneSize) {
    const auto table = with_good({c_ref_with("miscount", miscount_one_size, nullptr, nullptr)});
    const Result bad = expect_reported(Routine::count_facing, table, "miscount",
                                       "n=" + std::to_string(kMiscountedSize) + ", ");
    // What the line of `shadowvol check` would say (docs/TESTING.md quotes it).
    std::printf("count_facing miscount FAILED (%d of %d cases) first: %s\n", bad.failures,
                bad.cases, bad.detail.c_str());
    // Four facing modes at that size, each one too high.
    EXPECT_EQ(bad.failures, 4);
    EXPECT_NE(bad.detail.find("returned"), std::string::npos) << bad.detail;
    // Its other routines are c_ref's: still ok.
    const auto other = svcheck::check_routine(Routine::create_cap_triangles, table, kSeed);
    EXPECT_EQ(row(other, "miscount").status, Result::ok) << row(other, "miscount").detail;
}

TEST(RoutineChecks, ReportsAWritePastTheDocumentedBound) {
    const auto table = with_good(
        {c_ref_with("cap_past", nullptr, cap_writes_past_bound, nullptr),
         c_ref_with("facing_past", nullptr, nullptr, facing_writes_past_bound)});
    // (Each broken variant's other routine is c_ref's: ok in the other run.)
    expect_reported(Routine::create_cap_triangles, table, "cap_past",
                    "outside 6 * numTriangles ints at byte 0 past the bound");
    expect_reported(Routine::calculate_facing, table, "facing_past",
                    "below or past the facing bytes at byte 0 past the bound");
}

#if defined(SV_HAVE_ABI_CHECKER)
TEST(RoutineChecks, ReportsAClobberedCalleeSavedRegister) {
    const auto table = with_good(
        {c_ref_with("clobber", sv_broken_count_facing_clobber, nullptr, nullptr)});
    const Result bad = expect_reported(Routine::count_facing, table, "clobber",
                                       std::string("ABI broken: ") + sv_abi_callee_saved_name(0));
    // Every call breaks it, and only the ABI: the count is c_ref's.
    EXPECT_EQ(bad.failures, bad.cases);
    EXPECT_EQ(bad.detail.find("returned"), std::string::npos) << bad.detail;
}

TEST(RoutineChecks, ReportsDirtyUpperState) {
    if (!(sv_abi_detect() & SV_ABI_HAS_XINUSE) || !(sv_cpu_isa_detected() & SV_ISA_AVX2)) {
        GTEST_SKIP() << "no AVX or no XGETBV ecx=1 here: the dirty-upper check does not run";
    }
    const auto table = with_good(
        {c_ref_with("dirty", sv_broken_count_facing_dirty_ymm, nullptr, nullptr)});
    const Result bad = expect_reported(Routine::count_facing, table, "dirty", "missing vzeroupper");
    EXPECT_EQ(bad.failures, bad.cases);
}
#endif

// CreateSilTriangles that drops the last quad when there are 3 mod 7
// edges: wrong only inside a plan, for the per-light call.
int sil_drops_a_quad(int *out, const uint8_t *facing, const SilEdge *edges, int n) {
    const int r = sv_create_sil_triangles_c_ref(out, facing, edges, n);
    return r >= 6 && n % 7 == 3 ? r - 6 : r;
}

TEST(RoutineChecks, ReportsABrokenPlanInThePerLightCall) {
    // The built-in plan of each class with that kernel in it.
    static sv_plan plans[SV_NUM_SIZE_CLASSES];
    Variant v = svcheck::make_variant("broken_plan", nullptr, nullptr);
    for (int c = 0; c < SV_NUM_SIZE_CLASSES; c++) {
        plans[c] = *sv_plan_for(sv_size_class_triangles(c), SV_PLAN_ESTIMATE);
        plans[c].kernels.create_sil_triangles = sil_drops_a_quad;
        v.by_class[c].plan = &plans[c];
    }
    const Result bad = expect_reported(Routine::shadow_volume_for_light, with_good({v}),
                                       "broken_plan", "returned");
    EXPECT_GT(bad.failures, 0);
    EXPECT_LT(bad.failures, bad.cases); // only the 3-mod-7 edge counts
}

// A one-pass kernel that derives each segment's planes before it skins
// the segment's vertices: the planes read positions not yet written.
void planes_before_skinning(const sv_skin_planes_args *a) {
    size_t v0 = 0;
    int t0 = 0;
    const size_t k = (size_t)a->influences;
    for (int s = 0; s < std::max(a->segments, 1); s++) {
        const size_t v1 = a->segments ? a->vertex_end[s] : a->num_vertices;
        const int t1 = a->segments ? a->triangle_end[s] : a->num_triangles;
        sv_derive_planes_c_ref(a->out, a->indices + 3 * t0, t1 - t0, a->planes + t0);
        sv_skin_c_ref(a->joint_matrices, a->rest + 3 * v0, a->joints + k * v0, a->weights + k * v0,
                      a->influences, v1 - v0, a->out + 3 * v0);
        v0 = v1, t0 = t1;
    }
}

TEST(RoutineChecks, ReportsAOnePassKernelThatDerivesBeforeSkinning) {
    static const sv_skin_planes_variant broken = {"early", SV_ISA_NONE, "c_ref", "c_ref",
                                                  planes_before_skinning};
    Variant v = svcheck::make_variant("early", nullptr, nullptr);
    for (auto &k : v.by_class) k.skin_planes = &broken;
    const Result bad = expect_reported(Routine::skin_planes, with_good({v}), "early",
                                       "differs from c_ref's");
    EXPECT_GT(bad.failures, 0);
}

// The planes by clusters with a 16-entry lookup where the clusters need
// 32 (vpermps where vpermt2ps belongs): a corner at place 16 or beyond
// takes the vertex 16 places before it. Right on clusters of at most 16
// vertices: only the larger cases meet it.
void clustered_with_half_the_table(const float *positions, const sv_plane_clusters *c,
                                   Plane *planes) {
    for (int k = 0; k < c->num_clusters; k++) {
        const uint32_t *list = c->vertex_offsets + c->vertex_begin[k];
        for (int g = c->group_begin[k]; g < c->group_begin[k + 1]; g++) {
            const uint8_t *corners = c->corners + 48 * (size_t)g;
            for (int i = 0; i < 16; i++) {
                const float *p[3];
                for (int j = 0; j < 3; j++) {
                    p[j] = positions + list[corners[16 * j + i] & 15] / 4;
                }
                const int tri[3] = {0, 1, 2};
                const float corner_xyz[9] = {p[0][0], p[0][1], p[0][2], p[1][0], p[1][1],
                                             p[1][2], p[2][0], p[2][1], p[2][2]};
                Plane out;
                sv_derive_planes_c_ref(corner_xyz, tri, 1, &out);
                planes[c->plane_offsets[16 * (size_t)g + (size_t)i] / 16] = out;
            }
        }
    }
}

TEST(RoutineChecks, ReportsAClusteredKernelWithHalfTheTable) {
    static const sv_planes_clustered_variant broken = {"half_table", SV_ISA_NONE,
                                                       clustered_with_half_the_table};
    Variant v = svcheck::make_variant("half_table", nullptr, nullptr);
    for (auto &k : v.by_class) k.clustered = &broken;
    const Result bad = expect_reported(Routine::derive_planes_clustered, with_good({v}),
                                       "half_table", "differs from c_ref's");
    EXPECT_GT(bad.failures, 0);
}

// Seed 002's program as the seed writes it: rsq(0) = +inf for a light on
// the vertex, so that vertex comes out NaN (the contract keeps it in place).
// Right everywhere else: only the cases with the light on a vertex meet it.
void extrude_nan_on_the_light(const float *stream, int n, const sv_extrude_light *light,
                              Vec4 *out) {
    sv_extrude_c_ref(stream, n, light, out);
    const Vec4 &l = light->position;
    for (int i = 0; i < n; i++) {
        const float *p = stream + (size_t)SV_EXTRUDE_STREAM_FLOATS * (size_t)i;
        if (l.w == 1.0f && p[0] == l.x && p[1] == l.y && p[2] == l.z) {
            const float nan = std::numeric_limits<float>::quiet_NaN();
            out[i] = {nan, nan, nan, out[i].w};
        }
    }
}

TEST(RoutineChecks, ReportsAnExtrusionThatGivesNaNForALightOnAVertex) {
    static const sv_extrude_variant broken = {"seed_rsq", SV_ISA_NONE, extrude_nan_on_the_light};
    Variant v = svcheck::make_variant("seed_rsq", nullptr, nullptr);
    for (auto &k : v.by_class) k.extrude = &broken;
    const Result bad = expect_reported(Routine::extrude, with_good({v}), "seed_rsq",
                                       "differs from c_ref's");
    EXPECT_NE(bad.detail.find("the light on"), std::string::npos) << bad.detail;
    EXPECT_GT(bad.failures, 0);
    EXPECT_LT(bad.failures, bad.cases); // the other shapes are c_ref's
}

TEST(RoutineChecks, SkipsAVariantAboveTheIsaLimitWithTheReason) {
    const char *saved = sv_isa_limit_name();
    ASSERT_EQ(sv_set_isa_limit("c"), 0);
    Variant needs_sse2 = c_ref_with("needs_sse2", nullptr, nullptr, nullptr);
    needs_sse2.isa = SV_ISA_SSE2;
    const auto rs = svcheck::check_routine(Routine::count_facing, {needs_sse2}, kSeed);
    sv_set_isa_limit(saved);
    ASSERT_EQ(rs.size(), 1u);
    EXPECT_EQ(rs[0].status, Result::skipped);
    EXPECT_EQ(rs[0].cases, 0);
    EXPECT_EQ(rs[0].detail, "SV_ISA=c holds dispatch at c");
}

TEST(RoutineChecks, TheSameSeedGivesTheSameFailure) {
    // A failure that depends on the data: wrong where the count is 3
    // modulo 7 and neither 0 nor n (so only the half and random facing
    // modes, whose bytes the seed draws, meet it).
    static const auto odd_count = [](const uint8_t *f, int n) {
        const int c = sv_count_facing_c_ref(f, n);
        return c + (c % 7 == 3 && c != n ? 1 : 0);
    };
    const auto table = with_good({c_ref_with("odd", +odd_count, nullptr, nullptr)});
    const auto a = svcheck::check_routine(Routine::count_facing, table, kSeed);
    const auto b = svcheck::check_routine(Routine::count_facing, table, kSeed);
    const auto c = svcheck::check_routine(Routine::count_facing, table, kSeed + 1);
    ASSERT_EQ(row(a, "odd").status, Result::failed);
    EXPECT_EQ(row(a, "odd").detail, row(b, "odd").detail);
    EXPECT_EQ(row(a, "odd").failures, row(b, "odd").failures);
    EXPECT_NE(row(a, "odd").detail, row(c, "odd").detail);
}
