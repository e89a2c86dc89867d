/*
 * Only what the scene requires (issue 13): every shortcut of the frame
 * (frame.h's Shortcuts) changes no pixel. The proof, frame by frame: the
 * shaded image with every shortcut equals the image with none (--full:
 * every surface, no culling, both caps, z-fail) byte for byte, and the
 * shadow mask equals it wherever the light reaches. Each shortcut made too
 * tight on purpose (ShortcutFaults) is caught by the same comparison, each
 * decision is counted where the scene calls for it, and the frame is the
 * same bytes at every thread count.
 *
 * Copyright (C) 2026 the shadowvol authors. LGPL-2.1-or-later.
 */
#include <gtest/gtest.h>

#include <cmath>
#include <string>
#include <vector>

#include "frame.h"
#include "shadowvol_scene.h"
#include "test_lights.h"

namespace {

using namespace sv;
using namespace sv::render;

#ifdef SV_TEST_SMALL_FRAMES
constexpr int kW = 120, kH = 96;
#else
constexpr int kW = 240, kH = 192;
#endif

const std::string kCharacter = std::string(SV_MODELS_DIR) + "/character_1344.glb";

/* Moves surface S by (dx, dy, dz): positions, planes, box, revision. */
void translate(SceneSurface &s, double dx, double dy, double dz) {
    PreparedSurface &p = s.prepared;
    for (int v = 0; v < p.num_vertices(); v++) {
        p.positions[3 * (std::size_t)v] += (float)dx;
        p.positions[3 * (std::size_t)v + 1] += (float)dy;
        p.positions[3 * (std::size_t)v + 2] += (float)dz;
    }
    for (int t = 0; t < p.num_triangles(); t++) {
        const int *i = &p.indices[3 * (std::size_t)t];
        p.planes[(std::size_t)t] = triangle_plane(&p.positions[3 * (std::size_t)i[0]],
                                                  &p.positions[3 * (std::size_t)i[1]],
                                                  &p.positions[3 * (std::size_t)i[2]]);
    }
    s.lo = {s.lo.x + dx, s.lo.y + dy, s.lo.z + dz};
    s.hi = {s.hi.x + dx, s.hi.y + dy, s.hi.z + dz};
    s.revision++;
}

using svtest::point_light;
using svtest::spot_light;
using svtest::sun;

/* The character at the origin on the ground, a second one far away (out
 * of every range), a third behind the camera, and three lights: a point
 * light with a range and a spot light whose cone cuts the character in
 * half (the box straddles the light volume), and the sun. */
Scene test_scene() {
    Scene s;
    add_model(s, kCharacter, {});
    add_model(s, kCharacter, {{40, 0, 0}, 0, 1});
    add_model(s, kCharacter, {{0, 0, 14}, 0, 1});
    add_ground(s);
    s.camera.eye = {0.5, 2.6, 5.5};
    s.camera.target = {0, 0.6, 0};
    s.camera.fov_y_degrees = 50;
    s.camera.near_distance = 0.1;
    s.lights = {point_light({-1.6, 3.2, 1.4}, 7.0), spot_light({1.2, 3.0, 0.8}, {0, 1.6, 0}, 14, 9),
                sun({0.45, -0.8, -0.4})};
    validate_scene(s);
    return s;
}

/* The eye behind the character at chest height, in its shadow from a
 * point light in front of it at the same height, looking away from it at
 * the shadowed ground: z-pass is wrong there. */
void in_the_shadow(Scene &s) {
    s.lights[0] = point_light({0, 1.2, 1.5}, 14);
    s.camera.eye = {0, 1.2, -1.0};
    s.camera.target = {0, 0.3, -6};
    s.camera.near_distance = 0.05;
}

RenderOptions options(bool shortcuts, VolumeCache *cache = nullptr) {
    RenderOptions o;
    o.width = kW;
    o.height = kH;
    if (shortcuts) {
        o.cache = cache;
    } else {
        o.shortcuts = Shortcuts::none();
        o.mode = ModeChoice::automatic; /* Shortcuts::none() draws every volume in z-fail */
    }
    return o;
}

using Difference = FrameDifference;

Difference compare(const Scene &scene, const Frame &a, const Frame &b) {
    return compare_frames(scene, a, b);
}

int count(const Frame &f, VolumeFate fate) {
    int n = 0;
    for (const LightFrame &lf : f.lights) {
        for (const VolumeDecision &d : lf.decisions) n += d.fate == fate;
    }
    return n;
}

TEST(Shortcuts, EveryFrameEqualsTheFullFrameAndEachShortcutIsTaken) {
    Scene scene = test_scene();
    VolumeCache cache;
    int64_t built_with = 0, built_full = 0;
    int reused = 0, culled = 0, zpass = 0, dark_dropped = 0;
    for (int frame = 0; frame < 4; frame++) {
        /* Frame 1 moves the character, frame 2 the point light; frame 3
         * changes nothing (everything is reused). */
        if (frame == 1) translate(scene.surfaces[0], 0.25, 0, -0.1);
        if (frame == 2) scene.lights[0].position.x += 0.3;
        const Frame fast = render_frame(scene, options(true, &cache));
        const Frame full = render_frame(scene, options(false));
        const Difference d = compare(scene, fast, full);
        EXPECT_EQ(d.rgb_bytes, 0u) << "frame " << frame;
        EXPECT_EQ(d.mask_in_reach, 0u) << "frame " << frame;
        EXPECT_EQ(count(full, VolumeFate::out_of_reach) + count(full, VolumeFate::out_of_view) +
                      count(full, VolumeFate::reused),
                  0);
        for (const LightFrame &lf : fast.lights) {
            built_with += lf.built_indices;
            reused += lf.reused;
            culled += lf.culled;
            for (const VolumeDecision &v : lf.decisions) {
                zpass += v.indices_drawn > 0 && !v.zfail;
                dark_dropped += v.dark_cap_dropped;
            }
        }
        for (const LightFrame &lf : full.lights) built_full += lf.built_indices;
        /* Shortcut 1: the far character is beyond both ranges and the
         * cone. Shortcut 2: the one behind the camera casts away from the
         * view under the spot light. */
        EXPECT_GE(count(fast, VolumeFate::out_of_reach), 2) << "frame " << frame;
        EXPECT_GE(count(fast, VolumeFate::out_of_view), 1) << "frame " << frame;
    }
    EXPECT_GT(reused, 0);
    EXPECT_GT(culled, 0) << "the spot's cone cuts the character: its box straddles the pyramid";
    EXPECT_GT(zpass, 0);
    EXPECT_LT(built_with, built_full / 2) << "the shortcuts should build far fewer indices";
    (void)dark_dropped;
}

TEST(Shortcuts, CameraInsideAShadowGetsZFailFromTheNearPlaneTest) {
    Scene scene = test_scene();
    in_the_shadow(scene);
    validate_scene(scene);
    const Frame fast = render_frame(scene, options(true));
    const Frame full = render_frame(scene, options(false));
    const Difference d = compare(scene, fast, full);
    EXPECT_EQ(d.rgb_bytes, 0u);
    EXPECT_EQ(d.mask_in_reach, 0u);
    EXPECT_TRUE(fast.lights[0].decisions[0].zfail);
}

TEST(Shortcuts, DirectionalDarkCapDrawsNothing) {
    /* Shortcut 5 alone, in z-fail: the stencil is the same everywhere,
     * not only where lit, and dark caps were dropped. */
    Scene scene = test_scene();
    scene.lights = {sun({0.3, -0.9, -0.3})};
    RenderOptions with = options(false), without = options(false);
    with.shortcuts.no_directional_dark_cap = true;
    const Frame a = render_frame(scene, with), b = render_frame(scene, without);
    EXPECT_EQ(a.lights[0].stencil, b.lights[0].stencil);
    EXPECT_EQ(a.rgb, b.rgb);
    EXPECT_TRUE(a.lights[0].decisions[0].dark_cap_dropped);
    EXPECT_LT(a.lights[0].drawn_indices, b.lights[0].drawn_indices);
    /* The dropped triangles are ones that drew nothing in the full frame
     * (zero area, or their one point outside the view). */
    const raster::PassCounters &ca = a.lights[0].stencil_counters,
                               &cb = b.lights[0].stencil_counters;
    EXPECT_EQ(cb.triangles - ca.triangles,
              (uint64_t)(b.lights[0].drawn_indices - a.lights[0].drawn_indices) / 3);
    EXPECT_EQ(cb.triangles_degenerate + cb.triangles_outside - ca.triangles_degenerate -
                  ca.triangles_outside,
              cb.triangles - ca.triangles);
    EXPECT_EQ(ca.pixels_tested, cb.pixels_tested);
}

/* Each shortcut made too tight: the same proof must see it. */
struct FaultCase {
    const char *name;
    void (*apply)(ShortcutFaults &, Scene &);
    double move = 0.08; /* the character's move between the two frames */
};

TEST(Shortcuts, TheProofCatchesEachShortcutMadeTooTight) {
    const FaultCase cases[] = {
        {"light reach: ranges and cones at a fifth",
         [](ShortcutFaults &f, Scene &) { f.light_reach_scale = 0.2; }},
        {"view reach: the box without its shadow",
         [](ShortcutFaults &f, Scene &s) {
             f.view_reach_no_extrusion = true;
             /* A low sun from behind the camera: the shadow of the
              * character behind it falls forward into view. */
             s.lights = {sun({0, -0.15, -1})};
         }},
        {"culling: the light volume shrunk to half",
         [](ShortcutFaults &f, Scene &) { f.cull_inside_planes = true; }},
        {"caps: z-pass always",
         [](ShortcutFaults &f, Scene &s) {
             f.zpass_always = true;
             in_the_shadow(s);
         }},
        {"dark cap: dropped for a point light too",
         [](ShortcutFaults &f, Scene &s) {
             f.drop_dark_cap_always = true;
             in_the_shadow(s);
         }},
        {"reuse: a moved surface's old volume",
         [](ShortcutFaults &f, Scene &) { f.reuse_ignores_motion = true; }, 0.4},
    };
    for (const FaultCase &c : cases) {
        Scene scene = test_scene();
        RenderOptions o = options(true);
        VolumeCache cache;
        o.cache = &cache;
        c.apply(o.faults, scene);
        validate_scene(scene);
        (void)render_frame(scene, o); /* fills the cache */
        translate(scene.surfaces[0], c.move, 0, 0);
        const Frame fast = render_frame(scene, o);
        const Frame full = render_frame(scene, options(false));
        const Difference d = compare(scene, fast, full);
        EXPECT_GT(d.rgb_bytes, 0u) << c.name << ": the proof did not see it";
        EXPECT_GT(d.mask_in_reach, 0u) << c.name;
    }
}

TEST(Shortcuts, SameBytesAtEveryThreadCount) {
    Scene scene = test_scene();
    RenderOptions o = options(true);
    o.threads = 1;
    const Frame one = render_frame(scene, o);
    for (int threads : {2, 3, 5}) {
        o.threads = threads;
        const Frame many = render_frame(scene, o);
        EXPECT_EQ(many.threads, threads);
        EXPECT_EQ(one.rgb, many.rgb) << threads;
        EXPECT_TRUE(std::equal(one.target.depth.begin(), one.target.depth.end(),
                               many.target.depth.begin()));
        EXPECT_TRUE(
            std::equal(one.target.ids.begin(), one.target.ids.end(), many.target.ids.begin()));
        EXPECT_EQ(one.depth_counters.pixels_written, many.depth_counters.pixels_written);
        EXPECT_EQ(one.depth_counters.triangles_clipped, many.depth_counters.triangles_clipped);
        for (std::size_t li = 0; li < one.lights.size(); li++) {
            EXPECT_EQ(one.lights[li].stencil, many.lights[li].stencil)
                << threads << " light " << li;
            EXPECT_EQ(one.lights[li].stencil_counters.pixels_tested,
                      many.lights[li].stencil_counters.pixels_tested);
            EXPECT_EQ(one.lights[li].drawn_indices, many.lights[li].drawn_indices);
        }
    }
}

TEST(Shortcuts, TestsAreConservativeOnBoxes) {
    /* Light reach: a box touching the range is reached; one beyond it is
     * not; a spot's cone against boxes on and off its axis. */
    const SceneLight p = point_light({0, 0, 0}, 2);
    EXPECT_TRUE(light_reaches_box(p, {1.9, -1, -1}, {3, 1, 1}));
    EXPECT_FALSE(light_reaches_box(p, {2.0, -1, -1}, {3, 1, 1}));
    const SceneLight s = spot_light({0, 0, 0}, {0, -1, 0}, 20, 0);
    EXPECT_TRUE(light_reaches_box(s, {-0.1, -5, -0.1}, {0.1, -4, 0.1}));
    EXPECT_FALSE(light_reaches_box(s, {-0.1, 4, -0.1}, {0.1, 5, 0.1})) << "behind the spot";
    EXPECT_FALSE(light_reaches_box(s, {3, -1.1, -0.1}, {3.2, -1, 0.1})) << "beside the cone";
    /* The light-volume planes hold every point of the range and cone. */
    Plane planes[SV_NUM_LIGHT_PLANES];
    ASSERT_TRUE(light_volume_planes(spot_light({1, 2, 3}, {1, -5, 3.5}, 30, 6), planes));
    const SceneLight sp = spot_light({1, 2, 3}, {1, -5, 3.5}, 30, 6);
    uint32_t seed = 7;
    auto rnd = [&] { return (seed = seed * 1664525u + 1013904223u) / 4294967296.0; };
    for (int i = 0; i < 20000; i++) {
        const Vec3d d{rnd() * 2 - 1, rnd() * 2 - 1, rnd() * 2 - 1};
        const double n = std::sqrt(d.x * d.x + d.y * d.y + d.z * d.z);
        const double c = (d.x * sp.direction.x + d.y * sp.direction.y + d.z * sp.direction.z) / n;
        if (n > 1 || c <= std::cos(30 * M_PI / 180)) continue;
        const Vec3d q{1 + d.x * 6, 2 + d.y * 6, 3 + d.z * 6};
        for (const Plane &pl : planes) EXPECT_GE(pl.a * q.x + pl.b * q.y + pl.c * q.z + pl.d, 0.0);
    }
    EXPECT_EQ(classify_box(planes, {0.9, -1, 2.9}, {1.1, 1, 3.1}), BoxSide::inside);
    EXPECT_EQ(classify_box(planes, {-9, -1, -9}, {9, 1, 9}), BoxSide::straddles);
    EXPECT_EQ(classify_box(planes, {0, 5, 0}, {2, 6, 2}), BoxSide::outside);
}

TEST(Shortcuts, LightReachOfABoxHoldsEveryPointInReach) {
    /* The shortcut proof excuses mask differences out of a light's reach
     * through light_reaches_box, the same function shortcut 1 and the
     * lighting use; so it is checked here against the per-point test it
     * stands for. Random boxes under random point lights (with and
     * without a range) and spot lights (cones of 5 to 80 degrees): where
     * any sampled point of the box (corners, face centres, random points)
     * is in reach, the box must be reached. And the test must not be
     * trivially true: some boxes are out of reach. */
    uint32_t seed = 20261206;
    auto rnd = [&] { return (seed = seed * 1664525u + 1013904223u) / 4294967296.0; };
    auto in = [&](double lo, double hi) { return lo + (hi - lo) * rnd(); };
    int reached = 0, not_reached = 0, boxes_with_points_in_reach = 0;
    for (int trial = 0; trial < 4000; trial++) {
        const Vec3d at{in(-5, 5), in(-5, 5), in(-5, 5)};
        SceneLight l;
        if (trial % 2 == 0) {
            l = point_light(at, trial % 4 == 0 ? 0.0 : in(0.5, 6));
        } else {
            const Vec3d d{in(-1, 1), in(-1, 1), in(-1, 1)};
            const double n = std::sqrt(d.x * d.x + d.y * d.y + d.z * d.z);
            if (n < 1e-3) continue;
            l = spot_light(at, {at.x + d.x, at.y + d.y, at.z + d.z}, in(5, 80),
                           trial % 3 == 0 ? 0.0 : in(0.5, 8));
        }
        const Vec3d c{in(-6, 6), in(-6, 6), in(-6, 6)};
        const Vec3d h{in(0.01, 2), in(0.01, 2), in(0.01, 2)};
        const Vec3d lo{c.x - h.x, c.y - h.y, c.z - h.z}, hi{c.x + h.x, c.y + h.y, c.z + h.z};
        const bool box = light_reaches_box(l, lo, hi);
        (box ? reached : not_reached)++;
        bool any = false;
        for (int k = 0; k < 64 && !any; k++) {
            Vec3d q;
            if (k < 8) {
                q = {(k & 1) ? hi.x : lo.x, (k & 2) ? hi.y : lo.y, (k & 4) ? hi.z : lo.z};
            } else if (k < 14) {
                const int axis = (k - 8) / 2;
                const bool top = (k - 8) % 2;
                q = c;
                (axis == 0   ? q.x
                 : axis == 1 ? q.y
                             : q.z) = axis == 0   ? (top ? hi.x : lo.x)
                                      : axis == 1 ? (top ? hi.y : lo.y)
                                                  : (top ? hi.z : lo.z);
            } else {
                q = {in(lo.x, hi.x), in(lo.y, hi.y), in(lo.z, hi.z)};
            }
            any = point_in_light_reach(l, q);
        }
        boxes_with_points_in_reach += any;
        EXPECT_TRUE(!any || box) << "trial " << trial << ": a point of the box is in reach of "
                                 << l.describe() << " but the box is not";
    }
    EXPECT_GT(not_reached, 100) << "the property is trivially true";
    EXPECT_GT(boxes_with_points_in_reach, 100);
}

} // namespace
