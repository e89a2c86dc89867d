/*
 * The reference triangle walks: row_walk.h's spans, each through the C
 * row kernels of row_kernels_c.h, one pixel per step.
 *
 * Copyright (C) 2026 the shadowvol authors. LGPL-2.1-or-later.
 */
#include "row_kernels_c.h"
#include "row_walk.h"
#include "triangle_walk.h"

namespace sv::raster {

void walk_depth_c(const SetupTriangle &tri, const RowBand &band, const WalkBuffers &b,
                  RowCounts &n) {
    detail::walk_rows(tri, band, [&](const RowSpan &span, int y) {
        const std::size_t row = (std::size_t)y * (std::size_t)b.width;
        detail::prefetch_ahead(b.depth, nullptr, b.width, b.height, y, span.x_begin);
        c_rows::depth_c(span, {b.depth + row, b.ids + row, nullptr}, tri.id, n);
        n.rows++;
    });
}

template <bool kFail>
static void walk_stencil_c(const SetupTriangle &tri, const RowBand &band, const WalkBuffers &b,
                           uint8_t delta, RowCounts &n) {
    detail::walk_rows(tri, band, [&](const RowSpan &span, int y) {
        const std::size_t row = (std::size_t)y * (std::size_t)b.width;
        detail::prefetch_ahead(b.depth, b.stencil, b.width, b.height, y, span.x_begin);
        c_rows::stencil_c<kFail>(span, {b.depth + row, nullptr, b.stencil + row}, delta, n);
        n.rows++;
    });
}

void walk_zpass_c(const SetupTriangle &tri, const RowBand &band, const WalkBuffers &b,
                  uint8_t delta, RowCounts &n) {
    walk_stencil_c<false>(tri, band, b, delta, n);
}

void walk_zfail_c(const SetupTriangle &tri, const RowBand &band, const WalkBuffers &b,
                  uint8_t delta, RowCounts &n) {
    walk_stencil_c<true>(tri, band, b, delta, n);
}

} // namespace sv::raster
