/*
 * CalculateFacing (appendix A) and CalculateCullBits (appendix B) with SSE2,
 * AVX2 and AVX-512. The paper printed no SIMD for these two ("straight
 * forward"), so they are C intrinsics, not listing ports; each is
 * BIT-IDENTICAL to the reference C, for every input including NaN, Inf,
 * -0.0 and subnormals:
 *
 *  - the same operations in the same order: ((a*x + b*y) + c*z) + d*w for
 *    a facing test, ((a*x + b*y) + c*z) + d for a cull test, each product
 *    and sum rounded to float (no FMA: this file is built with
 *    -ffp-contract=off, and FMA intrinsics are not used);
 *  - the same comparisons: "> 0.0f" and "< 0.0f" are ordered compares (false
 *    for NaN), as the C operators are;
 *  - the same MXCSR: FTZ/DAZ affect both sides alike.
 *
 * The trick is the transpose. Planes and positions are arrays of 16-byte
 * structures (a, b, c, d) / (x, y, z, w); four of them are a 4x4 matrix,
 * and a transpose turns four loads into the registers A = (a0 a1 a2 a3),
 * B, C, D, so one mul/add chain evaluates four (8 with AVX2 in two 128-bit
 * lanes, 16 with AVX-512 through two vpermt2ps levels) dot products in the
 * reference's order. A horizontal add (haddps) would be cheaper but sums
 * (ax+by) + (cz+dw): a different rounding, so it is not used.
 *
 * Cull bits: one pass over the vertices tests every plane that the box test
 * left (the reference makes one pass per plane; the bits are independent,
 * so the bytes are equal) and stores each vertex's byte once.
 *
 * Tails: the SSE2 and AVX2 versions finish with the scalar reference
 * expression; the AVX-512 version uses masked loads and stores and reads
 * nothing past the arrays.
 *
 * Copyright (C) 2026 the shadowvol authors. LGPL-2.1-or-later.
 */
#include <immintrin.h>
#include <string.h>

#include "../facing_internal.h"
#include "../mask_bytes.h"
#include "shadowvol.h"
#include "../simd_exit.h"

/* The reference's expressions, for tails (the same operations). */
static inline uint8_t facing_one(const Plane *p, const Vec4 *l) {
    return p->a * l->x + p->b * l->y + p->c * l->z + p->d * l->w > 0.0f;
}

static inline uint8_t cull_one(const Vec4 *v, const Plane planes[SV_NUM_LIGHT_PLANES],
                               int frontBits) {
    uint8_t bits = 0;
    for (int i = 0; i < SV_NUM_LIGHT_PLANES; i++) {
        if (frontBits & (1 << i)) continue;
        const Plane *p = &planes[i];
        bits |= (uint8_t)((p->a * v->x + p->b * v->y + p->c * v->z + p->d < 0.0f) << i);
    }
    return bits;
}

/* What every SIMD CalculateCullBits starts from (appendix B's box test):
 * the light planes the surface box lies entirely in front of need no
 * per-vertex test; the others ("live") and their bit numbers are listed. */
typedef struct CullSetup {
    int frontBits;
    int nlive;
    Plane lp[SV_NUM_LIGHT_PLANES];
    int live[SV_NUM_LIGHT_PLANES];
} CullSetup;

/* 1 when the box is in front of every plane (the routine then returns 1
 * and writes nothing, as the reference does); else 0, with S filled. */
static int cull_setup(const Bounds *surfaceBounds, const Plane lightPlanes[SV_NUM_LIGHT_PLANES],
                      CullSetup *s) {
    s->frontBits = sv_cull_front_bits(surfaceBounds, lightPlanes);
    if (s->frontBits == (1 << SV_NUM_LIGHT_PLANES) - 1) return 1;
    s->nlive = 0;
    for (int k = 0; k < SV_NUM_LIGHT_PLANES; k++) {
        if (s->frontBits & (1 << k)) continue;
        s->lp[s->nlive] = lightPlanes[k];
        s->live[s->nlive++] = k;
    }
    return 0;
}

/* ---- C: the reference's expression, counted in the same loop ---------- */

int sv_calculate_facing_count_c(const Plane *planes, int numTriangles, const Vec4 *light,
                                uint8_t *facing) {
    if (numTriangles < 0) return 0;
    int count = 0;
    for (int i = 0; i < numTriangles; i++) {
        facing[i] = facing_one(&planes[i], light);
        count += facing[i];
    }
    facing[numTriangles] = 1;
    return count;
}

/* ---- SSE2 ---------------------------------------------------------------- */

/* Four 16-byte rows -> columns (the classic 4x4 transpose). */
#define TRANSPOSE4(r0, r1, r2, r3, c0, c1, c2, c3)                                                 \
    do {                                                                                           \
        __m128 t0_ = _mm_unpacklo_ps(r0, r1), t1_ = _mm_unpacklo_ps(r2, r3);                       \
        __m128 t2_ = _mm_unpackhi_ps(r0, r1), t3_ = _mm_unpackhi_ps(r2, r3);                       \
        (c0) = _mm_movelh_ps(t0_, t1_);                                                            \
        (c1) = _mm_movehl_ps(t1_, t0_);                                                            \
        (c2) = _mm_movelh_ps(t2_, t3_);                                                            \
        (c3) = _mm_movehl_ps(t3_, t2_);                                                            \
    } while (0)

/* Four facing tests of four planes at P: the compare mask, one dword of
 * all-ones or zero per plane. */
static inline __m128i facing4_sse2(const float *p, __m128 lx, __m128 ly, __m128 lz, __m128 lw) {
    __m128 a, b, c, d;
    TRANSPOSE4(_mm_loadu_ps(p), _mm_loadu_ps(p + 4), _mm_loadu_ps(p + 8), _mm_loadu_ps(p + 12), a,
               b, c, d);
    __m128 s = _mm_add_ps(_mm_mul_ps(a, lx), _mm_mul_ps(b, ly));
    s = _mm_add_ps(s, _mm_mul_ps(c, lz));
    s = _mm_add_ps(s, _mm_mul_ps(d, lw));
    return _mm_castps_si128(_mm_cmpgt_ps(s, _mm_setzero_ps()));
}

/* The body of sv_calculate_facing_sse2 and of its fused twin, which also
 * returns the number of facing triangles (WANT_COUNT: a constant in each
 * caller, so the compiler drops the counting where it is not wanted). */
static inline int facing_sse2(const Plane *planes, int numTriangles, const Vec4 *light,
                              uint8_t *facing, int wantCount) {
    if (numTriangles < 0) return 0;
    __m128i sums = _mm_setzero_si128(); /* psadbw: two 64-bit byte sums */
    int count = 0;
    const __m128 lx = _mm_set1_ps(light->x), ly = _mm_set1_ps(light->y);
    const __m128 lz = _mm_set1_ps(light->z), lw = _mm_set1_ps(light->w);
    const __m128i one = _mm_set1_epi8(1);
    const float *p =
        (const float *)planes; /* no member access: planes may be NULL when the count is 0 */
    int i = 0;
    /* Sixteen triangles per iteration: the four compare masks (dwords of
     * 0 or -1) are packed with signed saturation to words, then to bytes,
     * still 0 or -1, ANDed with 1 and stored as one 16-byte vector. The
     * first form moved each group of four through movemask, a multiply
     * spreading the bits and a 4-byte store: five scalar operations per
     * four triangles, which made it slower than the C (which gcc
     * vectorises with packs like these) on an Intel Sapphire Rapids. */
    for (; i <= numTriangles - 16; i += 16, p += 64) {
        const __m128i m0 = facing4_sse2(p, lx, ly, lz, lw);
        const __m128i m1 = facing4_sse2(p + 16, lx, ly, lz, lw);
        const __m128i m2 = facing4_sse2(p + 32, lx, ly, lz, lw);
        const __m128i m3 = facing4_sse2(p + 48, lx, ly, lz, lw);
        const __m128i bytes = _mm_packs_epi16(_mm_packs_epi32(m0, m1), _mm_packs_epi32(m2, m3));
        const __m128i b01 = _mm_and_si128(bytes, one);
        _mm_storeu_si128((__m128i *)(facing + i), b01);
        if (wantCount) sums = _mm_add_epi64(sums, _mm_sad_epu8(b01, _mm_setzero_si128()));
    }
    for (; i <= numTriangles - 4; i += 4, p += 16) {
        const __m128i m = facing4_sse2(p, lx, ly, lz, lw);
        const __m128i words = _mm_packs_epi32(m, m);
        const int bytes = _mm_cvtsi128_si32(_mm_and_si128(_mm_packs_epi16(words, words), one));
        memcpy(facing + i, &bytes, 4);
        if (wantCount) count += (int)(((uint32_t)bytes * 0x01010101u) >> 24);
    }
    for (; i < numTriangles; i++) {
        facing[i] = facing_one(&planes[i], light);
        if (wantCount) count += facing[i];
    }
    facing[numTriangles] = 1; /* for dangling edges to reference */
    if (!wantCount) return 0;
    return count + _mm_cvtsi128_si32(sums) + _mm_cvtsi128_si32(_mm_unpackhi_epi64(sums, sums));
}

void sv_calculate_facing_sse2(const Plane *planes, int numTriangles, const Vec4 *light,
                              uint8_t *facing) {
    (void)facing_sse2(planes, numTriangles, light, facing, 0);
}

int sv_calculate_facing_count_sse2(const Plane *planes, int numTriangles, const Vec4 *light,
                                   uint8_t *facing) {
    return facing_sse2(planes, numTriangles, light, facing, 1);
}

int sv_calculate_cull_bits_sse2(const Vec4 *positions, int numVerts, const Bounds *surfaceBounds,
                                const Plane lightPlanes[SV_NUM_LIGHT_PLANES], uint8_t *cullBits) {
    if (numVerts < 0) return 0;
    CullSetup cs;
    if (cull_setup(surfaceBounds, lightPlanes, &cs)) return 1;
    __m128 pa[SV_NUM_LIGHT_PLANES], pb[SV_NUM_LIGHT_PLANES], pc[SV_NUM_LIGHT_PLANES],
        pd[SV_NUM_LIGHT_PLANES];
    __m128i bit[SV_NUM_LIGHT_PLANES];
    for (int k = 0; k < cs.nlive; k++) {
        pa[k] = _mm_set1_ps(cs.lp[k].a), pb[k] = _mm_set1_ps(cs.lp[k].b);
        pc[k] = _mm_set1_ps(cs.lp[k].c), pd[k] = _mm_set1_ps(cs.lp[k].d);
        bit[k] = _mm_set1_epi32(1 << cs.live[k]);
    }
    const __m128 zero = _mm_setzero_ps();
    const float *v = (const float *)positions; /* (may be NULL when the count is 0) */
    int j = 0;
    /* Eight vertices per iteration, the bits gathered in vector lanes (a
     * plane's compare mask ANDed with its bit, ORed into the lane) and
     * packed to bytes once: dwords -> words -> bytes (values <= 63, so
     * the saturating packs are exact). Going through movemask and scalar
     * bit spreading per plane instead made this slower than the C. */
    for (; j <= numVerts - 8; j += 8, v += 32) {
        __m128i acc[2];
        for (int h = 0; h < 2; h++) {
            const float *q = v + 16 * h;
            __m128 x, y, z, w;
            TRANSPOSE4(_mm_loadu_ps(q), _mm_loadu_ps(q + 4), _mm_loadu_ps(q + 8),
                       _mm_loadu_ps(q + 12), x, y, z, w);
            (void)w;
            __m128i bits = _mm_setzero_si128();
            for (int k = 0; k < cs.nlive; k++) {
                __m128 s = _mm_add_ps(_mm_mul_ps(pa[k], x), _mm_mul_ps(pb[k], y));
                s = _mm_add_ps(s, _mm_mul_ps(pc[k], z));
                s = _mm_add_ps(s, pd[k]);
                bits = _mm_or_si128(bits,
                                    _mm_and_si128(_mm_castps_si128(_mm_cmplt_ps(s, zero)), bit[k]));
            }
            acc[h] = bits;
        }
        const __m128i words = _mm_packs_epi32(acc[0], acc[1]);
        _mm_storel_epi64((__m128i *)(cullBits + j), _mm_packus_epi16(words, words));
    }
    for (; j < numVerts; j++) cullBits[j] = cull_one(&positions[j], lightPlanes, cs.frontBits);
    return 0;
}

/* ---- AVX2 (x86-64-v3) ---------------------------------------------------- */

#define SV_TARGET_AVX2 __attribute__((target("avx2")))

/* Rows r0..r3 each hold two structures (low lane: s, high lane: s + 4);
 * an in-lane transpose gives 8 lanes of a, b, c, d in the order
 * (0 1 2 3 | 4 5 6 7). */
#define TRANSPOSE4x2(r0, r1, r2, r3, c0, c1, c2, c3)                                               \
    do {                                                                                           \
        __m256 t0_ = _mm256_unpacklo_ps(r0, r1), t1_ = _mm256_unpacklo_ps(r2, r3);                 \
        __m256 t2_ = _mm256_unpackhi_ps(r0, r1), t3_ = _mm256_unpackhi_ps(r2, r3);                 \
        (c0) = _mm256_castpd_ps(_mm256_unpacklo_pd(_mm256_castps_pd(t0_), _mm256_castps_pd(t1_))); \
        (c1) = _mm256_castpd_ps(_mm256_unpackhi_pd(_mm256_castps_pd(t0_), _mm256_castps_pd(t1_))); \
        (c2) = _mm256_castpd_ps(_mm256_unpacklo_pd(_mm256_castps_pd(t2_), _mm256_castps_pd(t3_))); \
        (c3) = _mm256_castpd_ps(_mm256_unpackhi_pd(_mm256_castps_pd(t2_), _mm256_castps_pd(t3_))); \
    } while (0)

/* Structures s and s + 4 of the 16-float rows at P, one per lane. */
SV_TARGET_AVX2 static inline __m256 load_pair(const float *p, int s) {
    return _mm256_insertf128_ps(_mm256_castps128_ps256(_mm_loadu_ps(p + 4 * s)),
                                _mm_loadu_ps(p + 4 * (s + 4)), 1);
}

/* Eight facing tests of the eight planes at P: the compare mask, one
 * dword of all-ones or zero per plane, in the order (0 1 2 3 | 4 5 6 7). */
SV_TARGET_AVX2 static inline __m256i facing8_avx2(const float *p, __m256 lx, __m256 ly, __m256 lz,
                                                  __m256 lw) {
    __m256 a, b, c, d;
    TRANSPOSE4x2(load_pair(p, 0), load_pair(p, 1), load_pair(p, 2), load_pair(p, 3), a, b, c, d);
    __m256 s = _mm256_add_ps(_mm256_mul_ps(a, lx), _mm256_mul_ps(b, ly));
    s = _mm256_add_ps(s, _mm256_mul_ps(c, lz));
    s = _mm256_add_ps(s, _mm256_mul_ps(d, lw));
    return _mm256_castps_si256(_mm256_cmp_ps(s, _mm256_setzero_ps(), _CMP_GT_OQ));
}

SV_TARGET_AVX2 static inline int facing_avx2(const Plane *planes, int numTriangles,
                                             const Vec4 *light, uint8_t *facing, int wantCount) {
    if (numTriangles < 0) return 0;
    __m256i sums = _mm256_setzero_si256(); /* vpsadbw: four 64-bit byte sums */
    int count = 0;
    const __m256 lx = _mm256_set1_ps(light->x), ly = _mm256_set1_ps(light->y);
    const __m256 lz = _mm256_set1_ps(light->z), lw = _mm256_set1_ps(light->w);
    const __m256i one = _mm256_set1_epi8(1);
    /* The packs below work per 128-bit lane: dword j of the packed vector
     * holds the four triangles from 4 * (2 * (j % 4) + j / 4) on (0, 8, 16,
     * 24 | 4, 12, 20, 28), so triangles 4k .. 4k + 3 are in dword order[k];
     * vpermd gathers them in triangle order. */
    const __m256i order = _mm256_setr_epi32(0, 4, 1, 5, 2, 6, 3, 7);
    const float *p =
        (const float *)planes; /* no member access: planes may be NULL when the count is 0 */
    int i = 0;
    /* 32 triangles per iteration, packed to bytes in registers (dwords ->
     * words -> bytes, signed saturation keeps 0 and -1), one 32-byte
     * store: no movemask, no scalar byte spreading. */
    for (; i <= numTriangles - 32; i += 32, p += 128) {
        const __m256i m0 = facing8_avx2(p, lx, ly, lz, lw);
        const __m256i m1 = facing8_avx2(p + 32, lx, ly, lz, lw);
        const __m256i m2 = facing8_avx2(p + 64, lx, ly, lz, lw);
        const __m256i m3 = facing8_avx2(p + 96, lx, ly, lz, lw);
        const __m256i bytes = _mm256_packs_epi16(_mm256_packs_epi32(m0, m1),
                                                 _mm256_packs_epi32(m2, m3));
        const __m256i b01 = _mm256_and_si256(_mm256_permutevar8x32_epi32(bytes, order), one);
        _mm256_storeu_si256((__m256i *)(facing + i), b01);
        if (wantCount) sums = _mm256_add_epi64(sums, _mm256_sad_epu8(b01, _mm256_setzero_si256()));
    }
    for (; i <= numTriangles - 8; i += 8, p += 32) {
        const unsigned m = (unsigned)_mm256_movemask_ps(
            _mm256_castsi256_ps(facing8_avx2(p, lx, ly, lz, lw)));
        /* Eight mask bits -> eight 0/1 bytes (mask_bytes.h: not pdep). */
        memcpy(facing + i, &kMaskBytes[m], 8);
        if (wantCount) count += __builtin_popcount(m);
    }
    for (; i < numTriangles; i++) {
        facing[i] = facing_one(&planes[i], light);
        if (wantCount) count += facing[i];
    }
    facing[numTriangles] = 1;
    if (!wantCount) {
        SV_VZEROUPPER_IF_UNOPTIMISED();
        return 0;
    }
    const __m128i s2 = _mm_add_epi64(_mm256_castsi256_si128(sums),
                                     _mm256_extracti128_si256(sums, 1));
    const int total = count + _mm_cvtsi128_si32(s2) + _mm_cvtsi128_si32(_mm_unpackhi_epi64(s2, s2));
    SV_VZEROUPPER_IF_UNOPTIMISED();
    return total;
}

SV_TARGET_AVX2 void sv_calculate_facing_avx2(const Plane *planes, int numTriangles,
                                             const Vec4 *light, uint8_t *facing) {
    (void)facing_avx2(planes, numTriangles, light, facing, 0);
}

SV_TARGET_AVX2 int sv_calculate_facing_count_avx2(const Plane *planes, int numTriangles,
                                                  const Vec4 *light, uint8_t *facing) {
    return facing_avx2(planes, numTriangles, light, facing, 1);
}

SV_TARGET_AVX2 int sv_calculate_cull_bits_avx2(const Vec4 *positions, int numVerts,
                                               const Bounds *surfaceBounds,
                                               const Plane lightPlanes[SV_NUM_LIGHT_PLANES],
                                               uint8_t *cullBits) {
    if (numVerts < 0) return 0;
    CullSetup cs;
    if (cull_setup(surfaceBounds, lightPlanes, &cs)) return 1;
    __m256 pa[SV_NUM_LIGHT_PLANES], pb[SV_NUM_LIGHT_PLANES], pc[SV_NUM_LIGHT_PLANES],
        pd[SV_NUM_LIGHT_PLANES];
    for (int k = 0; k < cs.nlive; k++) {
        pa[k] = _mm256_set1_ps(cs.lp[k].a), pb[k] = _mm256_set1_ps(cs.lp[k].b);
        pc[k] = _mm256_set1_ps(cs.lp[k].c), pd[k] = _mm256_set1_ps(cs.lp[k].d);
    }
    const __m256 zero = _mm256_setzero_ps();
    const float *v = (const float *)positions; /* (may be NULL when the count is 0) */
    int j = 0;
    for (; j <= numVerts - 8; j += 8, v += 32) {
        __m256 x, y, z, w;
        TRANSPOSE4x2(load_pair(v, 0), load_pair(v, 1), load_pair(v, 2), load_pair(v, 3), x, y, z,
                     w);
        (void)w;
        unsigned long long bytes = 0;
        for (int k = 0; k < cs.nlive; k++) {
            __m256 s = _mm256_add_ps(_mm256_mul_ps(pa[k], x), _mm256_mul_ps(pb[k], y));
            s = _mm256_add_ps(s, _mm256_mul_ps(pc[k], z));
            s = _mm256_add_ps(s, pd[k]);
            const unsigned m = (unsigned)_mm256_movemask_ps(_mm256_cmp_ps(s, zero, _CMP_LT_OQ));
            bytes |= kMaskBytes[m] << cs.live[k];
        }
        memcpy(cullBits + j, &bytes, 8);
    }
    for (; j < numVerts; j++) cullBits[j] = cull_one(&positions[j], lightPlanes, cs.frontBits);
    SV_VZEROUPPER_IF_UNOPTIMISED();
    return 0;
}

/* ---- AVX-512 (x86-64-v4: F, BW, VL) --------------------------------------- */

#define SV_TARGET_AVX512 __attribute__((target("avx512f,avx512bw,avx512vl,avx512dq")))

/* 16 structures (64 floats, in r0..r3) -> their four columns. Level 1:
 * vpermt2ps gathers, from each pair of registers, the a and b (resp. c and
 * d) of 8 structures; level 2: shuf_f32x4 joins the halves. */
SV_TARGET_AVX512 static inline void transpose16(__m512 r0, __m512 r1, __m512 r2, __m512 r3,
                                                __m512 *c0, __m512 *c1, __m512 *c2, __m512 *c3) {
    const __m512i ab = _mm512_setr_epi32(0, 4, 8, 12, 16, 20, 24, 28, 1, 5, 9, 13, 17, 21, 25, 29);
    const __m512i cd = _mm512_setr_epi32(2, 6, 10, 14, 18, 22, 26, 30, 3, 7, 11, 15, 19, 23, 27,
                                         31);
    const __m512 ab01 = _mm512_permutex2var_ps(r0, ab, r1); /* a0..a7 | b0..b7 */
    const __m512 cd01 = _mm512_permutex2var_ps(r0, cd, r1);
    const __m512 ab23 = _mm512_permutex2var_ps(r2, ab, r3); /* a8..a15 | b8..b15 */
    const __m512 cd23 = _mm512_permutex2var_ps(r2, cd, r3);
    *c0 = _mm512_shuffle_f32x4(ab01, ab23, 0x44); /* low halves: a0..a15 */
    *c1 = _mm512_shuffle_f32x4(ab01, ab23, 0xEE); /* high halves: b0..b15 */
    *c2 = _mm512_shuffle_f32x4(cd01, cd23, 0x44);
    *c3 = _mm512_shuffle_f32x4(cd01, cd23, 0xEE);
}

/* The 64 floats of 16 structures at P; only the first N structures are
 * read (masked: nothing past them), the others are zero. */
SV_TARGET_AVX512 static inline void load16(const float *p, int n, __m512 r[4]) {
    for (int q = 0; q < 4; q++) {
        const int have = n - 4 * q; /* structures in this register */
        const unsigned bits = have >= 4 ? 0xFFFFu : have <= 0 ? 0u : (1u << (4 * have)) - 1;
        const __mmask16 m = (__mmask16)bits;
        r[q] = _mm512_maskz_loadu_ps(m, p + 16 * q);
    }
}

/* The facing decisions of the 16 planes in R (their 64 floats as loaded):
 * bit t of the mask for plane t; lanes outside LIVE are 0. */
SV_TARGET_AVX512 static inline __mmask16
facing16_avx512(const __m512 r[4], __mmask16 live, __m512 lx, __m512 ly, __m512 lz, __m512 lw) {
    __m512 a, b, c, d;
    transpose16(r[0], r[1], r[2], r[3], &a, &b, &c, &d);
    __m512 s = _mm512_add_ps(_mm512_mul_ps(a, lx), _mm512_mul_ps(b, ly));
    s = _mm512_add_ps(s, _mm512_mul_ps(c, lz));
    s = _mm512_add_ps(s, _mm512_mul_ps(d, lw));
    return _mm512_mask_cmp_ps_mask(live, s, _mm512_setzero_ps(), _CMP_GT_OQ);
}

/* The same for the 16 planes at P, all read with plain loads. */
SV_TARGET_AVX512 static inline __mmask16 facing16_at_avx512(const float *p, __m512 lx, __m512 ly,
                                                            __m512 lz, __m512 lw) {
    const __m512 r[4] = {_mm512_loadu_ps(p), _mm512_loadu_ps(p + 16), _mm512_loadu_ps(p + 32),
                         _mm512_loadu_ps(p + 48)};
    return facing16_avx512(r, (__mmask16)0xFFFF, lx, ly, lz, lw);
}

SV_TARGET_AVX512 static inline int facing_avx512(const Plane *planes, int numTriangles,
                                                 const Vec4 *light, uint8_t *facing,
                                                 int wantCount) {
    if (numTriangles < 0) return 0;
    int count = 0;
    const __m512 lx = _mm512_set1_ps(light->x), ly = _mm512_set1_ps(light->y);
    const __m512 lz = _mm512_set1_ps(light->z), lw = _mm512_set1_ps(light->w);
    const __m128i one = _mm_set1_epi8(1);
    const __m256i one32 = _mm256_set1_epi8(1);
    const float *p =
        (const float *)planes; /* no member access: planes may be NULL when the count is 0 */
    const size_t total = (size_t)numTriangles;
    size_t i = 0;
    /* Whole blocks first, 32 triangles a step: plain loads (no masks to
     * compute), the two blocks' compare masks joined (kunpckwd) into one
     * 32-byte store. size_t and "what is left" comparisons: no index
     * passes numTriangles, none overflows for counts near INT_MAX. */
    for (; total - i >= 32; i += 32, p += 128) {
        const __mmask16 g0 = facing16_at_avx512(p, lx, ly, lz, lw);
        const __mmask16 g1 = facing16_at_avx512(p + 64, lx, ly, lz, lw);
        const __mmask32 g = _mm512_kunpackw((__mmask32)g1, (__mmask32)g0);
        _mm256_storeu_si256((__m256i *)(facing + i), _mm256_maskz_mov_epi8(g, one32));
        if (wantCount) count += __builtin_popcount((unsigned)g);
    }
    if (total - i >= 16) {
        const __mmask16 g = facing16_at_avx512(p, lx, ly, lz, lw);
        _mm_storeu_si128((__m128i *)(facing + i), _mm_maskz_mov_epi8(g, one));
        if (wantCount) count += __builtin_popcount((unsigned)g);
        i += 16, p += 64;
    }
    if (i < total) { /* the last 1-15: masked loads read nothing past them */
        const int n = (int)(total - i);
        const __mmask16 live = (__mmask16)((1u << n) - 1);
        __m512 r[4];
        load16(p, n, r);
        const __mmask16 gt = facing16_avx512(r, live, lx, ly, lz, lw);
        _mm_mask_storeu_epi8(facing + i, live, _mm_maskz_mov_epi8(gt, one));
        if (wantCount) count += __builtin_popcount((unsigned)gt);
    }
    facing[numTriangles] = 1;
    SV_VZEROUPPER_IF_UNOPTIMISED(); /* (clears ZMM_Hi256 too) */
    return count;
}

SV_TARGET_AVX512 void sv_calculate_facing_avx512(const Plane *planes, int numTriangles,
                                                 const Vec4 *light, uint8_t *facing) {
    (void)facing_avx512(planes, numTriangles, light, facing, 0);
}

SV_TARGET_AVX512 int sv_calculate_facing_count_avx512(const Plane *planes, int numTriangles,
                                                      const Vec4 *light, uint8_t *facing) {
    return facing_avx512(planes, numTriangles, light, facing, 1);
}

SV_TARGET_AVX512 int sv_calculate_cull_bits_avx512(const Vec4 *positions, int numVerts,
                                                   const Bounds *surfaceBounds,
                                                   const Plane lightPlanes[SV_NUM_LIGHT_PLANES],
                                                   uint8_t *cullBits) {
    if (numVerts < 0) return 0;
    CullSetup cs;
    if (cull_setup(surfaceBounds, lightPlanes, &cs)) return 1;
    __m512 pa[SV_NUM_LIGHT_PLANES], pb[SV_NUM_LIGHT_PLANES], pc[SV_NUM_LIGHT_PLANES],
        pd[SV_NUM_LIGHT_PLANES];
    __m128i bit[SV_NUM_LIGHT_PLANES];
    for (int k = 0; k < cs.nlive; k++) {
        pa[k] = _mm512_set1_ps(cs.lp[k].a), pb[k] = _mm512_set1_ps(cs.lp[k].b);
        pc[k] = _mm512_set1_ps(cs.lp[k].c), pd[k] = _mm512_set1_ps(cs.lp[k].d);
        bit[k] = _mm_set1_epi8((char)(1 << cs.live[k]));
    }
    const __m512 zero = _mm512_setzero_ps();
    const float *v = (const float *)positions; /* (may be NULL when the count is 0) */
    for (size_t j = 0, left = (size_t)numVerts; left > 0; j += 16, v += 64) {
        const int n = left < 16 ? (int)left : 16;
        left -= (size_t)n;
        __m512 r[4], x, y, z, w;
        load16(v, n, r);
        transpose16(r[0], r[1], r[2], r[3], &x, &y, &z, &w);
        (void)w;
        __m128i bytes = _mm_setzero_si128();
        for (int k = 0; k < cs.nlive; k++) {
            __m512 s = _mm512_add_ps(_mm512_mul_ps(pa[k], x), _mm512_mul_ps(pb[k], y));
            s = _mm512_add_ps(s, _mm512_mul_ps(pc[k], z));
            s = _mm512_add_ps(s, pd[k]);
            const __mmask16 lt = _mm512_cmp_ps_mask(s, zero, _CMP_LT_OQ);
            bytes = _mm_mask_mov_epi8(bytes, lt, _mm_or_si128(bytes, bit[k]));
        }
        _mm_mask_storeu_epi8(cullBits + j, (__mmask16)((1u << n) - 1), bytes);
    }
    SV_VZEROUPPER_IF_UNOPTIMISED();
    return 0;
}

/* ---- The table ----------------------------------------------------------- */

static const sv_facing_variant facing_variants[] = {
    {"c_ref", SV_ISA_NONE, sv_calculate_facing_c_ref, sv_calculate_cull_bits_c_ref,
     sv_calculate_facing_count_c},
    {"sse2", SV_ISA_SSE2, sv_calculate_facing_sse2, sv_calculate_cull_bits_sse2,
     sv_calculate_facing_count_sse2},
    {"avx2", SV_ISA_SSE2 | SV_ISA_AVX2, sv_calculate_facing_avx2, sv_calculate_cull_bits_avx2,
     sv_calculate_facing_count_avx2},
    {"avx512", SV_ISA_SSE2 | SV_ISA_AVX2 | SV_ISA_AVX512, sv_calculate_facing_avx512,
     sv_calculate_cull_bits_avx512, sv_calculate_facing_count_avx512},
};

const sv_facing_variant *sv_facing_variants(int *count) {
    if (count) *count = (int)(sizeof facing_variants / sizeof facing_variants[0]);
    return facing_variants;
}

const sv_facing_variant *sv_facing_variant_by_name(const char *name) {
    for (size_t i = 0; name && i < sizeof facing_variants / sizeof facing_variants[0]; i++) {
        if (strcmp(facing_variants[i].name, name) == 0) return &facing_variants[i];
    }
    return NULL;
}

const sv_facing_variant *sv_best_facing_variant(void) {
    const unsigned isa = sv_cpu_isa();
    size_t i = sizeof facing_variants / sizeof facing_variants[0];
    while (i-- > 1) {
        if ((facing_variants[i].isa & isa) == facing_variants[i].isa) return &facing_variants[i];
    }
    return &facing_variants[0];
}
