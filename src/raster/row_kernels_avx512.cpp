/*
 * The row kernels in AVX-512 (F, BW, VL, DQ): 16 pixels per step.
 *
 * Registers per step: each edge function in two zmm of 8 x int64 (lanes
 * 0-7 and 8-15 of the block); their OR's sign bits (vpmovq2m) give the
 * uncovered pixels, so coverage is one kor/knot per block. Depth: the 16
 * pixel positions in two zmm of double, z = zrow + dzdx * dx (separate
 * vmulpd and vaddpd: the same rounding as the C), vcvtpd2ps into one zmm
 * of float, one masked compare with the stored depth. The span's tail is
 * an opmask too, so stores never touch a pixel outside [x_begin, x_end);
 * depth is read a whole vector at a time (kFrameSlack: masked loads are
 * slow on AMD cores where their masked-off part reaches an untouched
 * page); stencil bytes are read masked to the pixels updated, inside the
 * row (the per-light stencil buffers have no slack).
 *
 * Copyright (C) 2026 the shadowvol authors. LGPL-2.1-or-later.
 */
/* GCC 12's own AVX-512 headers pass an undefined register to the masked
 * builtins behind _mm512_cvtpd_ps and _mm512_insertf32x8 and then warn
 * about it (a known false positive of -Wmaybe-uninitialized). */
#pragma GCC diagnostic ignored "-Wmaybe-uninitialized"
#include <immintrin.h>

#include "row_kernels.h"
#include "shadowvol.h"

#define SV_TARGET_AVX512 __attribute__((target("avx512f,avx512bw,avx512vl,avx512dq,popcnt")))

namespace sv::raster {
namespace {

struct Block16 {
    __m512i e_lo[3], e_hi[3], step16[3];
    __m512d lane_lo, lane_hi, half, x0, zrow, dzdx;
};

SV_TARGET_AVX512 inline void setup(const RowSpan &s, Block16 &b) {
    /* Lane i starts at e + i * step, built in registers (no store-forwarding
     * stall on a store of scalars and a vector load). */
    const __m512i iota = _mm512_setr_epi64(0, 1, 2, 3, 4, 5, 6, 7);
    for (int k = 0; k < 3; k++) {
        const __m512i st = _mm512_set1_epi64(s.step[k]);
        b.e_lo[k] = _mm512_add_epi64(_mm512_set1_epi64(s.e[k]), _mm512_mullo_epi64(st, iota));
        b.e_hi[k] = _mm512_add_epi64(b.e_lo[k], _mm512_set1_epi64(8 * s.step[k]));
        b.step16[k] = _mm512_set1_epi64(s.step[k] * 16);
    }
    b.lane_lo = _mm512_setr_pd(0, 1, 2, 3, 4, 5, 6, 7);
    b.lane_hi = _mm512_setr_pd(8, 9, 10, 11, 12, 13, 14, 15);
    b.half = _mm512_set1_pd(0.5);
    b.x0 = _mm512_set1_pd(s.x0);
    b.zrow = _mm512_set1_pd(s.zrow);
    b.dzdx = _mm512_set1_pd(s.dzdx);
}

/* Covered pixels of the block at x (within the span's TAIL mask). */
SV_TARGET_AVX512 inline __mmask16 covered(const Block16 &b, __mmask16 tail) {
    const __m512i lo = _mm512_or_si512(_mm512_or_si512(b.e_lo[0], b.e_lo[1]), b.e_lo[2]);
    const __m512i hi = _mm512_or_si512(_mm512_or_si512(b.e_hi[0], b.e_hi[1]), b.e_hi[2]);
    const __mmask16 negative = (__mmask16)(_mm512_movepi64_mask(lo) |
                                           ((unsigned)_mm512_movepi64_mask(hi) << 8));
    return (__mmask16)(~negative & tail);
}

SV_TARGET_AVX512 inline __m512 depth16(const Block16 &b, int x) {
    const __m512d xb = _mm512_set1_pd((double)x);
    const __m512d dx_lo = _mm512_sub_pd(_mm512_add_pd(_mm512_add_pd(xb, b.lane_lo), b.half), b.x0);
    const __m512d dx_hi = _mm512_sub_pd(_mm512_add_pd(_mm512_add_pd(xb, b.lane_hi), b.half), b.x0);
    const __m512d z_lo = _mm512_add_pd(b.zrow, _mm512_mul_pd(b.dzdx, dx_lo));
    const __m512d z_hi = _mm512_add_pd(b.zrow, _mm512_mul_pd(b.dzdx, dx_hi));
    return _mm512_insertf32x8(_mm512_zextps256_ps512(_mm512_cvtpd_ps(z_lo)), _mm512_cvtpd_ps(z_hi),
                              1);
}

SV_TARGET_AVX512 inline void advance(Block16 &b) {
    for (int k = 0; k < 3; k++) {
        b.e_lo[k] = _mm512_add_epi64(b.e_lo[k], b.step16[k]);
        b.e_hi[k] = _mm512_add_epi64(b.e_hi[k], b.step16[k]);
    }
}

/* Pixels of the block at x (a multiple of 16) that lie in the span. */
inline __mmask16 span_mask(int x, const RowSpan &s) {
    unsigned m = 0xffffu;
    if (x < s.x_begin) m &= 0xffffu << (s.x_begin - x);
    if (x + 16 > s.x_end) m &= 0xffffu >> (x + 16 - s.x_end);
    return (__mmask16)m;
}

/* Blocks start at multiples of 16 pixels: each depth load is one cache
 * line. The edge values are moved back to the block's start. */
inline RowSpan aligned(const RowSpan &s) {
    RowSpan a = s;
    const int x0 = s.x_begin & ~15;
    for (int k = 0; k < 3; k++) a.e[k] = s.e[k] - s.step[k] * (int64_t)(s.x_begin - x0);
    return a;
}

SV_TARGET_AVX512 void depth_avx512(const RowSpan &s, const RowBuffers &buf, int32_t id,
                                   RowCounts &n) {
    /* Local counts: a stencil byte store may alias *n, a local cannot. */
    uint64_t tested = 0, written = 0;
    if (s.x_end - s.x_begin <= kShortSpan) return kRowKernelsC.depth(s, buf, id, n);
    Block16 b;
    setup(aligned(s), b);
    const __m512i idv = _mm512_set1_epi32(id);
    for (int x = s.x_begin & ~15; x < s.x_end; x += 16) {
        const __mmask16 cov = covered(b, span_mask(x, s));
        if (cov) {
            const __m512 z = depth16(b, x);
            const __m512 d = _mm512_loadu_ps(buf.depth + x); /* kFrameSlack */
            const __mmask16 less = _mm512_mask_cmp_ps_mask(cov, z, d, _CMP_LT_OQ);
            _mm512_mask_storeu_ps(buf.depth + x, less, z);
            _mm512_mask_storeu_epi32(buf.ids + x, less, idv);
            tested += (uint64_t)__builtin_popcount(cov);
            written += (uint64_t)__builtin_popcount(less);
        }
        advance(b);
    }
    n.tested += tested;
    n.written += written;
}

template <bool kFail>
SV_TARGET_AVX512 void stencil_avx512(const RowSpan &s, const RowBuffers &buf, uint8_t delta,
                                     RowCounts &n) {
    /* Local counts: a stencil byte store may alias *n, a local cannot. */
    uint64_t tested = 0, written = 0;
    if (s.x_end - s.x_begin <= kShortSpan) {
        return (kFail ? kRowKernelsC.zfail : kRowKernelsC.zpass)(s, buf, delta, n);
    }
    Block16 b;
    setup(aligned(s), b);
    const __m128i dv = _mm_set1_epi8((char)delta);
    for (int x = s.x_begin & ~15; x < s.x_end; x += 16) {
        const __mmask16 cov = covered(b, span_mask(x, s));
        if (cov) {
            const __m512 z = depth16(b, x);
            const __m512 d = _mm512_loadu_ps(buf.depth + x); /* kFrameSlack */
            const __mmask16 less = _mm512_mask_cmp_ps_mask(cov, z, d, _CMP_LT_OQ);
            const __mmask16 upd = kFail ? (__mmask16)(cov & ~less) : less;
            if (upd) {
                /* Only the bytes it updates: the per-light stencil of a
                 * frame (render::LightFrame) is a plain vector with no
                 * kFrameSlack after it, and a whole-vector read ran past
                 * its end on the last row (AddressSanitizer, on the first
                 * AVX-512 machine the sanitizer build ran on). The lanes
                 * all lie in the row, so the masked load never touches a
                 * page the row does not. */
                const __m128i st = _mm_maskz_loadu_epi8(upd, buf.stencil + x);
                _mm_mask_storeu_epi8(buf.stencil + x, upd, _mm_add_epi8(st, dv));
            }
            tested += (uint64_t)__builtin_popcount(cov);
            written += (uint64_t)__builtin_popcount(upd);
        }
        advance(b);
    }
    n.tested += tested;
    n.written += written;
}

} // namespace

const RowKernels kRowKernelsAvx512 = {"avx512", SV_ISA_AVX512, depth_avx512, stencil_avx512<false>,
                                      stencil_avx512<true>};

} // namespace sv::raster
