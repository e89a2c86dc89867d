/*
 * The seed's vertex program (include/shadowvol_extrude.h) with AVX2 and
 * AVX-512, BIT-IDENTICAL to the C reference in extrude_internal.h: the same
 * float operations in the same order, no FMA (the file is built with
 * -ffp-contract=off and uses no FMA intrinsics); sqrt and division are
 * correctly rounded in both; the selections are the reference's ordered
 * compares (dot < 0: LT_OQ, NaN false; !(len2 > 0): NGT_UQ, NaN true), and
 * max(ext, 0) is maxps with 0 second, which returns 0 where ext is NaN or
 * not above 0, as the reference's  ext > 0 ? ext : 0 .
 *
 * The stream's six columns come in by gathers (offsets 6i within a step,
 * so they never overflow); the four output columns go back to rows by 4x4
 * transposes, one full-width store per two (four) vertices.
 *
 * Copyright (C) 2026 the shadowvol authors. LGPL-2.1-or-later.
 */
#include <immintrin.h>

#include "extrude_internal.h"
#include "../core/simd_exit.h"

#define SV_TARGET_AVX2 __attribute__((target("avx2")))
#define SV_TARGET_AVX512 __attribute__((target("avx512f,avx512vl,avx512dq,avx2")))

/* ---- AVX2 ------------------------------------------------------------------ */

/* The AVX2 variants: APPROX (a constant) picks the rsqrt variant's
 * 1/sqrt. */
SV_TARGET_AVX2 static inline __attribute__((always_inline)) void
extrude_avx2(const float *stream, int numVertices, const sv_extrude_light *light, Vec4 *out,
             int approx) {
    const Vec4 l = light->position;
    const float range = light->range;
    const int finite = sv_extrude_finite(&l, range);
    const __m256 lx = _mm256_set1_ps(l.x), ly = _mm256_set1_ps(l.y), lz = _mm256_set1_ps(l.z);
    const __m256 lw = _mm256_set1_ps(l.w), vrange = _mm256_set1_ps(range);
    const __m256 zero = _mm256_setzero_ps(), one = _mm256_set1_ps(1.0f);
    const __m256i offsets = _mm256_setr_epi32(0, 6, 12, 18, 24, 30, 36, 42);
    int i = 0;
    for (; i + 8 <= numVertices; i += 8) {
        const float *v = stream + SV_EXTRUDE_STREAM_FLOATS * (ptrdiff_t)i;
        const __m256 px = _mm256_i32gather_ps(v + 0, offsets, 4);
        const __m256 py = _mm256_i32gather_ps(v + 1, offsets, 4);
        const __m256 pz = _mm256_i32gather_ps(v + 2, offsets, 4);
        const __m256 nx = _mm256_i32gather_ps(v + 3, offsets, 4);
        const __m256 ny = _mm256_i32gather_ps(v + 4, offsets, 4);
        const __m256 nz = _mm256_i32gather_ps(v + 5, offsets, 4);
        const __m256 dx = _mm256_sub_ps(_mm256_mul_ps(px, lw), lx);
        const __m256 dy = _mm256_sub_ps(_mm256_mul_ps(py, lw), ly);
        const __m256 dz = _mm256_sub_ps(_mm256_mul_ps(pz, lw), lz);
        const __m256 len2 = _mm256_add_ps(_mm256_add_ps(_mm256_mul_ps(dx, dx),
                                                        _mm256_mul_ps(dy, dy)),
                                          _mm256_mul_ps(dz, dz));
        __m256 inv;
        if (approx) { /* y0 * (1.5 - (0.5 * len2) * (y0 * y0)), as sv_extrude_rsqrt_nr */
            const __m256 y0 = _mm256_rsqrt_ps(len2);
            inv = _mm256_mul_ps(y0, _mm256_sub_ps(_mm256_set1_ps(1.5f),
                                                  _mm256_mul_ps(_mm256_mul_ps(_mm256_set1_ps(0.5f),
                                                                              len2),
                                                                _mm256_mul_ps(y0, y0))));
        } else {
            inv = _mm256_div_ps(one, _mm256_sqrt_ps(len2));
        }
        const __m256 ux = _mm256_mul_ps(dx, inv);
        const __m256 uy = _mm256_mul_ps(dy, inv);
        const __m256 uz = _mm256_mul_ps(dz, inv);
        const __m256 dot = _mm256_add_ps(_mm256_add_ps(_mm256_mul_ps(nx, ux),
                                                       _mm256_mul_ps(ny, uy)),
                                         _mm256_mul_ps(nz, uz));
        const __m256 keep = _mm256_or_ps(_mm256_cmp_ps(dot, zero, _CMP_LT_OQ),
                                         _mm256_cmp_ps(len2, zero, _CMP_NGT_UQ));
        __m256 ox, oy, oz, ow;
        if (finite) {
            const __m256 len = _mm256_div_ps(one, inv);
            const __m256 ext = _mm256_max_ps(_mm256_sub_ps(vrange, len), zero);
            ox = _mm256_add_ps(_mm256_mul_ps(ux, ext), px);
            oy = _mm256_add_ps(_mm256_mul_ps(uy, ext), py);
            oz = _mm256_add_ps(_mm256_mul_ps(uz, ext), pz);
            ow = one;
        } else {
            ox = dx, oy = dy, oz = dz;
            ow = zero;
        }
        ox = _mm256_blendv_ps(ox, px, keep);
        oy = _mm256_blendv_ps(oy, py, keep);
        oz = _mm256_blendv_ps(oz, pz, keep);
        ow = _mm256_blendv_ps(ow, one, keep);
        /* Columns -> rows: r0 = vertex 0 | 4, r1 = 1 | 5, r2 = 2 | 6, r3 = 3 | 7. */
        const __m256 t0 = _mm256_unpacklo_ps(ox, oy), t1 = _mm256_unpackhi_ps(ox, oy);
        const __m256 t2 = _mm256_unpacklo_ps(oz, ow), t3 = _mm256_unpackhi_ps(oz, ow);
        const __m256 r0 = _mm256_shuffle_ps(t0, t2, 0x44), r1 = _mm256_shuffle_ps(t0, t2, 0xEE);
        const __m256 r2 = _mm256_shuffle_ps(t1, t3, 0x44), r3 = _mm256_shuffle_ps(t1, t3, 0xEE);
        float *o = (float *)(out + i);
        _mm256_storeu_ps(o + 0, _mm256_permute2f128_ps(r0, r1, 0x20));
        _mm256_storeu_ps(o + 8, _mm256_permute2f128_ps(r2, r3, 0x20));
        _mm256_storeu_ps(o + 16, _mm256_permute2f128_ps(r0, r1, 0x31));
        _mm256_storeu_ps(o + 24, _mm256_permute2f128_ps(r2, r3, 0x31));
    }
    for (; i < numVertices; i++)
        out[i] = sv_extrude_vertex(stream + SV_EXTRUDE_STREAM_FLOATS * (ptrdiff_t)i, &l, range,
                                   finite, approx);
}

SV_TARGET_AVX2
void sv_extrude_avx2(const float *stream, int numVertices, const sv_extrude_light *light,
                     Vec4 *out) {
    extrude_avx2(stream, numVertices, light, out, 0);
    SV_VZEROUPPER_IF_UNOPTIMISED();
}

SV_TARGET_AVX2
void sv_extrude_avx2_rsqrt(const float *stream, int numVertices, const sv_extrude_light *light,
                           Vec4 *out) {
    extrude_avx2(stream, numVertices, light, out, 1);
    SV_VZEROUPPER_IF_UNOPTIMISED();
}

/* ---- AVX-512 --------------------------------------------------------------- */

SV_TARGET_AVX512
void sv_extrude_avx512(const float *stream, int numVertices, const sv_extrude_light *light,
                       Vec4 *out) {
    const Vec4 l = light->position;
    const float range = light->range;
    const int finite = sv_extrude_finite(&l, range);
    const __m512 lx = _mm512_set1_ps(l.x), ly = _mm512_set1_ps(l.y), lz = _mm512_set1_ps(l.z);
    const __m512 lw = _mm512_set1_ps(l.w), vrange = _mm512_set1_ps(range);
    const __m512 zero = _mm512_setzero_ps(), one = _mm512_set1_ps(1.0f);
    const __m512i offsets = _mm512_mullo_epi32(_mm512_setr_epi32(0, 1, 2, 3, 4, 5, 6, 7, 8, 9, 10,
                                                                 11, 12, 13, 14, 15),
                                               _mm512_set1_epi32(6));
    for (int i = 0; i < numVertices; i += 16) {
        const int left = numVertices - i;
        /* One conversion of an unsigned (a conditional of two __mmask16 is an int). */
        const __mmask16 m = (__mmask16)(left >= 16 ? 0xFFFFu : (1u << left) - 1u);
        const float *v = stream + SV_EXTRUDE_STREAM_FLOATS * (ptrdiff_t)i;
        const __m512 px = _mm512_mask_i32gather_ps(zero, m, offsets, v + 0, 4);
        const __m512 py = _mm512_mask_i32gather_ps(zero, m, offsets, v + 1, 4);
        const __m512 pz = _mm512_mask_i32gather_ps(zero, m, offsets, v + 2, 4);
        const __m512 nx = _mm512_mask_i32gather_ps(zero, m, offsets, v + 3, 4);
        const __m512 ny = _mm512_mask_i32gather_ps(zero, m, offsets, v + 4, 4);
        const __m512 nz = _mm512_mask_i32gather_ps(zero, m, offsets, v + 5, 4);
        const __m512 dx = _mm512_sub_ps(_mm512_mul_ps(px, lw), lx);
        const __m512 dy = _mm512_sub_ps(_mm512_mul_ps(py, lw), ly);
        const __m512 dz = _mm512_sub_ps(_mm512_mul_ps(pz, lw), lz);
        const __m512 len2 = _mm512_add_ps(_mm512_add_ps(_mm512_mul_ps(dx, dx),
                                                        _mm512_mul_ps(dy, dy)),
                                          _mm512_mul_ps(dz, dz));
        const __m512 inv = _mm512_div_ps(one, _mm512_sqrt_ps(len2));
        const __m512 ux = _mm512_mul_ps(dx, inv);
        const __m512 uy = _mm512_mul_ps(dy, inv);
        const __m512 uz = _mm512_mul_ps(dz, inv);
        const __m512 dot = _mm512_add_ps(_mm512_add_ps(_mm512_mul_ps(nx, ux),
                                                       _mm512_mul_ps(ny, uy)),
                                         _mm512_mul_ps(nz, uz));
        const __mmask16 keep = (__mmask16)(_mm512_cmp_ps_mask(dot, zero, _CMP_LT_OQ) |
                                           _mm512_cmp_ps_mask(len2, zero, _CMP_NGT_UQ));
        __m512 ox, oy, oz, ow;
        if (finite) {
            const __m512 len = _mm512_div_ps(one, inv);
            const __m512 ext = _mm512_max_ps(_mm512_sub_ps(vrange, len), zero);
            ox = _mm512_add_ps(_mm512_mul_ps(ux, ext), px);
            oy = _mm512_add_ps(_mm512_mul_ps(uy, ext), py);
            oz = _mm512_add_ps(_mm512_mul_ps(uz, ext), pz);
            ow = one;
        } else {
            ox = dx, oy = dy, oz = dz;
            ow = zero;
        }
        ox = _mm512_mask_blend_ps(keep, ox, px);
        oy = _mm512_mask_blend_ps(keep, oy, py);
        oz = _mm512_mask_blend_ps(keep, oz, pz);
        ow = _mm512_mask_blend_ps(keep, ow, one);
        /* Columns -> rows: r0 = vertices 0 | 4 | 8 | 12, r1 = 1 | 5 | 9 | 13, ... */
        const __m512 t0 = _mm512_unpacklo_ps(ox, oy), t1 = _mm512_unpackhi_ps(ox, oy);
        const __m512 t2 = _mm512_unpacklo_ps(oz, ow), t3 = _mm512_unpackhi_ps(oz, ow);
        const __m512 r0 = _mm512_shuffle_ps(t0, t2, 0x44), r1 = _mm512_shuffle_ps(t0, t2, 0xEE);
        const __m512 r2 = _mm512_shuffle_ps(t1, t3, 0x44), r3 = _mm512_shuffle_ps(t1, t3, 0xEE);
        /* a = 0 4 1 5, b = 2 6 3 7, c = 8 12 9 13, d = 10 14 11 15 (vertices). */
        const __m512 a = _mm512_shuffle_f32x4(r0, r1, _MM_SHUFFLE(1, 0, 1, 0));
        const __m512 b = _mm512_shuffle_f32x4(r2, r3, _MM_SHUFFLE(1, 0, 1, 0));
        const __m512 c = _mm512_shuffle_f32x4(r0, r1, _MM_SHUFFLE(3, 2, 3, 2));
        const __m512 d = _mm512_shuffle_f32x4(r2, r3, _MM_SHUFFLE(3, 2, 3, 2));
        const __m512 rows[4] = {_mm512_shuffle_f32x4(a, b, _MM_SHUFFLE(2, 0, 2, 0)),
                                _mm512_shuffle_f32x4(a, b, _MM_SHUFFLE(3, 1, 3, 1)),
                                _mm512_shuffle_f32x4(c, d, _MM_SHUFFLE(2, 0, 2, 0)),
                                _mm512_shuffle_f32x4(c, d, _MM_SHUFFLE(3, 1, 3, 1))};
        float *o = (float *)(out + i);
        if (left >= 16) {
            for (int k = 0; k < 4; k++) _mm512_storeu_ps(o + 16 * k, rows[k]);
        } else {
            /* Store k holds vertices 4k .. 4k+3: four floats each. */
            for (int k = 0; 4 * k < left; k++) {
                const int n = left - 4 * k >= 4 ? 4 : left - 4 * k;
                _mm512_mask_storeu_ps(o + 16 * k, (__mmask16)((1u << (4 * n)) - 1), rows[k]);
            }
        }
    }
    SV_VZEROUPPER_IF_UNOPTIMISED();
}
