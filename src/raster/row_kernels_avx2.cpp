/*
 * The row kernels in AVX2 (and POPCNT; within the project's avx2 level):
 * 8 pixels per step.
 *
 * Each edge function is two ymm of 4 x int64; vmovmskpd of their OR gives
 * the 8 uncovered bits. Depth: two ymm of 4 doubles (separate vmulpd and
 * vaddpd, the C's rounding), vcvtpd2ps, one 8-wide compare, vmovmskps.
 * Depth and ids are written with vmaskmov; the 8 stencil bytes are read,
 * incremented under a byte mask packed from the lane masks, and written
 * back whole (bytes outside the mask are unchanged) when the block lies
 * in the span; in a block the span covers in part the stencil bytes are
 * updated one by one, so nothing outside the span is written. Blocks are
 * aligned to 8 pixels; depth is read a whole vector at a time, also
 * before x_begin and past x_end in the row (see kFrameSlack).
 *
 * Copyright (C) 2026 the shadowvol authors. LGPL-2.1-or-later.
 */
#include <immintrin.h>

#include "row_kernels.h"
#include "shadowvol.h"

#define SV_TARGET_AVX2 __attribute__((target("avx2,popcnt")))

namespace sv::raster {
namespace {

struct Block8 {
    __m256i e_a[3], e_b[3], step8[3];
    __m256d lane_a, lane_b, half, x0, zrow, dzdx;
};

SV_TARGET_AVX2 inline void setup(const RowSpan &s, Block8 &b) {
    /* Lane i starts at e + i * step: built in registers (a store of four
     * scalars and a vector load would stall on store forwarding, and most
     * spans of a shadow volume's slivers are only a few pixels long). */
    for (int k = 0; k < 3; k++) {
        const int64_t e = s.e[k], st = s.step[k];
        b.e_a[k] = _mm256_set_epi64x(e + 3 * st, e + 2 * st, e + st, e);
        b.e_b[k] = _mm256_add_epi64(b.e_a[k], _mm256_set1_epi64x(4 * st));
        b.step8[k] = _mm256_set1_epi64x(8 * st);
    }
    b.lane_a = _mm256_setr_pd(0, 1, 2, 3);
    b.lane_b = _mm256_setr_pd(4, 5, 6, 7);
    b.half = _mm256_set1_pd(0.5);
    b.x0 = _mm256_set1_pd(s.x0);
    b.zrow = _mm256_set1_pd(s.zrow);
    b.dzdx = _mm256_set1_pd(s.dzdx);
}

SV_TARGET_AVX2 inline unsigned covered(const Block8 &b) {
    const __m256i a = _mm256_or_si256(_mm256_or_si256(b.e_a[0], b.e_a[1]), b.e_a[2]);
    const __m256i c = _mm256_or_si256(_mm256_or_si256(b.e_b[0], b.e_b[1]), b.e_b[2]);
    const unsigned negative = (unsigned)_mm256_movemask_pd(_mm256_castsi256_pd(a)) |
                              (unsigned)_mm256_movemask_pd(_mm256_castsi256_pd(c)) << 4;
    return ~negative & 0xffu;
}

SV_TARGET_AVX2 inline __m256 depth8(const Block8 &b, int x) {
    const __m256d xb = _mm256_set1_pd((double)x);
    const __m256d dx_a = _mm256_sub_pd(_mm256_add_pd(_mm256_add_pd(xb, b.lane_a), b.half), b.x0);
    const __m256d dx_b = _mm256_sub_pd(_mm256_add_pd(_mm256_add_pd(xb, b.lane_b), b.half), b.x0);
    const __m256d z_a = _mm256_add_pd(b.zrow, _mm256_mul_pd(b.dzdx, dx_a));
    const __m256d z_b = _mm256_add_pd(b.zrow, _mm256_mul_pd(b.dzdx, dx_b));
    return _mm256_set_m128(_mm256_cvtpd_ps(z_b), _mm256_cvtpd_ps(z_a));
}

SV_TARGET_AVX2 inline __m256i lane_mask(unsigned bits) {
    const __m256i bit = _mm256_setr_epi32(1, 2, 4, 8, 16, 32, 64, 128);
    return _mm256_cmpeq_epi32(_mm256_and_si256(_mm256_set1_epi32((int)bits), bit), bit);
}

SV_TARGET_AVX2 inline void advance(Block8 &b) {
    for (int k = 0; k < 3; k++) {
        b.e_a[k] = _mm256_add_epi64(b.e_a[k], b.step8[k]);
        b.e_b[k] = _mm256_add_epi64(b.e_b[k], b.step8[k]);
    }
}

/* Pixels of the block at x (a multiple of 8) that lie in the span. */
inline unsigned span_bits(int x, const RowSpan &s) {
    unsigned m = 0xffu;
    if (x < s.x_begin) m &= 0xffu << (s.x_begin - x);
    if (x + 8 > s.x_end) m &= 0xffu >> (x + 8 - s.x_end);
    return m;
}

/* Blocks start at multiples of 8 pixels, so every 32-byte depth load lies
 * in one cache line (a shadow volume's spans are mostly a few pixels, and
 * a load split over two lines that miss costs twice). The edge values are
 * moved back to the block's start. */
inline RowSpan aligned(const RowSpan &s) {
    RowSpan a = s;
    const int x0 = s.x_begin & ~7;
    for (int k = 0; k < 3; k++) a.e[k] = s.e[k] - s.step[k] * (int64_t)(s.x_begin - x0);
    return a;
}

SV_TARGET_AVX2 void depth_avx2(const RowSpan &s, const RowBuffers &buf, int32_t id, RowCounts &n) {
    /* Local counts: a stencil byte store may alias *n, a local cannot. */
    uint64_t tested = 0, written = 0;
    if (s.x_end - s.x_begin <= kShortSpan) return kRowKernelsC.depth(s, buf, id, n);
    Block8 b;
    setup(aligned(s), b);
    const __m256i idv = _mm256_set1_epi32(id);
    for (int x = s.x_begin & ~7; x < s.x_end; x += 8) {
        const unsigned cov = covered(b) & span_bits(x, s);
        if (cov) {
            const __m256 z = depth8(b, x);
            /* A whole aligned vector even where the span covers part of
             * the block (kFrameSlack). */
            const __m256 d = _mm256_loadu_ps(buf.depth + x);
            const unsigned less = (unsigned)_mm256_movemask_ps(_mm256_cmp_ps(z, d, _CMP_LT_OQ)) &
                                  cov;
            if (less) {
                const __m256i m = lane_mask(less);
                _mm256_maskstore_ps(buf.depth + x, m, z);
                _mm256_maskstore_epi32(buf.ids + x, m, idv);
            }
            tested += (uint64_t)_mm_popcnt_u32(cov);
            written += (uint64_t)_mm_popcnt_u32(less);
        }
        advance(b);
    }
    n.tested += tested;
    n.written += written;
}

template <bool kFail>
SV_TARGET_AVX2 void stencil_avx2(const RowSpan &s, const RowBuffers &buf, uint8_t delta,
                                 RowCounts &n) {
    /* Local counts: a stencil byte store may alias *n, a local cannot. */
    uint64_t tested = 0, written = 0;
    if (s.x_end - s.x_begin <= kShortSpan) {
        return (kFail ? kRowKernelsC.zfail : kRowKernelsC.zpass)(s, buf, delta, n);
    }
    Block8 b;
    setup(aligned(s), b);
    for (int x = s.x_begin & ~7; x < s.x_end; x += 8) {
        const unsigned inside = span_bits(x, s);
        const unsigned cov = covered(b) & inside;
        if (cov) {
            const __m256 z = depth8(b, x);
            const __m256 d = _mm256_loadu_ps(buf.depth + x);
            const unsigned less = (unsigned)_mm256_movemask_ps(_mm256_cmp_ps(z, d, _CMP_LT_OQ));
            const unsigned upd = (kFail ? ~less : less) & cov;
            if (upd == 0) {
            } else if (inside == 0xffu) {
                /* The 8 lane masks packed to 8 bytes of 0 or 0xff (two
                 * signed saturating packs), ANDed with delta: the per-byte
                 * increment, added without carries between bytes. (Not
                 * pdep: microcoded and slow on AMD cores before Zen 3.)
                 * The 8 bytes all lie in the span. */
                const __m256i m = lane_mask(upd);
                const __m128i m16 = _mm_packs_epi32(_mm256_castsi256_si128(m),
                                                    _mm256_extracti128_si256(m, 1));
                const __m128i inc = _mm_and_si128(_mm_packs_epi16(m16, m16),
                                                  _mm_set1_epi8((char)delta));
                const __m128i st = _mm_loadl_epi64((const __m128i *)(buf.stencil + x));
                _mm_storel_epi64((__m128i *)(buf.stencil + x), _mm_add_epi8(st, inc));
            } else {
                /* A block the span covers in part: byte by byte, so
                 * nothing outside the span is written. */
                for (unsigned m = upd; m; m &= m - 1) {
                    uint8_t &p = buf.stencil[x + __builtin_ctz(m)];
                    p = (uint8_t)(p + delta);
                }
            }
            tested += (uint64_t)_mm_popcnt_u32(cov);
            written += (uint64_t)_mm_popcnt_u32(upd);
        }
        advance(b);
    }
    n.tested += tested;
    n.written += written;
}

} // namespace

const RowKernels kRowKernelsAvx2 = {"avx2", SV_ISA_AVX2, depth_avx2, stencil_avx2<false>,
                                    stencil_avx2<true>};

} // namespace sv::raster
