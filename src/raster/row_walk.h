/*
 * How a set-up triangle's rows are walked (internal to src/raster): the
 * span of each row, the per-row depth, the prefetch ahead, and the stencil
 * increment of a face. walk_rows is the reference every triangle walk
 * follows (triangle_walk_c.cpp calls it; the SIMD walks compute the same
 * spans with the same double operations, lane by lane).
 *
 * Copyright (C) 2026 the shadowvol authors. LGPL-2.1-or-later.
 */
#ifndef SV_RASTER_ROW_WALK_H
#define SV_RASTER_ROW_WALK_H

#include <algorithm>
#include <cstddef>
#include <cstdint>

#include "rasterizer.h"

namespace sv::raster::detail {

/* Bounds of the row-span recurrence: an edge's x bound is clamped to
 * +-kBoundClamp pixels before it is floored (far outside any target). */
constexpr double kBoundClamp = 1e9;

/* floor(v) for |v| <= 2^62, without a call to libm (x86-64's baseline
 * has no roundsd). */
inline int64_t floor_to_int(double v) {
    const int64_t t = (int64_t)v;
    return (double)t > v ? t - 1 : t;
}

/* The rows of TRI inside BAND, as [first, last] (first > last: none). */
inline void band_rows_of(const SetupTriangle &tri, const RowBand &band, int &first, int &last) {
    first = std::max(tri.y_first, band.row_begin);
    last = std::min(tri.y_last, band.row_end - 1);
}

/* Depth at row Y's pixel centres is zrow + dzdx * (((double)x + 0.5) - x0):
 * zrow in the one operation order every walk uses. */
inline double row_depth(const SetupTriangle &tri, int y) {
    return tri.z0 + tri.b * (((double)y + 0.5) - tri.y0);
}

/* Whether a row is outside an edge with no step in x (a horizontal
 * edge): E_ROW is the row's edge functions. walk_rows skips such a row. */
inline bool outside_flat_edge(const SetupTriangle &tri, const int64_t e_row[3]) {
    bool out = false;
    for (int e = 0; e < 3; e++) out |= tri.step_x[e] == 0 && e_row[e] < 0;
    return out;
}

/* z-pass: front faces +1, back faces -1; z-fail: back +1, front -1 (mod
 * 256). */
inline uint8_t stencil_delta(StencilMode mode, bool front) {
    return ((mode == StencilMode::zpass) == front) ? 1 : 255;
}

/* The slivers of a shadow volume walk down the rows a few pixels at a time,
 * a new cache line of depth (and of stencil) per row, with a stride the
 * hardware prefetchers follow poorly: ask for the line a few rows ahead. */
constexpr int kPrefetchRows = 6;
inline void prefetch_ahead(const float *depth, const uint8_t *stencil, int width, int height, int y,
                           int x) {
    if (y + kPrefetchRows >= height) return;
    const std::size_t i = (std::size_t)(y + kPrefetchRows) * (std::size_t)width +
                          (std::size_t)(x & ~15);
    __builtin_prefetch(depth + i);
    if (stencil) __builtin_prefetch(stencil + i, 1);
}

/* EMIT(span, y) for each row of TRI inside BAND whose span is not empty.
 * Each edge's x bound on a row, -E_row / step_x, stepped by its slope
 * from row to row (one add): a conservative span padded by a pixel; the
 * kernel's integer test is the exact one, so where the walk starts (the
 * band's first row or the triangle's) changes no pixel. The padding
 * holds: after snapping |X|, |Y| < 2^21 + 2^8 (snap_polygon's guard band,
 * kMaxTargetSide), so |E| < 2^44, |step_x| >= 256 (when not 0) and
 * |bound| < 2^36, whose ulp is 2^-16 pixel; 8192 rows of additions stay
 * below 0.13 pixel. */
template <class Emit> void walk_rows(const SetupTriangle &tri, const RowBand &band, Emit &&emit) {
    int y_first = 0, y_last = 0;
    band_rows_of(tri, band, y_first, y_last);
    if (y_first > y_last) return;
    double bound[3], slope[3];
    int64_t e_row[3];
    for (int e = 0; e < 3; e++) {
        e_row[e] = tri.e_origin[e] + tri.step_y[e] * y_first;
        if (tri.step_x[e] != 0) {
            bound[e] = -(double)e_row[e] / (double)tri.step_x[e];
            slope[e] = -(double)tri.step_y[e] / (double)tri.step_x[e];
        } else {
            bound[e] = slope[e] = 0;
        }
    }
    for (int y = y_first; y <= y_last; y++) {
        int lo = tri.x_first, hi = tri.x_last;
        bool empty = false;
        for (int e = 0; e < 3; e++) {
            if (tri.step_x[e] == 0) {
                empty |= e_row[e] < 0;
                continue;
            }
            double b = bound[e];
            b = b < -kBoundClamp ? -kBoundClamp : b > kBoundClamp ? kBoundClamp : b;
            const int64_t ib = floor_to_int(b);
            if (tri.step_x[e] > 0) {
                lo = ib - 1 > lo ? (int)(ib - 1) : lo;
            } else {
                hi = ib + 1 < hi ? (int)(ib + 1) : hi;
            }
            bound[e] += slope[e];
        }
        if (empty || lo > hi) {
            for (int e = 0; e < 3; e++) e_row[e] += tri.step_y[e];
            continue;
        }
        RowSpan span;
        for (int e = 0; e < 3; e++) {
            span.e[e] = e_row[e] + tri.step_x[e] * lo;
            span.step[e] = tri.step_x[e];
        }
        span.zrow = row_depth(tri, y);
        span.dzdx = tri.a;
        span.x0 = tri.x0;
        span.x_begin = lo;
        span.x_end = hi + 1;
        emit(span, y);
        for (int e = 0; e < 3; e++) e_row[e] += tri.step_y[e];
    }
}

} // namespace sv::raster::detail

#endif
