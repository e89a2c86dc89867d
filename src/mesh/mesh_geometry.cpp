/*
 * Per-surface geometry: triangle planes, the double-length shadow vertex
 * buffer (and its per-light CPU variant), the surface bounds for appendix
 * B. See include/shadowvol_mesh.h for the formulas.
 *
 * Copyright (C) 2026 the shadowvol authors. LGPL-2.1-or-later.
 */
#include "shadowvol_mesh.h"

#include <algorithm>
#include <cmath>

namespace sv {

Plane triangle_plane(const float p0[3], const float p1[3], const float p2[3]) {
    const double e1x = (double)p1[0] - p0[0], e1y = (double)p1[1] - p0[1],
                 e1z = (double)p1[2] - p0[2];
    const double e2x = (double)p2[0] - p0[0], e2y = (double)p2[1] - p0[1],
                 e2z = (double)p2[2] - p0[2];
    double nx = e1y * e2z - e1z * e2y;
    double ny = e1z * e2x - e1x * e2z;
    double nz = e1x * e2y - e1y * e2x;
    const double len = std::sqrt(nx * nx + ny * ny + nz * nz);
    if (nx == 0.0 && ny == 0.0 && nz == 0.0) {
        return Plane{0.0f, 0.0f, 0.0f, 0.0f};
    }
    if (!(len > 0.0) || !std::isfinite(len)) {
        // n.n under- or overflowed double: rescale by the largest component.
        const double m = std::max({std::fabs(nx), std::fabs(ny), std::fabs(nz)});
        nx /= m;
        ny /= m;
        nz /= m;
        const double l2 = std::sqrt(nx * nx + ny * ny + nz * nz);
        nx /= l2;
        ny /= l2;
        nz /= l2;
    } else {
        nx /= len;
        ny /= len;
        nz /= len;
    }
    const double d = -(nx * p0[0] + ny * p0[1] + nz * p0[2]);
    return Plane{(float)nx, (float)ny, (float)nz, (float)d};
}

std::vector<Vec4> positions_vec4(const PreparedSurface &s) {
    std::vector<Vec4> out((std::size_t)s.num_vertices());
    for (int v = 0; v < s.num_vertices(); v++) {
        const float *p = &s.positions[3 * (std::size_t)v];
        out[(std::size_t)v] = Vec4{p[0], p[1], p[2], 1.0f};
    }
    return out;
}

AlignedVector<Vec4> shadow_vertices(const PreparedSurface &s) {
    const int n = s.num_vertices();
    AlignedVector<Vec4> out((std::size_t)n * 2);
    for (int v = 0; v < n; v++) {
        const float *p = &s.positions[3 * (std::size_t)v];
        out[2 * (std::size_t)v] = Vec4{p[0], p[1], p[2], 1.0f};
        out[2 * (std::size_t)v + 1] = Vec4{p[0], p[1], p[2], 0.0f};
    }
    return out;
}

void shadow_vertices_for_light(const PreparedSurface &s, const Vec4 &light, Vec4 *out) {
    const int n = s.num_vertices();
    for (int v = 0; v < n; v++) {
        const float *p = &s.positions[3 * (std::size_t)v];
        out[2 * (std::size_t)v] = Vec4{p[0], p[1], p[2], 1.0f};
        out[2 * (std::size_t)v + 1] = Vec4{p[0] * light.w - light.x, p[1] * light.w - light.y,
                                           p[2] * light.w - light.z, 0.0f};
    }
}

AlignedVector<Vec4> shadow_vertices_for_light(const PreparedSurface &s, const Vec4 &light) {
    AlignedVector<Vec4> out((std::size_t)s.num_vertices() * 2);
    shadow_vertices_for_light(s, light, out.data());
    return out;
}

Bounds surface_bounds(const PreparedSurface &s) {
    const int n = s.num_vertices();
    if (n == 0) {
        return Bounds{{0, 0, 0, 0}, {0, 0, 0, 0}};
    }
    float lo[3], hi[3];
    for (int c = 0; c < 3; c++) {
        lo[c] = hi[c] = s.positions[c];
    }
    for (int v = 1; v < n; v++) {
        for (int c = 0; c < 3; c++) {
            float f = s.positions[3 * (std::size_t)v + c];
            lo[c] = std::min(lo[c], f);
            hi[c] = std::max(hi[c], f);
        }
    }
    float center[3], ext[3];
    for (int c = 0; c < 3; c++) {
        center[c] = (float)(((double)lo[c] + hi[c]) * 0.5);
        const double need = std::max((double)hi[c] - center[c], (double)center[c] - lo[c]);
        float e = (float)need;
        while ((double)e < need) {
            e = std::nextafter(e, INFINITY);
        }
        // center +- e is evaluated in float by appendix B's callers too:
        // grow e until the float box holds both ends.
        while (center[c] + e < hi[c] || center[c] - e > lo[c]) {
            e = std::nextafter(e, INFINITY);
        }
        ext[c] = e;
    }
    return Bounds{{center[0], center[1], center[2], 0}, {ext[0], ext[1], ext[2], 0}};
}

} // namespace sv
