/*
 * Per-tile depth ranges (tile_depth_range.h).
 *
 * Copyright (C) 2026 the shadowvol authors. LGPL-2.1-or-later.
 */
#include "tile_depth_range.h"

#include <algorithm>
#include <vector>

#include "pass_bins.h"

namespace sv::render::detail {

TileGrid tile_depth_ranges(const float *depth, int width, int height, int side) {
    TileGrid g;
    g.side = side;
    g.inv_side = 1.0 / side;
    g.width = width;
    g.height = height;
    g.tiles_x = (width + side - 1) / side;
    g.tiles_y = (height + side - 1) / side;
    const std::size_t n = (std::size_t)g.tiles_x * (std::size_t)g.tiles_y;
    g.z_min.assign(n, 1.0f);
    g.z_max.assign(n, 0.0f);
    parallel(g.tiles_y, [&](int ty) {
        /* Each column's range over the tile row first (element-wise, which
         * the compiler vectorises), then each tile's over its columns:
         * one reduction per tile, not per tile and row. Depth holds no
         * NaN, so the order of the minima changes nothing. */
        std::vector<float> col_lo(depth + (std::size_t)g.y0(ty) * (std::size_t)width,
                                  depth + (std::size_t)g.y0(ty) * (std::size_t)width + width);
        std::vector<float> col_hi(col_lo);
        for (int y = g.y0(ty) + 1; y < g.y1(ty); y++) {
            const float *row = depth + (std::size_t)y * (std::size_t)width;
            float *lo = col_lo.data(), *hi = col_hi.data();
            for (int x = 0; x < width; x++) {
                lo[x] = row[x] < lo[x] ? row[x] : lo[x];
                hi[x] = row[x] > hi[x] ? row[x] : hi[x];
            }
        }
        float *lo = g.z_min.data() + (std::size_t)ty * (std::size_t)g.tiles_x;
        float *hi = g.z_max.data() + (std::size_t)ty * (std::size_t)g.tiles_x;
        for (int tx = 0; tx < g.tiles_x; tx++) {
            float a = lo[tx], b = hi[tx];
            for (int x = g.x0(tx); x < g.x1(tx); x++) {
                a = std::min(a, col_lo[(std::size_t)x]);
                b = std::max(b, col_hi[(std::size_t)x]);
            }
            lo[tx] = a;
            hi[tx] = b;
        }
    });
    return g;
}

TileGrid coarser_grid(const TileGrid &fine, int factor) {
    TileGrid g;
    g.side = fine.side * factor;
    g.inv_side = 1.0 / g.side;
    g.width = fine.width;
    g.height = fine.height;
    g.tiles_x = (fine.tiles_x + factor - 1) / factor;
    g.tiles_y = (fine.tiles_y + factor - 1) / factor;
    const std::size_t n = (std::size_t)g.tiles_x * (std::size_t)g.tiles_y;
    g.z_min.assign(n, 1.0f);
    g.z_max.assign(n, 0.0f);
    for (int ty = 0; ty < fine.tiles_y; ty++) {
        for (int tx = 0; tx < fine.tiles_x; tx++) {
            const std::size_t f = (std::size_t)ty * (std::size_t)fine.tiles_x + (std::size_t)tx;
            const std::size_t c = (std::size_t)(ty / factor) * (std::size_t)g.tiles_x +
                                  (std::size_t)(tx / factor);
            g.z_min[c] = std::min(g.z_min[c], fine.z_min[f]);
            g.z_max[c] = std::max(g.z_max[c], fine.z_max[f]);
        }
    }
    return g;
}

} // namespace sv::render::detail
