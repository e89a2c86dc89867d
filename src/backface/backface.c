/*
 * Seed 001's four view back-face culling methods, and AVX2 / AVX-512 twins
 * of the fourth (include/shadowvol_backface.h has the contracts). The
 * listings' errors fixed here are in docs/ERRATA.md ("Seed 001"):
 *  - the non-compact listing closes the function after clearing the bit
 *    array (a stray brace), and the compact one returns from inside its
 *    triangle loop (the closing braces of the loop and the function
 *    swapped): both would count at most the first triangle;
 *  - the SIMD listing tests the SIGN BITS of TN (move_mask) where the
 *    scalar ones test TN <= 0: +0 would be back-facing there, -0 and a
 *    negative NaN front-facing. Here every method makes the scalar test
 *    (an ordered compare), so all compact methods agree bit for bit;
 *  - the SIMD listing loops over (n + 3) / 4 blocks and counts every lane
 *    of the last one: the padding triangles (zero normal, tn 0: TN = 0)
 *    would be counted front-facing and mark vertex 0. The last block's
 *    lanes past n are masked off;
 *  - `_m_empty()` (EMMS) ends MMX use in the 1999 listing (Is16vec4 lived
 *    in MMX registers); SSE2 converts the int16 normals in xmm registers,
 *    so there is no MMX state to clear.
 * The compact arithmetic is sv_calculate_facing_fixed16's (the view scaled
 * by 1/32767 once per call, so the division the seed does per triangle is
 * gone and its error bound applies); the non-compact one is the seed's.
 *
 * Copyright (C) 2026 the shadowvol authors. LGPL-2.1-or-later.
 */
#include <immintrin.h>
#include <string.h>

#include "../accuracy/mxcsr_guard.h"
#include "shadowvol_backface.h"

/* The seed's SELECT_VTX: bit v % 32 of word v / 32. */
#define SELECT_VTX(bits, v) ((bits)[(v) >> 5] |= 1u << ((v)&31))

/* A triangle's decision F: its front byte (when asked), and its three
 * vertices marked when it is front-facing. Returns F (0 or 1). */
static inline int record(int f, uint8_t *front, int i, uint32_t *bits, uint16_t a, uint16_t b,
                         uint16_t c) {
    if (front) front[i] = (uint8_t)f;
    if (f && bits) {
        SELECT_VTX(bits, a);
        SELECT_VTX(bits, b);
        SELECT_VTX(bits, c);
    }
    return f;
}

static void clear_bits(uint32_t *bits, int numVertices) {
    if (bits && numVertices > 0) memset(bits, 0, ((size_t)numVertices + 31) / 32 * sizeof *bits);
}

/* The view for the compact arithmetic: xyz / 32767 (once), w. */
static inline void scaled_view(const Vec4 *view, float v[4]) {
    v[0] = view->x / 32767.0f;
    v[1] = view->y / 32767.0f;
    v[2] = view->z / 32767.0f;
    v[3] = view->w;
}

/* ---- 1. Non-compact: 32-byte triangles ----------------------------------- */

__attribute__((noinline)) static int noncompact_body(const sv_cull_triangle *tris, int n,
                                                     int numVertices, const Vec4 *view,
                                                     uint32_t *bits, uint8_t *front) {
    clear_bits(bits, numVertices);
    const float vx = view->x, vy = view->y, vz = view->z, w = view->w;
    int ff = 0;
    for (int i = 0; i < n; i++) {
        const sv_cull_triangle *t = &tris[i];
        /* The viewing vector (P w - V; P - V for a camera at V: x * 1 is
         * exact) and its dot product with the normal, left to right. */
        const float tx = t->px * w - vx, ty = t->py * w - vy, tz = t->pz * w - vz;
        const float tn = tx * t->nx + ty * t->ny + tz * t->nz;
        ff += record(tn <= 0.0f, front, i, bits, t->v1, t->v2, t->v3);
    }
    return ff;
}

int sv_backface_noncompact(const sv_cull_triangle *tris, int numTriangles, int numVertices,
                           const Vec4 *view, uint32_t *vertexBits, uint8_t *front) {
    if (numTriangles < 0) return 0;
    const unsigned saved = sv_mxcsr_enter();
    const int ff = noncompact_body(tris, numTriangles, numVertices, view, vertexBits, front);
    sv_mxcsr_leave(saved);
    return ff;
}

/* ---- 2. Compact: 16-byte triangles --------------------------------------- */

__attribute__((noinline)) static int compact_body(const sv_cull_triangle16 *tris, int n,
                                                  int numVertices, const Vec4 *view, uint32_t *bits,
                                                  uint8_t *front) {
    clear_bits(bits, numVertices);
    float v[4];
    scaled_view(view, v);
    int ff = 0;
    for (int i = 0; i < n; i++) {
        const sv_cull_triangle16 *t = &tris[i];
        /* fixed16's s, left to right; int16 -> float is exact */
        const float s = (float)t->nx * v[0] + (float)t->ny * v[1] + (float)t->nz * v[2] -
                        t->tn * v[3];
        ff += record(s >= 0.0f, front, i, bits, t->v1, t->v2, t->v3);
    }
    return ff;
}

int sv_backface_compact(const sv_cull_triangle16 *tris, int numTriangles, int numVertices,
                        const Vec4 *view, uint32_t *vertexBits, uint8_t *front) {
    if (numTriangles < 0) return 0;
    const unsigned saved = sv_mxcsr_enter();
    const int ff = compact_body(tris, numTriangles, numVertices, view, vertexBits, front);
    sv_mxcsr_leave(saved);
    return ff;
}

/* ---- What every block method does with a step's mask ---------------------- */

/* MASK: bit j = triangle first + j is front-facing (lanes past n clear). */
static inline int emit_mask(const sv_cull_block4 *blocks, int first, unsigned mask, int lanes,
                            uint32_t *bits, uint8_t *front) {
    if (front) {
        for (int j = 0; j < lanes; j++) front[first + j] = (uint8_t)((mask >> j) & 1);
    }
    if (bits) {
        for (unsigned m = mask; m; m &= m - 1) { /* once per front-facing triangle */
            const int j = __builtin_ctz(m);
            const uint16_t *v = blocks[(first + j) / SV_CULL_BLOCK].v[(first + j) % SV_CULL_BLOCK];
            SELECT_VTX(bits, v[0]);
            SELECT_VTX(bits, v[1]);
            SELECT_VTX(bits, v[2]);
        }
    }
    return __builtin_popcount(mask);
}

/* Valid lanes of a step of LANES triangles starting at FIRST. */
static inline unsigned lane_mask(int first, int n, int lanes) {
    const int left = n - first;
    return left >= lanes ? (lanes == 32 ? ~0u : (1u << lanes) - 1) : (1u << left) - 1;
}

/* ---- 3 and 4. Compact SIMD (SSE2), four per step -------------------------- */

/* Four int16 (8 bytes) -> four floats, exact. SSE2 has no pmovsxwd:
 * interleave each word with itself, then shift the copy out arithmetically. */
static inline __m128 int16x4_to_ps(const int16_t *p) {
    const __m128i w = _mm_loadl_epi64((const __m128i *)p);
    return _mm_cvtepi32_ps(_mm_srai_epi32(_mm_unpacklo_epi16(w, w), 16));
}

static inline unsigned block_mask_sse2(const sv_cull_block4 *b, __m128 v0, __m128 v1, __m128 v2,
                                       __m128 vw) {
    const __m128 s = _mm_sub_ps(_mm_add_ps(_mm_add_ps(_mm_mul_ps(int16x4_to_ps(b->nx), v0),
                                                      _mm_mul_ps(int16x4_to_ps(b->ny), v1)),
                                           _mm_mul_ps(int16x4_to_ps(b->nz), v2)),
                                _mm_mul_ps(_mm_load_ps(b->tn), vw));
    /* s >= 0, ordered (NaN: not front), as the scalar test */
    return (unsigned)_mm_movemask_ps(_mm_cmpge_ps(s, _mm_setzero_ps()));
}

static inline int sse2_blocks(const sv_cull_block4 *blocks, int firstBlock, int n, const float v[4],
                              uint32_t *bits, uint8_t *front, int prefetch) {
    const __m128 v0 = _mm_set1_ps(v[0]), v1 = _mm_set1_ps(v[1]), v2 = _mm_set1_ps(v[2]),
                 vw = _mm_set1_ps(v[3]);
    const int nb = (n + SV_CULL_BLOCK - 1) / SV_CULL_BLOCK;
    int ff = 0;
    for (int b = firstBlock; b < nb; b++) {
        if (prefetch) {
            /* 1 KiB ahead: 16 lines, a few hundred ticks of work at the
             * rate these loops run, about a memory latency (not tuned to
             * a CPU; the benchmark shows where it pays). Prefetching past
             * the end of the array cannot fault. */
            _mm_prefetch((const char *)(blocks + b + 16), _MM_HINT_T0);
        }
        const unsigned m = block_mask_sse2(&blocks[b], v0, v1, v2, vw) &
                           lane_mask(SV_CULL_BLOCK * b, n, SV_CULL_BLOCK);
        if (m || front)
            ff += emit_mask(blocks, SV_CULL_BLOCK * b, m,
                            n - SV_CULL_BLOCK * b < SV_CULL_BLOCK ? n - SV_CULL_BLOCK * b
                                                                  : SV_CULL_BLOCK,
                            bits, front);
    }
    return ff;
}

__attribute__((noinline)) static int sse2_body(const sv_cull_block4 *blocks, int n, int numVertices,
                                               const Vec4 *view, uint32_t *bits, uint8_t *front,
                                               int prefetch) {
    clear_bits(bits, numVertices);
    float v[4];
    scaled_view(view, v);
    return prefetch ? sse2_blocks(blocks, 0, n, v, bits, front, 1)
                    : sse2_blocks(blocks, 0, n, v, bits, front, 0);
}

int sv_backface_compact_sse2(const sv_cull_block4 *blocks, int numTriangles, int numVertices,
                             const Vec4 *view, uint32_t *vertexBits, uint8_t *front) {
    if (numTriangles < 0) return 0;
    const unsigned saved = sv_mxcsr_enter();
    const int ff = sse2_body(blocks, numTriangles, numVertices, view, vertexBits, front, 0);
    sv_mxcsr_leave(saved);
    return ff;
}

int sv_backface_compact_sse2_prefetch(const sv_cull_block4 *blocks, int numTriangles,
                                      int numVertices, const Vec4 *view, uint32_t *vertexBits,
                                      uint8_t *front) {
    if (numTriangles < 0) return 0;
    const unsigned saved = sv_mxcsr_enter();
    const int ff = sse2_body(blocks, numTriangles, numVertices, view, vertexBits, front, 1);
    sv_mxcsr_leave(saved);
    return ff;
}

/* ---- AVX2: two blocks (eight triangles) per step -------------------------- */

#define SV_TARGET_AVX2 __attribute__((target("avx2,bmi,popcnt")))

/* Eight int16 of two blocks -> eight floats. */
SV_TARGET_AVX2 static inline __m256 int16x8_to_ps(const int16_t *a, const int16_t *b) {
    const __m128i w = _mm_unpacklo_epi64(_mm_loadl_epi64((const __m128i *)a),
                                         _mm_loadl_epi64((const __m128i *)b));
    return _mm256_cvtepi32_ps(_mm256_cvtepi16_epi32(w));
}

SV_TARGET_AVX2 __attribute__((noinline)) static int avx2_body(const sv_cull_block4 *blocks, int n,
                                                              int numVertices, const Vec4 *view,
                                                              uint32_t *bits, uint8_t *front) {
    clear_bits(bits, numVertices);
    float v[4];
    scaled_view(view, v);
    const __m256 v0 = _mm256_set1_ps(v[0]), v1 = _mm256_set1_ps(v[1]), v2 = _mm256_set1_ps(v[2]),
                 vw = _mm256_set1_ps(v[3]);
    const int steps = n / 8;
    int ff = 0;
    for (int k = 0; k < steps; k++) {
        const sv_cull_block4 *a = &blocks[2 * k], *b = &blocks[2 * k + 1];
        const __m256 tn = _mm256_insertf128_ps(_mm256_castps128_ps256(_mm_load_ps(a->tn)),
                                               _mm_load_ps(b->tn), 1);
        /* The same operations in the same order as the scalar compact
         * routine, eight lanes at a time (no FMA: not in the target). */
        const __m256 s = _mm256_sub_ps(
            _mm256_add_ps(_mm256_add_ps(_mm256_mul_ps(int16x8_to_ps(a->nx, b->nx), v0),
                                        _mm256_mul_ps(int16x8_to_ps(a->ny, b->ny), v1)),
                          _mm256_mul_ps(int16x8_to_ps(a->nz, b->nz), v2)),
            _mm256_mul_ps(tn, vw));
        const unsigned m = (unsigned)_mm256_movemask_ps(
            _mm256_cmp_ps(s, _mm256_setzero_ps(), _CMP_GE_OQ));
        if (m || front) ff += emit_mask(blocks, 8 * k, m, 8, bits, front);
    }
    /* An odd last block, and the last block's padding lanes: SSE2, the
     * same arithmetic. */
    return ff + sse2_blocks(blocks, 2 * steps, n, v, bits, front, 0);
}

int sv_backface_compact_avx2(const sv_cull_block4 *blocks, int numTriangles, int numVertices,
                             const Vec4 *view, uint32_t *vertexBits, uint8_t *front) {
    if (numTriangles < 0) return 0;
    const unsigned saved = sv_mxcsr_enter();
    const int ff = avx2_body(blocks, numTriangles, numVertices, view, vertexBits, front);
    sv_mxcsr_leave(saved);
    return ff;
}

/* ---- AVX-512: four blocks (sixteen triangles) per step -------------------- */

#define SV_TARGET_AVX512 __attribute__((target("avx512f,avx512bw,avx512vl,avx512dq,bmi,popcnt")))

SV_TARGET_AVX512 static inline __m512 int16x16_to_ps(const sv_cull_block4 *b, int field) {
    const int16_t *p[4];
    for (int i = 0; i < 4; i++) p[i] = field == 0 ? b[i].nx : field == 1 ? b[i].ny : b[i].nz;
    const __m128i lo = _mm_unpacklo_epi64(_mm_loadl_epi64((const __m128i *)p[0]),
                                          _mm_loadl_epi64((const __m128i *)p[1]));
    const __m128i hi = _mm_unpacklo_epi64(_mm_loadl_epi64((const __m128i *)p[2]),
                                          _mm_loadl_epi64((const __m128i *)p[3]));
    return _mm512_cvtepi32_ps(
        _mm512_cvtepi16_epi32(_mm256_inserti128_si256(_mm256_castsi128_si256(lo), hi, 1)));
}

SV_TARGET_AVX512 __attribute__((noinline)) static int avx512_body(const sv_cull_block4 *blocks,
                                                                  int n, int numVertices,
                                                                  const Vec4 *view, uint32_t *bits,
                                                                  uint8_t *front) {
    clear_bits(bits, numVertices);
    float v[4];
    scaled_view(view, v);
    const __m512 v0 = _mm512_set1_ps(v[0]), v1 = _mm512_set1_ps(v[1]), v2 = _mm512_set1_ps(v[2]),
                 vw = _mm512_set1_ps(v[3]);
    const int steps = n / 16;
    int ff = 0;
    for (int k = 0; k < steps; k++) {
        const sv_cull_block4 *b = &blocks[4 * k];
        __m512 tn = _mm512_castps128_ps512(_mm_load_ps(b[0].tn));
        tn = _mm512_insertf32x4(tn, _mm_load_ps(b[1].tn), 1);
        tn = _mm512_insertf32x4(tn, _mm_load_ps(b[2].tn), 2);
        tn = _mm512_insertf32x4(tn, _mm_load_ps(b[3].tn), 3);
        const __m512 s =
            _mm512_sub_ps(_mm512_add_ps(_mm512_add_ps(_mm512_mul_ps(int16x16_to_ps(b, 0), v0),
                                                      _mm512_mul_ps(int16x16_to_ps(b, 1), v1)),
                                        _mm512_mul_ps(int16x16_to_ps(b, 2), v2)),
                          _mm512_mul_ps(tn, vw));
        const unsigned m = (unsigned)_mm512_cmp_ps_mask(s, _mm512_setzero_ps(), _CMP_GE_OQ);
        if (m || front) ff += emit_mask(blocks, 16 * k, m, 16, bits, front);
    }
    return ff + sse2_blocks(blocks, 4 * steps, n, v, bits, front, 0);
}

int sv_backface_compact_avx512(const sv_cull_block4 *blocks, int numTriangles, int numVertices,
                               const Vec4 *view, uint32_t *vertexBits, uint8_t *front) {
    if (numTriangles < 0) return 0;
    const unsigned saved = sv_mxcsr_enter();
    const int ff = avx512_body(blocks, numTriangles, numVertices, view, vertexBits, front);
    sv_mxcsr_leave(saved);
    return ff;
}
