/*
 * The triangle walks of row_kernels.h in AVX-512 (F, BW, VL, DQ): a whole
 * set-up triangle's rows inside a band in one call, with no call, no
 * branch per edge and no scalar pixel loop per row.
 *
 * Per row:
 *  - The span: the three edges' x bounds are the lanes of one ymm of
 *    doubles, stepped by their slopes with one vaddpd, clamped, floored
 *    (vroundpd) and converted to int32 together; the left edges' lanes
 *    (step_x > 0) give the span's first pixel (a horizontal max over the
 *    lanes of a per-triangle blend), the right edges' its last. These are
 *    row_walk.h's operations lane by lane, so the spans are walk_rows'.
 *  - The pixels: spans of up to 8 pixels (most rows of a sliver) are one
 *    block of 8 lanes, longer ones blocks of 16, starting at the span's
 *    first pixel (not aligned: one block instead of two for a short span
 *    across a 16-pixel boundary). Edge functions: one zmm of 8 x int64 per
 *    edge and 8 lanes, the scalar value at the block's pixel broadcast
 *    and added to step * lane (per triangle); the OR's sign bits
 *    (vpmovq2m) are the uncovered lanes. Depth: 8 lanes of double per zmm
 *    (separate vmulpd and vaddpd: the C's rounding), vcvtpd2ps, one
 *    compare under the covered mask. Every store is masked to the pixels
 *    it updates; stencil bytes are read masked too (the per-light stencil
 *    buffers have no slack after them).
 *
 * Register map of a row (the compiler allocates; the roles): bound, slope
 * (ymm, lanes 0-2 the edges); left, right (xmm lane masks); the edges' lane
 * steps (three zmm for lanes 0-7, three for 8-15); the lane offsets, 0.5,
 * x0, dzdx and the row's zrow (zmm of double); delta or the id (broadcast).
 *
 * Input contracts: a triangle from Rasterizer::setup (pixel bounds inside
 * the target, |bound| within the clamp), rows inside the target; depth
 * readable kFrameSlack bytes past its end (a block's whole-vector depth
 * load reaches at most 15 pixels past the span).
 *
 * Copyright (C) 2026 the shadowvol authors. LGPL-2.1-or-later.
 */
/* GCC 12's own AVX-512 headers pass an undefined register to the masked
 * builtins behind _mm512_cvtpd_ps and _mm512_insertf32x8 and then warn
 * about it (a known false positive of -Wmaybe-uninitialized). */
#pragma GCC diagnostic ignored "-Wmaybe-uninitialized"
#include <immintrin.h>

#include "row_span_simd.h"
#include "row_walk.h"
#include "shadowvol.h"
#include "triangle_walk.h"

#define SV_TARGET_AVX512 __attribute__((target("avx512f,avx512bw,avx512vl,avx512dq,popcnt")))

namespace sv::raster {
namespace {

enum class Pass { depth, zpass, zfail };

/* What stays fixed over a triangle's pixels. */
struct PixelConstants {
    __m512i lane_step_lo[3], lane_step_hi[3]; /* step_x * lane, lanes 0-7 and 8-15 */
    __m512d lane_lo, lane_hi, half, x0, dzdx;
    __m512i value; /* the id (depth pass) or delta (stencil), broadcast */
};

SV_TARGET_AVX512 inline PixelConstants pixel_constants(const SetupTriangle &tri, int value) {
    PixelConstants c;
    const __m512i iota = _mm512_setr_epi64(0, 1, 2, 3, 4, 5, 6, 7);
    for (int e = 0; e < 3; e++) {
        const __m512i st = _mm512_set1_epi64(tri.step_x[e]);
        c.lane_step_lo[e] = _mm512_mullo_epi64(st, iota);
        c.lane_step_hi[e] = _mm512_add_epi64(c.lane_step_lo[e], _mm512_slli_epi64(st, 3));
    }
    c.lane_lo = _mm512_setr_pd(0, 1, 2, 3, 4, 5, 6, 7);
    c.lane_hi = _mm512_setr_pd(8, 9, 10, 11, 12, 13, 14, 15);
    c.half = _mm512_set1_pd(0.5);
    c.x0 = _mm512_set1_pd(tri.x0);
    c.dzdx = _mm512_set1_pd(tri.a);
    c.value = _mm512_set1_epi32(value);
    return c;
}

/* Depth at LANES pixels from x, in the C's operation order. */
SV_TARGET_AVX512 inline __m256 depth8(const PixelConstants &c, __m512d zrow, __m512d xb,
                                      __m512d lanes) {
    const __m512d dx = _mm512_sub_pd(_mm512_add_pd(_mm512_add_pd(xb, lanes), c.half), c.x0);
    return _mm512_cvtpd_ps(_mm512_add_pd(zrow, _mm512_mul_pd(c.dzdx, dx)));
}

/* The pixels [x, x + 8) of a row under TAIL (the span's part of them). */
template <Pass kPass>
SV_TARGET_AVX512 inline void block8(const PixelConstants &c, const int64_t ex[3], __m512d zrow,
                                    int x, __mmask8 tail, const WalkBuffers &b, std::size_t row,
                                    uint64_t &tested, uint64_t &written) {
    const __m512i o = _mm512_or_si512(
        _mm512_or_si512(_mm512_add_epi64(_mm512_set1_epi64(ex[0]), c.lane_step_lo[0]),
                        _mm512_add_epi64(_mm512_set1_epi64(ex[1]), c.lane_step_lo[1])),
        _mm512_add_epi64(_mm512_set1_epi64(ex[2]), c.lane_step_lo[2]));
    const __mmask8 cov = (__mmask8)(~_mm512_movepi64_mask(o) & tail);
    const __m256 z = depth8(c, zrow, _mm512_set1_pd((double)x), c.lane_lo);
    const __m256 d = _mm256_loadu_ps(b.depth + row + x); /* kFrameSlack */
    const __mmask8 less = _mm256_mask_cmp_ps_mask(cov, z, d, _CMP_LT_OQ);
    const __mmask8 upd = kPass == Pass::zfail ? (__mmask8)(cov & ~less) : less;
    if constexpr (kPass == Pass::depth) {
        _mm256_mask_storeu_ps(b.depth + row + x, upd, z);
        _mm256_mask_storeu_epi32(b.ids + row + x, upd, _mm512_castsi512_si256(c.value));
    } else {
        /* Read under the span's mask, known before the depth test: the
         * load need not wait for the compare (a second cache miss in
         * series with the depth's, on every row of a sliver). */
        uint8_t *s = b.stencil + row + x;
        const __m128i st = _mm_maskz_loadu_epi8(tail, s);
        _mm_mask_storeu_epi8(s, upd, _mm_add_epi8(st, _mm512_castsi512_si128(c.value)));
    }
    tested += (uint64_t)__builtin_popcount(cov);
    written += (uint64_t)__builtin_popcount(upd);
}

/* The pixels [x, x + 16) of a row under TAIL. */
template <Pass kPass>
SV_TARGET_AVX512 inline void block16(const PixelConstants &c, const int64_t ex[3], __m512d zrow,
                                     int x, __mmask16 tail, const WalkBuffers &b, std::size_t row,
                                     uint64_t &tested, uint64_t &written) {
    __m512i o_lo = _mm512_setzero_si512(), o_hi = _mm512_setzero_si512();
    for (int e = 0; e < 3; e++) {
        const __m512i v = _mm512_set1_epi64(ex[e]);
        o_lo = _mm512_or_si512(o_lo, _mm512_add_epi64(v, c.lane_step_lo[e]));
        o_hi = _mm512_or_si512(o_hi, _mm512_add_epi64(v, c.lane_step_hi[e]));
    }
    const unsigned negative = (unsigned)_mm512_movepi64_mask(o_lo) |
                              ((unsigned)_mm512_movepi64_mask(o_hi) << 8);
    const __mmask16 cov = (__mmask16)(~negative & tail);
    const __m512d xb = _mm512_set1_pd((double)x);
    const __m512 z = _mm512_insertf32x8(_mm512_castps256_ps512(depth8(c, zrow, xb, c.lane_lo)),
                                        depth8(c, zrow, xb, c.lane_hi), 1);
    const __m512 d = _mm512_loadu_ps(b.depth + row + x); /* kFrameSlack */
    const __mmask16 less = _mm512_mask_cmp_ps_mask(cov, z, d, _CMP_LT_OQ);
    const __mmask16 upd = kPass == Pass::zfail ? (__mmask16)(cov & ~less) : less;
    if constexpr (kPass == Pass::depth) {
        _mm512_mask_storeu_ps(b.depth + row + x, upd, z);
        _mm512_mask_storeu_epi32(b.ids + row + x, upd, c.value);
    } else {
        uint8_t *s = b.stencil + row + x;
        const __m128i st = _mm_maskz_loadu_epi8(tail, s);
        _mm_mask_storeu_epi8(s, upd, _mm_add_epi8(st, _mm512_castsi512_si128(c.value)));
    }
    tested += (uint64_t)__builtin_popcount(cov);
    written += (uint64_t)__builtin_popcount(upd);
}

template <Pass kPass>
SV_TARGET_AVX512 void walk(const SetupTriangle &tri, const RowBand &band, const WalkBuffers &b,
                           int value, RowCounts &n) {
    detail::RowLoop l;
    if (!detail::begin_rows(tri, band, l)) return;
    const PixelConstants c = pixel_constants(tri, value);
    /* Local counts: a stencil byte store may alias n, a local cannot. */
    uint64_t tested = 0, written = 0, rows = 0;
    for (; l.y <= l.y_last; detail::next_row(tri, l)) {
        int lo = 0, hi = 0;
        if (detail::span_of_row(tri, l, lo, hi)) {
            rows++;
            const int y = l.y;
            const int64_t *e_row = l.e_row;
            const std::size_t row = (std::size_t)y * (std::size_t)b.width;
            detail::prefetch_ahead(b.depth, b.stencil, b.width, b.height, y, lo);
            const __m512d zrow = _mm512_set1_pd(detail::row_depth(tri, y));
            for (int x = lo;; x += 16) {
                const int64_t ex[3] = {e_row[0] + tri.step_x[0] * x, e_row[1] + tri.step_x[1] * x,
                                       e_row[2] + tri.step_x[2] * x};
                const int left = hi - x + 1;
                if (left <= 8) {
                    block8<kPass>(c, ex, zrow, x, (__mmask8)((1u << left) - 1), b, row, tested,
                                  written);
                    break;
                }
                block16<kPass>(c, ex, zrow, x, (__mmask16)(left >= 16 ? 0xffffu : (1u << left) - 1),
                               b, row, tested, written);
                if (left <= 16) break;
            }
        }
    }
    n.tested += tested;
    n.written += written;
    n.rows += rows;
}

} // namespace

void walk_depth_avx512(const SetupTriangle &tri, const RowBand &band, const WalkBuffers &b,
                       RowCounts &n) {
    walk<Pass::depth>(tri, band, b, tri.id, n);
}

void walk_zpass_avx512(const SetupTriangle &tri, const RowBand &band, const WalkBuffers &b,
                       uint8_t delta, RowCounts &n) {
    walk<Pass::zpass>(tri, band, b, (int)(0x01010101u * delta), n);
}

void walk_zfail_avx512(const SetupTriangle &tri, const RowBand &band, const WalkBuffers &b,
                       uint8_t delta, RowCounts &n) {
    walk<Pass::zfail>(tri, band, b, (int)(0x01010101u * delta), n);
}

const RowKernels kRowKernelsAvx512 = {"avx512", SV_ISA_AVX512, walk_depth_avx512, walk_zpass_avx512,
                                      walk_zfail_avx512};

} // namespace sv::raster
