/*
 * Frames (src/render): the stencil against ray-cast truth on the bundled
 * character and every real model, under a point, a spot and a
 * directional light, in z-pass and z-fail; z-pass against z-fail; the
 * camera inside a shadow (z-pass wrong, z-fail right, auto picks z-fail);
 * the Mesa judge; PNGs; the scene's checks.
 *
 * Copyright (C) 2026 the shadowvol authors. LGPL-2.1-or-later.
 */
#include <gtest/gtest.h>

#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

#include <stb/stb_image.h>

#include "frame.h"
#include "gl_compare.h"
#include "images.h"
#include "model_surfaces.h"
#include "scene_options.h"
#include "shadowvol_scene.h"
#include "test_conditions.h"
#include "truth.h"

namespace {

using namespace sv;
using namespace sv::render;

/* Sanitizer builds render smaller frames (the same code, 10-20x slower). */
#ifdef SV_TEST_SMALL_FRAMES
constexpr int kW = 128, kH = 104;
#else
constexpr int kW = 320, kH = 256;
#endif

Scene model_on_ground(const std::string &path) {
    Scene s;
    add_model(s, path, {});
    add_ground(s);
    s.camera = frame_camera(s, (double)kW / kH);
    return s;
}

/* A point, a spot and a directional light around the scene's bounds. */
std::vector<SceneLight> three_lights(const Scene &s) {
    return {auto_light(s, LightKind::point), auto_light(s, LightKind::spot),
            auto_light(s, LightKind::directional)};
}

void expect_truth_holds(const Scene &scene, const Frame &f, const std::string &what) {
    const TruthCaster caster(scene);
    for (std::size_t li = 0; li < f.lights.size(); li++) {
        const Truth t = caster.cast(f, (int)li, 2);
        const Comparison c = caster.compare(f, (int)li, t);
        EXPECT_EQ(c.off_boundary_mismatches, 0u)
            << what << ", light " << f.lights[li].light.describe() << ": first at pixel "
            << (c.first_off_boundary.empty() ? -1 : c.first_off_boundary[0] % f.width) << ","
            << (c.first_off_boundary.empty() ? -1 : c.first_off_boundary[0] / f.width);
        EXPECT_GT(c.compared, 0u) << what;
        /* The test means something only if there is shadow to get right. */
        EXPECT_GT(c.shadowed, 0u) << what << ", light " << li << ": no shadow in view";
        EXPECT_LE(c.mismatches, c.boundary) << what;
    }
}

TEST(Render, BundledCharacterMatchesTruthInBothModes) {
    Scene scene = model_on_ground(SV_MODELS_DIR "/character_1344.glb");
    scene.lights = three_lights(scene);
    validate_scene(scene);
    for (ModeChoice m : {ModeChoice::zpass, ModeChoice::zfail, ModeChoice::automatic}) {
        RenderOptions o;
        o.width = kW, o.height = kH, o.mode = m;
        const Frame f = render_frame(scene, o);
        ASSERT_EQ(f.lights.size(), 3u);
        for (const LightFrame &lf : f.lights) EXPECT_GE(lf.volumes.size(), 1u);
        expect_truth_holds(scene, f, std::string("character, ") + mode_name(m));
    }
}

TEST(Render, EverySharedModelsCharacterMatchesTruth) {
    /* Every .glb of ../shared/models and of its open/ folder (the open and
     * non-manifold characters of issue 27). */
    const std::vector<std::string> models = svtest::seed_model_paths("SharedModels");
    EXPECT_FALSE(models.empty()) << "no .glb in " << svtest::shared_models_dir();
    for (const std::string &path : models) {
        Scene scene = model_on_ground(path);
        scene.lights = three_lights(scene);
        validate_scene(scene);
        for (ModeChoice m : {ModeChoice::zpass, ModeChoice::zfail}) {
            RenderOptions o;
            o.width = kW, o.height = kH, o.mode = m;
            expect_truth_holds(scene, render_frame(scene, o), path + ", " + mode_name(m));
        }
    }
}

TEST(Render, ZPassEqualsZFailWhereZPassIsValid) {
    Scene scene = model_on_ground(SV_MODELS_DIR "/character_1344.glb");
    scene.lights = three_lights(scene);
    validate_scene(scene);
    for (const SceneSurface &s : scene.surfaces) {
        for (const SceneLight &l : scene.lights) {
            ASSERT_FALSE(near_plane_may_be_shadowed(scene.camera, (double)kW / kH, s, l))
                << "the camera was meant to be out of every shadow";
        }
    }
    RenderOptions a, b;
    a.width = b.width = kW, a.height = b.height = kH;
    a.mode = ModeChoice::zpass, b.mode = ModeChoice::zfail;
    const Frame fa = render_frame(scene, a), fb = render_frame(scene, b);
    for (std::size_t li = 0; li < fa.lights.size(); li++) {
        uint64_t differ = 0, surface_pixels = 0;
        for (std::size_t i = 0; i < fa.lights[li].stencil.size(); i++) {
            if (fa.target.ids[i] < 0) continue;
            surface_pixels++;
            differ += (fa.lights[li].stencil[i] != 0) != (fb.lights[li].stencil[i] != 0);
        }
        EXPECT_EQ(differ, 0u) << "light " << li << " of " << surface_pixels << " pixels";
        EXPECT_GT(fb.lights[li].drawn_indices, fa.lights[li].drawn_indices)
            << "z-fail draws the caps too";
    }
}

/* The camera stands on the ground in the shadow of a large box held up
 * over it, the light above the box: the near plane lies inside the box's
 * shadow volume. */
Scene camera_in_shadow() {
    Scene scene;
    add_model(scene, SV_MODELS_DIR "/character_1344.glb", {{0, 0, 0}, 0, 1});
    add_ground(scene);
    /* A wide flat slab over the camera, as a closed box (12 triangles). */
    const float x0 = -1.5f, x1 = 1.5f, y0 = 2.6f, y1 = 2.8f, z0 = 0.5f, z1 = 4.5f;
    const float p[] = {x0, y0, z0, x1, y0, z0, x1, y1, z0, x0, y1, z0,
                       x0, y0, z1, x1, y0, z1, x1, y1, z1, x0, y1, z1};
    const uint32_t idx[] = {0, 3, 2, 0, 2, 1, 4, 5, 6, 4, 6, 7, 0, 1, 5, 0, 5, 4,
                            3, 7, 6, 3, 6, 2, 0, 4, 7, 0, 7, 3, 1, 2, 6, 1, 6, 5};
    SceneSurface slab;
    slab.name = "slab";
    slab.prepared = prepare_surface(p, 8, idx, 36);
    slab.lo = {x0, y0, z0};
    slab.hi = {x1, y1, z1};
    scene.surfaces.push_back(std::move(slab));
    scene.camera.eye = {0.3, 1.2, 3.0};
    scene.camera.target = {0, 0.8, 0};
    scene.camera.near_distance = 0.05;
    SceneLight l;
    l.kind = LightKind::point;
    l.position = {0.2, 6.0, 2.6};
    default_intensity(scene, l);
    scene.lights = {l};
    validate_scene(scene);
    return scene;
}

TEST(Render, CameraInsideAVolumeZPassWrongZFailRight) {
    const Scene scene = camera_in_shadow();
    const SceneSurface &slab = scene.surfaces.back();
    ASSERT_TRUE(near_plane_may_be_shadowed(scene.camera, (double)kW / kH, slab, scene.lights[0]));
    const TruthCaster caster(scene);
    RenderOptions o;
    o.width = kW, o.height = kH;
    o.mode = ModeChoice::zpass;
    const Frame zp = render_frame(scene, o);
    const Comparison cp = caster.compare(zp, 0, caster.cast(zp, 0, 2));
    EXPECT_GT(cp.off_boundary_mismatches, cp.compared / 10) << "z-pass should be wrong here";
    for (ModeChoice m : {ModeChoice::zfail, ModeChoice::automatic}) {
        o.mode = m;
        const Frame zf = render_frame(scene, o);
        const Comparison cf = caster.compare(zf, 0, caster.cast(zf, 0, 2));
        EXPECT_EQ(cf.off_boundary_mismatches, 0u) << mode_name(m);
        EXPECT_GT(cf.shadowed, cf.compared / 2)
            << "most of what the camera sees is in the slab's shadow";
        EXPECT_GE(zf.lights[0].zfail_volumes, 1) << mode_name(m);
    }
}

TEST(Render, NearPlaneTestIsConservativeAndNotAlwaysTrue) {
    const Scene far_cam = model_on_ground(SV_MODELS_DIR "/character_1344.glb");
    const std::vector<SceneLight> lights = three_lights(far_cam);
    int safe = 0;
    for (const SceneLight &l : lights)
        safe += !near_plane_may_be_shadowed(far_cam.camera, 1.25, far_cam.surfaces[0], l);
    EXPECT_EQ(safe, 3);
    /* A directional light from behind the camera: the camera's near
     * rectangle is not in the character's shadow; from in front of it,
     * with the character between, it may be. */
    Camera c = far_cam.camera;
    SceneLight sun;
    sun.kind = LightKind::directional;
    sun.direction = {c.target.x - c.eye.x, c.target.y - c.eye.y, c.target.z - c.eye.z};
    EXPECT_FALSE(near_plane_may_be_shadowed(c, 1.25, far_cam.surfaces[0], sun));
    sun.direction = {-sun.direction.x, -sun.direction.y, -sun.direction.z};
    EXPECT_TRUE(near_plane_may_be_shadowed(c, 1.25, far_cam.surfaces[0], sun));
}

TEST(Render, MesaDrawsTheSameStencil) {
    Scene scene = model_on_ground(SV_MODELS_DIR "/character_1344.glb");
    scene.lights = three_lights(scene);
    validate_scene(scene);
    for (ModeChoice m : {ModeChoice::zpass, ModeChoice::zfail}) {
        RenderOptions o;
        o.width = kW, o.height = kH, o.mode = m;
        const Frame f = render_frame(scene, o);
        std::string renderer, note;
        const std::vector<GlComparison> g = compare_with_mesa(scene, f, &renderer, &note);
        if (g.empty()) {
            std::printf("NOTE: %s\n", note.c_str());
            GTEST_SKIP() << note;
        }
        ASSERT_EQ(g.size(), f.lights.size());
        for (std::size_t li = 0; li < g.size(); li++) {
            EXPECT_EQ(g[li].other, 0u) << mode_name(m) << " light " << li;
            /* Differences only where the two rasterisers' rounding meets:
             * a tiny fraction of the frame. */
            EXPECT_LT(g[li].differing, (uint64_t)(kW * kH / 500))
                << mode_name(m) << " light " << li;
            EXPECT_EQ(g[li].differing, g[li].on_edge + g[li].depth_tie + g[li].other);
        }
    }
}

TEST(Render, DifferenceClassifierFindsARealDifference) {
    /* A stencil with a pixel flipped far from any volume edge is "other". */
    Scene scene = model_on_ground(SV_MODELS_DIR "/character_1344.glb");
    scene.lights = three_lights(scene);
    RenderOptions o;
    o.width = kW, o.height = kH;
    const Frame f = render_frame(scene, o);
    std::vector<uint8_t> theirs = f.lights[0].stencil;
    const std::size_t corner = 2 * (std::size_t)kW + 2; /* sky: no volume there */
    theirs[corner] ^= 1;
    const GlComparison g = classify_differences(scene, f, 0, f.lights[0].stencil, theirs, {});
    EXPECT_EQ(g.differing, 1u);
    EXPECT_EQ(g.other, 1u);
    EXPECT_EQ(g.cls[corner], 3);
}

TEST(Render, PngsDecodeToWhatWasWritten) {
    Scene scene = model_on_ground(SV_MODELS_DIR "/character_1344.glb");
    scene.lights = three_lights(scene);
    RenderOptions o;
    o.width = 64, o.height = 48;
    const Frame f = render_frame(scene, o);
    Image shaded(f.width, f.height);
    shaded.rgb = f.rgb;
    char dir[] = "/tmp/sv_render_png_XXXXXX";
    ASSERT_NE(mkdtemp(dir), nullptr);
    const std::string path = std::string(dir) + "/shaded.png";
    write_png(path, shaded);
    int w = 0, h = 0, n = 0;
    unsigned char *px = stbi_load(path.c_str(), &w, &h, &n, 3);
    ASSERT_NE(px, nullptr);
    EXPECT_EQ(w, 64);
    EXPECT_EQ(h, 48);
    EXPECT_EQ(0, std::memcmp(px, shaded.rgb.data(), shaded.rgb.size()));
    stbi_image_free(px);
    const Image panels = side_by_side({stencil_image(f.lights[0].stencil, shaded), shaded});
    EXPECT_EQ(panels.width, 64 * 2 + 4);
    std::remove(path.c_str());
    rmdir(dir);
    EXPECT_THROW(write_png("/nonexistent-dir/x.png", shaded), std::runtime_error);
}

TEST(Render, ShadedImageIsLitAndShadowed) {
    /* The picture itself: the ground in a light's shadow is darker than
     * the ground outside it. */
    Scene scene = model_on_ground(SV_MODELS_DIR "/character_1344.glb");
    scene.lights = {three_lights(scene)[2]};
    RenderOptions o;
    o.width = kW, o.height = kH;
    const Frame f = render_frame(scene, o);
    double lit = 0, shadow = 0;
    int nl = 0, ns = 0;
    for (std::size_t i = 0; i < f.target.ids.size(); i++) {
        int s, t;
        if (f.target.ids[i] < 0) continue;
        f.decode_id(f.target.ids[i], s, t);
        if (!scene.surfaces[(std::size_t)s].ground) continue;
        const double y = f.rgb[3 * i] + f.rgb[3 * i + 1] + f.rgb[3 * i + 2];
        if (f.lights[0].stencil[i])
            shadow += y, ns++;
        else
            lit += y, nl++;
    }
    ASSERT_GT(ns, 0);
    ASSERT_GT(nl, 0);
    EXPECT_LT(shadow / ns, 0.6 * (lit / nl));
}

TEST(Render, TruthChecksTheDepthPassWithItsOwnRays) {
    /* The truth's own camera rays agree with the depth pass on at least one
     * in 16 of the pixels off every edge of the depth pass; a depth pass
     * that shows the wrong triangle over a patch is caught, and fails the
     * comparison off the boundary. */
    Scene scene = model_on_ground(SV_MODELS_DIR "/character_1344.glb");
    scene.lights = three_lights(scene);
    RenderOptions opt;
    opt.width = kW;
    opt.height = kH;
    Frame f = render_frame(scene, opt);
    uint64_t off_edges = 0;
    for (int y = 0; y < kH; y++) {
        for (int x = 0; x < kW; x++) {
            const int32_t id = f.target.ids[(std::size_t)y * kW + x];
            bool same = id >= 0;
            for (int dy = -1; dy <= 1 && same; dy++) {
                for (int dx = -1; dx <= 1 && same; dx++) {
                    const int nx = x + dx, ny = y + dy;
                    if (nx < 0 || ny < 0 || nx >= kW || ny >= kH) continue;
                    same = f.target.ids[(std::size_t)ny * kW + nx] == id;
                }
            }
            off_edges += same;
        }
    }
    const TruthCaster caster(scene);
    const Truth t = caster.cast(f, 0, 2);
    const Comparison c = caster.compare(f, 0, t);
    EXPECT_GE(c.primary_checked * 16 + 16 * 16, off_edges) << "fewer than 1 in 16 checked";
    EXPECT_GT(c.primary_checked, 0u);
    EXPECT_EQ(c.primary_disagreements, 0u);
    EXPECT_EQ(c.off_boundary_mismatches, 0u);
    /* The depth pass made wrong: an 8 x 8 patch of the character shows the
     * ground's first triangle (8: the sanitizer build's 128 x 104 frame
     * shows the character too small for larger patches). */
    const int32_t ground_id = f.surface_first_id.back();
    int changed = 0;
    for (std::size_t i = 0; i < f.target.ids.size() && changed < 64; i++) {
        const int x = (int)(i % kW), y = (int)(i / kW);
        if (x + 8 > kW || y + 8 > kH) continue;
        bool character = true;
        for (int dy = 0; dy < 8 && character; dy++) {
            for (int dx = 0; dx < 8 && character; dx++) {
                const int32_t id = f.target.ids[i + (std::size_t)dy * kW + dx];
                character = id >= 0 && id < ground_id;
            }
        }
        if (!character) continue;
        for (int dy = 0; dy < 8; dy++) {
            for (int dx = 0; dx < 8; dx++) f.target.ids[i + (std::size_t)dy * kW + dx] = ground_id;
        }
        changed = 64;
    }
    ASSERT_EQ(changed, 64) << "no 8 x 8 patch of the character in view";
    const Truth bad = caster.cast(f, 0, 2);
    const Comparison cb = caster.compare(f, 0, bad);
    EXPECT_GT(cb.primary_disagreements, 0u);
    EXPECT_GE(cb.off_boundary_mismatches, cb.primary_disagreements);
}

TEST(Render, RefusesFramesBeyondTheBoundInTheLibrary) {
    /* The CLIs check --size; the library checks too (the rasteriser's
     * edge functions are proved for 8192 per side). */
    const Scene scene = model_on_ground(std::string(SV_MODELS_DIR) + "/character_1344.glb");
    for (const auto &[w, h] : {std::pair{kMaxFrameSide + 1, 16}, std::pair{16, 0},
                               std::pair{-3, 16}, std::pair{kMaxFrameSide, kMaxFrameSide + 1}}) {
        RenderOptions opt;
        opt.width = w;
        opt.height = h;
        EXPECT_THROW(render_frame(scene, opt), std::invalid_argument) << w << "x" << h;
    }
}

TEST(Scene, BadInputIsRefusedClearly) {
    EXPECT_THROW(parse_light("point:1,2"), SceneError);
    EXPECT_THROW(parse_light("point:nan,0,0"), SceneError);
    EXPECT_THROW(parse_light("point:0,inf,0"), SceneError);
    EXPECT_THROW(parse_light("point:0,1,0,-3"), SceneError);
    EXPECT_THROW(parse_light("spot:0,1,0,0,-1,0,50,40"), SceneError);
    EXPECT_THROW(parse_light("spot:0,1,0,0,0,0,10,40"), SceneError);
    EXPECT_THROW(parse_light("dir:0,0,0"), SceneError);
    EXPECT_THROW(parse_light("laser:1,2,3"), SceneError);
    EXPECT_THROW(parse_camera("eye=0,1,2"), SceneError);
    EXPECT_THROW(parse_camera("eye=0,1,2,target=0,1,x"), SceneError);
    EXPECT_THROW(parse_camera("eye=0,1,2,target=0,0,0,fov=180"), SceneError);
    EXPECT_THROW(parse_model_placement("a.glb@1,2"), SceneError);
    EXPECT_THROW(parse_model_placement("a.glb@1,2,3,0,0"), SceneError);
    const Camera c = parse_camera("eye=0,1,2,target=0,0.5,0,fov=30,near=0.2");
    EXPECT_EQ(c.eye.z, 2);
    EXPECT_EQ(c.target.y, 0.5);
    EXPECT_EQ(c.fov_y_degrees, 30);
    EXPECT_EQ(c.near_distance, 0.2);
    EXPECT_EQ(parse_camera("eye=0,1,2,target=0,0,0").near_distance, 0) << "not given: to be fitted";
    const ModelPlacement m = parse_model_placement("dir@x/a.glb@1,2,3,90,2");
    EXPECT_EQ(m.path, "dir@x/a.glb");
    EXPECT_EQ(m.placement.yaw_degrees, 90);
    EXPECT_EQ(m.placement.scale, 2);
    EXPECT_EQ(m.animation, "") << "no ':': the file's first animation";
    /* An animation per file (issue 30): after the last ':', a '@' in it is its own. */
    const ModelPlacement run = parse_model_placement("a.glb@1,2,3:Run@2");
    EXPECT_EQ(run.path, "a.glb");
    EXPECT_EQ(run.placement.translation.z, 3);
    EXPECT_EQ(run.animation, "Run@2");
    EXPECT_EQ(parse_model_placement("a.glb:3").animation, "3");
    EXPECT_EQ(parse_model_placement("a.glb:3").path, "a.glb");
    /* A file name with a ':' is written with a ':' after it. */
    const ModelPlacement colon = parse_model_placement("c:/x:y.glb@0,1,0:");
    EXPECT_EQ(colon.path, "c:/x:y.glb");
    EXPECT_EQ(colon.placement.translation.y, 1);
    EXPECT_EQ(colon.animation, "");
    EXPECT_EQ(parse_model_placement("c:/x.glb").path, "c") << "the ':' rule, as documented";
    EXPECT_THROW(parse_model_placement(":walk"), SceneError);
    EXPECT_THROW(parse_model_placement("a.glb@1,2:walk"), SceneError);
    const SceneLight l = parse_light("dir:0,-2,0");
    EXPECT_DOUBLE_EQ(l.direction.y, -1.0);
    EXPECT_TRUE(parse_light("spot:auto").placed_automatically);
    EXPECT_THROW(parse_light("laser:auto"), SceneError);

    Scene scene = model_on_ground(SV_MODELS_DIR "/character_1344.glb");
    SceneLight at_vertex;
    at_vertex.position = {scene.surfaces[0].prepared.positions[0],
                          scene.surfaces[0].prepared.positions[1],
                          scene.surfaces[0].prepared.positions[2]};
    scene.lights = {at_vertex};
    EXPECT_THROW(validate_scene(scene), SceneError);
    scene.lights.clear();
    scene.camera.target = scene.camera.eye;
    EXPECT_THROW(validate_scene(scene), SceneError);
    EXPECT_THROW(add_model(scene, SV_MODELS_DIR "/character_1344.glb", {{0, 0, 0}, 0, 0}),
                 SceneError);
    EXPECT_THROW(add_model(scene, SV_MODELS_DIR "/character_1344.glb", {{NAN, 0, 0}, 0, 1}),
                 SceneError);
}

TEST(Scene, NotesALightInsideAClosedSurface) {
    Scene scene = model_on_ground(SV_MODELS_DIR "/character_1344.glb");
    SceneLight inside;
    inside.position = {0, 1.2, 0}; /* in the torso */
    scene.lights = {inside};
    validate_scene(scene);
    bool noted = false;
    for (const std::string &n : scene.notes)
        noted |= n.find("inside the closed surface") != std::string::npos;
    EXPECT_TRUE(noted);
    /* And the picture is still right: everything outside is in shadow. */
    RenderOptions o;
    o.width = kW / 2, o.height = kH / 2;
    o.mode = ModeChoice::zfail;
    const Frame f = render_frame(scene, o);
    const TruthCaster caster(scene);
    const Comparison c = caster.compare(f, 0, caster.cast(f, 0, 2));
    EXPECT_EQ(c.off_boundary_mismatches, 0u);
    EXPECT_EQ(c.lit, 0u);
}

} // namespace
