/*
 * The GLSL judge of seed 002's vertex program (issue 31,
 * src/judge/mesa_extrude.h): the program as a GLSL vertex shader on Mesa's
 * llvmpipe, read back by transform feedback, against the CPU emulation
 * (sv_extrude_c_ref) on the bundled character's shadow mesh and on every
 * model of ../shared/models, under a ranged point light, one without range
 * and a directional light.
 *
 * What may differ, and by how much: GLSL's inversesqrt is not correctly
 * rounded (2 ULP allowed) where the emulation divides by a correctly
 * rounded sqrt, and llvmpipe may fuse the mad. So
 *   - a kept vertex is (p, 1) on both sides, bit for bit;
 *   - a vertex extruded to infinity is (p * w - l, 0): products by w = 1 or
 *     0 are exact, so the subtraction is the CPU's, bit for bit;
 *   - a vertex extruded to a finite point differs by at most a few ULP of
 *     the range (the length 1/inv and the unit vector each carry the
 *     rsq's error);
 *   - the facing decision (dot < 0) may differ only where the dot is within
 *     a few ULP of 0: a face edge-on to the light.
 * The test asserts those bounds and prints the largest differences.
 * Where OSMesa is built in, no context is a failure, never a skip.
 *
 * Copyright (C) 2026 the shadowvol authors. LGPL-2.1-or-later.
 */
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <string>
#include <vector>

#include "mesa_extrude.h"
#include "shadowvol_extrude.h"
#include "shadowvol_mesh.h"
#include "model_surfaces.h"
#include "test_conditions.h"

namespace {

using namespace sv;

bool same_bits(float a, float b) {
    uint32_t x = 0, y = 0;
    std::memcpy(&x, &a, sizeof x);
    std::memcpy(&y, &b, sizeof y);
    return x == y;
}

struct Differences {
    uint64_t vertices = 0, kept_or_infinite = 0, finite = 0;
    uint64_t bits_differ = 0;    /* kept or infinite vertices whose bits differ */
    uint64_t facing_differs = 0; /* one side kept the vertex, the other moved it */
    double facing_max_dot = 0;   /* |dot| of the emulation at those vertices */
    double finite_max_error = 0; /* largest |GLSL - CPU| of a finite vertex, per unit range */
};

/* The facing dot of vertex I as the emulation computes it (its inputs'
 * expression, in float), to see how close to 0 a disagreement lies. */
double emulated_dot(const float *v, const sv_extrude_light &l) {
    const Vec4 &L = l.position;
    const float dx = v[0] * L.w - L.x, dy = v[1] * L.w - L.y, dz = v[2] * L.w - L.z;
    const float len2 = (dx * dx + dy * dy) + dz * dz;
    const float inv = 1.0f / std::sqrt(len2);
    return (double)((v[3] * (dx * inv) + v[4] * (dy * inv)) + v[5] * (dz * inv));
}

/* Runs both on STREAM; false when no context (and the reason in *WHY). */
bool compare(const std::vector<float> &stream, const sv_extrude_light &light, Differences &d,
             std::string *why, std::string *renderer) {
    const int n = (int)(stream.size() / SV_EXTRUDE_STREAM_FLOATS);
    std::vector<Vec4> gpu, cpu((std::size_t)n);
    if (!gl::mesa_extrude(stream.data(), n, light, gpu, why, renderer)) return false;
    sv_extrude_c_ref(stream.data(), n, &light, cpu.data());
    for (int i = 0; i < n; i++) {
        const Vec4 &g = gpu[(std::size_t)i], &c = cpu[(std::size_t)i];
        const float *v = &stream[(std::size_t)i * SV_EXTRUDE_STREAM_FLOATS];
        d.vertices++;
        const bool c_kept = c.w == 1.0f && c.x == v[0] && c.y == v[1] && c.z == v[2];
        const bool g_kept = g.w == 1.0f && g.x == v[0] && g.y == v[1] && g.z == v[2];
        if (c_kept != g_kept && !(c.w == 1.0f && g.w == 1.0f && light.range > 0)) {
            d.facing_differs++;
            d.facing_max_dot = std::max(d.facing_max_dot, std::fabs(emulated_dot(v, light)));
            continue;
        }
        if (c.w == 0.0f || c_kept) {
            d.kept_or_infinite++;
            d.bits_differ += !(same_bits(g.x, c.x) && same_bits(g.y, c.y) && same_bits(g.z, c.z) &&
                               same_bits(g.w, c.w));
        } else {
            d.finite++;
            const double e = std::max({std::fabs((double)g.x - c.x), std::fabs((double)g.y - c.y),
                                       std::fabs((double)g.z - c.z)});
            d.finite_max_error = std::max(d.finite_max_error, e / light.range);
        }
    }
    return true;
}

/* The lights around a STREAM's positions: a point light with a range
 * beyond them (most extruded vertices land on its sphere), the same point
 * without range, a directional light. */
std::vector<sv_extrude_light> lights_for(const std::vector<float> &stream) {
    float lo[3] = {1e30f, 1e30f, 1e30f}, hi[3] = {-1e30f, -1e30f, -1e30f};
    for (std::size_t v = 0; v + SV_EXTRUDE_STREAM_FLOATS <= stream.size();
         v += SV_EXTRUDE_STREAM_FLOATS) {
        for (std::size_t c = 0; c < 3; c++) {
            lo[c] = std::min(lo[c], stream[v + c]);
            hi[c] = std::max(hi[c], stream[v + c]);
        }
    }
    const float size = std::max({hi[0] - lo[0], hi[1] - lo[1], hi[2] - lo[2]});
    const Vec4 point{hi[0] + 0.5f * size, hi[1] + size, hi[2] + 0.7f * size, 1.0f};
    return {{point, 3.0f * size}, {point, 0.0f}, {{0.3f, 0.9f, 0.2f, 0.0f}, 0.0f}};
}

/* Every surface's shadow mesh of the model at PATH (the caster rule: open
 * shells two-sided), one stream. */
std::vector<float> model_stream(const std::string &path) {
    std::vector<float> stream;
    for (const PreparedSurface &s : svtest::prepared_surfaces(path)) {
        const ShadowMesh m = build_shadow_mesh(s, CasterRule::automatic);
        stream.insert(stream.end(), m.stream.begin(), m.stream.end());
    }
    return stream;
}

void expect_bounds(const Differences &d, const std::string &what) {
    EXPECT_EQ(d.bits_differ, 0u) << what << ": kept or infinite vertices differ";
    /* A few ULP of the range: inversesqrt's 2 ULP, carried by the length
     * and the unit vector, and a fused mad. */
    EXPECT_LE(d.finite_max_error, 1e-6) << what;
    /* Facing flips only at a face edge-on to the light. */
    EXPECT_LE(d.facing_differs, d.vertices / 1000 + 1) << what;
    if (d.facing_differs) {
        EXPECT_LT(d.facing_max_dot, 1e-5) << what;
    }
}

/* Skips (exit 77) only where OSMesa is not built in. */
#define SV_GLSL_JUDGE_OR_SKIP(ok, why)                                                             \
    if (!(ok)) {                                                                                   \
        ASSERT_FALSE(gl::mesa_extrude_available_at_build()) << "OSMesa is built in: " << (why);    \
        GTEST_SKIP() << (why);                                                                     \
    }

void report(const Differences &d, const std::string &what, const std::string &renderer) {
    std::printf("[ glsl     ] %s (%s): %llu vertices; kept or infinite %llu, bits differ %llu; "
                "finite %llu, largest difference %.3g of the range; facing differs at %llu "
                "(|dot| <= %.3g)\n",
                what.c_str(), renderer.c_str(), (unsigned long long)d.vertices,
                (unsigned long long)d.kept_or_infinite, (unsigned long long)d.bits_differ,
                (unsigned long long)d.finite, d.finite_max_error,
                (unsigned long long)d.facing_differs, d.facing_max_dot);
}

/* One line a light: the model's name, and the differences. */
void check_model(const std::string &path) {
    const std::vector<float> stream = model_stream(path);
    for (const sv_extrude_light &l : lights_for(stream)) {
        Differences d;
        std::string why, renderer;
        const bool ok = compare(stream, l, d, &why, &renderer);
        SV_GLSL_JUDGE_OR_SKIP(ok, why);
        const std::string what = path.substr(path.rfind('/') + 1) +
                                 (l.position.w == 0.0f ? ", directional"
                                  : l.range > 0        ? ", point with range"
                                                       : ", point without range");
        report(d, what, renderer);
        expect_bounds(d, what);
        EXPECT_EQ(d.vertices, stream.size() / SV_EXTRUDE_STREAM_FLOATS);
    }
}

TEST(MesaExtrude, CharacterAgreesWithTheEmulationWithinGlslsRounding) {
    check_model(SV_MODELS_DIR "/character_1344.glb");
}

TEST(MesaExtrude, NoVerticesAndTheLightOnAVertex) {
    std::vector<Vec4> out{{1, 2, 3, 4}};
    std::string why;
    const sv_extrude_light l{{1, 2, 3, 1}, 5};
    const bool ok = gl::mesa_extrude(nullptr, 0, l, out, &why);
    SV_GLSL_JUDGE_OR_SKIP(ok, why);
    EXPECT_TRUE(out.empty());
    /* The light on the vertex: kept in place by both (not NaN). */
    const std::vector<float> one = {1, 2, 3, 0, 1, 0};
    ASSERT_TRUE(gl::mesa_extrude(one.data(), 1, l, out, &why)) << why;
    ASSERT_EQ(out.size(), 1u);
    EXPECT_EQ(out[0].x, 1.0f);
    EXPECT_EQ(out[0].y, 2.0f);
    EXPECT_EQ(out[0].z, 3.0f);
    EXPECT_EQ(out[0].w, 1.0f);
    EXPECT_THROW(gl::mesa_extrude(one.data(), -1, l, out, &why), std::invalid_argument);
}

TEST(MesaExtrudeSharedModels, EveryModelAgreesWithTheEmulationWithinGlslsRounding) {
    const std::vector<std::string> models = svtest::seed_model_paths("SharedModels");
    ASSERT_FALSE(models.empty());
    for (const std::string &path : models) check_model(path);
}

} // namespace
