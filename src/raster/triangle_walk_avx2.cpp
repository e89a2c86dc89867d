/*
 * The triangle walks of row_kernels.h in AVX2 (and POPCNT): a whole
 * set-up triangle's rows inside a band in one call, with no call, no
 * branch per edge and no scalar pixel loop per row.
 *
 * Per row: the span from row_span_simd.h (the three edges' bounds in one
 * vector: walk_rows' spans), then blocks of 8 pixels from the span's first
 * pixel. Edge functions: two ymm of 4 x int64 per edge (the scalar value
 * at the block's pixel broadcast and added to step * lane, per triangle);
 * vmovmskpd of their OR gives the 8 uncovered bits. Depth: two ymm of 4
 * doubles (separate vmulpd and vaddpd, the C's rounding), vcvtpd2ps, one
 * 8-wide compare, vmovmskps. Depth and ids are written with vmaskmov. The
 * stencil's 8 bytes are read, incremented under a byte mask packed from
 * the lane masks and written back whole when they lie within the
 * triangle's pixel bounds (bytes outside the mask are rewritten unchanged:
 * row_kernels.h's contract); at the bounds' right end byte by byte.
 *
 * Register map of a block (the compiler allocates; the roles): the edges'
 * lane steps (six ymm: 3 edges x lanes 0-3 and 4-7), the lane offsets,
 * 0.5, x0, dzdx and the row's zrow (ymm of double), the id (broadcast).
 *
 * Input contracts: as triangle_walk_avx512.cpp (depth readable kFrameSlack
 * bytes past its end: a block's depth load reaches at most 7 pixels past
 * the span).
 *
 * Copyright (C) 2026 the shadowvol authors. LGPL-2.1-or-later.
 */
#include <immintrin.h>

#include "row_span_simd.h"
#include "row_walk.h"
#include "shadowvol.h"
#include "triangle_walk.h"

#define SV_TARGET_AVX2 __attribute__((target("avx2,popcnt")))

namespace sv::raster {
namespace {

enum class Pass { depth, zpass, zfail };

/* What stays fixed over a triangle's pixels. */
struct PixelConstants {
    __m256i lane_step_a[3], lane_step_b[3]; /* step_x * lane, lanes 0-3 and 4-7 */
    __m256d lane_a, lane_b, half, x0, dzdx;
    __m256i id;
    __m128i delta; /* 8 bytes of delta */
};

SV_TARGET_AVX2 inline PixelConstants pixel_constants(const SetupTriangle &tri, uint8_t delta) {
    PixelConstants c;
    for (int e = 0; e < 3; e++) {
        const int64_t st = tri.step_x[e];
        c.lane_step_a[e] = _mm256_set_epi64x(3 * st, 2 * st, st, 0);
        c.lane_step_b[e] = _mm256_add_epi64(c.lane_step_a[e], _mm256_set1_epi64x(4 * st));
    }
    c.lane_a = _mm256_setr_pd(0, 1, 2, 3);
    c.lane_b = _mm256_setr_pd(4, 5, 6, 7);
    c.half = _mm256_set1_pd(0.5);
    c.x0 = _mm256_set1_pd(tri.x0);
    c.dzdx = _mm256_set1_pd(tri.a);
    c.id = _mm256_set1_epi32(tri.id);
    c.delta = _mm_set1_epi8((char)delta);
    return c;
}

SV_TARGET_AVX2 inline __m256i lane_mask(unsigned bits) {
    const __m256i bit = _mm256_setr_epi32(1, 2, 4, 8, 16, 32, 64, 128);
    return _mm256_cmpeq_epi32(_mm256_and_si256(_mm256_set1_epi32((int)bits), bit), bit);
}

/* The pixels [x, x + 8) of a row under TAIL (the span's part of them). */
template <Pass kPass>
SV_TARGET_AVX2 inline void
block8(const SetupTriangle &tri, const PixelConstants &c, const int64_t ex[3], __m256d zrow, int x,
       unsigned tail, const WalkBuffers &b, std::size_t row, uint64_t &tested, uint64_t &written) {
    __m256i o_a = _mm256_setzero_si256(), o_b = _mm256_setzero_si256();
    for (int e = 0; e < 3; e++) {
        const __m256i v = _mm256_set1_epi64x(ex[e]);
        o_a = _mm256_or_si256(o_a, _mm256_add_epi64(v, c.lane_step_a[e]));
        o_b = _mm256_or_si256(o_b, _mm256_add_epi64(v, c.lane_step_b[e]));
    }
    const unsigned negative = (unsigned)_mm256_movemask_pd(_mm256_castsi256_pd(o_a)) |
                              (unsigned)_mm256_movemask_pd(_mm256_castsi256_pd(o_b)) << 4;
    const unsigned cov = ~negative & tail;
    const __m256d xb = _mm256_set1_pd((double)x);
    const __m256d dx_a = _mm256_sub_pd(_mm256_add_pd(_mm256_add_pd(xb, c.lane_a), c.half), c.x0);
    const __m256d dx_b = _mm256_sub_pd(_mm256_add_pd(_mm256_add_pd(xb, c.lane_b), c.half), c.x0);
    const __m256 z =
        _mm256_set_m128(_mm256_cvtpd_ps(_mm256_add_pd(zrow, _mm256_mul_pd(c.dzdx, dx_b))),
                        _mm256_cvtpd_ps(_mm256_add_pd(zrow, _mm256_mul_pd(c.dzdx, dx_a))));
    const __m256 d = _mm256_loadu_ps(b.depth + row + x); /* kFrameSlack */
    const unsigned less = (unsigned)_mm256_movemask_ps(_mm256_cmp_ps(z, d, _CMP_LT_OQ)) & cov;
    const unsigned upd = kPass == Pass::zfail ? ~less & cov : less;
    tested += (uint64_t)_mm_popcnt_u32(cov);
    written += (uint64_t)_mm_popcnt_u32(upd);
    if (upd == 0) return;
    if constexpr (kPass == Pass::depth) {
        const __m256i m = lane_mask(upd);
        _mm256_maskstore_ps(b.depth + row + x, m, z);
        _mm256_maskstore_epi32(b.ids + row + x, m, c.id);
    } else if (x + 8 <= tri.x_last + 1) {
        /* The 8 lane masks packed to 8 bytes of 0 or 0xff (two signed
         * saturating packs), ANDed with delta: the per-byte increment,
         * added without carries between bytes. (Not pdep: microcoded and
         * slow on AMD cores before Zen 3.) */
        const __m256i m = lane_mask(upd);
        const __m128i m16 = _mm_packs_epi32(_mm256_castsi256_si128(m),
                                            _mm256_extracti128_si256(m, 1));
        const __m128i inc = _mm_and_si128(_mm_packs_epi16(m16, m16), c.delta);
        uint8_t *s = b.stencil + row + x;
        _mm_storel_epi64((__m128i *)s, _mm_add_epi8(_mm_loadl_epi64((const __m128i *)s), inc));
    } else {
        const uint8_t delta = (uint8_t)_mm_cvtsi128_si32(c.delta);
        for (unsigned m = upd; m; m &= m - 1) {
            uint8_t &p = b.stencil[row + (std::size_t)x + (std::size_t)__builtin_ctz(m)];
            p = (uint8_t)(p + delta);
        }
    }
}

template <Pass kPass>
SV_TARGET_AVX2 void walk(const SetupTriangle &tri, const RowBand &band, const WalkBuffers &b,
                         uint8_t delta, RowCounts &n) {
    detail::RowLoop l;
    if (!detail::begin_rows(tri, band, l)) return;
    const PixelConstants c = pixel_constants(tri, delta);
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
            const __m256d zrow = _mm256_set1_pd(detail::row_depth(tri, y));
            for (int x = lo;; x += 8) {
                const int64_t ex[3] = {e_row[0] + tri.step_x[0] * x, e_row[1] + tri.step_x[1] * x,
                                       e_row[2] + tri.step_x[2] * x};
                const int left = hi - x + 1;
                block8<kPass>(tri, c, ex, zrow, x, left >= 8 ? 0xffu : (1u << left) - 1, b, row,
                              tested, written);
                if (left <= 8) break;
            }
        }
    }
    n.tested += tested;
    n.written += written;
    n.rows += rows;
}

} // namespace

void walk_depth_avx2(const SetupTriangle &tri, const RowBand &band, const WalkBuffers &b,
                     RowCounts &n) {
    walk<Pass::depth>(tri, band, b, 0, n);
}

void walk_zpass_avx2(const SetupTriangle &tri, const RowBand &band, const WalkBuffers &b,
                     uint8_t delta, RowCounts &n) {
    walk<Pass::zpass>(tri, band, b, delta, n);
}

void walk_zfail_avx2(const SetupTriangle &tri, const RowBand &band, const WalkBuffers &b,
                     uint8_t delta, RowCounts &n) {
    walk<Pass::zfail>(tri, band, b, delta, n);
}

const RowKernels kRowKernelsAvx2 = {"avx2", SV_ISA_AVX2, walk_depth_avx2, walk_zpass_avx2,
                                    walk_zfail_avx2};

} // namespace sv::raster
