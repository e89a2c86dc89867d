/*
 * The reference's normal of 16 triangles in AVX-512 (include/shadowvol_planes.h,
 * "Plane derivation": n = e1 x e2, len2 = (nx*nx + ny*ny) + nz*nz, each
 * product and sum rounded on its own, no FMA), shared by the plane
 * kernels that gather their corners from memory (planes_simd.c) and from
 * registers (planes_clustered_avx512.c).
 *
 * Copyright (C) 2026 the shadowvol authors. LGPL-2.1-or-later.
 */
#ifndef SV_PLANES_AVX512_NORMAL_H
#define SV_PLANES_AVX512_NORMAL_H

#include <immintrin.h>
#include <math.h>

/* Edges (ax, ay, az) = p1 - p0 and (bx, by, bz) = p2 - p0 in; the normal
 * and len2 out; returns the lanes with a plane (0 < len2 < inf). */
__attribute__((target("avx512f"))) static inline __mmask16
sv_normal16_avx512(__m512 ax, __m512 ay, __m512 az, __m512 bx, __m512 by, __m512 bz, __m512 *nx,
                   __m512 *ny, __m512 *nz, __m512 *len2) {
    *nx = _mm512_sub_ps(_mm512_mul_ps(ay, bz), _mm512_mul_ps(az, by));
    *ny = _mm512_sub_ps(_mm512_mul_ps(az, bx), _mm512_mul_ps(ax, bz));
    *nz = _mm512_sub_ps(_mm512_mul_ps(ax, by), _mm512_mul_ps(ay, bx));
    *len2 = _mm512_add_ps(_mm512_add_ps(_mm512_mul_ps(*nx, *nx), _mm512_mul_ps(*ny, *ny)),
                          _mm512_mul_ps(*nz, *nz));
    return _mm512_cmp_ps_mask(*len2, _mm512_setzero_ps(), _CMP_GT_OQ) &
           _mm512_cmp_ps_mask(*len2, _mm512_set1_ps(INFINITY), _CMP_LT_OQ);
}

#endif
