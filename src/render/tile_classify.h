/*
 * Seed 004's per-tile test (section 3 and appendix A; internal to
 * src/render): where a volume's piece lies against a tile's 3D box (the
 * tile's square, its depth range). A piece that neither crosses the box
 * nor is open (volume_pieces.h) leaves the same count on every pixel of
 * the tile, so the tile's count is read at one sample point.
 *
 * The test is conservative where it must be: "misses" only when the
 * piece's edge functions put the whole square outside one edge, or
 * nothing of it is left after clipping it to the square; "front" and
 * "behind" from the depth plane's range over the clipped piece, widened
 * by a margin for the rounding of the plane and
 * for the vertices of a clipped polygon that lie off its plane (snapped
 * to 1/256 pixel: a plane through three of them misses the others by
 * up to a fraction of the slope), and decided in float as the depth test
 * is: "front" when every covered pixel passes LESS, "behind" when every
 * one fails it.
 *
 * Copyright (C) 2026 the shadowvol authors. LGPL-2.1-or-later.
 */
#ifndef SV_RENDER_TILE_CLASSIFY_H
#define SV_RENDER_TILE_CLASSIFY_H

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>

#include "rasterizer.h"
#include "stencil_method.h"
#include "tile_depth_range.h"

namespace sv::render::detail {

enum class TileSide : uint8_t {
    misses,  /* the piece is nowhere inside the tile's square */
    front,   /* every point of it over the square is in front of the box */
    behind,  /* ... behind the box */
    crosses, /* it may cross the box: the tile is a boundary tile */
};

/* The edge function E of piece P at pixel-corner point (X, Y) (pixels). */
inline int64_t edge_at_corner(const raster::SetupTriangle &p, int e, int x, int y) {
    /* e_origin is at pixel (0, 0)'s centre; the steps are whole multiples
     * of 256, so the half-pixel offset is exact. */
    return p.e_origin[e] + p.step_x[e] * x + p.step_y[e] * y - (p.step_x[e] + p.step_y[e]) / 2;
}

/* The range [LO, HI] of piece P's depth plane over the part of the piece
 * inside square [X0, X1] x [Y0, Y1] (pixels): the piece clipped to the
 * square (widened by 1/1024 pixel, so rounding cannot lose a point that is
 * inside), the plane at the clipped corners; MARGIN for the plane's
 * rounding and for the corners of a clipped polygon that are off its plane
 * (PieceExtent::off_plane): where two pieces share a point their planes
 * differ by no more than the two margins, so one cannot be "front" while
 * the other is "behind" there. False: nothing of the piece is inside the
 * square. */
inline bool depth_range_in_square(const raster::SetupTriangle &p, const raster::PieceExtent &ext,
                                  int X0, int X1, int Y0, int Y1, double &lo, double &hi,
                                  double &margin) {
    constexpr double kWiden = 1.0 / 1024;
    double px[9], py[9], qx[9], qy[9];
    int n = 3;
    for (int i = 0; i < 3; i++) px[i] = (double)ext.X[i] / 256, py[i] = (double)ext.Y[i] / 256;
    /* Sutherland-Hodgman against the square's four sides. */
    const double bound[4] = {X0 - kWiden, X1 + kWiden, Y0 - kWiden, Y1 + kWiden};
    for (int side = 0; side < 4 && n > 0; side++) {
        const bool is_x = side < 2, keep_above = (side % 2) == 0;
        auto dist = [&](double x, double y) {
            const double v = is_x ? x : y;
            return keep_above ? v - bound[side] : bound[side] - v;
        };
        int m = 0;
        for (int i = 0; i < n; i++) {
            const int j = (i + 1) % n;
            const double di = dist(px[i], py[i]), dj = dist(px[j], py[j]);
            if (di >= 0) qx[m] = px[i], qy[m] = py[i], m++;
            if ((di >= 0) != (dj >= 0)) {
                const double u = di / (di - dj);
                qx[m] = px[i] + u * (px[j] - px[i]);
                qy[m] = py[i] + u * (py[j] - py[i]);
                if (is_x)
                    qx[m] = bound[side];
                else
                    qy[m] = bound[side];
                m++;
            }
        }
        n = m;
        for (int i = 0; i < n; i++) px[i] = qx[i], py[i] = qy[i];
    }
    if (n == 0) return false;
    lo = std::numeric_limits<double>::infinity();
    hi = -lo;
    double size = 0;
    for (int i = 0; i < n; i++) {
        const double zx = p.a * (px[i] - p.x0), zy = p.b * (py[i] - p.y0);
        const double z = p.z0 + zx + zy;
        lo = std::min(lo, z);
        hi = std::max(hi, z);
        size = std::max(size, std::fabs(zx) + std::fabs(zy));
    }
    /* The clipped corners are rounded too: up to the widening's worth of
     * slope, plus the plane's own rounding. */
    margin = 1e-9 + 1e-12 * size + (std::fabs(p.a) + std::fabs(p.b)) * kWiden;
    margin += ext.off_plane * (1 + 1e-9);
    return true;
}

/* The range [LO, HI] of piece P's depth plane over the whole square
 * [X0, X1] x [Y0, Y1] (pixels), with depth_range_in_square's MARGIN: a
 * superset of the piece's part there, so as conservative, and exact where
 * the piece covers the square (no clipping needed). */
inline void depth_range_over_square(const raster::SetupTriangle &p, const raster::PieceExtent &ext,
                                    int X0, int X1, int Y0, int Y1, double &lo, double &hi,
                                    double &margin) {
    const double zx0 = p.a * (X0 - p.x0), zx1 = p.a * (X1 - p.x0);
    const double zy0 = p.b * (Y0 - p.y0), zy1 = p.b * (Y1 - p.y0);
    lo = p.z0 + std::min(zx0, zx1) + std::min(zy0, zy1);
    hi = p.z0 + std::max(zx0, zx1) + std::max(zy0, zy1);
    const double size = std::max(std::fabs(zx0), std::fabs(zx1)) +
                        std::max(std::fabs(zy0), std::fabs(zy1));
    margin = 1e-9 + 1e-12 * size + ext.off_plane * (1 + 1e-9);
}

/* Does piece P's every edge function leave some point of the square
 * [X0, X1] x [Y0, Y1] inside (false: it misses the square for sure), and
 * is the whole square inside all three (*INSIDE)? Exact integers. */
inline bool edges_reach_square(const raster::SetupTriangle &p, int X0, int X1, int Y0, int Y1,
                               bool *inside) {
    bool all = true;
    for (int e = 0; e < 3; e++) {
        const int64_t c00 = edge_at_corner(p, e, X0, Y0), dx = p.step_x[e] * (X1 - X0),
                      dy = p.step_y[e] * (Y1 - Y0);
        const int64_t most = c00 + std::max<int64_t>(dx, 0) + std::max<int64_t>(dy, 0);
        if (most < 0) return false;
        const int64_t least = c00 + std::min<int64_t>(dx, 0) + std::min<int64_t>(dy, 0);
        all &= least >= 0;
    }
    if (inside) *inside = all;
    return true;
}

/* Where the piece lies against the tile's box, from a depth range: front,
 * behind or crosses. */
inline TileSide side_of_range(double lo, double hi, double margin, float z_min, float z_max) {
    if ((float)(hi + margin) < z_min) return TileSide::front;
    if (lo - margin >= (double)z_max) return TileSide::behind;
    return TileSide::crosses;
}

/* The piece's x extent inside one tile row (pixels, widened), from
 * piece_columns_in_row: a rectangle that holds the piece's part of each
 * tile of the row. */
struct RowExtent {
    double lo_x, hi_x, lo_y, hi_y;
};

inline TileSide classify_piece(const raster::SetupTriangle &p, const raster::PieceExtent &ext,
                               const TileGrid &g, int tx, int ty, const StencilFaults &faults,
                               const RowExtent *row = nullptr) {
    const int X0 = g.x0(tx), X1 = g.x1(tx), Y0 = g.y0(ty), Y1 = g.y1(ty);
    constexpr int64_t kSub = 256;
    if (ext.max_x <= X0 * kSub || ext.min_x >= X1 * kSub || ext.max_y <= Y0 * kSub ||
        ext.min_y >= Y1 * kSub) {
        return TileSide::misses;
    }
    bool covers_square = false;
    if (!edges_reach_square(p, X0, X1, Y0, Y1, &covers_square)) return TileSide::misses;
    const std::size_t t = (std::size_t)ty * (std::size_t)g.tiles_x + (std::size_t)tx;
    const float z_min = g.z_min[t], z_max = g.z_max[t];
    double lo = 0, hi = 0, margin = 0;
    if (faults.tile_box_test_too_tight) {
        lo = hi = p.z0 + p.a * ((X0 + X1) * 0.5 - p.x0) + p.b * ((Y0 + Y1) * 0.5 - p.y0);
    } else if (covers_square) {
        /* Most tiles of a large piece: the square itself, no clipping. */
        depth_range_over_square(p, ext, X0, X1, Y0, Y1, lo, hi, margin);
    } else {
        /* First the plane over the rectangle that holds the piece's part of
         * the tile (its extent in the tile row, cut to the square): most
         * tiles a long sliver passes are decided there, without the clip. */
        if (row) {
            const double rx0 = std::max((double)X0, row->lo_x),
                         rx1 = std::min((double)X1, row->hi_x);
            const double ry0 = std::max((double)Y0, row->lo_y),
                         ry1 = std::min((double)Y1, row->hi_y);
            if (rx0 <= rx1 && ry0 <= ry1) {
                const double zx0 = p.a * (rx0 - p.x0), zx1 = p.a * (rx1 - p.x0);
                const double zy0 = p.b * (ry0 - p.y0), zy1 = p.b * (ry1 - p.y0);
                lo = p.z0 + std::min(zx0, zx1) + std::min(zy0, zy1);
                hi = p.z0 + std::max(zx0, zx1) + std::max(zy0, zy1);
                const double size = std::max(std::fabs(zx0), std::fabs(zx1)) +
                                    std::max(std::fabs(zy0), std::fabs(zy1));
                margin = 1e-9 + 1e-12 * size + ext.off_plane * (1 + 1e-9);
                const TileSide quick = side_of_range(lo, hi, margin, z_min, z_max);
                if (quick != TileSide::crosses) return quick;
            }
        }
        if (!depth_range_in_square(p, ext, X0, X1, Y0, Y1, lo, hi, margin)) return TileSide::misses;
    }
    return side_of_range(lo, hi, margin, z_min, z_max);
}

/* A piece's edges as piece_columns_in_row walks them: per edge its upper
 * end, its y range and its slope dx/dy (1/256 pixel), computed once per
 * piece instead of once per tile row. */
struct PieceEdges {
    double x_top[3], x_bottom[3], y_top[3], y_bottom[3];
    double slope[3];     /* 0 where the edge is flat (y_top == y_bottom) */
    double min_y, max_y; /* the piece's, pixels, widened by 1/256 */
    explicit PieceEdges(const raster::PieceExtent &ext) {
        for (int i = 0; i < 3; i++) {
            const int j = (i + 1) % 3;
            const bool down = ext.Y[i] <= ext.Y[j];
            const int a = down ? i : j, b = down ? j : i;
            x_top[i] = (double)ext.X[a];
            y_top[i] = (double)ext.Y[a];
            y_bottom[i] = (double)ext.Y[b];
            slope[i] = ext.Y[a] == ext.Y[b]
                           ? 0
                           : (double)(ext.X[b] - ext.X[a]) / (double)(ext.Y[b] - ext.Y[a]);
            x_bottom[i] = (double)ext.X[b];
        }
        min_y = (double)(ext.min_y - 1) / 256;
        max_y = (double)(ext.max_y + 1) / 256;
    }
};

/* The tile columns [FIRST, LAST] that piece E meets within tile row
 * [Y0, Y1) (pixels), widened by 1/256 pixel: a convex polygon's x extent
 * inside a horizontal slab is that of its edges clipped to the slab, so a
 * long diagonal sliver visits the tiles along it, not its bounding box.
 * ROW gets that extent. False: the piece does not reach the slab. */
inline bool piece_columns_in_row(const PieceEdges &e, const TileGrid &g, int Y0, int Y1, int &first,
                                 int &last, RowExtent *row = nullptr) {
    constexpr double kSub = 256;
    const double lo_y = Y0 * kSub - 1, hi_y = Y1 * kSub + 1;
    double lo_x = std::numeric_limits<double>::infinity(), hi_x = -lo_x;
    for (int i = 0; i < 3; i++) {
        const double y_min = std::max(e.y_top[i], lo_y), y_max = std::min(e.y_bottom[i], hi_y);
        if (y_min > y_max) continue;
        double x0 = 0, x1 = 0;
        if (e.y_top[i] == e.y_bottom[i]) {
            x0 = e.x_top[i], x1 = e.x_bottom[i];
        } else {
            x0 = e.x_top[i] + e.slope[i] * (y_min - e.y_top[i]);
            x1 = e.x_top[i] + e.slope[i] * (y_max - e.y_top[i]);
        }
        lo_x = std::min({lo_x, x0, x1});
        hi_x = std::max({hi_x, x0, x1});
    }
    if (!(lo_x <= hi_x)) return false;
    if (row) {
        row->lo_x = (lo_x - 1) / kSub;
        row->hi_x = (hi_x + 1) / kSub;
        row->lo_y = e.min_y;
        row->hi_y = e.max_y;
    }
    /* A tile is 2^10 to 2^13 units wide: multiplying by its inverse is
     * exact. */
    const double per_tile = g.inv_side * (1.0 / kSub);
    const double f = std::floor((lo_x - 1) * per_tile), l = std::floor((hi_x + 1) * per_tile);
    if (l < 0 || f > g.tiles_x - 1) return false;
    first = (int)std::max(0.0, f);
    last = (int)std::min((double)(g.tiles_x - 1), l);
    return true;
}

/* Piece P against tile TX of the row whose extent ROW piece_columns_in_row
 * gave (the tile one of the columns it returned): the plane's range over
 * the rectangle ROW leaves of the square first, the clip to the square
 * only where that cannot decide (without CLIP: "crosses" there). The columns come from the piece's edges,
 * so no edge test is needed; a tile the piece only nearly reaches is
 * classified as if it reached it, which costs nothing: its sample is not
 * covered, and "crosses" only walks pixels the walk finds empty. */
inline TileSide classify_in_row(const raster::SetupTriangle &p, const raster::PieceExtent &ext,
                                const TileGrid &g, int tx, int ty, const RowExtent &row,
                                const StencilFaults &faults, bool clip = true) {
    if (faults.tile_box_test_too_tight) return classify_piece(p, ext, g, tx, ty, faults);
    const int X0 = g.x0(tx), X1 = g.x1(tx), Y0 = g.y0(ty), Y1 = g.y1(ty);
    const std::size_t t = (std::size_t)ty * (std::size_t)g.tiles_x + (std::size_t)tx;
    const float z_min = g.z_min[t], z_max = g.z_max[t];
    const double rx0 = std::max((double)X0, row.lo_x), rx1 = std::min((double)X1, row.hi_x);
    const double ry0 = std::max((double)Y0, row.lo_y), ry1 = std::min((double)Y1, row.hi_y);
    double lo = 0, hi = 0, margin = 0;
    if (rx0 <= rx1 && ry0 <= ry1) {
        const double zx0 = p.a * (rx0 - p.x0), zx1 = p.a * (rx1 - p.x0);
        const double zy0 = p.b * (ry0 - p.y0), zy1 = p.b * (ry1 - p.y0);
        lo = p.z0 + std::min(zx0, zx1) + std::min(zy0, zy1);
        hi = p.z0 + std::max(zx0, zx1) + std::max(zy0, zy1);
        const double size = std::max(std::fabs(zx0), std::fabs(zx1)) +
                            std::max(std::fabs(zy0), std::fabs(zy1));
        margin = 1e-9 + 1e-12 * size + ext.off_plane * (1 + 1e-9);
        const TileSide quick = side_of_range(lo, hi, margin, z_min, z_max);
        if (quick != TileSide::crosses) return quick;
    }
    if (!clip) return TileSide::crosses;
    if (!depth_range_in_square(p, ext, X0, X1, Y0, Y1, lo, hi, margin)) return TileSide::misses;
    return side_of_range(lo, hi, margin, z_min, z_max);
}

/* A segment (window pixels) as segment_columns_in_row walks it: its upper
 * end, its y range and its slope dx/dy, computed once. */
struct SegmentLine {
    double x_top, y_top, x_bottom, y_bottom, slope; /* slope 0 where flat */
    SegmentLine(double x0, double y0, double x1, double y1) {
        const bool down = y0 <= y1;
        x_top = down ? x0 : x1, y_top = down ? y0 : y1;
        x_bottom = down ? x1 : x0, y_bottom = down ? y1 : y0;
        slope = y_top == y_bottom ? 0 : (x_bottom - x_top) / (y_bottom - y_top);
    }
};

/* The tile columns [FIRST, LAST] of tile row [Y0, Y1) whose squares,
 * widened by 1/8 pixel (the rasteriser's snapped edge is within 1/512
 * pixel of segment S), S may meet: the x extent of S inside the row's
 * slab, widened. False: none. */
inline bool segment_columns_in_row(const SegmentLine &s, const TileGrid &g, int Y0, int Y1,
                                   int &first, int &last) {
    constexpr double kWiden = 2.0 / 16;
    const double lo_y = Y0 - kWiden, hi_y = Y1 + kWiden;
    const double ya = std::max(s.y_top, lo_y), yb = std::min(s.y_bottom, hi_y);
    if (!(ya <= yb)) return false;
    double lo_x = 0, hi_x = 0;
    if (s.y_top == s.y_bottom) {
        lo_x = std::min(s.x_top, s.x_bottom), hi_x = std::max(s.x_top, s.x_bottom);
    } else {
        const double xa = s.x_top + s.slope * (ya - s.y_top),
                     xb = s.x_top + s.slope * (yb - s.y_top);
        lo_x = std::min(xa, xb), hi_x = std::max(xa, xb);
    }
    const double f = std::floor((lo_x - kWiden) * g.inv_side),
                 l = std::floor((hi_x + kWiden) * g.inv_side);
    if (!(l >= 0) || !(f <= g.tiles_x - 1)) return false;
    first = (int)std::max(0.0, f);
    last = (int)std::min((double)(g.tiles_x - 1), l);
    return true;
}

/* The tile's sample point: its first pixel (always inside the frame). */
inline void tile_sample(const TileGrid &g, int tx, int ty, const StencilFaults &faults, int &sx,
                        int &sy) {
    sx = g.x0(tx);
    sy = g.y0(ty);
    if (faults.sample_outside_tile) sx = g.x1(tx) < g.width ? g.x1(tx) : g.x0(tx) - 1;
}

/* Can piece P cover the sample (first pixel) of any tile in columns
 * [TX0, TX1] and rows [TY0, TY1]? False only when one edge function is
 * negative at all of them (linear: its largest value is at a corner of
 * the samples' grid). */
inline bool covers_any_sample(const raster::SetupTriangle &p, const TileGrid &g, int tx0, int tx1,
                              int ty0, int ty1) {
    const int x0 = g.x0(tx0), y0 = g.y0(ty0);
    const int64_t span_x = (int64_t)(tx1 - tx0) * g.side, span_y = (int64_t)(ty1 - ty0) * g.side;
    for (int e = 0; e < 3; e++) {
        const int64_t at = p.e_origin[e] + p.step_x[e] * x0 + p.step_y[e] * y0;
        const int64_t most = at + std::max<int64_t>(p.step_x[e] * span_x, 0) +
                             std::max<int64_t>(p.step_y[e] * span_y, 0);
        if (most < 0) return false;
    }
    return true;
}

/* Does piece P cover pixel (X, Y)'s centre (the row kernels' exact test)? */
inline bool covers_pixel(const raster::SetupTriangle &p, int x, int y) {
    int64_t all = 0;
    for (int e = 0; e < 3; e++) all |= p.e_origin[e] + p.step_x[e] * x + p.step_y[e] * y;
    return all >= 0;
}

} // namespace sv::render::detail

#endif
