/*
 * Seed 002's saturating stencil operations (IncrSat on one pass, DecrSat on
 * the other; issue 31, StencilPassInputs::saturate) in every stencil
 * method: where 256 copies of the character overlap, the saturating and the
 * wrap-around stencils differ (the wrap-around count is 0 where all 256
 * volumes hold the pixel, the saturating one is not), and bf, db, hier and
 * auto (forced each way) leave the same saturating bytes at 1, 2, 3 and all threads, in z-fail
 * (the seed's) and z-pass. A saturating count is not a sum modulo 256, so
 * db's closed-volume skip and hier's wholesale tile updates would break
 * this equality if they were still applied.
 *
 * Copyright (C) 2026 the shadowvol authors. LGPL-2.1-or-later.
 */
#include <gtest/gtest.h>

#include <algorithm>
#include <cstdio>
#include <limits>
#include <string>
#include <utility>
#include <vector>

#include "frame.h"
#include "shadowvol_mesh.h"
#include "shadowvol_scene.h"
#include "test_lights.h"

namespace {

using namespace sv;
using namespace sv::render;

const std::string kCharacter = std::string(SV_MODELS_DIR) + "/character_1344.glb";

/* The frame size is fixed (no SV_TEST_SMALL_FRAMES): the test must see
 * the counts wrap. */
constexpr int kW = 96, kH = 80;

Scene copies_of_the_character(int n) {
    Scene s;
    for (int i = 0; i < n; i++) add_model(s, kCharacter, {});
    add_ground(s);
    s.camera.eye = {0.0, 4.0, 4.0};
    s.camera.target = {0, 0, -0.5};
    s.camera.fov_y_degrees = 50;
    s.camera.near_distance = 0.1;
    s.lights = {svtest::sun({0.05, -1, -0.3})};
    validate_scene(s);
    return s;
}

/* N copies of a closed box floating over the ground under a low sun,
 * seen from above: the ground's tiles inside the shadow are crossed by no
 * piece, so hier would count them wholesale, and at the box's own pixels
 * (in front of every piece of its volume) db would skip the volume as
 * closed. Both are exact for sums, not for saturating counts. */
Scene copies_of_a_box(int n) {
    const float p[] = {-1, 1, -1, 1, 1, -1, 1, 1, 1, -1, 1, 1,
                       -1, 2, -1, 1, 2, -1, 1, 2, 1, -1, 2, 1};
    const uint32_t ix[] = {0, 1, 2, 0, 2, 3, 4, 6, 5, 4, 7, 6, 0, 4, 5, 0, 5, 1,
                           1, 5, 6, 1, 6, 2, 2, 6, 7, 2, 7, 3, 3, 7, 4, 3, 4, 0};
    Scene s;
    for (int i = 0; i < n; i++) {
        SceneSurface b;
        b.name = "box";
        b.prepared = prepare_surface(p, 8, ix, 36);
        update_bounds(b);
        s.surfaces.push_back(std::move(b));
    }
    SceneSurface g;
    g.name = "ground";
    g.ground = true;
    const float gp[] = {-6, 0, -6, 6, 0, -6, 6, 0, 6, -6, 0, 6};
    const uint32_t gi[] = {0, 2, 1, 0, 3, 2};
    g.prepared = prepare_surface(gp, 4, gi, 6);
    update_bounds(g);
    s.surfaces.push_back(std::move(g));
    s.camera.eye = {0.3, 9, 2.5};
    s.camera.target = {0, 0, 0};
    s.camera.fov_y_degrees = 50;
    s.camera.near_distance = 0.1;
    s.lights = {svtest::sun({0.8, -1, 0.3})};
    validate_scene(s);
    return s;
}

/* Stencil bytes that differ (all of them when the sizes do). */
uint64_t differing(const std::vector<uint8_t> &a, const std::vector<uint8_t> &b) {
    if (a.size() != b.size()) return std::max(a.size(), b.size());
    uint64_t n = 0;
    for (std::size_t i = 0; i < a.size(); i++) n += a[i] != b[i];
    return n;
}

RenderOptions options(StencilMethod m, ModeChoice mode, int threads, bool saturate) {
    RenderOptions o;
    o.width = kW;
    o.height = kH;
    o.stencil = m;
    o.mode = mode;
    o.threads = threads;
    o.stencil_saturate = saturate;
    return o;
}

TEST(StencilSaturate, DiffersFromWrapAroundPast255AndEqualsAcrossMethodsAndThreads) {
    const Scene one = copies_of_the_character(1);
    const Scene many = copies_of_the_character(256);
    /* z-fail, the seed's; z-pass and the thread counts on the boxes below
     * (256 characters are a third of a million triangles a frame). */
    for (ModeChoice mode : {ModeChoice::zfail}) {
        const std::vector<uint8_t> single =
            render_frame(one, options(StencilMethod::brute_force, mode, 1, true)).lights[0].stencil;
        const std::vector<uint8_t> wrap = render_frame(many, options(StencilMethod::brute_force,
                                                                     mode, 1, false))
                                              .lights[0]
                                              .stencil;
        const std::vector<uint8_t> sat = render_frame(many, options(StencilMethod::brute_force,
                                                                    mode, 1, true))
                                             .lights[0]
                                             .stencil;
        ASSERT_EQ(sat.size(), wrap.size());
        uint64_t shadowed = 0, wrapped_to_zero = 0, saturated_shadowed = 0, differ = 0;
        uint64_t false_shadow = 0;
        for (std::size_t i = 0; i < sat.size(); i++) {
            differ += sat[i] != wrap[i];
            /* The copies coincide, so every count is 256 times the single
             * copy's: a saturating count above 0 means more increments
             * than decrements, which one copy shows too. */
            false_shadow += sat[i] != 0 && single[i] == 0;
            if (single[i] == 0) continue;
            shadowed++;
            wrapped_to_zero += wrap[i] == 0;
            saturated_shadowed += sat[i] != 0;
        }
        std::printf("[ saturate ] %s: %llu of one copy's %llu shadowed pixels wrap to 0 under "
                    "256 copies; saturating: %llu shadowed; %llu stencil bytes differ\n",
                    mode_name(mode), (unsigned long long)wrapped_to_zero,
                    (unsigned long long)shadowed, (unsigned long long)saturated_shadowed,
                    (unsigned long long)differ);
        EXPECT_GT(shadowed, 0u);
        EXPECT_GT(wrapped_to_zero, 0u) << mode_name(mode) << ": no count wrapped";
        EXPECT_GT(differ, 0u) << mode_name(mode);
        /* Saturation keeps shadow where the wrap-around count came back to
         * 0, but not everywhere: where a pixel's decrements reach 255 too
         * (a ray that crosses a fold of the volume: 256 front faces and
         * 512 back faces become 255 and 255), it is lost. Never made up. */
        EXPECT_GT(saturated_shadowed, 0u) << mode_name(mode);
        EXPECT_EQ(false_shadow, 0u) << mode_name(mode);
        const std::pair<StencilMethod, int> runs[] = {{StencilMethod::depth_bounds, 3},
                                                      {StencilMethod::hierarchical, 0}};
        for (const auto &[m, threads] : runs) {
            const Frame f = render_frame(many, options(m, mode, threads, true));
            EXPECT_EQ(differing(f.lights[0].stencil, sat), 0u)
                << stencil_method_name(m) << ", " << mode_name(mode) << ", " << threads
                << " threads";
        }
    }
}

/* Where hier would count a tile wholesale and db would skip a closed
 * volume's pixels, 256 boxes in one place: the saturating stencil of every
 * method at 1, 2, 3 and all threads (tiles of 8, and of 32 at 3) is bf's
 * at 2, and it is not the wrap-around one. */
TEST(StencilSaturate, WholeTilesAndSkippedPixelsOf256BoxesEqualBruteForce) {
    const Scene many = copies_of_a_box(256);
    for (ModeChoice mode : {ModeChoice::zfail, ModeChoice::zpass}) {
        RenderOptions o = options(StencilMethod::brute_force, mode, 2, true);
        o.width = 160, o.height = 128;
        const Frame bf = render_frame(many, o);
        o.stencil_saturate = false;
        const Frame wrap = render_frame(many, o);
        o.stencil_saturate = true;
        uint64_t shadowed = 0, differ = 0;
        for (std::size_t i = 0; i < bf.lights[0].stencil.size(); i++) {
            shadowed += bf.lights[0].stencil[i] != 0;
            differ += bf.lights[0].stencil[i] != wrap.lights[0].stencil[i];
        }
        EXPECT_GT(shadowed, 500u) << mode_name(mode);
        EXPECT_GT(differ, 500u) << mode_name(mode);
        for (int threads : {1, 2, 3, 0}) {
            for (StencilMethod m : {StencilMethod::brute_force, StencilMethod::depth_bounds,
                                    StencilMethod::hierarchical, StencilMethod::automatic}) {
                o.stencil = m;
                o.threads = threads;
                o.stencil_tile = threads == 3 ? 32 : 8;
                /* auto: its bf at 2 threads, its hier at the others. */
                o.stencil_rule.hier_from_area_per_piece =
                    threads == 2 ? std::numeric_limits<double>::infinity() : 0.0;
                EXPECT_EQ(differing(render_frame(many, o).lights[0].stencil, bf.lights[0].stencil),
                          0u)
                    << stencil_method_name(m) << ", " << mode_name(mode) << ", " << threads
                    << " threads";
            }
        }
    }
}

/* Where no pixel sees more than 255 operations of either kind and the
 * volumes are closed, saturating and wrapping agree byte for byte. */
TEST(StencilSaturate, EqualsWrapAroundBelow255) {
    const Scene one = copies_of_the_character(2);
    for (ModeChoice mode : {ModeChoice::zfail, ModeChoice::zpass}) {
        for (StencilMethod m : {StencilMethod::brute_force, StencilMethod::depth_bounds,
                                StencilMethod::hierarchical}) {
            const Frame w = render_frame(one, options(m, mode, 2, false));
            const Frame s = render_frame(one, options(m, mode, 2, true));
            EXPECT_EQ(differing(w.lights[0].stencil, s.lights[0].stencil), 0u)
                << stencil_method_name(m) << ", " << mode_name(mode);
        }
    }
}

} // namespace
