/*
 * The double variant of appendix A: sv::triangle_plane's plane kept in
 * double (it is computed in double and rounded to float only at the end),
 * the light's float components converted exactly, and
 *   s = ((a*x + b*y) + c*z) + d*w  in double;  facing = s > 0.
 * Twice the memory of a float plane (32 bytes), half the lanes per vector;
 * in exchange the plane's rounding to float (the reference's largest error)
 * is gone. The AVX2 routine performs the same operations lane by lane (no
 * FMA: this file is compiled with -ffp-contract=off), so it is
 * bit-identical to the scalar one.
 *
 * Copyright (C) 2026 the shadowvol authors. LGPL-2.1-or-later.
 */
#include <immintrin.h>
#include <string.h>

#include "mxcsr_guard.h"
#include "shadowvol_accuracy.h"

static inline uint8_t double_one(const PlaneD *p, double x, double y, double z, double w) {
    return p->a * x + p->b * y + p->c * z + p->d * w > 0.0;
}

__attribute__((noinline)) static void double_body(const PlaneD *planes, int numTriangles,
                                                  const Vec4 *light, uint8_t *facing) {
    const double x = light->x, y = light->y, z = light->z, w = light->w;
    for (int i = 0; i < numTriangles; i++) facing[i] = double_one(&planes[i], x, y, z, w);
    facing[numTriangles] = 1;
}

void sv_calculate_facing_double(const PlaneD *planes, int numTriangles, const Vec4 *light,
                                uint8_t *facing) {
    if (numTriangles < 0) return;
    const unsigned saved = sv_mxcsr_enter();
    double_body(planes, numTriangles, light, facing);
    sv_mxcsr_leave(saved);
}

/* ---- AVX2 ------------------------------------------------------------------ */

#define SV_TARGET_AVX2 __attribute__((target("avx2")))

/* Four planes (one per register) -> a, b, c, d of the four. */
SV_TARGET_AVX2 static inline void transpose4d(__m256d r0, __m256d r1, __m256d r2, __m256d r3,
                                              __m256d *a, __m256d *b, __m256d *c, __m256d *d) {
    const __m256d t0 = _mm256_unpacklo_pd(r0, r1); /* a0 a1 | c0 c1 */
    const __m256d t1 = _mm256_unpackhi_pd(r0, r1); /* b0 b1 | d0 d1 */
    const __m256d t2 = _mm256_unpacklo_pd(r2, r3); /* a2 a3 | c2 c3 */
    const __m256d t3 = _mm256_unpackhi_pd(r2, r3); /* b2 b3 | d2 d3 */
    *a = _mm256_permute2f128_pd(t0, t2, 0x20);
    *b = _mm256_permute2f128_pd(t1, t3, 0x20);
    *c = _mm256_permute2f128_pd(t0, t2, 0x31);
    *d = _mm256_permute2f128_pd(t1, t3, 0x31);
}

SV_TARGET_AVX2 static inline unsigned facing4(const PlaneD *p, __m256d lx, __m256d ly, __m256d lz,
                                              __m256d lw) {
    __m256d a, b, c, d;
    transpose4d(_mm256_loadu_pd(&p[0].a), _mm256_loadu_pd(&p[1].a), _mm256_loadu_pd(&p[2].a),
                _mm256_loadu_pd(&p[3].a), &a, &b, &c, &d);
    __m256d s = _mm256_add_pd(_mm256_mul_pd(a, lx), _mm256_mul_pd(b, ly));
    s = _mm256_add_pd(s, _mm256_mul_pd(c, lz));
    s = _mm256_add_pd(s, _mm256_mul_pd(d, lw));
    return (unsigned)_mm256_movemask_pd(_mm256_cmp_pd(s, _mm256_setzero_pd(), _CMP_GT_OQ));
}

SV_TARGET_AVX2 __attribute__((noinline)) static void
double_avx2_body(const PlaneD *planes, int numTriangles, const Vec4 *light, uint8_t *facing) {
    const __m256d lx = _mm256_set1_pd(light->x), ly = _mm256_set1_pd(light->y);
    const __m256d lz = _mm256_set1_pd(light->z), lw = _mm256_set1_pd(light->w);
    int i = 0;
    for (; i <= numTriangles - 8; i += 8) {
        const unsigned m = facing4(planes + i, lx, ly, lz, lw) |
                           facing4(planes + i + 4, lx, ly, lz, lw) << 4;
        /* Eight mask bits -> eight 0/1 bytes: the multiply moves bit k of
         * each nibble to byte k. */
        const uint32_t lo = ((m & 0xFu) * 0x00204081u) & 0x01010101u;
        const uint32_t hi = ((m >> 4) * 0x00204081u) & 0x01010101u;
        memcpy(facing + i, &lo, 4);
        memcpy(facing + i + 4, &hi, 4);
    }
    const double x = light->x, y = light->y, z = light->z, w = light->w;
    for (; i < numTriangles; i++) facing[i] = double_one(&planes[i], x, y, z, w);
    facing[numTriangles] = 1;
}

void sv_calculate_facing_double_avx2(const PlaneD *planes, int numTriangles, const Vec4 *light,
                                     uint8_t *facing) {
    if (numTriangles < 0) return;
    const unsigned saved = sv_mxcsr_enter();
    double_avx2_body(planes, numTriangles, light, facing);
    sv_mxcsr_leave(saved);
}
