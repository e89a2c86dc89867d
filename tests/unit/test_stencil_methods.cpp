/*
 * The stencil methods (issue 28): depth bounds ("db") and hierarchical
 * ("hier", seed 004) leave every light's stencil byte for byte as brute
 * force ("bf") does, on every test scene, in both modes and with every
 * light kind, at 1, 2, 3 and all threads, every tile size, and frame sizes
 * that are no multiple of the tile; each of hier's tests made wrong on
 * purpose (StencilFaults) is caught by the same comparison; hier's
 * per-pixel stage tests a fraction of brute force's pixels on a crowd; and
 * what the classifying methods keep from frame to frame (the receivers'
 * triangles grouped) follows a changed mesh.
 *
 * Copyright (C) 2026 the shadowvol authors. LGPL-2.1-or-later.
 */
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <limits>
#include <stdexcept>
#include <string>
#include <vector>

#include "frame.h"
#include "row_kernels.h"
#include "sequence.h"
#include "shadowvol_mesh.h"
#include "surface_triangles.h"
#include "shadowvol_scene.h"
#include "test_lights.h"
#include "test_conditions.h"

namespace {

using namespace sv;
using namespace sv::render;

#ifdef SV_TEST_SMALL_FRAMES
constexpr int kW = 120, kH = 96;
#else
constexpr int kW = 240, kH = 192;
#endif
/* Sizes that are no multiple of any tile side: edge tiles on both sides. */
constexpr int kOddW = 257, kOddH = 131;

const std::string kCharacter = std::string(SV_MODELS_DIR) + "/character_1344.glb";

using svtest::point_light;
using svtest::spot_light;
using svtest::sun;

/* The character on the ground with a point, a spot and a directional
 * light (as test_shortcuts.cpp's scene). */
Scene character_scene() {
    Scene s;
    add_model(s, kCharacter, {});
    add_model(s, kCharacter, {{1.4, 0, -1.2}, 0.7, 1});
    add_ground(s);
    s.camera.eye = {0.5, 2.6, 5.5};
    s.camera.target = {0, 0.6, 0};
    s.camera.fov_y_degrees = 50;
    s.camera.near_distance = 0.1;
    s.lights = {point_light({-1.6, 3.2, 1.4}, 9.0), spot_light({1.2, 3.0, 0.8}, {0, 1.6, 0}, 24, 9),
                sun({0.45, -0.8, -0.4})};
    validate_scene(s);
    return s;
}

/* The eye inside the character's shadow from a point light in front of
 * it, looking away at the shadowed ground: volumes cross the near plane. */
Scene inside_a_shadow() {
    Scene s = character_scene();
    s.lights = {point_light({0, 1.2, 1.5}, 14), sun({0.1, -0.3, -1})};
    s.camera.eye = {0, 1.2, -1.0};
    s.camera.target = {0, 0.3, -6};
    s.camera.near_distance = 0.05;
    validate_scene(s);
    return s;
}

/* The ground seen almost edge-on: tiles whose depth range spans far. */
Scene grazing_ground() {
    Scene s = character_scene();
    s.camera.eye = {0.3, 0.12, 6.0};
    s.camera.target = {0, 0.05, 0};
    validate_scene(s);
    return s;
}

/* A crowd of characters (the seed's "knights" in our terms, at test size):
 * a 5 x 4 grid under a point light. */
Scene crowd() {
    Scene s;
    for (int i = 0; i < 5; i++) {
        for (int j = 0; j < 4; j++) {
            add_model(s, kCharacter, {{(i - 2) * 1.3, 0, -j * 1.5}, 0.4 * (i + j), 1});
        }
    }
    add_ground(s);
    s.camera.eye = {0.5, 7, 12};
    s.camera.target = {0, 0.5, -2};
    s.camera.fov_y_degrees = 50;
    s.camera.near_distance = 0.1;
    s.lights = {point_light({-6.0, 3.5, 1.0}, 0)};
    validate_scene(s);
    return s;
}

RenderOptions options(int w, int h, StencilMethod m, ModeChoice mode, int threads) {
    RenderOptions o;
    o.width = w;
    o.height = h;
    o.stencil = m;
    o.mode = mode;
    o.threads = threads;
    return o;
}

/* Light by light, the stencil bytes that differ between A and B. */
uint64_t stencil_differences(const Frame &a, const Frame &b) {
    uint64_t n = 0;
    for (std::size_t li = 0; li < a.lights.size(); li++) {
        const auto &x = a.lights[li].stencil, &y = b.lights[li].stencil;
        if (x.size() != y.size()) return UINT64_MAX;
        for (std::size_t i = 0; i < x.size(); i++) n += x[i] != y[i];
    }
    return n;
}

struct Case {
    const char *name;
    Scene (*make)();
};
const Case kScenes[] = {{"character", character_scene},
                        {"inside a shadow", inside_a_shadow},
                        {"grazing ground", grazing_ground},
                        {"crowd", crowd}};

TEST(StencilMethods, EqualBruteForceOnEveryTestSceneModeAndThreadCount) {
    for (const Case &c : kScenes) {
        const Scene scene = c.make();
        for (ModeChoice mode : {ModeChoice::zpass, ModeChoice::zfail, ModeChoice::automatic}) {
            for (const auto &[w, h] : {std::pair{kW, kH}, std::pair{kOddW, kOddH}}) {
                const Frame bf = render_frame(scene,
                                              options(w, h, StencilMethod::brute_force, mode, 1));
                uint64_t walked = 0;
                for (const LightFrame &lf : bf.lights) walked += lf.stencil_counters.pixels_tested;
                ASSERT_GT(walked, 0u) << c.name << ": the scene draws no volume";
                for (StencilMethod m : {StencilMethod::depth_bounds, StencilMethod::hierarchical}) {
                    for (int threads : {1, 2, 3, 0}) {
                        const Frame f = render_frame(scene, options(w, h, m, mode, threads));
                        EXPECT_EQ(stencil_differences(f, bf), 0u)
                            << c.name << ", " << stencil_method_name(m) << ", " << mode_name(mode)
                            << ", " << w << "x" << h << ", " << threads << " threads";
                        EXPECT_EQ(f.rgb, bf.rgb) << c.name << ", " << stencil_method_name(m);
                    }
                }
            }
        }
    }
}

/* hier takes the receiver's own caps by coverage in z-fail (the equality
 * tests hold with it), never in z-pass (no caps) nor under saturation
 * (its two counts are no sum of deltas). */
TEST(StencilMethods, HierTakesTheReceiversCapsByCoverageInZfailAlone) {
    const Scene scene = character_scene();
    auto rows = [](const Frame &f) {
        uint64_t n = 0;
        for (const LightFrame &lf : f.lights) n += lf.stencil_coverage_rows;
        return n;
    };
    const Frame zfail = render_frame(scene, options(kW, kH, StencilMethod::hierarchical,
                                                    ModeChoice::zfail, 1));
    EXPECT_GT(rows(zfail), 0u);
    EXPECT_EQ(rows(render_frame(scene, options(kW, kH, StencilMethod::hierarchical,
                                               ModeChoice::zpass, 1))),
              0u);
    RenderOptions saturating = options(kW, kH, StencilMethod::hierarchical, ModeChoice::zfail, 1);
    saturating.stencil_saturate = true;
    EXPECT_EQ(rows(render_frame(scene, saturating)), 0u);
}

/* Every row kernel this entry's tier runs: hier's per-pixel stage and db
 * leave bf's bytes through it too. */
SV_TIERED_TEST(StencilMethods, EqualBruteForceWithEveryRowKernel) {
    int n = 0;
    const raster::RowKernels *const *all = raster::row_kernels_all(&n);
    const Scene scene = crowd();
    for (int i = 0; i < n; i++) {
        if (!svtest::in_this_run(all[i]->isa, all[i]->name)) continue;
        for (ModeChoice mode : {ModeChoice::zpass, ModeChoice::zfail}) {
            RenderOptions o = options(kOddW, kOddH, StencilMethod::brute_force, mode, 2);
            o.kernels = all[i];
            const Frame bf = render_frame(scene, o);
            for (StencilMethod m : {StencilMethod::depth_bounds, StencilMethod::hierarchical}) {
                o.stencil = m;
                EXPECT_EQ(stencil_differences(render_frame(scene, o), bf), 0u)
                    << all[i]->name << ", " << stencil_method_name(m) << ", " << mode_name(mode);
            }
        }
    }
}

/* Issue 27's general rule on every shell (each triangle's prism, edges as
 * repeated quads): the volumes open and close by multiplicity. */
TEST(StencilMethods, GeneralCasterRuleEqualsBruteForce) {
    for (const Case &c : kScenes) {
        const Scene scene = c.make();
        for (ModeChoice mode : {ModeChoice::zpass, ModeChoice::zfail, ModeChoice::automatic}) {
            RenderOptions o = options(kOddW, kOddH, StencilMethod::brute_force, mode, 3);
            o.caster_rule = CasterRule::general;
            const Frame bf = render_frame(scene, o);
            for (StencilMethod m : {StencilMethod::depth_bounds, StencilMethod::hierarchical}) {
                o.stencil = m;
                EXPECT_EQ(stencil_differences(render_frame(scene, o), bf), 0u)
                    << c.name << ", " << stencil_method_name(m) << ", " << mode_name(mode);
            }
        }
    }
}

TEST(StencilMethods, HierEqualsBruteForceAtEveryTileSize) {
    for (const Case &c : kScenes) {
        const Scene scene = c.make();
        for (ModeChoice mode : {ModeChoice::zpass, ModeChoice::zfail}) {
            const Frame bf = render_frame(scene, options(kOddW, kOddH, StencilMethod::brute_force,
                                                         mode, 1));
            for (int tile : {4, 8, 16, 32}) {
                RenderOptions o = options(kOddW, kOddH, StencilMethod::hierarchical, mode, 3);
                o.stencil_tile = tile;
                EXPECT_EQ(stencil_differences(render_frame(scene, o), bf), 0u)
                    << c.name << ", " << mode_name(mode) << ", tile " << tile;
            }
        }
    }
}

TEST(StencilMethods, DemoSceneFramesEqualBruteForce) {
    SequenceOptions so;
    so.file = SV_DEMO_SCENE;
    so.aspect = (double)kW / kH;
    SceneSequence seq(so);
    for (double t : {0.0, 0.4}) {
        seq.set_time(t);
        for (ModeChoice mode : {ModeChoice::zpass, ModeChoice::automatic}) {
            const Frame bf = render_frame(seq.scene(),
                                          options(kW, kH, StencilMethod::brute_force, mode, 0));
            for (StencilMethod m : {StencilMethod::depth_bounds, StencilMethod::hierarchical}) {
                const Frame f = render_frame(seq.scene(), options(kW, kH, m, mode, 0));
                EXPECT_EQ(stencil_differences(f, bf), 0u)
                    << "t " << t << ", " << stencil_method_name(m) << ", " << mode_name(mode);
            }
        }
    }
}

/* auto (per light bf or hier, by StencilRule) equals brute force
 * whichever it takes: its rule forced to hier for every light (threshold
 * 0), to bf (infinity), and the default, at 1, 2, 3 and all threads; each
 * light ran what the rule says for its load. */
TEST(StencilMethods, AutoEqualsBruteForceWhicheverItTakes) {
    const double rules[] = {0.0, std::numeric_limits<double>::infinity(),
                            kDefaultHierFromAreaPerPiece};
    for (const Case &c : kScenes) {
        const Scene scene = c.make();
        for (ModeChoice mode : {ModeChoice::zpass, ModeChoice::zfail}) {
            const Frame bf = render_frame(scene, options(kOddW, kOddH, StencilMethod::brute_force,
                                                         mode, 1));
            for (double rule : rules) {
                for (int threads : {1, 2, 3, 0}) {
                    RenderOptions o = options(kOddW, kOddH, StencilMethod::automatic, mode,
                                              threads);
                    o.stencil_rule.hier_from_area_per_piece = rule;
                    const Frame f = render_frame(scene, o);
                    EXPECT_EQ(stencil_differences(f, bf), 0u)
                        << c.name << ", " << mode_name(mode) << ", rule " << rule << ", " << threads
                        << " threads";
                    for (const LightFrame &lf : f.lights) {
                        const bool hier = o.stencil_rule.choose_hier(lf.stencil_load);
                        EXPECT_EQ(lf.stencil_ran,
                                  hier ? StencilMethod::hierarchical : StencilMethod::brute_force)
                            << c.name << ", rule " << rule;
                        if (rule == 0 && lf.stencil_load.pieces) {
                            EXPECT_EQ(lf.stencil_ran, StencilMethod::hierarchical) << c.name;
                        }
                        if (std::isinf(rule)) {
                            EXPECT_EQ(lf.stencil_ran, StencilMethod::brute_force) << c.name;
                        }
                    }
                }
            }
        }
    }
}

/* Each of hier's tests made wrong is caught, run by hier itself and by
 * auto with its rule forced to hier (the same stages on auto's shared
 * set-up). */
TEST(StencilMethods, TheEqualityCatchesEachHierTestMadeWrong) {
    struct Fault {
        const char *name;
        void (*apply)(StencilFaults &);
        bool zfail_only; /* the receiver's caps are drawn in z-fail alone */
    };
    const Fault faults[] = {
        {"tile box test too tight", [](StencilFaults &f) { f.tile_box_test_too_tight = true; },
         false},
        {"sample point outside its tile", [](StencilFaults &f) { f.sample_outside_tile = true; },
         false},
        {"caps' edges not boundary", [](StencilFaults &f) { f.cap_edges_not_boundary = true; },
         true},
        {"caps' spans a pixel short", [](StencilFaults &f) { f.cap_spans_short = true; }, true},
    };
    for (const Fault &fault : faults) {
        for (StencilMethod m : {StencilMethod::hierarchical, StencilMethod::automatic}) {
            for (ModeChoice mode : {ModeChoice::zpass, ModeChoice::zfail}) {
                if (fault.zfail_only && mode != ModeChoice::zfail) continue;
                uint64_t seen = 0;
                for (const Case &c : kScenes) {
                    const Scene scene = c.make();
                    const Frame bf = render_frame(scene, options(kW, kH, StencilMethod::brute_force,
                                                                 mode, 1));
                    RenderOptions o = options(kW, kH, m, mode, 1);
                    o.stencil_rule.hier_from_area_per_piece = 0; /* auto: hier everywhere */
                    /* The seed's tiles: at this frame size they are many, so a
                     * wrong test has room to show (the default, larger tiles
                     * leave a few dozen). */
                    o.stencil_tile = 8;
                    fault.apply(o.stencil_faults);
                    seen += stencil_differences(render_frame(scene, o), bf);
                }
                EXPECT_GT(seen, 0u) << fault.name << ", " << stencil_method_name(m) << ", "
                                    << mode_name(mode) << ": the equality did not see it";
            }
        }
    }
}

/* The seed's claim in our terms: the per-pixel stage tests a fifth of
 * brute force's pixels or fewer on the crowd, with 4-pixel tiles at the
 * test's size and the seed's 8-pixel tiles at twice it (the ratio grows
 * with resolution: boundary tiles grow with the side, the volumes' area
 * with its square; measured 6.6x and 7.0x at 320x256 with 4-pixel tiles,
 * 6.4x and 6.9x at 640x512 with 8). db tests no more than bf. */
TEST(StencilMethods, HierTestsAFifthOfBruteForcesPixelsOnACrowd) {
    const Scene scene = crowd();
    struct Size {
        int w, h, tile;
    };
#ifdef SV_TEST_SMALL_FRAMES
    const Size sizes[] = {{320, 256, 4}};
#else
    const Size sizes[] = {{320, 256, 4}, {640, 512, 8}};
#endif

    for (const Size &sz : sizes) {
        for (ModeChoice mode : {ModeChoice::zpass, ModeChoice::zfail}) {
            const Frame bf = render_frame(scene,
                                          options(sz.w, sz.h, StencilMethod::brute_force, mode, 0));
            RenderOptions o = options(sz.w, sz.h, StencilMethod::hierarchical, mode, 0);
            o.stencil_tile = sz.tile;
            const Frame hier = render_frame(scene, o);
            const Frame db = render_frame(scene, options(sz.w, sz.h, StencilMethod::depth_bounds,
                                                         mode, 0));
            const uint64_t b = bf.lights[0].stencil_counters.pixels_tested,
                           h = hier.lights[0].stencil_counters.pixels_tested,
                           d = db.lights[0].stencil_counters.pixels_tested;
            std::printf("%dx%d tile %d, %s: pixels tested bf %llu, db %llu, hier %llu (bf / hier "
                        "%.2f)\n",
                        sz.w, sz.h, sz.tile, mode_name(mode), (unsigned long long)b,
                        (unsigned long long)d, (unsigned long long)h,
                        (double)b / (double)(h ? h : 1));
            EXPECT_EQ(stencil_differences(hier, bf), 0u);
            EXPECT_EQ(stencil_differences(db, bf), 0u);
            EXPECT_LE(d, b) << mode_name(mode);
            EXPECT_GT(h, 0u);
            EXPECT_LE(5 * h, b) << sz.w << "x" << sz.h << ", " << mode_name(mode)
                                << ": hier tested " << h << " of bf's " << b;
        }
    }
}

/* 256 copies of the character in one place: inside all their shadows the
 * count wraps to 0 (every method's stencil wraps as brute force's does, so
 * only the equality with it is judged there). */
TEST(StencilMethods, WrapAroundOf256OverlappingVolumesEqualsBruteForce) {
    Scene one;
    add_model(one, kCharacter, {});
    add_ground(one);
    one.camera.eye = {0.0, 4.0, 4.0};
    one.camera.target = {0, 0, -0.5};
    one.camera.fov_y_degrees = 50;
    one.camera.near_distance = 0.1;
    one.lights = {sun({0.05, -1, -0.3})};
    Scene many = one;
    many.surfaces.clear();
    for (int i = 0; i < 256; i++) add_model(many, kCharacter, {});
    add_ground(many);
    validate_scene(one);
    validate_scene(many);
    for (ModeChoice mode : {ModeChoice::zpass, ModeChoice::zfail}) {
        const Frame single = render_frame(one,
                                          options(96, 80, StencilMethod::brute_force, mode, 0));
        const Frame bf = render_frame(many, options(96, 80, StencilMethod::brute_force, mode, 0));
        uint64_t wrapped = 0;
        for (std::size_t i = 0; i < bf.lights[0].stencil.size(); i++) {
            wrapped += single.lights[0].stencil[i] != 0 && bf.lights[0].stencil[i] == 0;
        }
        EXPECT_GT(wrapped, 0u) << mode_name(mode) << ": no count wrapped";
        for (StencilMethod m : {StencilMethod::depth_bounds, StencilMethod::hierarchical}) {
            EXPECT_EQ(stencil_differences(render_frame(many, options(96, 80, m, mode, 0)), bf), 0u)
                << stencil_method_name(m) << ", " << mode_name(mode);
        }
    }
}

/* The grouping of a surface's triangles kept across frames is keyed by
 * its index list: a changed list (the same surface number) is grouped
 * again at the next frame, and within a frame the first one asked for is
 * kept (the scene does not change within a frame). */
TEST(StencilMethods, KeptSurfaceTrianglesFollowAChangedIndexList) {
    /* One quad, cut along one diagonal (A) or the other (B). */
    const float positions[] = {0, 0, 0, 1, 0, 0, 1, 1, 0, 0, 1, 0};
    const uint32_t cut_a[] = {0, 1, 2, 0, 2, 3}, cut_b[] = {0, 1, 3, 1, 2, 3};
    const PreparedSurface a = prepare_surface(positions, 4, cut_a, 6);
    const PreparedSurface b = prepare_surface(positions, 4, cut_b, 6);
    auto has_all = [](const detail::SurfaceTriangles &g, const PreparedSurface &p) {
        bool all = true;
        for (int t = 0; t < p.num_triangles(); t++) {
            const int *i = &p.indices[3 * (std::size_t)t];
            all &= g.contains(i[2], i[0], i[1]);
        }
        return all;
    };
    auto has_none = [](const detail::SurfaceTriangles &g, const PreparedSurface &p) {
        bool any = false;
        for (int t = 0; t < p.num_triangles(); t++) {
            const int *i = &p.indices[3 * (std::size_t)t];
            any |= g.contains(i[0], i[1], i[2]);
        }
        return !any;
    };
    detail::SurfaceTrianglesCache cache;
    cache.fit(1);
    cache.begin_frame();
    EXPECT_TRUE(has_all(cache.get(0, a), a));
    EXPECT_TRUE(has_none(cache.get(0, a), b));
    EXPECT_TRUE(has_all(cache.get(0, b), a)) << "within a frame the first list is kept";
    cache.begin_frame();
    EXPECT_TRUE(has_all(cache.get(0, b), b)) << "the changed list was not grouped again";
    EXPECT_TRUE(has_none(cache.get(0, b), a));
    cache.begin_frame();
    EXPECT_TRUE(has_all(cache.get(0, a), a));
}

/* One FrameScratch (what a sequence keeps) through frames of different
 * scenes whose surface numbers name other meshes (surface 2: the ground,
 * then a character): each frame's stencils equal brute force's. */
TEST(StencilMethods, ScratchKeptAcrossScenesEqualsBruteForce) {
    FrameScratch scratch;
    for (Scene (*make)() : {character_scene, crowd, character_scene}) {
        const Scene scene = make();
        const Frame bf = render_frame(scene, options(kW, kH, StencilMethod::brute_force,
                                                     ModeChoice::zfail, 1));
        for (StencilMethod m : {StencilMethod::hierarchical, StencilMethod::depth_bounds}) {
            RenderOptions o = options(kW, kH, m, ModeChoice::zfail, 2);
            o.scratch = &scratch;
            EXPECT_EQ(stencil_differences(render_frame(scene, o), bf), 0u)
                << stencil_method_name(m) << ", " << scene.surfaces.size() << " surfaces";
        }
    }
}

TEST(StencilMethods, HierRefusesATileSideItHasNot) {
    const Scene scene = character_scene();
    RenderOptions o = options(64, 48, StencilMethod::hierarchical, ModeChoice::automatic, 1);
    o.stencil_tile = 12;
    EXPECT_THROW(render_frame(scene, o), std::invalid_argument);
}

TEST(StencilMethods, NamesRoundTrip) {
    for (StencilMethod m : {StencilMethod::brute_force, StencilMethod::depth_bounds,
                            StencilMethod::hierarchical, StencilMethod::automatic}) {
        StencilMethod back = StencilMethod::brute_force;
        ASSERT_TRUE(stencil_method_by_name(stencil_method_name(m), back));
        EXPECT_EQ(back, m);
    }
    StencilMethod untouched = StencilMethod::hierarchical;
    EXPECT_FALSE(stencil_method_by_name("hi", untouched));
    EXPECT_EQ(untouched, StencilMethod::hierarchical);
    EXPECT_EQ(stencil_method_names(), "bf, db, hier, auto");
}

} // namespace
