/*
 * The shading pass of shading_pass.h.
 *
 * Copyright (C) 2026 the shadowvol authors. LGPL-2.1-or-later.
 */
#include "shading_pass.h"

#include <algorithm>
#include <cmath>
#include <vector>

#include "frame_math.h"
#include "pass_bins.h"

namespace sv::render {

using namespace detail;

namespace {

/* A light's constants for the lighting pass, worked out once a frame. */
struct LightTerms {
    const SceneLight *l;
    double cos_outer, cos_inner, inv_range2;
    explicit LightTerms(const SceneLight &light)
        : l(&light), cos_outer(std::cos(light.outer_degrees * kPi / 180.0)),
          cos_inner(std::cos(light.inner_degrees * kPi / 180.0)),
          inv_range2(light.range > 0 ? 1.0 / (light.range * light.range) : 0) {}
};

/* Radiance factor of light T at P with unit normal N (Lambert,
 * attenuation, cone), without the colour. */
double irradiance(const LightTerms &t, const Vec3d &p, const Vec3d &n) {
    const SceneLight &l = *t.l;
    if (l.kind == LightKind::directional) {
        return l.intensity * std::max(0.0, -dot(n, l.direction));
    }
    const Vec3d d = sub(l.position, p);
    const double dist2 = dot(d, d);
    const Vec3d dir = mul(d, 1.0 / std::sqrt(dist2));
    double a = l.intensity * std::max(0.0, dot(n, dir)) / dist2;
    if (l.range > 0) {
        /* KHR_lights_punctual's recommended window. */
        const double q = dist2 * t.inv_range2;
        const double w = std::clamp(1.0 - q * q, 0.0, 1.0);
        a *= w * w;
    }
    if (l.kind == LightKind::spot) {
        const double c = -dot(dir, l.direction);
        const double s = t.cos_inner > t.cos_outer
                             ? std::clamp((c - t.cos_outer) / (t.cos_inner - t.cos_outer), 0.0, 1.0)
                             : (c >= t.cos_outer ? 1.0 : 0.0);
        a *= s * s;
    }
    return a;
}

/* Linear radiance to an 8-bit display value: a soft shoulder 1 - e^-1.2x
 * (so several lights overlapping do not wash out one light's shadow) and
 * gamma 2.2, through a table of 1/1024 steps up to 8 (a pow and an exp per
 * channel and pixel were most of the lighting pass). */
uint8_t to_display8(double linear) {
    constexpr int kSteps = 1024, kMax = 8;
    static const std::vector<uint8_t> table = [] {
        std::vector<uint8_t> t(kSteps * kMax + 1);
        for (int i = 0; i <= kSteps * kMax; i++) {
            const double v = 1.0 - std::exp(-1.2 * i / kSteps);
            t[(std::size_t)i] = (uint8_t)std::lround(255.0 * std::pow(v, 1.0 / 2.2));
        }
        return t;
    }();
    const double c = std::clamp(linear, 0.0, (double)kMax);
    /* c >= 0: truncating c * kSteps + 0.5 rounds to the nearest step (a
     * tie of the last bit going up is as good as down here), without a
     * libm call per channel. */
    return table[(std::size_t)(c * kSteps + 0.5)]; // NOLINT(bugprone-incorrect-roundings)
}

} // namespace

ShadingResult shading_pass(const Scene &scene, const Frame &f,
                           const std::vector<const uint8_t *> &lit_facing, double ambient) {
    ShadingResult result;
    const uint64_t k0 = ticks();
    const int width = f.width, height = f.height;
    const int num_surfaces = (int)scene.surfaces.size(), num_lights = (int)f.lights.size();
    const int num_bands = band_count(height);
    result.rgb.assign((std::size_t)width * height * 3, 0);
    std::vector<LightTerms> terms;
    terms.reserve((std::size_t)num_lights);
    for (int li = 0; li < num_lights; li++) terms.emplace_back(f.lights[(std::size_t)li].light);
    parallel(num_bands, [&](int b) {
        const raster::RowBand band = band_rows(b, height);
        for (int py = band.row_begin; py < band.row_end; py++) {
            for (int px = 0; px < width; px++) {
                const std::size_t i = (std::size_t)py * width + px;
                uint8_t *out = &result.rgb[3 * i];
                const int32_t id = f.target.ids[i];
                if (id < 0) {
                    const double sky = 0.30 + 0.25 * (1.0 - (double)py / height);
                    out[0] = to_display8(sky * 0.55), out[1] = to_display8(sky * 0.65),
                    out[2] = to_display8(sky);
                    continue;
                }
                int si, t;
                f.decode_id(id, si, t);
                const SceneSurface &s = scene.surfaces[(std::size_t)si];
                const Vec3d P = visible_point(f, scene, si, t, px, py);
                const Plane &pl = s.prepared.planes[(std::size_t)t];
                Vec3d n{pl.a, pl.b, pl.c};
                const bool front_seen = dot(n, sub(scene.camera.eye, P)) > 0;
                double rgb[3] = {ambient, ambient, ambient};
                if (s.ground) {
                    /* A faint checker, so the ground reads as a plane. */
                    const bool odd = ((int)std::floor(P.x * 2) + (int)std::floor(P.z * 2)) & 1;
                    for (double &c : rgb) c *= odd ? 0.9 : 1.0;
                }
                if (front_seen) {
                    for (int li = 0; li < num_lights; li++) {
                        const LightFrame &lf = f.lights[(std::size_t)li];
                        const uint8_t *facing = lit_facing[(std::size_t)li * num_surfaces + si];
                        if (lf.stencil[i] != 0 || !facing || !facing[(std::size_t)t]) continue;
                        const double en = irradiance(terms[(std::size_t)li], P, n);
                        for (int c = 0; c < 3; c++) rgb[c] += en * lf.light.color[(std::size_t)c];
                    }
                }
                for (int c = 0; c < 3; c++) out[c] = to_display8(rgb[c] * s.albedo[(std::size_t)c]);
            }
        }
    });
    result.ticks = ticks() - k0;
    return result;
}

} // namespace sv::render
