/*
 * The lighting pass (src/render/shading_pass.cpp and its row kernels):
 * the AVX2 row kernel shades every pixel as the C one does, byte for byte,
 * under every kind of light, on frames whose width leaves a partial last
 * step, with sky beside the surfaces; lights past the 64 of one sweep are
 * added as the first 64 are; and every thread count gives the same bytes.
 *
 * The C kernel's own bytes are the pass's first ones: tools/pin_bytes.sh's
 * manifest holds them for every render and scene it pins.
 *
 * Copyright (C) 2026 the shadowvol authors. LGPL-2.1-or-later.
 */
#include <gtest/gtest.h>

#include <cstdio>
#include <string>
#include <vector>

#include "frame.h"
#include "frame_vs_mesa.h"
#include "row_kernels.h"
#include "shadowvol_scene.h"
#include "test_conditions.h"
#include "test_lights.h"

namespace {

using namespace sv;
using namespace sv::render;

#ifdef SV_TEST_SMALL_FRAMES
constexpr int kW = 123, kH = 77;
#else
constexpr int kW = 243, kH = 157; /* 243 = 4 * 60 + 3: a partial last step in every row */
#endif

const std::string kCharacter = std::string(SV_MODELS_DIR) + "/character_1344.glb";

/* The character on the ground, the sky above it, and a light of every
 * shape the pass distinguishes: a point light with a range and one
 * without, a spot with a soft cone and one with a hard edge (inner ==
 * outer), and the sun. */
Scene lit_scene() {
    Scene s;
    add_model(s, kCharacter, {});
    add_model(s, kCharacter, {{1.3, 0, -1.0}, 0.8, 1});
    add_ground(s);
    s.camera.eye = {0.8, 1.9, 4.2};
    s.camera.target = {0, 1.4, 0};
    s.camera.fov_y_degrees = 55;
    SceneLight unlimited = svtest::point_light({1.5, 2.5, 2.0}, 0);
    unlimited.intensity = 5;
    SceneLight hard_spot = svtest::spot_light({-1.0, 3.5, 1.0}, {0.2, 0, 0}, 20, 0);
    hard_spot.inner_degrees = hard_spot.outer_degrees;
    s.lights = {svtest::point_light({-1.6, 3.2, 1.4}, 7.0), unlimited,
                svtest::spot_light({1.2, 3.0, 0.8}, {0, 1.6, 0}, 14, 9), hard_spot,
                svtest::sun({0.45, -0.8, -0.4})};
    validate_scene(s);
    return s;
}

std::vector<const raster::RowKernels *> runnable_kernels() {
    int n = 0;
    const raster::RowKernels *const *all = raster::row_kernels_all(&n);
    std::vector<const raster::RowKernels *> out;
    for (int i = 0; i < n; i++) {
        if (svtest::in_this_run(all[i]->isa, all[i]->name)) out.push_back(all[i]);
    }
    return out;
}

Frame render(const Scene &scene, const raster::RowKernels *kernels, int threads) {
    RenderOptions opt;
    opt.width = kW;
    opt.height = kH;
    opt.kernels = kernels;
    opt.threads = threads;
    return render_frame(scene, opt);
}

/* The first pixel where A and B differ, or -1. */
long first_difference(const std::vector<uint8_t> &a, const std::vector<uint8_t> &b) {
    if (a.size() != b.size()) return 0;
    for (std::size_t i = 0; i < a.size(); i++) {
        if (a[i] != b[i]) return (long)(i / 3);
    }
    return -1;
}

SV_TIERED_TEST(Shading, EveryRowKernelShadesAsTheC) {
    const Scene scene = lit_scene();
    const Frame c = render(scene, raster::row_kernels_by_name("c"), 1);
    /* The frame is worth comparing: sky, lit and shadowed pixels. */
    int sky = 0, surface = 0;
    for (int32_t id : c.target.ids) (id < 0 ? sky : surface)++;
    EXPECT_GT(sky, kW * kH / 20);
    EXPECT_GT(surface, kW * kH / 4);
    for (const raster::RowKernels *k : runnable_kernels()) {
        for (int threads : {1, 3}) {
            const Frame f = render(scene, k, threads);
            const long at = first_difference(c.rgb, f.rgb);
            EXPECT_EQ(at, -1) << k->name << " at " << threads << " thread(s): pixel " << at % kW
                              << "," << at / kW;
        }
    }
}

SV_TIERED_TEST(Shading, DividerLanesCountTheLightFormula) {
    /* What bench --frame reads the pass's bound from: the lanes that went
     * through a point or spot light's square root and divides. The C
     * kernel counts its pixels, a SIMD kernel its whole steps (at least as
     * many, at most 8 times); none under directional lights alone. */
    const Scene scene = lit_scene();
    Scene directional = scene;
    directional.lights.clear();
    for (const SceneLight &l : scene.lights) {
        if (l.kind == LightKind::directional) directional.lights.push_back(l);
    }
    ASSERT_FALSE(directional.lights.empty());
    ASSERT_LT(directional.lights.size(), scene.lights.size());
    const uint64_t c = render(scene, raster::row_kernels_by_name("c"), 1).shading_divider_lanes;
    EXPECT_GT(c, 0u);
    for (const raster::RowKernels *k : runnable_kernels()) {
        EXPECT_EQ(render(directional, k, 1).shading_divider_lanes, 0u) << k->name;
        const uint64_t n = render(scene, k, 2).shading_divider_lanes;
        EXPECT_GE(n, c) << k->name;
        EXPECT_LE(n, 8 * c) << k->name;
    }
}

SV_TIERED_TEST(Shading, LightsPastTheFirstSweepAddAsTheFirst) {
    /* Sixty-four lights of zero intensity, then the scene's five: the
     * first sweep adds +0 everywhere, the second the five lights, so the
     * picture is the five lights' own, byte for byte. */
    const Scene five = lit_scene();
    Scene many = five;
    many.lights.clear();
    for (int i = 0; i < 64; i++) {
        SceneLight dark = svtest::point_light({-3.0 + 0.1 * i, 4.0, 2.0}, 0);
        dark.intensity = 0;
        many.lights.push_back(dark);
    }
    for (const SceneLight &l : five.lights) many.lights.push_back(l);
    validate_scene(many);
    for (const raster::RowKernels *k : runnable_kernels()) {
        const Frame a = render(five, k, 0), b = render(many, k, 0);
        const long at = first_difference(a.rgb, b.rgb);
        EXPECT_EQ(at, -1) << k->name << ": pixel " << at % kW << "," << at / kW;
    }
}

} // namespace

namespace {

TEST(Shading, MesaDrawsTheSameFrameOffEdges) {
    /* Mesa's llvmpipe draws the whole frame (depth pre-pass with the
     * ambient term; per light its volumes into the stencil and its light
     * where the stencil is 0): every pixel within kFrameTolerance of ours
     * but where the two rasterisers' edges meet. The comparison sees a
     * real difference: the same frame with Mesa given four times the
     * ambient term differs on most of the pixels. */
    const Scene scene = lit_scene();
    RenderOptions opt;
    /* A fixed size, also in the sanitizer build: at smaller ones edges are
     * most of the picture and the wrong frame below shows less. */
    opt.width = 243;
    opt.height = 157;
    const Frame f = render_frame(scene, opt);
    std::string note;
    const MesaFrameComparison m = compare_frame_with_mesa(scene, f, opt.ambient, 1, 1, &note);
    if (!m.ran) {
        std::printf("NOTE: %s\n", note.c_str());
        GTEST_SKIP() << note;
    }
    std::printf("Mesa's frame (%s): %llu pixels compared, %llu equal, %llu on an edge, %llu "
                "other (at most %d levels off)\n",
                m.renderer.c_str(), (unsigned long long)m.compared, (unsigned long long)m.equal,
                (unsigned long long)m.on_edge, (unsigned long long)m.other, m.max_difference_other);
    EXPECT_GT(m.compared, (uint64_t)(243 * 157 / 4));
    EXPECT_EQ(m.other, 0u);
    EXPECT_EQ(m.stencil_other, 0u);
    EXPECT_LT(m.on_edge, m.compared / 50);
    EXPECT_GT(m.total_seconds, 0);

    const MesaFrameComparison wrong = compare_frame_with_mesa(scene, f, opt.ambient * 4, 1, 1,
                                                              &note);
    EXPECT_GT(wrong.other, m.compared / 4);
}

} // namespace
