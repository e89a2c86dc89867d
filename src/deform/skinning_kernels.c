/*
 * CPU skinning of positions (include/shadowvol_skin.h): the C reference,
 * its SIMD versions and their table.
 *
 * Every kernel computes, for each vertex v with influences k = 0..n-1
 * (joint j_k, weight w_k, joint matrix M_j: 16 floats, column-major):
 *
 *     B = w_0 * M_(j_0)                   each of the 12 used elements
 *     B = B + w_k * M_(j_k)               k = 1 .. n-1, in that order
 *     out.r = ((B[0][r]*x + B[1][r]*y) + B[2][r]*z) + B[3][r]     r = 0, 1, 2
 *
 * in float, every multiply and add rounded on its own (this file is built
 * with -ffp-contract=off and no kernel uses FMA). IEEE multiplication and
 * addition are commutative, and the SIMD kernels do the same operations in
 * the same order, lane by lane, so they give the C reference's bits: the
 * stated bound is 0 ulps, and the tests compare with ==. (Where a kernel
 * multiplies B[3] by 1.0f, that is exact.) What differs is only how the
 * lanes are used:
 *   sse2    one vertex at a time, one column of B per register (4 mul + 4
 *           add per influence), the fourth lane (row 3) ignored;
 *   avx2    one vertex at a time, two columns per register (2 + 2);
 *   avx512  one vertex at a time, the whole matrix in one register (1 + 1);
 *           the final sum adds its four 128-bit lanes in the C's order.
 * Row 3 of a joint matrix is loaded but never used.
 *
 * Copyright (C) 2026 the shadowvol authors. LGPL-2.1-or-later.
 */
#include <immintrin.h>
#include <string.h>

#include "shadowvol_skin.h"
#include "../core/simd_exit.h"

#define SV_SKIN_ARGS                                                                               \
    const float *joint_matrices, const float *rest, const uint16_t *joints, const float *weights,  \
        int influences, size_t num_vertices, float *out

void sv_skin_c_ref(SV_SKIN_ARGS) {
    for (size_t v = 0; v < num_vertices; v++) {
        const uint16_t *j = joints + v * (size_t)influences;
        const float *w = weights + v * (size_t)influences;
        float b[16];
        const float *m = joint_matrices + 16 * (size_t)j[0];
        for (int e = 0; e < 16; e++) {
            b[e] = w[0] * m[e];
        }
        for (int k = 1; k < influences; k++) {
            m = joint_matrices + 16 * (size_t)j[k];
            for (int e = 0; e < 16; e++) {
                b[e] = b[e] + w[k] * m[e];
            }
        }
        const float x = rest[3 * v], y = rest[3 * v + 1], z = rest[3 * v + 2];
        for (int r = 0; r < 3; r++) {
            out[3 * v + r] = ((b[r] * x + b[4 + r] * y) + b[8 + r] * z) + b[12 + r];
        }
    }
}

/* xyz of P to out[0..2] (nothing past). */
static inline __attribute__((always_inline)) void store3_sse(float *out, __m128 p) {
    _mm_storel_pi((__m64 *)out, p);
    _mm_store_ss(out + 2, _mm_movehl_ps(p, p));
}

/* Each SIMD kernel is one inline vertex routine, instantiated for 4 and 8
 * influences (the counts the loader gives: the loop over influences is
 * then unrolled, which saves a third of the instructions) and for any
 * other count. The arithmetic is the same in all three. */
#define SV_SKIN_LOOP(vertex_fn)                                                                    \
    do {                                                                                           \
        if (influences == 4) {                                                                     \
            for (size_t v = 0; v < num_vertices; v++)                                              \
                vertex_fn(joint_matrices, rest + 3 * v, joints + 4 * v, weights + 4 * v, 4,        \
                          out + 3 * v);                                                            \
        } else if (influences == 8) {                                                              \
            for (size_t v = 0; v < num_vertices; v++)                                              \
                vertex_fn(joint_matrices, rest + 3 * v, joints + 8 * v, weights + 8 * v, 8,        \
                          out + 3 * v);                                                            \
        } else {                                                                                   \
            const size_t n = (size_t)influences;                                                   \
            for (size_t v = 0; v < num_vertices; v++)                                              \
                vertex_fn(joint_matrices, rest + 3 * v, joints + n * v, weights + n * v,           \
                          influences, out + 3 * v);                                                \
        }                                                                                          \
    } while (0)

static inline __attribute__((always_inline)) void vertex_sse2(const float *joint_matrices,
                                                              const float *p, const uint16_t *j,
                                                              const float *w, int n, float *out) {
    const float *m = joint_matrices + 16 * (size_t)j[0];
    __m128 wk = _mm_set1_ps(w[0]);
    __m128 c0 = _mm_mul_ps(wk, _mm_loadu_ps(m));
    __m128 c1 = _mm_mul_ps(wk, _mm_loadu_ps(m + 4));
    __m128 c2 = _mm_mul_ps(wk, _mm_loadu_ps(m + 8));
    __m128 c3 = _mm_mul_ps(wk, _mm_loadu_ps(m + 12));
    for (int k = 1; k < n; k++) {
        m = joint_matrices + 16 * (size_t)j[k];
        wk = _mm_set1_ps(w[k]);
        c0 = _mm_add_ps(c0, _mm_mul_ps(wk, _mm_loadu_ps(m)));
        c1 = _mm_add_ps(c1, _mm_mul_ps(wk, _mm_loadu_ps(m + 4)));
        c2 = _mm_add_ps(c2, _mm_mul_ps(wk, _mm_loadu_ps(m + 8)));
        c3 = _mm_add_ps(c3, _mm_mul_ps(wk, _mm_loadu_ps(m + 12)));
    }
    __m128 r = _mm_add_ps(_mm_mul_ps(c0, _mm_set1_ps(p[0])), _mm_mul_ps(c1, _mm_set1_ps(p[1])));
    r = _mm_add_ps(r, _mm_mul_ps(c2, _mm_set1_ps(p[2])));
    r = _mm_add_ps(r, c3);
    store3_sse(out, r);
}

void sv_skin_sse2(SV_SKIN_ARGS) { SV_SKIN_LOOP(vertex_sse2); }

static inline __attribute__((always_inline, target("avx2"))) void
vertex_avx2(const float *joint_matrices, const float *p, const uint16_t *j, const float *w, int n,
            float *out) {
    const float *m = joint_matrices + 16 * (size_t)j[0];
    __m256 wk = _mm256_set1_ps(w[0]);
    __m256 c01 = _mm256_mul_ps(wk, _mm256_loadu_ps(m));     /* columns 0 | 1 */
    __m256 c23 = _mm256_mul_ps(wk, _mm256_loadu_ps(m + 8)); /* columns 2 | 3 */
    for (int k = 1; k < n; k++) {
        m = joint_matrices + 16 * (size_t)j[k];
        wk = _mm256_set1_ps(w[k]);
        c01 = _mm256_add_ps(c01, _mm256_mul_ps(wk, _mm256_loadu_ps(m)));
        c23 = _mm256_add_ps(c23, _mm256_mul_ps(wk, _mm256_loadu_ps(m + 8)));
    }
    const __m256 xy = _mm256_set_m128(_mm_set1_ps(p[1]), _mm_set1_ps(p[0]));
    const __m256 z1 = _mm256_set_m128(_mm_set1_ps(1.0f), _mm_set1_ps(p[2]));
    const __m256 a = _mm256_mul_ps(c01, xy); /* B0*x | B1*y */
    const __m256 b = _mm256_mul_ps(c23, z1); /* B2*z | B3 */
    __m128 r = _mm_add_ps(_mm256_castps256_ps128(a), _mm256_extractf128_ps(a, 1));
    r = _mm_add_ps(r, _mm256_castps256_ps128(b));
    r = _mm_add_ps(r, _mm256_extractf128_ps(b, 1));
    store3_sse(out, r);
}

__attribute__((target("avx2"))) void sv_skin_avx2(SV_SKIN_ARGS) {
    SV_SKIN_LOOP(vertex_avx2);
    SV_VZEROUPPER_IF_UNOPTIMISED();
}

static inline __attribute__((always_inline, target("avx512f,avx512vl"))) void
vertex_avx512(const float *joint_matrices, const float *p, const uint16_t *j, const float *w, int n,
              float *out) {
    __m512 b = _mm512_mul_ps(_mm512_set1_ps(w[0]),
                             _mm512_loadu_ps(joint_matrices + 16 * (size_t)j[0]));
    for (int k = 1; k < n; k++) {
        b = _mm512_add_ps(b, _mm512_mul_ps(_mm512_set1_ps(w[k]),
                                           _mm512_loadu_ps(joint_matrices + 16 * (size_t)j[k])));
    }
    /* lanes 0-3 x, 4-7 y, 8-11 z, 12-15 1 */
    const __m512 xyz1 = _mm512_insertf32x4(
        _mm512_insertf32x4(_mm512_insertf32x4(_mm512_castps128_ps512(_mm_set1_ps(p[0])),
                                              _mm_set1_ps(p[1]), 1),
                           _mm_set1_ps(p[2]), 2),
        _mm_set1_ps(1.0f), 3);
    const __m512 t = _mm512_mul_ps(b, xyz1);
    __m128 r = _mm_add_ps(_mm512_castps512_ps128(t), _mm512_extractf32x4_ps(t, 1));
    r = _mm_add_ps(r, _mm512_extractf32x4_ps(t, 2));
    r = _mm_add_ps(r, _mm512_extractf32x4_ps(t, 3));
    _mm_mask_storeu_ps(out, 0x7, r);
}

__attribute__((target("avx512f,avx512vl"))) void sv_skin_avx512(SV_SKIN_ARGS) {
    SV_SKIN_LOOP(vertex_avx512);
    SV_VZEROUPPER_IF_UNOPTIMISED();
}

const sv_skin_variant *sv_skin_variants(int *count) {
    static const sv_skin_variant kVariants[] = {
        {"c_ref", SV_ISA_NONE, &sv_skin_c_ref},
        {"sse2", SV_ISA_SSE2, &sv_skin_sse2},
        {"avx2", SV_ISA_AVX2, &sv_skin_avx2},
        {"avx512", SV_ISA_AVX512, &sv_skin_avx512},
    };
    if (count) *count = (int)(sizeof kVariants / sizeof kVariants[0]);
    return kVariants;
}

const sv_skin_variant *sv_skin_variant_by_name(const char *name) {
    int n = 0;
    const sv_skin_variant *v = sv_skin_variants(&n);
    for (int i = 0; name && i < n; i++) {
        if (strcmp(v[i].name, name) == 0) return &v[i];
    }
    return NULL;
}
