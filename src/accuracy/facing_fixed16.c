/*
 * The fixed16 variant of appendix A, after seed 001 (Levi, Zohar, Barad,
 * Klimovitski, "compact backface culling", Gamasutra 1999): a normal of
 * three 16-bit fixed-point components and a precomputed dot product tn per
 * triangle, 10 bytes instead of a float plane's 16:
 *   l = (x, y, z) / 32767                              (float, once)
 *   s = ((qx*lx + qy*ly) + qz*lz) - tn*w               (float)
 *   facing = s > 0
 * The seed computes TN = tn - (V . N) / SHRT_MAX and culls on TN <= 0; the
 * light here is the viewer there, the division by 32767 is folded into the
 * light once per call (so no product can overflow before a float plane's
 * would), and the sign is turned so that s > 0 means facing, as in
 * appendix A.
 *
 * Layout: blocks of eight triangles, structure of arrays (the seed's SIMD
 * layout, eight wide for AVX2); the scalar routine reads the same blocks,
 * so one preparation serves both and the two are bit-identical (same
 * operations; int16 -> float is exact; no FMA: -ffp-contract=off).
 * The seed's scalar structure carries the three vertex indices in the
 * other 6 bytes of its 16; the cap routines here read the surface's index
 * array instead, so they are not repeated.
 *
 * Why not half-precision normals (F16C, vcvtph2ps) in the same 10 bytes:
 * a half has 11 significant bits where int16 scaled to +-32767 has 15 and
 * a sign over the whole range, and one conversion instruction instead of
 * two (vpmovsxwd + vcvtdq2ps) buys little in a loop bound by the compare
 * and the byte stores. Measured with the same layout and light rotation
 * (directional lights, AMD EPYC VM): koala 0.31 against 0.36 ticks per
 * triangle, 2.8e-5 against 2.2e-6 of the facing bytes wrong; spot 0.32
 * against 0.37, 3.3e-5 against 5.4e-6. Six to thirteen times the errors
 * for 15% of a cost that is already the smallest of any variant, and a
 * CPU feature (F16C) the library's dispatch does not track: not a trade
 * worth a variant.
 *
 * Copyright (C) 2026 the shadowvol authors. LGPL-2.1-or-later.
 */
#include <immintrin.h>
#include <string.h>

#include "mxcsr_guard.h"
#include "shadowvol_accuracy.h"

/* The light's float scaling (part of the variant's definition). */
static inline void scaled_light(const Vec4 *light, float l[4]) {
    l[0] = light->x / 32767.0f;
    l[1] = light->y / 32767.0f;
    l[2] = light->z / 32767.0f;
    l[3] = light->w;
}

static inline uint8_t fixed16_one(const sv_plane16_block *b, int k, const float l[4]) {
    const float s = (float)b->nx[k] * l[0] + (float)b->ny[k] * l[1] + (float)b->nz[k] * l[2] -
                    b->tn[k] * l[3];
    return s > 0.0f;
}

__attribute__((noinline)) static void fixed16_body(const sv_plane16_block *blocks, int numTriangles,
                                                   const Vec4 *light, uint8_t *facing) {
    float l[4];
    scaled_light(light, l);
    for (int i = 0; i < numTriangles; i++) {
        facing[i] = fixed16_one(&blocks[i / SV_PLANE16_BLOCK], i % SV_PLANE16_BLOCK, l);
    }
    facing[numTriangles] = 1;
}

void sv_calculate_facing_fixed16(const sv_plane16_block *blocks, int numTriangles,
                                 const Vec4 *light, uint8_t *facing) {
    if (numTriangles < 0) return;
    const unsigned saved = sv_mxcsr_enter();
    fixed16_body(blocks, numTriangles, light, facing);
    sv_mxcsr_leave(saved);
}

/* ---- AVX2 ------------------------------------------------------------------ */

#define SV_TARGET_AVX2 __attribute__((target("avx2,bmi2")))

/* Eight int16 -> eight floats (exact). */
SV_TARGET_AVX2 static inline __m256 load_q(const int16_t *q) {
    return _mm256_cvtepi32_ps(_mm256_cvtepi16_epi32(_mm_loadu_si128((const __m128i *)q)));
}

/* The eight facing bits of one block. */
SV_TARGET_AVX2 static inline unsigned block_mask(const sv_plane16_block *b, __m256 lx, __m256 ly,
                                                 __m256 lz, __m256 lw) {
    __m256 s = _mm256_add_ps(_mm256_mul_ps(load_q(b->nx), lx), _mm256_mul_ps(load_q(b->ny), ly));
    s = _mm256_add_ps(s, _mm256_mul_ps(load_q(b->nz), lz));
    s = _mm256_sub_ps(s, _mm256_mul_ps(_mm256_loadu_ps(b->tn), lw));
    return (unsigned)_mm256_movemask_ps(_mm256_cmp_ps(s, _mm256_setzero_ps(), _CMP_GT_OQ));
}

/* PREFETCH is a compile-time constant: the two public routines are this
 * one body with and without the prefetch, nothing else differs. Four
 * blocks (320 bytes, five cache lines) ahead: far enough to cover a miss
 * to L2 at a few ticks per block. A prefetch past the array is harmless
 * (it never faults). */
SV_TARGET_AVX2 static inline void fixed16_avx2_impl(const sv_plane16_block *blocks,
                                                    int numTriangles, const Vec4 *light,
                                                    uint8_t *facing, int prefetch) {
    float l[4];
    scaled_light(light, l);
    const __m256 lx = _mm256_set1_ps(l[0]), ly = _mm256_set1_ps(l[1]);
    const __m256 lz = _mm256_set1_ps(l[2]), lw = _mm256_set1_ps(l[3]);
    const int full = numTriangles / SV_PLANE16_BLOCK;
    for (int k = 0; k < full; k++) {
        if (prefetch) {
            /* The address as an integer: blocks + k + 4 may lie past the
             * array, where pointer arithmetic is undefined. */
            _mm_prefetch((const char *)((uintptr_t)(blocks + k) + 4 * sizeof *blocks), _MM_HINT_T0);
        }
        const unsigned long long bytes = _pdep_u64(block_mask(&blocks[k], lx, ly, lz, lw),
                                                   0x0101010101010101ull);
        memcpy(facing + (size_t)k * SV_PLANE16_BLOCK, &bytes, 8);
    }
    /* The last, partial block is in memory in full (its unused entries are
     * zero): evaluate it whole, store only its triangles' bytes. */
    const int rest = numTriangles % SV_PLANE16_BLOCK;
    if (rest) {
        const unsigned long long bytes = _pdep_u64(block_mask(&blocks[full], lx, ly, lz, lw),
                                                   0x0101010101010101ull);
        memcpy(facing + (size_t)full * SV_PLANE16_BLOCK, &bytes, (size_t)rest);
    }
    facing[numTriangles] = 1;
}

SV_TARGET_AVX2 __attribute__((noinline)) static void
fixed16_avx2_body(const sv_plane16_block *blocks, int numTriangles, const Vec4 *light,
                  uint8_t *facing) {
    fixed16_avx2_impl(blocks, numTriangles, light, facing, 0);
}

SV_TARGET_AVX2 __attribute__((noinline)) static void
fixed16_avx2_prefetch_body(const sv_plane16_block *blocks, int numTriangles, const Vec4 *light,
                           uint8_t *facing) {
    fixed16_avx2_impl(blocks, numTriangles, light, facing, 1);
}

void sv_calculate_facing_fixed16_avx2(const sv_plane16_block *blocks, int numTriangles,
                                      const Vec4 *light, uint8_t *facing) {
    if (numTriangles < 0) return;
    const unsigned saved = sv_mxcsr_enter();
    fixed16_avx2_body(blocks, numTriangles, light, facing);
    sv_mxcsr_leave(saved);
}

void sv_calculate_facing_fixed16_avx2_prefetch(const sv_plane16_block *blocks, int numTriangles,
                                               const Vec4 *light, uint8_t *facing) {
    if (numTriangles < 0) return;
    const unsigned saved = sv_mxcsr_enter();
    fixed16_avx2_prefetch_body(blocks, numTriangles, light, facing);
    sv_mxcsr_leave(saved);
}
