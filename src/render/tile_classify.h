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

inline TileSide classify_piece(const raster::SetupTriangle &p, const raster::PieceExtent &ext,
                               const TileGrid &g, int tx, int ty, const StencilFaults &faults) {
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
    } else if (!depth_range_in_square(p, ext, X0, X1, Y0, Y1, lo, hi, margin)) {
        return TileSide::misses;
    }
    if ((float)(hi + margin) < z_min) return TileSide::front;
    if (lo - margin >= (double)z_max) return TileSide::behind;
    return TileSide::crosses;
}

/* Does segment S (window pixels) meet the square of tile (TX, TY),
 * widened by 1/16 pixel (the rasteriser's snapped edge is within 1/512
 * pixel of it)? Liang-Barsky. */
inline bool segment_meets_tile(double x0, double y0, double x1, double y1, const TileGrid &g,
                               int tx, int ty) {
    constexpr double kWiden = 1.0 / 16;
    const double dx = x1 - x0, dy = y1 - y0;
    const double lo_x = g.x0(tx) - kWiden, hi_x = g.x1(tx) + kWiden;
    const double lo_y = g.y0(ty) - kWiden, hi_y = g.y1(ty) + kWiden;
    double u0 = 0, u1 = 1;
    const double pp[4] = {-dx, dx, -dy, dy};
    const double qq[4] = {x0 - lo_x, hi_x - x0, y0 - lo_y, hi_y - y0};
    for (int i = 0; i < 4; i++) {
        if (pp[i] == 0) {
            if (qq[i] < 0) return false;
            continue;
        }
        const double r = qq[i] / pp[i];
        if (pp[i] < 0)
            u0 = std::max(u0, r);
        else
            u1 = std::min(u1, r);
        if (u0 > u1) return false;
    }
    return true;
}

/* The tile columns [FIRST, LAST] that piece EXT meets within tile row
 * [Y0, Y1) (pixels), widened by 1/256 pixel: a convex polygon's x extent
 * inside a horizontal slab is that of its edges clipped to the slab, so a
 * long diagonal sliver visits the tiles along it, not its bounding box.
 * False: the piece does not reach the slab. */
inline bool piece_columns_in_row(const raster::PieceExtent &ext, const TileGrid &g, int Y0, int Y1,
                                 int &first, int &last) {
    constexpr double kSub = 256;
    const double lo_y = Y0 * kSub - 1, hi_y = Y1 * kSub + 1;
    double lo_x = std::numeric_limits<double>::infinity(), hi_x = -lo_x;
    for (int i = 0; i < 3; i++) {
        const int j = (i + 1) % 3;
        const double xa = (double)ext.X[i], ya = (double)ext.Y[i];
        const double xb = (double)ext.X[j], yb = (double)ext.Y[j];
        const double y_min = std::max(std::min(ya, yb), lo_y);
        const double y_max = std::min(std::max(ya, yb), hi_y);
        if (y_min > y_max) continue;
        if (ya == yb) {
            lo_x = std::min({lo_x, xa, xb});
            hi_x = std::max({hi_x, xa, xb});
            continue;
        }
        const double slope = (xb - xa) / (yb - ya);
        const double x0 = xa + slope * (y_min - ya), x1 = xa + slope * (y_max - ya);
        lo_x = std::min({lo_x, x0, x1});
        hi_x = std::max({hi_x, x0, x1});
    }
    if (!(lo_x <= hi_x)) return false;
    const double tile = kSub * g.side;
    const double f = std::floor((lo_x - 1) / tile), l = std::floor((hi_x + 1) / tile);
    if (l < 0 || f > g.tiles_x - 1) return false;
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

/* Does piece P cover pixel (X, Y)'s centre (the row kernels' exact test)? */
inline bool covers_pixel(const raster::SetupTriangle &p, int x, int y) {
    int64_t all = 0;
    for (int e = 0; e < 3; e++) all |= p.e_origin[e] + p.step_x[e] * x + p.step_y[e] * y;
    return all >= 0;
}

} // namespace sv::render::detail

#endif
