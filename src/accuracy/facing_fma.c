/*
 * The fma variant of appendix A: the reference's float planes, the dot
 * product fused,
 *   s = fma(d, w, fma(c, z, fma(b, y, a * x)));  facing = s > 0
 * four roundings instead of seven. The order is part of the definition:
 * the scalar routine spells it with fmaf (correctly rounded by definition,
 * so the same on every CPU; a library call where the CPU has no FMA), and
 * the AVX2 routine performs the same operations lane by lane, so the two
 * are bit-identical.
 *
 * This file is compiled with -ffp-contract=off like the reference: every
 * fused operation here is written out, none is left to the compiler, so
 * a*x stays a rounded product and no other expression is fused behind our
 * back.
 *
 * Copyright (C) 2026 the shadowvol authors. LGPL-2.1-or-later.
 */
#include <immintrin.h>
#include <math.h>
#include <string.h>

#include "mxcsr_guard.h"
#include "shadowvol_accuracy.h"

static inline uint8_t fma_one(const Plane *p, const Vec4 *l) {
    return fmaf(p->d, l->w, fmaf(p->c, l->z, fmaf(p->b, l->y, p->a * l->x))) > 0.0f;
}

__attribute__((noinline)) static void fma_body(const Plane *planes, int numTriangles,
                                               const Vec4 *light, uint8_t *facing) {
    for (int i = 0; i < numTriangles; i++) facing[i] = fma_one(&planes[i], light);
    facing[numTriangles] = 1;
}

void sv_calculate_facing_fma(const Plane *planes, int numTriangles, const Vec4 *light,
                             uint8_t *facing) {
    if (numTriangles < 0) return;
    const unsigned saved = sv_mxcsr_enter();
    fma_body(planes, numTriangles, light, facing);
    sv_mxcsr_leave(saved);
}

/* ---- AVX2 + FMA ------------------------------------------------------------ */

#define SV_TARGET_AVX2_FMA __attribute__((target("avx2,fma,bmi2")))

/* Planes s and s + 4 of the eight at P, one per 128-bit lane. */
SV_TARGET_AVX2_FMA static inline __m256 load_pair(const float *p, int s) {
    return _mm256_insertf128_ps(_mm256_castps128_ps256(_mm_loadu_ps(p + 4 * s)),
                                _mm_loadu_ps(p + 4 * (s + 4)), 1);
}

/* Eight planes (rows r0..r3 of two planes each, from load_pair) -> a, b,
 * c, d of planes 0..7 in order: the 4x4 transpose within each lane. */
SV_TARGET_AVX2_FMA static inline void transpose8(__m256 r0, __m256 r1, __m256 r2, __m256 r3,
                                                 __m256 *a, __m256 *b, __m256 *c, __m256 *d) {
    const __m256 t0 = _mm256_unpacklo_ps(r0, r1), t1 = _mm256_unpacklo_ps(r2, r3);
    const __m256 t2 = _mm256_unpackhi_ps(r0, r1), t3 = _mm256_unpackhi_ps(r2, r3);
    *a = _mm256_castpd_ps(_mm256_unpacklo_pd(_mm256_castps_pd(t0), _mm256_castps_pd(t1)));
    *b = _mm256_castpd_ps(_mm256_unpackhi_pd(_mm256_castps_pd(t0), _mm256_castps_pd(t1)));
    *c = _mm256_castpd_ps(_mm256_unpacklo_pd(_mm256_castps_pd(t2), _mm256_castps_pd(t3)));
    *d = _mm256_castpd_ps(_mm256_unpackhi_pd(_mm256_castps_pd(t2), _mm256_castps_pd(t3)));
}

SV_TARGET_AVX2_FMA __attribute__((noinline)) static void
fma_avx2_body(const Plane *planes, int numTriangles, const Vec4 *light, uint8_t *facing) {
    const __m256 lx = _mm256_set1_ps(light->x), ly = _mm256_set1_ps(light->y);
    const __m256 lz = _mm256_set1_ps(light->z), lw = _mm256_set1_ps(light->w);
    const __m256 zero = _mm256_setzero_ps();
    int i = 0;
    /* i <= n - 8, not i + 8 <= n: no overflow for counts near INT_MAX. */
    for (; i <= numTriangles - 8; i += 8) {
        const float *p = &planes[i].a;
        __m256 a, b, c, d;
        transpose8(load_pair(p, 0), load_pair(p, 1), load_pair(p, 2), load_pair(p, 3), &a, &b, &c,
                   &d);
        __m256 s = _mm256_mul_ps(a, lx);
        s = _mm256_fmadd_ps(b, ly, s);
        s = _mm256_fmadd_ps(c, lz, s);
        s = _mm256_fmadd_ps(d, lw, s);
        const unsigned m = (unsigned)_mm256_movemask_ps(_mm256_cmp_ps(s, zero, _CMP_GT_OQ));
        const unsigned long long bytes = _pdep_u64(m, 0x0101010101010101ull);
        memcpy(facing + i, &bytes, 8);
    }
    for (; i < numTriangles; i++) facing[i] = fma_one(&planes[i], light);
    facing[numTriangles] = 1;
}

void sv_calculate_facing_fma_avx2(const Plane *planes, int numTriangles, const Vec4 *light,
                                  uint8_t *facing) {
    if (numTriangles < 0) return;
    const unsigned saved = sv_mxcsr_enter();
    fma_avx2_body(planes, numTriangles, light, facing);
    sv_mxcsr_leave(saved);
}
