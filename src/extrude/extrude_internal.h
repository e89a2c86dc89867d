/*
 * The reference expression of include/shadowvol_extrude.h for one vertex,
 * shared by the C reference and the SIMD variants' tails (so they are the
 * same operations by construction). Built with -ffp-contract=off, like
 * every C file of the library.
 *
 * Copyright (C) 2026 the shadowvol authors. LGPL-2.1-or-later.
 */
#ifndef SV_EXTRUDE_INTERNAL_H
#define SV_EXTRUDE_INTERNAL_H

#include <math.h>
#include <stddef.h>
#include <xmmintrin.h>

#include "shadowvol_extrude.h"

/* sqrtf without errno handling (and without libm): the correctly rounded
 * square root, sqrtss, as sqrtps computes it lane by lane. */
static inline float sv_extrude_sqrt(float x) { return _mm_cvtss_f32(_mm_sqrt_ss(_mm_set_ss(x))); }

/* Whether LIGHT and RANGE extrude to the seed's finite length (else to
 * infinity, w = 0). */
static inline int sv_extrude_finite(const Vec4 *light, float range) {
    return light->w != 0.0f && range > 0.0f && range < INFINITY;
}

/* rsqrtss refined by one Newton-Raphson step, in this order (the rsqrt
 * variant's SIMD does the same lane by lane):
 *   y0 = rsqrt(x);  y = y0 * (1.5f - (0.5f * x) * (y0 * y0)) */
static inline float sv_extrude_rsqrt_nr(float x) {
    const float y0 = _mm_cvtss_f32(_mm_rsqrt_ss(_mm_set_ss(x)));
    return y0 * (1.5f - (0.5f * x) * (y0 * y0));
}

/* One vertex at P (three floats) whose facing is decided by the normal N
 * (three floats: the seed's dp3 with the vertex's own light direction) or,
 * where N is NULL, given by FACE_KEEPS (the neighbour fix of
 * src/extrude/skinned_normals.h: one decision for the face's three
 * vertices); the rest of the program is the same either way. APPROX: the
 * rsqrt variant's 1/sqrt (sv_extrude_rsqrt_nr) instead of the correctly
 * rounded one. */
static inline Vec4 sv_extrude_vertex_facing(const float *p, const float *n, int face_keeps,
                                            const Vec4 *l, float range, int finite, int approx) {
    const float px = p[0], py = p[1], pz = p[2];
    const float dx = px * l->w - l->x;
    const float dy = py * l->w - l->y;
    const float dz = pz * l->w - l->z;
    const float len2 = (dx * dx + dy * dy) + dz * dz;
    const float inv = approx ? sv_extrude_rsqrt_nr(len2) : 1.0f / sv_extrude_sqrt(len2);
    const float ux = dx * inv, uy = dy * inv, uz = dz * inv;
    const int keeps = n ? (n[0] * ux + n[1] * uy) + n[2] * uz < 0.0f : face_keeps;
    Vec4 o;
    if (keeps || !(len2 > 0.0f)) {
        o.x = px, o.y = py, o.z = pz, o.w = 1.0f;
    } else if (!finite) {
        o.x = dx, o.y = dy, o.z = dz, o.w = 0.0f;
    } else {
        const float len = 1.0f / inv;
        float ext = range - len;
        ext = ext > 0.0f ? ext : 0.0f;
        o.x = ux * ext + px, o.y = uy * ext + py, o.z = uz * ext + pz, o.w = 1.0f;
    }
    return o;
}

/* One vertex of the seed's stream (position, then the face's normal). */
static inline Vec4 sv_extrude_vertex(const float *v, const Vec4 *l, float range, int finite,
                                     int approx) {
    return sv_extrude_vertex_facing(v, v + 3, 0, l, range, finite, approx);
}

/* The reference expression. */
static inline Vec4 sv_extrude_one(const float *v, const Vec4 *l, float range, int finite) {
    return sv_extrude_vertex(v, l, range, finite, 0);
}

#endif /* SV_EXTRUDE_INTERNAL_H */
