/*
 * The reference expressions of include/shadowvol_planes.h for one triangle,
 * shared by the C reference and the SIMD variants' tails and fix-ups (so
 * they are the same operations by construction). Built with
 * -ffp-contract=off, like every C file of the library.
 *
 * Copyright (C) 2026 the shadowvol authors. LGPL-2.1-or-later.
 */
#ifndef SV_PLANES_INTERNAL_H
#define SV_PLANES_INTERNAL_H

#include <math.h>
#include <stddef.h>
#include <xmmintrin.h>

#include "shadowvol_planes.h"

static inline const float *sv_planes_corner(const float *positions, int index) {
    return positions + 3 * (ptrdiff_t)index;
}

/* sqrtf without errno handling (and without libm): the correctly rounded
 * square root, sqrtss, as sqrtps computes it lane by lane. */
static inline float sv_planes_sqrt(float x) { return _mm_cvtss_f32(_mm_sqrt_ss(_mm_set_ss(x))); }

static inline Plane sv_plane_one(const float *positions, const int *tri) {
    const float *p0 = sv_planes_corner(positions, tri[0]);
    const float *p1 = sv_planes_corner(positions, tri[1]);
    const float *p2 = sv_planes_corner(positions, tri[2]);
    const float e1x = p1[0] - p0[0], e1y = p1[1] - p0[1], e1z = p1[2] - p0[2];
    const float e2x = p2[0] - p0[0], e2y = p2[1] - p0[1], e2z = p2[2] - p0[2];
    const float nx = e1y * e2z - e1z * e2y;
    const float ny = e1z * e2x - e1x * e2z;
    const float nz = e1x * e2y - e1y * e2x;
    const float len2 = (nx * nx + ny * ny) + nz * nz;
    Plane p = {0.0f, 0.0f, 0.0f, 0.0f};
    if (!(len2 > 0.0f && len2 < INFINITY)) return p;
    const float len = sv_planes_sqrt(len2);
    const float inv = 1.0f / len;
    p.a = nx * inv;
    p.b = ny * inv;
    p.c = nz * inv;
    p.d = -((p.a * p0[0] + p.b * p0[1]) + p.c * p0[2]);
    return p;
}

static inline uint8_t sv_facing_from_positions_one(const float *positions, const int *tri,
                                                   const Vec4 *l) {
    const float *p0 = sv_planes_corner(positions, tri[0]);
    const float *p1 = sv_planes_corner(positions, tri[1]);
    const float *p2 = sv_planes_corner(positions, tri[2]);
    const float e1x = p1[0] - p0[0], e1y = p1[1] - p0[1], e1z = p1[2] - p0[2];
    const float e2x = p2[0] - p0[0], e2y = p2[1] - p0[1], e2z = p2[2] - p0[2];
    const float nx = e1y * e2z - e1z * e2y;
    const float ny = e1z * e2x - e1x * e2z;
    const float nz = e1x * e2y - e1y * e2x;
    const float vx = l->x - p0[0] * l->w;
    const float vy = l->y - p0[1] * l->w;
    const float vz = l->z - p0[2] * l->w;
    return (nx * vx + ny * vy) + nz * vz > 0.0f;
}

#endif
