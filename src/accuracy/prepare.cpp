/*
 * Per-surface data of the accuracy variants: double planes, and seed 001's
 * compact fixed16 planes. Built once per surface, like its float planes.
 * Compiled with -ffp-contract=off: these numbers enter the error bounds
 * (error_bounds.cpp), which assume each operation rounded once.
 *
 * Copyright (C) 2026 the shadowvol authors. LGPL-2.1-or-later.
 */
#include <algorithm>
#include <cfloat>
#include <cmath>

#include "mxcsr_guard.h"
#include "shadowvol_accuracy.h"

namespace sv {

namespace {

bool all_finite(const float p0[3], const float p1[3], const float p2[3]) {
    for (int i = 0; i < 3; i++) {
        if (!std::isfinite(p0[i]) || !std::isfinite(p1[i]) || !std::isfinite(p2[i])) {
            return false;
        }
    }
    return true;
}

/* sv::triangle_plane (src/mesh/mesh_geometry.cpp) step for step, without the
 * final rounding to float: so (float) of each component is that function's
 * plane, bit for bit (tests/unit/test_accuracy.cpp checks it). For float input
 * n . n neither overflows nor underflows (|n| lies in [2^-298, 2^260]), so
 * that function's rescaling branch never runs and is not repeated here. */
__attribute__((noinline)) PlaneD plane_double_impl(const float p0[3], const float p1[3],
                                                   const float p2[3]) {
    if (!all_finite(p0, p1, p2)) return PlaneD{0, 0, 0, 0};
    const double e1x = (double)p1[0] - p0[0], e1y = (double)p1[1] - p0[1],
                 e1z = (double)p1[2] - p0[2];
    const double e2x = (double)p2[0] - p0[0], e2y = (double)p2[1] - p0[1],
                 e2z = (double)p2[2] - p0[2];
    double nx = e1y * e2z - e1z * e2y;
    double ny = e1z * e2x - e1x * e2z;
    double nz = e1x * e2y - e1y * e2x;
    if (nx == 0.0 && ny == 0.0 && nz == 0.0) return PlaneD{0, 0, 0, 0};
    const double len = std::sqrt(nx * nx + ny * ny + nz * nz);
    nx /= len;
    ny /= len;
    nz /= len;
    const double d = -(nx * p0[0] + ny * p0[1] + nz * p0[2]);
    return PlaneD{nx, ny, nz, d};
}

__attribute__((noinline)) void double_planes_impl(const PreparedSurface &s, PlaneD *out) {
    const int nt = s.num_triangles();
    for (int t = 0; t < nt; t++) {
        const float *p0 = &s.positions[3 * (std::size_t)s.indices[3 * (std::size_t)t]];
        const float *p1 = &s.positions[3 * (std::size_t)s.indices[3 * (std::size_t)t + 1]];
        const float *p2 = &s.positions[3 * (std::size_t)s.indices[3 * (std::size_t)t + 2]];
        out[t] = plane_double_impl(p0, p1, p2);
    }
}

/* The double normal scaled so that its largest component is exactly 1,
 * times 32767, rounded half away from zero (std::round: independent of the
 * rounding mode); tn = (q / 32767) . centroid, the centroid and the dot
 * product in double, rounded to float once (overflow gives +-inf, which the
 * bound reports as "no promise"). */
__attribute__((noinline)) void plane16_impl(const float p0[3], const float p1[3], const float p2[3],
                                            int16_t q[3], float *tn) {
    q[0] = q[1] = q[2] = 0;
    *tn = 0.0f;
    const PlaneD n = plane_double_impl(p0, p1, p2);
    const double m = std::max({std::fabs(n.a), std::fabs(n.b), std::fabs(n.c)});
    if (!(m > 0.0)) return; /* zero-area or non-finite: never facing */
    const double nn[3] = {n.a, n.b, n.c};
    for (int i = 0; i < 3; i++) q[i] = (int16_t)std::round(32767.0 * (nn[i] / m));
    double c[3];
    for (int i = 0; i < 3; i++) c[i] = ((double)p0[i] + p1[i] + p2[i]) / 3.0;
    const double t = ((double)q[0] * c[0] + (double)q[1] * c[1] + (double)q[2] * c[2]) / 32767.0;
    /* Out of float range: +-inf explicitly (a C++ conversion would be
     * undefined). */
    *tn = std::fabs(t) > (double)FLT_MAX ? (t > 0 ? INFINITY : -INFINITY) : (float)t;
}

__attribute__((noinline)) void fixed16_planes_impl(const PreparedSurface &s,
                                                   sv_plane16_block *out) {
    const int nt = s.num_triangles();
    for (int t = 0; t < nt; t++) {
        const float *p0 = &s.positions[3 * (std::size_t)s.indices[3 * (std::size_t)t]];
        const float *p1 = &s.positions[3 * (std::size_t)s.indices[3 * (std::size_t)t + 1]];
        const float *p2 = &s.positions[3 * (std::size_t)s.indices[3 * (std::size_t)t + 2]];
        sv_plane16_block &b = out[(std::size_t)t / SV_PLANE16_BLOCK];
        const int k = t % SV_PLANE16_BLOCK;
        int16_t q[3];
        plane16_impl(p0, p1, p2, q, &b.tn[k]);
        b.nx[k] = q[0];
        b.ny[k] = q[1];
        b.nz[k] = q[2];
    }
}

} // namespace

/* The public functions run their arithmetic under the default MXCSR
 * (mxcsr_guard.h): under a caller's DAZ, converting a subnormal position to
 * double would read 0, and the prepared data would depend on the caller. */

PlaneD triangle_plane_double(const float p0[3], const float p1[3], const float p2[3]) {
    const unsigned saved = sv_mxcsr_enter();
    const PlaneD p = plane_double_impl(p0, p1, p2);
    sv_mxcsr_leave(saved);
    return p;
}

AlignedVector<PlaneD> double_planes(const PreparedSurface &s) {
    AlignedVector<PlaneD> out((std::size_t)s.num_triangles());
    const unsigned saved = sv_mxcsr_enter();
    double_planes_impl(s, out.data());
    sv_mxcsr_leave(saved);
    return out;
}

void triangle_plane16(const float p0[3], const float p1[3], const float p2[3], int16_t q[3],
                      float *tn) {
    const unsigned saved = sv_mxcsr_enter();
    plane16_impl(p0, p1, p2, q, tn);
    sv_mxcsr_leave(saved);
}

AlignedVector<sv_plane16_block> fixed16_planes(const PreparedSurface &s) {
    /* Zero-initialised: the last block's unused entries stay 0. */
    AlignedVector<sv_plane16_block> out(((std::size_t)s.num_triangles() + SV_PLANE16_BLOCK - 1) /
                                        SV_PLANE16_BLOCK);
    const unsigned saved = sv_mxcsr_enter();
    fixed16_planes_impl(s, out.data());
    sv_mxcsr_leave(saved);
    return out;
}

} // namespace sv
