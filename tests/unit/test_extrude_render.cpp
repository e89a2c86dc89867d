/*
 * Seed 002's volumes rendered (issue 31, `--volume extrude`,
 * src/render/extruded_volumes.h), and the proof: for closed meshes
 * (and open ones through the general caster rule) with receivers inside
 * the light's range, the extruded volume's shadow mask equals the paper's
 * pixel for pixel off shadow boundaries, and both judges (ray truth, Mesa)
 * agree with it, on the bundled character, every model of ../shared/models
 * and ../shared/models/open, and the demo scene.
 *
 * Where the finite extrusion may differ from the infinite one: the seed
 * moves an extruded vertex to the light's sphere (clamp0(range - |vLP|)),
 * and its far cap is the extruded faces, flat triangles whose corners lie
 * on that sphere: chords, inside it. A receiver point P is in both volumes
 * or in neither whenever |P - L| is below the far cap's nearest distance
 * from the light d (every light ray meets the far cap, and the side quads'
 * far edges, which are the far cap's edges, at d or beyond): the finite
 * volume along the ray through P reaches past P exactly where the infinite
 * one holds P. At |P - L| >= d (a shell of width at most the chords'
 * sagitta below the range) they may differ, and only there the test
 * allows it, counting how many did.
 *
 * Copyright (C) 2026 the shadowvol authors. LGPL-2.1-or-later.
 */
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <string>
#include <vector>

#include "extruded_volumes.h"
#include "frame.h"
#include "gl_compare.h"
#include "mesa_stencil.h"
#include "model_surfaces.h"
#include "sequence.h"
#include "shadowvol_scene.h"
#include "test_conditions.h"
#include "truth.h"

namespace {

using namespace sv;
using namespace sv::render;

/* Fixed (no SV_TEST_SMALL_FRAMES): already the 160x120. */
constexpr int kW = 160, kH = 120;

RenderOptions options(VolumeSource v) {
    RenderOptions o;
    o.width = kW;
    o.height = kH;
    o.threads = 0;
    o.volume = v;
    o.stencil_saturate = v == VolumeSource::extrude; /* the seed's state */
    return o;
}

struct Vec3 {
    double x, y, z;
};
Vec3 sub3(Vec3 a, Vec3 b) { return {a.x - b.x, a.y - b.y, a.z - b.z}; }
double dot3(Vec3 a, Vec3 b) { return a.x * b.x + a.y * b.y + a.z * b.z; }
Vec3 axpy(Vec3 p, double t, Vec3 d) { return {p.x + t * d.x, p.y + t * d.y, p.z + t * d.z}; }
double dist3(Vec3 a, Vec3 b) { return std::sqrt(dot3(sub3(a, b), sub3(a, b))); }

/* The point of triangle ABC nearest to P (Ericson, Real-Time Collision
 * Detection, 5.1.5), for degenerate triangles too. */
Vec3 closest_on_triangle(Vec3 p, Vec3 a, Vec3 b, Vec3 c) {
    const Vec3 ab = sub3(b, a), ac = sub3(c, a), ap = sub3(p, a);
    const double d1 = dot3(ab, ap), d2 = dot3(ac, ap);
    if (d1 <= 0 && d2 <= 0) return a;
    const Vec3 bp = sub3(p, b);
    const double d3 = dot3(ab, bp), d4 = dot3(ac, bp);
    if (d3 >= 0 && d4 <= d3) return b;
    const double vc = d1 * d4 - d3 * d2;
    if (vc <= 0 && d1 >= 0 && d3 <= 0 && d1 - d3 > 0) return axpy(a, d1 / (d1 - d3), ab);
    const Vec3 cp = sub3(p, c);
    const double d5 = dot3(ab, cp), d6 = dot3(ac, cp);
    if (d6 >= 0 && d5 <= d6) return c;
    const double vb = d5 * d2 - d1 * d6;
    if (vb <= 0 && d2 >= 0 && d6 <= 0 && d2 - d6 > 0) return axpy(a, d2 / (d2 - d6), ac);
    const double va = d3 * d6 - d5 * d4;
    if (va <= 0 && d4 - d3 >= 0 && d5 - d6 >= 0 && (d4 - d3) + (d5 - d6) > 0) {
        return axpy(b, (d4 - d3) / ((d4 - d3) + (d5 - d6)), sub3(c, b));
    }
    const double sum = va + vb + vc;
    if (!(sum > 0)) { /* a degenerate triangle: its nearest corner or edge */
        Vec3 best = a;
        for (const Vec3 &q : {b, c}) {
            if (dist3(p, q) < dist3(p, best)) best = q;
        }
        return best;
    }
    return axpy(axpy(a, vb / sum, ab), vc / sum, ac);
}

/* The far cap's nearest distance from the light (see above): over every
 * triangle of the light's seed volumes whose three corners are extruded to
 * finite points. Infinity where nothing is extruded to a finite point. */
double far_cap_distance(const Frame &f, int li) {
    const LightFrame &lf = f.lights[(std::size_t)li];
    const Vec3 L{lf.light.position.x, lf.light.position.y, lf.light.position.z};
    double d = std::numeric_limits<double>::infinity();
    for (const Volume &vol : lf.volumes) {
        if (vol.extruded.empty()) continue;
        for (std::size_t i = 0; i + 2 < vol.indices.size(); i += 3) {
            Vec3 c[3];
            bool far = true;
            for (int k = 0; k < 3; k++) {
                const int v = vol.indices[i + (std::size_t)k];
                const Vec4 &e = vol.extruded[(std::size_t)(v >> 1)];
                far &= (v & 1) && e.w == 1.0f;
                c[k] = {e.x, e.y, e.z};
            }
            if (far) d = std::min(d, dist3(L, closest_on_triangle(L, c[0], c[1], c[2])));
        }
    }
    return d;
}

/* Per pixel: 1 where the seen point is at least D from light LI's position
 * (less a relative 1e-6 for the rounding of the vertices), where the seed's
 * finite volume may differ from the infinite one. */
std::vector<uint8_t> beyond_far_cap(const Scene &scene, const Frame &f, int li, double d) {
    std::vector<uint8_t> out((std::size_t)kW * kH, 0);
    if (!std::isfinite(d)) return out;
    const Vec3d &lp = f.lights[(std::size_t)li].light.position;
    for (int y = 0; y < f.height; y++) {
        for (int x = 0; x < f.width; x++) {
            const int32_t id = f.target.ids[(std::size_t)y * (std::size_t)f.width + (std::size_t)x];
            if (id < 0) continue;
            int si = 0, t = 0;
            f.decode_id(id, si, t);
            const Vec3d p = visible_point(f, scene, si, t, x, y);
            const double r = dist3({p.x, p.y, p.z}, {lp.x, lp.y, lp.z});
            out[(std::size_t)y * (std::size_t)f.width + (std::size_t)x] = r >= d * (1 - 1e-6);
        }
    }
    return out;
}

struct ProofCounts {
    uint64_t mask_differences = 0, allowed_differences = 0, truth_off_boundary = 0;
    uint64_t shadowed = 0, mesa_other = 0;
};

/* The proof on SCENE's lights (see the file's comment); WHAT names the
 * case. MESA: compare with Mesa too (fails where OSMesa is built but no
 * context comes up). */
ProofCounts expect_proof(const Scene &scene, const std::string &what, bool mesa) {
    const Frame paper = render_frame(scene, options(VolumeSource::silhouette));
    const Frame seed = render_frame(scene, options(VolumeSource::extrude));
    const TruthCaster caster(scene);
    ProofCounts total;
    for (int li = 0; li < (int)seed.lights.size(); li++) {
        const std::string at = what + ", light " + seed.lights[(std::size_t)li].light.describe();
        const Truth truth = caster.cast(seed, li, 0);
        const double d = far_cap_distance(seed, li);
        const std::vector<uint8_t> allowed = beyond_far_cap(scene, seed, li, d);
        if (std::isfinite(d)) {
            uint64_t n = 0;
            for (uint8_t x : allowed) n += x;
            std::printf("[ far cap  ] %s: nearest at %.4g of the range %.4g (%.4f); %llu pixels "
                        "beyond it\n",
                        at.c_str(), d, seed.lights[(std::size_t)li].light.range,
                        d / seed.lights[(std::size_t)li].light.range, (unsigned long long)n);
        }
        /* The seed's stencil where it may differ set to the truth's answer:
         * no other pixel may break the truth. */
        Frame judged = seed;
        std::vector<uint8_t> &st = judged.lights[(std::size_t)li].stencil;
        const std::vector<uint8_t> &a = paper.lights[(std::size_t)li].stencil;
        const std::vector<uint8_t> &b = seed.lights[(std::size_t)li].stencil;
        uint64_t differ = 0, allowed_differ = 0;
        for (std::size_t i = 0; i < st.size(); i++) {
            const bool d = (a[i] != 0) != (b[i] != 0);
            if (allowed[i]) {
                allowed_differ += d;
                if (truth.cls[i] == kTruthLit || truth.cls[i] == kTruthShadowed)
                    st[i] = truth.cls[i] == kTruthShadowed ? 1 : 0;
                continue;
            }
            /* Compared where the truth is (a lit or a shadowed point:
             * not the background, nor a point facing away from the light,
             * which no volume method lights). */
            if (truth.cls[i] != kTruthLit && truth.cls[i] != kTruthShadowed) continue;
            const int x = (int)(i % (std::size_t)kW), y = (int)(i / (std::size_t)kW);
            differ += d && !on_boundary(truth, kW, kH, x, y);
        }
        const Comparison c = caster.compare(judged, li, truth);
        EXPECT_EQ(c.off_boundary_mismatches, 0u)
            << at << ": the seed's volume against the truth, first at pixel "
            << (c.first_off_boundary.empty() ? -1 : c.first_off_boundary[0] % kW) << ","
            << (c.first_off_boundary.empty() ? -1 : c.first_off_boundary[0] / kW);
        const Comparison cp = caster.compare(paper, li, truth);
        EXPECT_EQ(differ, 0u) << at << ": the seed's mask against the paper's off boundaries"
                              << " (the paper's against the truth: " << cp.mismatches
                              << " mismatches, " << cp.off_boundary_mismatches
                              << " off boundaries; the seed's: " << c.mismatches << ", "
                              << c.boundary << " boundary pixels)";
        total.mask_differences += differ;
        total.allowed_differences += allowed_differ;
        total.truth_off_boundary += c.off_boundary_mismatches;
        total.shadowed += c.shadowed;
    }
    if (mesa) {
        std::string renderer, note;
        const std::vector<GlComparison> g = compare_with_mesa(scene, seed, &renderer, &note);
        if (g.empty()) {
            EXPECT_FALSE(gl::mesa_available_at_build()) << what << ": OSMesa is built in: " << note;
        } else {
            for (std::size_t li = 0; li < g.size(); li++) {
                EXPECT_EQ(g[li].other, 0u) << what << ", Mesa, light " << li;
                total.mesa_other += g[li].other;
            }
        }
    }
    std::printf("[ proof    ] %s: %llu shadowed pixels; masks differ off boundaries at %llu, "
                "beyond the far cap at %llu; truth off boundaries %llu; Mesa other %llu\n",
                what.c_str(), (unsigned long long)total.shadowed,
                (unsigned long long)total.mask_differences,
                (unsigned long long)total.allowed_differences,
                (unsigned long long)total.truth_off_boundary, (unsigned long long)total.mesa_other);
    return total;
}

Scene model_on_ground(const std::string &path) {
    Scene s;
    add_model(s, path, {});
    add_ground(s);
    s.camera = frame_camera(s, (double)kW / kH);
    return s;
}

/* A point light with a range that covers the receivers in view but ends
 * before the ground's far corners (the seed's finite extrusion, its far
 * cap in reach), one without a range, and a directional light. */
std::vector<SceneLight> seed_lights(const Scene &s) {
    SceneLight ranged = auto_light(s, LightKind::point);
    Vec3d lo, hi;
    s.bounds(lo, hi, false);
    const double dx = std::max(std::fabs(ranged.position.x - lo.x),
                               std::fabs(ranged.position.x - hi.x));
    const double dy = std::max(std::fabs(ranged.position.y - lo.y),
                               std::fabs(ranged.position.y - hi.y));
    const double dz = std::max(std::fabs(ranged.position.z - lo.z),
                               std::fabs(ranged.position.z - hi.z));
    ranged.range = 2.5 * std::sqrt(dx * dx + dy * dy + dz * dz);
    SceneLight unranged = auto_light(s, LightKind::point);
    unranged.range = 0;
    return {ranged, unranged, auto_light(s, LightKind::directional)};
}

TEST(ExtrudeRender, DegenerateQuadsAreSetUpAndRejectedAndCostNoFill) {
    Scene scene = model_on_ground(SV_MODELS_DIR "/character_1344.glb");
    scene.lights = seed_lights(scene);
    validate_scene(scene);
    const Frame paper = render_frame(scene, options(VolumeSource::silhouette));
    const Frame seed = render_frame(scene, options(VolumeSource::extrude));
    for (std::size_t li = 0; li < seed.lights.size(); li++) {
        const raster::PassCounters &p = paper.lights[li].stencil_counters;
        const raster::PassCounters &s = seed.lights[li].stencil_counters;
        std::printf("[ set-up   ] light %zu: paper %llu triangles (%llu zero-area), %llu pixels; "
                    "seed %llu triangles (%llu zero-area), %llu pixels\n",
                    li, (unsigned long long)p.triangles, (unsigned long long)p.triangles_degenerate,
                    (unsigned long long)p.pixels_tested, (unsigned long long)s.triangles,
                    (unsigned long long)s.triangles_degenerate,
                    (unsigned long long)s.pixels_tested);
        /* The character's volume: its 1344 faces and one quad per edge,
         * 4F triangles, and the ground's paper volume beside it. */
        EXPECT_GE(s.triangles, 4u * 1344u);
        EXPECT_GT(s.triangles, p.triangles);
        /* The quads that stay degenerate, most of the 2016 edges' 4032
         * triangles, are rejected as zero-area where set-up meets them in
         * view (outside the view they are rejected first). */
        EXPECT_GT(s.triangles_degenerate + s.triangles_outside,
                  p.triangles_degenerate + p.triangles_outside + 2000u);
    }
}

TEST(ExtrudeRender, BundledCharacterEqualsThePapersVolumeAndTheJudges) {
    Scene scene = model_on_ground(SV_MODELS_DIR "/character_1344.glb");
    scene.lights = seed_lights(scene);
    validate_scene(scene);
    const ProofCounts c = expect_proof(scene, "character", true);
    EXPECT_GT(c.shadowed, 0u);
}

TEST(ExtrudeRenderSharedModels, EveryModelEqualsThePapersVolumeAndTheJudges) {
    const std::vector<std::string> models = svtest::seed_model_paths("SharedModels");
    EXPECT_FALSE(models.empty()) << "no .glb in " << svtest::shared_models_dir();
    for (const std::string &path : models) {
        Scene scene = model_on_ground(path);
        scene.lights = seed_lights(scene);
        validate_scene(scene);
        const ProofCounts c = expect_proof(scene, path.substr(path.rfind('/') + 1), true);
        EXPECT_GT(c.shadowed, 0u) << path;
    }
}

TEST(ExtrudeRender, DemoSceneEqualsThePapersVolumeAndTheJudges) {
    SequenceOptions so;
    so.file = SV_DEMO_SCENE;
    so.aspect = (double)kW / kH;
    SceneSequence seq(so);
    seq.set_time(0.0);
    validate_scene(seq.scene());
    const ProofCounts c = expect_proof(seq.scene(), "demo scene", true);
    /* Its point light's range ends inside the terrain: the finite
     * extrusion's far cap is in view there. */
    EXPECT_GT(c.allowed_differences, 0u);
    EXPECT_GT(c.shadowed, 0u);
}

} // namespace
