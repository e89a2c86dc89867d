// Skinning and planes in one pass (include/shadowvol_anim.h,
// src/anim/skin_planes*): the schedule's promises (every triangle of a
// segment has its corners skinned by then; the ends reach the whole
// surface; a bad index is refused), every kernel BIT-IDENTICAL to "skin
// with the C reference, then sv_derive_planes_c_ref" at every vertex and
// triangle count to 40 and every segment length, nothing written around
// the outputs, every call through the ABI checker; a schedule that skins
// too little is caught by the same comparison (so it could fail); and the
// skinned characters of the demo scene (the bundled character, skinned), ../shared/models and its open/ folder
// over a few frames of each of their animations. The choice by measurement:
// the planner keeps a choice per class and routine, a measurement records
// runnable kernels, the wisdom file carries them, unknown names are not taken.
//
// Copyright (C) 2026 the shadowvol authors. LGPL-2.1-or-later.
#include "test_support.h"

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <stdexcept>
#include <string>
#include <vector>

#include "shadowvol_anim.h"
#include "shadowvol_planes.h"
#include "model_surfaces.h"
#include "shadowvol_skin.h"

namespace {

using svtest::GuardedBuffer;
using svtest::Rng;

std::vector<const sv::SkinPlanesKernel *> runnable() {
    int n = 0;
    const sv::SkinPlanesKernel *k = sv::skin_planes_kernels(&n);
    std::vector<const sv::SkinPlanesKernel *> out;
    for (int i = 0; i < n; i++) {
        if (svtest::in_this_run(k[i].isa, k[i].name)) out.push_back(&k[i]);
    }
    return out;
}

// A random skinned surface: JOINTS joint matrices, V vertices, T triangles
// whose corners are drawn near the triangle's place in the list (as in an
// exported mesh: the schedule then cuts real segments) or anywhere.
struct RandomSkin {
    int influences = 4;
    std::vector<float> matrices, rest, weights;
    std::vector<uint16_t> joints;
    std::vector<int> indices;
    size_t vertices = 0;
    int triangles = 0;
};

RandomSkin random_skin(Rng &rng, size_t v, int t, int influences, bool local) {
    RandomSkin s;
    const int kJoints = 19;
    s.influences = influences;
    s.vertices = v;
    s.triangles = v == 0 ? 0 : t;
    s.matrices.resize(16 * kJoints);
    for (float &m : s.matrices) m = float(rng.unit() * 4 - 2);
    s.rest.resize(3 * v);
    for (float &p : s.rest) p = float((rng.unit() - 0.5) * 10);
    s.joints.resize(v * (size_t)influences);
    s.weights.resize(v * (size_t)influences);
    for (size_t i = 0; i < s.joints.size(); i++) {
        s.joints[i] = uint16_t(rng.below(kJoints));
        s.weights[i] = rng.chance(0.2) ? 0.0f : float(rng.unit());
    }
    for (int k = 0; k < s.triangles; k++) {
        for (int c = 0; c < 3; c++) {
            size_t i = rng.below(v);
            if (local) {
                const size_t centre = (size_t)k * v / (size_t)s.triangles;
                i = std::min(v - 1, centre + rng.below(4));
            }
            // some repeated corners: zero-area triangles, the zero plane
            s.indices.push_back(rng.chance(0.05) && c > 0 ? s.indices.back() : (int)i);
        }
    }
    return s;
}

sv_skin_planes_args args_for(const RandomSkin &s, const sv::SkinPlanesSchedule *sch, float *out,
                             Plane *planes) {
    sv_skin_planes_args a{};
    a.joint_matrices = s.matrices.data();
    a.rest = s.rest.data();
    a.joints = s.joints.data();
    a.weights = s.weights.data();
    a.influences = s.influences;
    a.num_vertices = s.vertices;
    a.indices = s.indices.data();
    a.num_triangles = s.triangles;
    a.segments = sch ? (int)sch->triangle_end.size() : 0;
    a.vertex_end = sch ? sch->vertex_end.data() : nullptr;
    a.triangle_end = sch ? sch->triangle_end.data() : nullptr;
    a.out = out;
    a.planes = planes;
    return a;
}

// The definition: skin with the C reference, then the reference planes.
void reference(const RandomSkin &s, std::vector<float> &pos, std::vector<Plane> &planes) {
    pos.assign(3 * s.vertices, 0.0f);
    planes.assign((size_t)s.triangles, Plane{});
    int n = 0;
    sv::skinning_kernels(&n)[0].fn(s.matrices.data(), s.rest.data(), s.joints.data(),
                                   s.weights.data(), s.influences, s.vertices, pos.data());
    sv_derive_planes_c_ref(pos.data(), s.indices.data(), s.triangles, planes.data());
}

// Runs K with schedule SCH (nullptr: one segment) into guarded outputs and
// compares with the reference; returns the mismatching floats and planes.
size_t mismatches(Rng &rng, const sv::SkinPlanesKernel &k, const RandomSkin &s,
                  const sv::SkinPlanesSchedule *sch, bool *guards_ok) {
    std::vector<float> want_pos;
    std::vector<Plane> want_planes;
    reference(s, want_pos, want_planes);
    GuardedBuffer pos(3 * s.vertices * sizeof(float), 4 * rng.below(16));
    GuardedBuffer planes((size_t)s.triangles * sizeof(Plane), 4 * rng.below(16));
    pos.fill(0xCD);
    planes.fill(0xCD);
    const sv_skin_planes_args a = args_for(s, sch, pos.as<float>(), planes.as<Plane>());
    svtest::checked_call(rng, k.fn, &a);
    *guards_ok = pos.guards_intact() && planes.guards_intact();
    size_t bad = 0;
    if (s.vertices) bad += std::memcmp(pos.data(), want_pos.data(), pos.size()) != 0;
    for (int t = 0; t < s.triangles; t++) {
        // NOLINTNEXTLINE(bugprone-suspicious-memory-comparison): Plane is four floats, no padding
        bad += std::memcmp(planes.data() + (size_t)t * sizeof(Plane), &want_planes[(size_t)t],
                           sizeof(Plane)) != 0;
    }
    return bad;
}

TEST(SkinPlanes, TableAndNames) {
    int n = 0;
    const sv::SkinPlanesKernel *k = sv::skin_planes_kernels(&n);
    ASSERT_GE(n, 4);
    EXPECT_STREQ(k[0].name, "c_ref");
    for (int i = 0; i < n; i++) {
        EXPECT_EQ(sv::skin_planes_kernel_by_name(k[i].name), &k[i]);
        // Each runs kernels that exist and need no more than it declares.
        const sv::SkinningKernel *sk = sv::skinning_kernel_by_name(k[i].skinning);
        const sv_planes_variant *pv = sv_planes_variant_by_name(k[i].planes);
        ASSERT_NE(sk, nullptr) << k[i].name;
        ASSERT_NE(pv, nullptr) << k[i].name;
        EXPECT_EQ(sk->isa & k[i].isa, sk->isa) << k[i].name;
        EXPECT_EQ(pv->isa & k[i].isa, pv->isa) << k[i].name;
    }
    EXPECT_EQ(sv::skin_planes_kernel_by_name("nope"), nullptr);
}

TEST(SkinPlanes, ScheduleCoversTheSurfaceAndSkinsEnough) {
    Rng rng(svtest::seed() ^ 0x5c4ed);
    SCOPED_TRACE(svtest::seed_trace());
    for (int seg : {0, 1, 2, 7, 64, 256}) {
        for (size_t v : {1, 2, 5, 40, 300}) {
            for (bool local : {true, false}) {
                const RandomSkin s = random_skin(rng, v, (int)rng.below(120), 4, local);
                const sv::SkinPlanesSchedule sch = sv::skin_planes_schedule(s.indices.data(),
                                                                            s.triangles, v, seg);
                ASSERT_FALSE(sch.triangle_end.empty());
                ASSERT_EQ(sch.vertex_end.size(), sch.triangle_end.size());
                EXPECT_EQ(sch.vertex_end.back(), v);
                EXPECT_EQ(sch.triangle_end.back(), s.triangles);
                int t0 = 0;
                size_t v0 = 0;
                for (size_t i = 0; i < sch.triangle_end.size(); i++) {
                    ASSERT_GE(sch.triangle_end[i], t0);
                    ASSERT_GE(sch.vertex_end[i], v0);
                    if (seg > 0) {
                        EXPECT_LE(sch.triangle_end[i] - t0, seg);
                    }
                    for (int t = t0; t < sch.triangle_end[i]; t++) {
                        for (int c = 0; c < 3; c++) {
                            ASSERT_LT((size_t)s.indices[(size_t)(3 * t + c)], sch.vertex_end[i])
                                << "triangle " << t << " in segment " << i;
                        }
                    }
                    t0 = sch.triangle_end[i];
                    v0 = sch.vertex_end[i];
                }
            }
        }
    }
    // No triangles: one segment that skins every vertex.
    const sv::SkinPlanesSchedule none = sv::skin_planes_schedule(nullptr, 0, 9);
    ASSERT_EQ(none.vertex_end.size(), 1u);
    EXPECT_EQ(none.vertex_end[0], 9u);
    EXPECT_EQ(none.triangle_end[0], 0);
}

TEST(SkinPlanes, ScheduleRefusesBadIndices) {
    const int bad_high[] = {0, 1, 3};
    EXPECT_THROW(sv::skin_planes_schedule(bad_high, 1, 3), sv::PrepareError);
    const int bad_low[] = {0, -1, 2};
    EXPECT_THROW(sv::skin_planes_schedule(bad_low, 1, 3), sv::PrepareError);
    EXPECT_THROW(sv::skin_planes_schedule(nullptr, 2, 3), sv::PrepareError);
    EXPECT_THROW(sv::skin_planes_schedule(bad_high, -1, 3), sv::PrepareError);
    try {
        sv::skin_planes_schedule(bad_high, 1, 3);
    } catch (const sv::PrepareError &e) {
        EXPECT_NE(std::string(e.what()).find("index 2 is 3"), std::string::npos) << e.what();
    }
}

SV_TIERED_TEST(SkinPlanes, EveryKernelEveryTailEverySegmentLength) {
    Rng rng(svtest::seed() ^ 0x5ca1e);
    SCOPED_TRACE(svtest::seed_trace());
    const std::vector<const sv::SkinPlanesKernel *> kernels = runnable();
    for (int influences : {1, 4, 8}) {
        for (size_t v = 0; v <= 40; v++) {
            const int t = (int)rng.below(3 * v + 2);
            const RandomSkin s = random_skin(rng, v, t, influences, rng.chance(0.5));
            for (int seg : {0, 1, 3, 8, 17, 256}) {
                const sv::SkinPlanesSchedule sch = sv::skin_planes_schedule(s.indices.data(),
                                                                            s.triangles, v, seg);
                for (const sv::SkinPlanesKernel *k : kernels) {
                    bool guards = false;
                    EXPECT_EQ(mismatches(rng, *k, s, &sch, &guards), 0u)
                        << k->name << ": " << v << " vertices, " << s.triangles
                        << " triangles, segments of " << seg << ", influences " << influences;
                    EXPECT_TRUE(guards) << k->name << " wrote outside its outputs";
                }
            }
            for (const sv::SkinPlanesKernel *k : kernels) { // no schedule: one segment
                bool guards = false;
                EXPECT_EQ(mismatches(rng, *k, s, nullptr, &guards), 0u) << k->name;
                EXPECT_TRUE(guards) << k->name;
            }
        }
    }
}

// A schedule that lets a segment's planes run before its corners are
// skinned must show in the comparison (the planes then read the 0xCD
// filler): the test above could fail.
SV_TIERED_TEST(SkinPlanes, AScheduleThatSkinsTooLittleIsCaught) {
    Rng rng(svtest::seed() ^ 0xbad5);
    const RandomSkin s = random_skin(rng, 64, 120, 4, true);
    sv::SkinPlanesSchedule sch = sv::skin_planes_schedule(s.indices.data(), s.triangles, 64, 16);
    ASSERT_GE(sch.vertex_end.size(), 3u);
    sch.vertex_end[0] = 0; // the first segment's triangles now see unskinned corners
    for (const sv::SkinPlanesKernel *k : runnable()) {
        if (std::string(k->name) == "c_ref") continue; // the definition has no segments
        bool guards = false;
        EXPECT_GT(mismatches(rng, *k, s, &sch, &guards), 0u) << k->name;
    }
}

// The skinned surfaces of every character, over their animations: the
// scene's own call (pose_surface_with_planes) against pose_surface with the
// C kernel and the reference planes.
class SkinPlanesModels : public ::testing::TestWithParam<std::string> {};

INSTANTIATE_TEST_SUITE_P(ModelSets, SkinPlanesModels, ::testing::ValuesIn(svtest::model_sets()),
                         [](const ::testing::TestParamInfo<std::string> &i) { return i.param; });

SV_TIERED_TEST_P(SkinPlanesModels, SkinnedCharactersOverTheirAnimations) {
    const std::vector<const sv::SkinPlanesKernel *> kernels = runnable();
    int skinned = 0;
    // The bundled set: the demo scene (its character is the bundled one,
    // skinned); the shared set: every real character and the open one.
    const std::vector<std::string> paths = GetParam() == "bundled"
                                               ? std::vector<std::string>{SV_DEMO_SCENE}
                                               : svtest::seed_model_paths(GetParam());
    for (const std::string &path : paths) {
        SCOPED_TRACE(path);
        const sv::AnimatedAsset a = sv::load_animated_gltf(path);
        for (const sv::AnimatedSurface &as : a.surfaces) {
            if (as.skin < 0) continue;
            skinned++;
            const sv::PreparedSurface &p = as.prepared;
            const sv::SkinPlanesSchedule sch =
                sv::skin_planes_schedule(p.indices.data(), p.num_triangles(),
                                         as.rest_positions.size() / 3);
            const int anims = std::max<int>(1, (int)a.animations.size());
            for (int an = 0; an < anims; an++) {
                const int animation = a.animations.empty() ? -1 : an;
                for (int f = 0; f < 3; f++) {
                    double time = 0;
                    if (animation >= 0) {
                        const sv::Animation &A = a.animations[(size_t)animation];
                        time = A.start + (A.end - A.start) * f / 3.0;
                    }
                    const sv::Pose pose = sv::pose_at(a, animation, time);
                    std::vector<float> want(p.positions.size());
                    std::vector<Plane> want_planes(p.planes.size());
                    sv::pose_surface(a, as, pose, sv::Mat4d{}, want.data(),
                                     sv::skinning_kernel_by_name("c_ref"));
                    sv_derive_planes_c_ref(want.data(), p.indices.data(), p.num_triangles(),
                                           want_planes.data());
                    for (const sv::SkinPlanesKernel *k : kernels) {
                        std::vector<float> got(p.positions.size(), -1.0f);
                        std::vector<Plane> got_planes(p.planes.size());
                        sv::pose_surface_with_planes(a, as, pose, sv::Mat4d{}, *k, sch, got.data(),
                                                     got_planes.data());
                        ASSERT_EQ(std::memcmp(got.data(), want.data(), 4 * got.size()), 0)
                            << as.name << ", " << k->name << ", animation " << an << ", frame "
                            << f;
                        ASSERT_EQ(std::memcmp(got_planes.data(), want_planes.data(),
                                              sizeof(Plane) * got_planes.size()),
                                  0)
                            << as.name << ", " << k->name << ", animation " << an << ", frame "
                            << f;
                    }
                }
            }
        }
    }
    std::printf("[ skin+planes ] %s: %d skinned surfaces\n", GetParam().c_str(), skinned);
    EXPECT_GT(skinned, 0) << "no skinned surface in " << GetParam();
}

} // namespace

namespace {

// ================================================ the choice by measurement

struct PlanReset {
    PlanReset() { sv_plan_reset(); }
    ~PlanReset() { sv_plan_reset(); }
};

TEST(DeformPlan, ChoicesAreKeptPerClassAndRoutine) {
    PlanReset reset;
    sv_deform_choice c;
    EXPECT_EQ(sv_deform_choice_for(0, SV_DEFORM_SKINNING, &c), 0);
    EXPECT_EQ(sv_deform_choice_for(SV_NUM_SIZE_CLASSES, SV_DEFORM_SKINNING, &c), -1);
    EXPECT_EQ(sv_deform_choice_for(0, SV_NUM_DEFORM_ROUTINES, &c), -1);
    EXPECT_EQ(sv_deform_choice_set(1, SV_DEFORM_DERIVE_PLANES, "avx2", 4.25), 0);
    ASSERT_EQ(sv_deform_choice_for(1, SV_DEFORM_DERIVE_PLANES, &c), 1);
    EXPECT_STREQ(c.variant, "avx2");
    EXPECT_EQ(c.ticks, 4.25);
    EXPECT_STREQ(c.source, "measured");
    EXPECT_EQ(sv_deform_choice_for(0, SV_DEFORM_DERIVE_PLANES, &c), 0); // other classes untouched
    for (const char *bad : {"", "AVX2", "two passes", "a/b", "x123456789012345678901234567890ab"}) {
        EXPECT_EQ(sv_deform_choice_set(0, SV_DEFORM_SKINNING, bad, 1.0), -1) << bad;
    }
    EXPECT_EQ(sv_deform_choice_set(0, SV_DEFORM_SKINNING, "avx2", -1.0), -1);
    EXPECT_STREQ(sv_deform_routine_name(SV_DEFORM_SKIN_PLANES), "skin_planes");
    EXPECT_EQ(sv_deform_routine_name(SV_NUM_DEFORM_ROUTINES), nullptr);
}

// Without a choice the static one; a choice naming a kernel that is not in
// the table (an old or foreign wisdom file) is not taken.
TEST(DeformPlan, StaticChoiceAndUnknownNames) {
    PlanReset reset;
    sv::DeformPlan p = sv::deform_plan_for(1000);
    EXPECT_EQ(p.skinning, sv::best_skinning_kernel());
    EXPECT_EQ(p.planes, sv_best_planes_variant());
    EXPECT_EQ(p.skin_planes, nullptr);
    EXPECT_STREQ(p.source, "static");
    ASSERT_EQ(sv_deform_choice_set(0, SV_DEFORM_SKINNING, "avx1024", 1.0), 0);
    ASSERT_EQ(sv_deform_choice_set(0, SV_DEFORM_SKIN_PLANES, "nope", 1.0), 0);
    p = sv::deform_plan_for(1000);
    EXPECT_EQ(p.skinning, sv::best_skinning_kernel());
    EXPECT_EQ(p.skin_planes, nullptr);
    ASSERT_EQ(sv_deform_choice_set(0, SV_DEFORM_SKINNING, "c_ref", 1.0), 0);
    ASSERT_EQ(sv_deform_choice_set(0, SV_DEFORM_SKIN_PLANES, "c_ref", 1.0), 0);
    p = sv::deform_plan_for(1000);
    EXPECT_STREQ(p.skinning->name, "c_ref");
    ASSERT_NE(p.skin_planes, nullptr);
    EXPECT_STREQ(p.skin_planes->name, "c_ref");
    EXPECT_STREQ(p.source, "measured");
    EXPECT_EQ(sv::deform_plan_for(100000).skin_planes, nullptr); // class 2: nothing chosen
}

// A measurement records a runnable choice for each routine, its timings
// cover every kernel this CPU runs, and the scene's lookup returns it.
TEST(DeformPlan, MeasurementChoosesRunnableKernels) {
    PlanReset reset;
    const std::vector<sv::DeformTiming> t = sv::measure_deform_plan(0);
    int want = 2; // "two passes", and "none" for the clusters
    int n = 0;
    const sv::SkinningKernel *sk = sv::skinning_kernels(&n);
    for (int i = 0; i < n; i++) want += (sk[i].isa & sv_cpu_isa()) == sk[i].isa;
    const sv_planes_variant *pv = sv_planes_variants(&n);
    for (int i = 0; i < n; i++) want += (pv[i].isa & sv_cpu_isa()) == pv[i].isa;
    const sv::SkinPlanesKernel *fk = sv::skin_planes_kernels(&n);
    for (int i = 0; i < n; i++) want += (fk[i].isa & sv_cpu_isa()) == fk[i].isa;
    const sv_planes_clustered_variant *cv = sv_planes_clustered_variants(&n);
    for (int i = 0; i < n; i++) want += (cv[i].isa & sv_cpu_isa()) == cv[i].isa;
    EXPECT_EQ((int)t.size(), want);
    for (const sv::DeformTiming &x : t) {
        EXPECT_GT(x.ticks_per_triangle, 0.0) << x.variant;
        EXPECT_TRUE(std::isfinite(x.ticks_per_triangle)) << x.variant;
    }
    sv_deform_choice c;
    for (int r = 0; r < SV_NUM_DEFORM_ROUTINES; r++) {
        ASSERT_EQ(sv_deform_choice_for(0, (sv_deform_routine)r, &c), 1) << r;
        EXPECT_STREQ(c.source, "measured");
    }
    const sv::DeformPlan p = sv::deform_plan_for(1344);
    ASSERT_EQ(sv_deform_choice_for(0, SV_DEFORM_SKINNING, &c), 1);
    EXPECT_STREQ(p.skinning->name, c.variant);
    ASSERT_EQ(sv_deform_choice_for(0, SV_DEFORM_DERIVE_PLANES, &c), 1);
    EXPECT_STREQ(p.planes->name, c.variant);
    ASSERT_EQ(sv_deform_choice_for(0, SV_DEFORM_SKIN_PLANES, &c), 1);
    EXPECT_STREQ(p.skin_planes ? p.skin_planes->name : "none", c.variant);
    EXPECT_STREQ(p.source, "measured");
    std::printf("[ deform   ] class 0: skinning %s, planes %s, %s\n", p.skinning->name,
                p.planes->name, p.skin_planes ? p.skin_planes->name : "two passes");
    EXPECT_THROW(sv::measure_deform_plan(SV_NUM_SIZE_CLASSES), std::runtime_error);
}

// The wisdom file carries the choices to the next process; a measurement
// in this process outranks it.
TEST(DeformPlan, WisdomRoundTrip) {
    PlanReset reset;
    const std::string path = ::testing::TempDir() + "/skin_planes_wisdom";
    std::remove(path.c_str());
    ASSERT_EQ(sv_deform_choice_set(0, SV_DEFORM_SKINNING, "sse2", 3.5), 0);
    ASSERT_EQ(sv_deform_choice_set(0, SV_DEFORM_DERIVE_PLANES, "c_ref", 14.25), 0);
    ASSERT_EQ(sv_deform_choice_set(0, SV_DEFORM_SKIN_PLANES, "none", 17.75), 0);
    ASSERT_EQ(sv_wisdom_save(path.c_str()), 0);
    sv_plan_reset();
    sv_deform_choice c;
    ASSERT_EQ(sv_deform_choice_for(0, SV_DEFORM_SKINNING, &c), 0);
    ASSERT_EQ(sv_wisdom_load(path.c_str()), 1);
    ASSERT_EQ(sv_deform_choice_for(0, SV_DEFORM_SKINNING, &c), 1);
    EXPECT_STREQ(c.variant, "sse2");
    EXPECT_EQ(c.ticks, 3.5);
    EXPECT_STREQ(c.source, "wisdom");
    ASSERT_EQ(sv_deform_choice_for(0, SV_DEFORM_SKIN_PLANES, &c), 1);
    EXPECT_STREQ(c.variant, "none");
    const sv::DeformPlan p = sv::deform_plan_for(10);
    EXPECT_STREQ(p.skinning->name, "sse2");
    EXPECT_STREQ(p.planes->name, "c_ref");
    EXPECT_EQ(p.skin_planes, nullptr);
    EXPECT_STREQ(p.source, "wisdom");
    // Measured here: the file does not replace it.
    ASSERT_EQ(sv_deform_choice_set(0, SV_DEFORM_SKINNING, "c_ref", 8.0), 0);
    ASSERT_EQ(sv_wisdom_load(path.c_str()), 1);
    ASSERT_EQ(sv_deform_choice_for(0, SV_DEFORM_SKINNING, &c), 1);
    EXPECT_STREQ(c.variant, "c_ref");
    EXPECT_STREQ(c.source, "measured");
    std::remove(path.c_str());
}

} // namespace
