/*
 * The span recurrence of row_walk.h's walk_rows with the three edges in
 * the lanes of one vector (AVX2; callable from the AVX2 and the AVX-512
 * triangle walks, whose targets include it): per row one vaddpd steps
 * the bounds, one vroundpd floors them, and a horizontal max (min) over
 * the left (right) edges' lanes gives the span. The same double
 * operations as walk_rows lane by lane, so the same spans.
 *
 * Copyright (C) 2026 the shadowvol authors. LGPL-2.1-or-later.
 */
#ifndef SV_RASTER_ROW_SPAN_SIMD_H
#define SV_RASTER_ROW_SPAN_SIMD_H

#include <immintrin.h>

#include <algorithm>
#include <climits>

#include "row_walk.h"

#define SV_TARGET_ROW_SPAN __attribute__((target("avx2")))

namespace sv::raster::detail {

/* The span recurrence of detail::walk_rows, three edges in one vector. */
struct SpanBounds {
    __m256d bound, slope;
    __m128i left, right; /* int32 lanes: all ones where the edge bounds that side */
    int x_first, x_last;
};

SV_TARGET_ROW_SPAN inline SpanBounds span_bounds(const SetupTriangle &tri, const int64_t e_row[3]) {
    double bd[3], sl[3];
    int left[3], right[3];
    for (int e = 0; e < 3; e++) {
        const int64_t sx = tri.step_x[e];
        bd[e] = sx != 0 ? -(double)e_row[e] / (double)sx : 0.0;
        sl[e] = sx != 0 ? -(double)tri.step_y[e] / (double)sx : 0.0;
        left[e] = sx > 0 ? -1 : 0;
        right[e] = sx < 0 ? -1 : 0;
    }
    SpanBounds s;
    s.bound = _mm256_set_pd(0.0, bd[2], bd[1], bd[0]);
    s.slope = _mm256_set_pd(0.0, sl[2], sl[1], sl[0]);
    s.left = _mm_set_epi32(0, left[2], left[1], left[0]);
    s.right = _mm_set_epi32(0, right[2], right[1], right[0]);
    s.x_first = tri.x_first;
    s.x_last = tri.x_last;
    return s;
}

/* This row's span [lo, hi] (lo > hi: empty), and the bounds stepped to the
 * next row. */
SV_TARGET_ROW_SPAN inline void next_span(SpanBounds &s, int &lo, int &hi) {
    const __m256d b = _mm256_min_pd(_mm256_max_pd(s.bound, _mm256_set1_pd(-detail::kBoundClamp)),
                                    _mm256_set1_pd(detail::kBoundClamp));
    const __m128i ib = _mm256_cvtpd_epi32(
        _mm256_round_pd(b, _MM_FROUND_TO_NEG_INF | _MM_FROUND_NO_EXC));
    const __m128i one = _mm_set1_epi32(1);
    __m128i l = _mm_blendv_epi8(_mm_set1_epi32(INT_MIN), _mm_sub_epi32(ib, one), s.left);
    __m128i r = _mm_blendv_epi8(_mm_set1_epi32(INT_MAX), _mm_add_epi32(ib, one), s.right);
    l = _mm_max_epi32(l, _mm_shuffle_epi32(l, _MM_SHUFFLE(1, 0, 3, 2)));
    r = _mm_min_epi32(r, _mm_shuffle_epi32(r, _MM_SHUFFLE(1, 0, 3, 2)));
    l = _mm_max_epi32(l, _mm_shuffle_epi32(l, _MM_SHUFFLE(2, 3, 0, 1)));
    r = _mm_min_epi32(r, _mm_shuffle_epi32(r, _MM_SHUFFLE(2, 3, 0, 1)));
    lo = std::max(s.x_first, _mm_cvtsi128_si32(l));
    hi = std::min(s.x_last, _mm_cvtsi128_si32(r));
    s.bound = _mm256_add_pd(s.bound, s.slope);
}

/* The rows of a triangle inside a band, each with its span: the loop of
 * every SIMD walk. begin_rows() sets it up (false: no rows), span_of_row()
 * gives this row's span (false: walk_rows skips the row: its span is empty
 * or it lies outside a horizontal edge, an edge with no step in x, which
 * bounds no span), next_row() steps to the next row. E_ROW holds the row's
 * edge functions at pixel 0. */
struct RowLoop {
    int y = 0, y_last = -1;
    int64_t e_row[3] = {0, 0, 0};
    SpanBounds sb;
    bool flat = false;
};

SV_TARGET_ROW_SPAN inline bool begin_rows(const SetupTriangle &tri, const RowBand &band,
                                          RowLoop &l) {
    band_rows_of(tri, band, l.y, l.y_last);
    if (l.y > l.y_last) return false;
    for (int e = 0; e < 3; e++) l.e_row[e] = tri.e_origin[e] + tri.step_y[e] * l.y;
    l.sb = span_bounds(tri, l.e_row);
    l.flat = tri.step_x[0] == 0 || tri.step_x[1] == 0 || tri.step_x[2] == 0;
    return true;
}

SV_TARGET_ROW_SPAN inline bool span_of_row(const SetupTriangle &tri, RowLoop &l, int &lo, int &hi) {
    next_span(l.sb, lo, hi);
    return lo <= hi && !(l.flat && outside_flat_edge(tri, l.e_row));
}

SV_TARGET_ROW_SPAN inline void next_row(const SetupTriangle &tri, RowLoop &l) {
    for (int e = 0; e < 3; e++) l.e_row[e] += tri.step_y[e];
    l.y++;
}

} // namespace sv::raster::detail

#endif
