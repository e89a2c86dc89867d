/*
 * The lighting pass's per-pixel terms in scalar form (internal to
 * src/render): the reference the SIMD row kernels repeat lane by lane.
 * Each clamp is written as vmaxpd / vminpd compute it (x > 0 ? x : 0),
 * which equals std::clamp and std::max on every number and sends a NaN to
 * the bound.
 *
 * Copyright (C) 2026 the shadowvol authors. LGPL-2.1-or-later.
 */
#ifndef SV_RENDER_SHADING_TERMS_H
#define SV_RENDER_SHADING_TERMS_H

#include <cmath>
#include <cstddef>
#include <cstdint>

#include "shading_rows.h"

namespace sv::render::detail {

inline double dot3(const double *a, const double *b) {
    return a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
}
inline double max0(double x) { return x > 0 ? x : 0.0; }
inline double min_of(double x, double bound) { return x < bound ? x : bound; }
inline double clamp01(double x) { return min_of(max0(x), 1.0); }

/* The ground's faint checker: floor(2x) + floor(2z) odd, in double (an
 * int conversion would overflow far from the origin). */
inline bool checker_odd(double x, double z) {
    const double sum = std::floor(x * 2) + std::floor(z * 2);
    return sum - 2 * std::floor(sum * 0.5) != 0;
}

/* Radiance factor of light L at P with unit normal N (Lambert, the
 * KHR_lights_punctual range window, the spot cone), without the colour.
 * DIVIDED, when given, is incremented when the square root and divides
 * ran (a point or spot light, not outside the cone for certain). */
inline double irradiance(const ShadeLight &l, const double *p, const double *n,
                         uint64_t *divided = nullptr) {
    if (l.kind == 2) {
        return l.intensity * max0(-dot3(n, l.direction));
    }
    const double d[3] = {l.position[0] - p[0], l.position[1] - p[1], l.position[2] - p[2]};
    const double dist2 = dot3(d, d);
    if (l.dark_cos2 > 0) {
        /* Outside the spot's cone for certain: s below is 0, and so the
         * light (a finite a times 0). */
        const double along = -dot3(d, l.direction);
        if (along <= 0 || along * along < l.dark_cos2 * dist2) return 0;
    }
    if (divided) ++*divided;
    const double inv = 1.0 / std::sqrt(dist2);
    const double dir[3] = {d[0] * inv, d[1] * inv, d[2] * inv};
    double a = l.intensity * max0(dot3(n, dir)) / dist2;
    if (l.has_range) {
        const double q = dist2 * l.inv_range2;
        const double w = clamp01(1.0 - q * q);
        a *= w * w;
    }
    if (l.kind == 1) {
        const double c = -dot3(dir, l.direction);
        const double s = l.has_soft_cone ? clamp01((c - l.cos_outer) / (l.cos_inner - l.cos_outer))
                                         : (c >= l.cos_outer ? 1.0 : 0.0);
        a *= s * s;
    }
    return a;
}

/* The display table's entry for linear radiance V (clamped to
 * [0, kDisplayMax]; c * steps + 0.5 truncated rounds to the nearest step). */
inline std::size_t display_index(double v) {
    const double c = min_of(max0(v), (double)kDisplayMax);
    return (std::size_t)(c * kDisplaySteps + 0.5); // NOLINT(bugprone-incorrect-roundings)
}

} // namespace sv::render::detail

#endif
