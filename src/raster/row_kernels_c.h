/*
 * The rows in plain C++, one pixel per step, as inline templates: the
 * reference walk's pixels (triangle_walk_c.cpp), which the SIMD walks
 * must match bit for bit, and the depth-bounds walk's
 * (Rasterizer::walk_stencil_bounded).
 *
 * Copyright (C) 2026 the shadowvol authors. LGPL-2.1-or-later.
 */
#ifndef SV_RASTER_ROW_KERNELS_C_H
#define SV_RASTER_ROW_KERNELS_C_H

#include "row_kernels.h"

namespace sv::raster::c_rows {

/* The depth of pixel x, in the operation order every version uses. */
inline float depth_at(const RowSpan &s, int x) {
    const double dx = ((double)x + 0.5) - s.x0;
    return (float)(s.zrow + s.dzdx * dx);
}

inline void depth_c(const RowSpan &s, const RowBuffers &b, int32_t id, RowCounts &n) {
    /* Local counts: a stencil byte store may alias *n, a local cannot. */
    uint64_t tested = 0, written = 0;
    int64_t e0 = s.e[0], e1 = s.e[1], e2 = s.e[2];
    for (int x = s.x_begin; x < s.x_end; x++) {
        if ((e0 | e1 | e2) >= 0) {
            tested++;
            const float z = depth_at(s, x);
            if (z < b.depth[x]) {
                b.depth[x] = z;
                b.ids[x] = id;
                written++;
            }
        }
        e0 += s.step[0], e1 += s.step[1], e2 += s.step[2];
    }
    n.tested += tested;
    n.written += written;
}

template <bool kFail>
inline void stencil_c(const RowSpan &s, const RowBuffers &b, uint8_t delta, RowCounts &n) {
    /* Local counts: a stencil byte store may alias *n, a local cannot. */
    uint64_t tested = 0, written = 0;
    int64_t e0 = s.e[0], e1 = s.e[1], e2 = s.e[2];
    for (int x = s.x_begin; x < s.x_end; x++) {
        if ((e0 | e1 | e2) >= 0) {
            tested++;
            const bool less = depth_at(s, x) < b.depth[x];
            if (less != kFail) {
                b.stencil[x] = (uint8_t)(b.stencil[x] + delta);
                written++;
            }
        }
        e0 += s.step[0], e1 += s.step[1], e2 += s.step[2];
    }
    n.tested += tested;
    n.written += written;
}

/* stencil_c behind a depth-bounds test on the STORED depth d (as
 * EXT_depth_bounds_test): pixels with !(d > lo) or d > hi are neither
 * tested nor counted. kSaturate: the seed's IncrSat in place of the
 * addition, stencil = min(255, stencil + 1) (DELTA unused: the caller
 * keeps the decrements in a count of their own, stencil_pass.h). */
template <bool kFail, bool kSaturate = false>
inline void stencil_bounded_c(const RowSpan &s, const RowBuffers &b, uint8_t delta, float lo,
                              float hi, RowCounts &n) {
    uint64_t tested = 0, written = 0;
    int64_t e0 = s.e[0], e1 = s.e[1], e2 = s.e[2];
    for (int x = s.x_begin; x < s.x_end; x++) {
        const float d = b.depth[x];
        if ((e0 | e1 | e2) >= 0 && d > lo && !(d > hi)) {
            tested++;
            const bool less = depth_at(s, x) < d;
            if (less != kFail) {
                if constexpr (kSaturate) {
                    b.stencil[x] = (uint8_t)(b.stencil[x] + (b.stencil[x] != 255));
                } else {
                    b.stencil[x] = (uint8_t)(b.stencil[x] + delta);
                }
                written++;
            }
        }
        e0 += s.step[0], e1 += s.step[1], e2 += s.step[2];
    }
    n.tested += tested;
    n.written += written;
}

} // namespace sv::raster::c_rows

#endif
