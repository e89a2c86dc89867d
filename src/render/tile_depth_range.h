/*
 * The screen in square tiles, each with the range of the depth the depth
 * pass left in it (seed 004, section 3: "each tile's 3D box"; internal to
 * src/render). Tiles at the right and bottom edges hold only the pixels
 * inside the frame.
 *
 * Copyright (C) 2026 the shadowvol authors. LGPL-2.1-or-later.
 */
#ifndef SV_RENDER_TILE_DEPTH_RANGE_H
#define SV_RENDER_TILE_DEPTH_RANGE_H

#include <vector>

namespace sv::render::detail {

struct TileGrid {
    int side = 8;
    double inv_side = 1.0 / 8; /* 1 / side, exact (a power of two) */
    int width = 0, height = 0; /* the frame's pixels */
    int tiles_x = 0, tiles_y = 0;
    std::vector<float> z_min, z_max; /* per tile, row-major */
    /* The pixels of tile (tx, ty): [x0, x1) x [y0, y1). */
    int x0(int tx) const { return tx * side; }
    int x1(int tx) const { return tx * side + side < width ? tx * side + side : width; }
    int y0(int ty) const { return ty * side; }
    int y1(int ty) const { return ty * side + side < height ? ty * side + side : height; }
};

/* Runs on the calling task arena's threads (a tile row each). */
TileGrid tile_depth_ranges(const float *depth, int width, int height, int side);

/* FINE's tiles in blocks of FACTOR x FACTOR: each block a tile of side
 * FACTOR * FINE.side whose depth range holds those of its tiles (coarse
 * tile (cx, cy) holds fine tiles [cx * FACTOR, cx * FACTOR + FACTOR) x
 * [cy * FACTOR, ...), cut at the frame's edge). */
TileGrid coarser_grid(const TileGrid &fine, int factor);

} // namespace sv::render::detail

#endif
