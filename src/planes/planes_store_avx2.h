/*
 * Eight planes from their four columns in AVX2: a 4x8 transpose (unpack,
 * shuffle, then the 128-bit halves swapped across) and four stores.
 * Shared by the AVX2 plane kernel (planes_simd.c) and the bench's floor
 * under the kernels (bench/suites/planes_floor.cpp), so that both store
 * the same way.
 *
 * Copyright (C) 2026 the shadowvol authors. LGPL-2.1-or-later.
 */
#ifndef SV_PLANES_STORE_AVX2_H
#define SV_PLANES_STORE_AVX2_H

#include <immintrin.h>

#include "shadowvol.h"

/* Plane columns a..d of triangles 0..7 in lane order (0 1 2 3 | 4 5 6 7)
 * -> OUT[0..7] (unaligned). */
__attribute__((target("avx2"))) static inline void
sv_store_planes8_avx2(Plane *out, __m256 a, __m256 b, __m256 c, __m256 d) {
    const __m256 u0 = _mm256_unpacklo_ps(a, b), u1 = _mm256_unpacklo_ps(c, d);
    const __m256 u2 = _mm256_unpackhi_ps(a, b), u3 = _mm256_unpackhi_ps(c, d);
    const __m256 o0 = _mm256_shuffle_ps(u0, u1, _MM_SHUFFLE(1, 0, 1, 0));
    const __m256 o1 = _mm256_shuffle_ps(u0, u1, _MM_SHUFFLE(3, 2, 3, 2));
    const __m256 o2 = _mm256_shuffle_ps(u2, u3, _MM_SHUFFLE(1, 0, 1, 0));
    const __m256 o3 = _mm256_shuffle_ps(u2, u3, _MM_SHUFFLE(3, 2, 3, 2));
    _mm256_storeu_ps(&out[0].a, _mm256_permute2f128_ps(o0, o1, 0x20));
    _mm256_storeu_ps(&out[2].a, _mm256_permute2f128_ps(o2, o3, 0x20));
    _mm256_storeu_ps(&out[4].a, _mm256_permute2f128_ps(o0, o1, 0x31));
    _mm256_storeu_ps(&out[6].a, _mm256_permute2f128_ps(o2, o3, 0x31));
}

#endif
