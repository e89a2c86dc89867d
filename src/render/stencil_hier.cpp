/*
 * The hierarchical stencil method ("hier"; seed 004, Aila and
 * Akenine-Moeller, "A Hierarchical Shadow Volume Algorithm", 2004,
 * sections 3-5 and appendix A), exact against brute force:
 *
 *  - the screen in tiles (RenderOptions::stencil_tile, 8 by default) with
 *    the depth pass's range per tile (tile_depth_range.h);
 *  - stage 1, per volume and tile row: every piece against the boxes of
 *    the tiles it overlaps (tile_classify.h). A piece that may cross the
 *    box makes the tile a boundary tile of the volume. Otherwise it is in
 *    front of the box or behind it over the whole tile; the pieces that
 *    count in the volume's mode (z-fail: behind, appendix A; z-pass: in
 *    front, see below) and cover the tile's sample point add their delta
 *    to the tile's count;
 *  - stage 2: a volume's boundary tiles walked per pixel with its pieces
 *    (the rasteriser's row walk, clamped to the tile), and its count added
 *    to every pixel of each other tile it touched.
 *
 * Why one sample per tile is exact. Within a tile that no piece of the
 * volume crosses, brute force's count at a pixel is the sum of the deltas
 * of the counting pieces that cover it (the others fail or pass the depth
 * test there, as their whole extent over the tile does). Walking from one
 * pixel centre to another, that sum changes only where the walk crosses an
 * edge of a counting piece; every other piece on that edge counts too (a
 * piece sharing a point with it inside the tile is on the same side of
 * the box), so where the edge is closed (its directed uses cancel, as in
 * the closed z-fail volume) the changes cancel: the fill rule decides a
 * shared edge's pixels the same way for every triangle on it. Open edges
 * (open_edges.h: the ends of a z-pass volume's silhouette quads, a culled
 * volume's cut, the neighbours of a triangle that snapped to nothing) are
 * the exception: a counting piece whose open edge's visible part, or whose
 * cut by the near plane, meets the tile makes it a boundary tile. A cap
 * that is the receiver's own triangle fails its test at every pixel it
 * covers (volume_pieces.h), so it counts as behind every box, except where
 * the edges at which those caps do not close among themselves meet it. The
 * test against the box clips the piece to the tile's square, so a sliver
 * crossing the tile between pixel centres is seen too (volume_pieces.h
 * keeps pieces that cover no centre).
 *
 * The z-pass form (derived here; the seed gives z-fail): a pixel's z-pass
 * count is the deltas of the pieces in front of it, so in a tile no piece
 * crosses, the pieces in front of the whole box count (front faces +1,
 * back faces -1) where they cover the sample point, and those behind it
 * do not; z-fail counts those behind (back +1, front -1), appendix A.
 *
 * The seed's S_min/S_max, FS buffer and PSV cache are its bandwidth model
 * (Table 1, counted later); the stencil the frame keeps is the per-pixel
 * one, byte for byte brute force's (additions mod 256 commute, so tiles
 * and volumes may be done in any order: the same bytes at every thread
 * count).
 *
 * Copyright (C) 2026 the shadowvol authors. LGPL-2.1-or-later.
 */
#include <algorithm>
#include <stdexcept>
#include <string>

#include "frame_math.h"
#include "pass_bins.h"
#include "stencil_pass.h"
#include "tile_classify.h"
#include "tile_depth_range.h"
#include "volume_pieces.h"

namespace sv::render {

using namespace detail;

namespace {

inline int clamp_int(int64_t v, int lo, int hi) {
    return (int)std::min<int64_t>(hi, std::max<int64_t>(lo, v));
}

inline int64_t floor_div(int64_t a, int64_t b) { /* b > 0 */
    return a >= 0 ? a / b : -((-a + b - 1) / b);
}

/* The tile columns (or rows) that extent [lo, hi] (1/256 pixel) meets. */
inline void tile_span(int64_t lo, int64_t hi, int side, int count, int &first, int &last) {
    first = clamp_int(floor_div(lo, 256 * (int64_t)side), 0, count - 1);
    last = clamp_int(floor_div(hi, 256 * (int64_t)side), 0, count - 1);
}

/* The tile columns of one tile row that a piece's segments may meet
 * (segment_columns_in_row), at most four segments (a triangle's three
 * edges and its cut by the near plane). */
struct SegmentColumns {
    int first[4], last[4], n = 0;
    /* Segments [BEGIN, END) of SEGS; false when there are more than four
     * (the caller then takes every tile as met). */
    bool add(const std::vector<VolumePieces::Segment> &segs, int begin, int end, const TileGrid &g,
             int Y0, int Y1) {
        if (end - begin > 4) return false;
        for (int si = begin; si < end; si++) {
            const VolumePieces::Segment &sg = segs[(std::size_t)si];
            if (segment_columns_in_row(sg.x0, sg.y0, sg.x1, sg.y1, g, Y0, Y1, first[n], last[n]))
                n++;
        }
        return true;
    }
    bool meet(int tx) const {
        bool hit = false;
        for (int i = 0; i < n; i++) hit |= tx >= first[i] && tx <= last[i];
        return hit;
    }
};

struct RowTotals {
    raster::RowCounts walked;
    uint64_t pairs = 0, boundary_pairs = 0, boundary_tiles = 0, wholesale_pixels = 0;
};

} // namespace

StencilPassResult stencil_pass_hierarchical(const StencilPassInputs &in) {
    if (!valid_stencil_tile(in.tile)) {
        throw std::invalid_argument("stencil tile side " + std::to_string(in.tile) +
                                    ": 4, 8, 16 or 32");
    }
    StencilPassResult result;
    const raster::Rasterizer &rast = *in.rast;
    const int width = in.target->width, height = in.target->height;
    const double t0 = now_seconds();
    const uint64_t k0 = ticks();
    result.stencil.assign((std::size_t)width * height, 0);
    const TileGrid grid = tile_depth_ranges(in.target->depth.data(), width, height, in.tile);
    const VolumePieces vp = set_up_volume_pieces(in);
    result.counters = vp.counters;
    /* Pieces binned to tile rows by their extent, in submission order (so
     * a volume's pieces are consecutive in every row). */
    std::vector<std::vector<int>> rows((std::size_t)grid.tiles_y);
    for (int q = 0; q < (int)vp.pieces.size(); q++) {
        const raster::PieceExtent &e = vp.extents[(std::size_t)q];
        int first = 0, last = 0;
        tile_span(e.min_y, e.max_y, grid.side, grid.tiles_y, first, last);
        for (int ty = first; ty <= last; ty++) rows[(std::size_t)ty].push_back(q);
    }
    std::vector<PieceEdges> edges;
    edges.reserve(vp.pieces.size());
    for (const raster::PieceExtent &e : vp.extents) edges.emplace_back(e);
    std::vector<RowTotals> totals((std::size_t)grid.tiles_y);
    parallel(grid.tiles_y, [&](int ty) {
        const std::vector<int> &bin = rows[(std::size_t)ty];
        RowTotals &tot = totals[(std::size_t)ty];
        const int Y0 = grid.y0(ty), Y1 = grid.y1(ty);
        const std::size_t nx = (std::size_t)grid.tiles_x;
        /* Per tile of the row, for the volume at hand: 0 untouched, 1
         * classified, 2 boundary; its sampled count. Across volumes: the
         * counts to add wholesale, and whether any volume walked it. */
        std::vector<uint8_t> state(nx, 0), count(nx, 0), wholesale(nx, 0), walked(nx, 0);
        std::vector<int> touched;
        for (std::size_t i = 0; i < bin.size();) {
            const int vol = vp.volume[(std::size_t)bin[i]];
            std::size_t j = i;
            while (j < bin.size() && vp.volume[(std::size_t)bin[j]] == vol) j++;
            const bool zfail = vp.zfail[(std::size_t)vol];
            for (std::size_t k = i; k < j; k++) {
                const int q = bin[k];
                const raster::SetupTriangle &p = vp.pieces[(std::size_t)q];
                const raster::PieceExtent &e = vp.extents[(std::size_t)q];
                int first = 0, last = 0;
                RowExtent row_extent{};
                if (!piece_columns_in_row(edges[(std::size_t)q], grid, Y0, Y1, first, last,
                                          &row_extent)) {
                    continue;
                }
                const bool receiver = vp.receiver[(std::size_t)q] != 0;
                /* The columns this row's part of each open edge may meet
                 * (a tile there is a boundary tile wherever the piece
                 * counts), and for the receiver's own triangle those of
                 * each edge where the receiver's triangles do not close. */
                const uint8_t open = vp.open[(std::size_t)q];
                bool open_whole = (open & kOpenWhole) != 0;
                SegmentColumns open_columns, cap_columns;
                if (open && !open_whole) {
                    open_whole = !open_columns.add(vp.open_segments, vp.open_first[(std::size_t)q],
                                                   vp.open_first[(std::size_t)q + 1], grid, Y0, Y1);
                }
                bool cap_whole = false;
                if (receiver) {
                    cap_whole = !cap_columns.add(vp.cap_segments, vp.cap_first[(std::size_t)q],
                                                 vp.cap_first[(std::size_t)q + 1], grid, Y0, Y1);
                }
                for (int tx = first; tx <= last; tx++) {
                    uint8_t &st = state[(std::size_t)tx];
                    if (st == 2) continue;
                    TileSide side = TileSide::behind;
                    if (!receiver) {
                        side = classify_in_row(p, e, grid, tx, ty, row_extent, in.faults);
                        if (side == TileSide::misses) continue;
                    } else if (cap_whole || cap_columns.meet(tx)) {
                        /* The receiver's own triangle fails its test at every
                         * pixel it covers: "behind" in every tile, except
                         * where an edge at which the receiver's triangles do
                         * not close meets the tile (the other pieces on it may
                         * count otherwise). */
                        side = TileSide::crosses;
                    }
                    if (st == 0) {
                        st = 1;
                        count[(std::size_t)tx] = 0;
                        touched.push_back(tx);
                    }
                    if (side == TileSide::crosses) {
                        st = 2;
                        continue;
                    }
                    if ((side == TileSide::behind) != zfail) continue; /* does not count */
                    if (open_whole || open_columns.meet(tx)) {
                        st = 2;
                        continue;
                    }
                    int sx = 0, sy = 0;
                    tile_sample(grid, tx, ty, in.faults, sx, sy);
                    if (covers_pixel(p, sx, sy)) {
                        count[(std::size_t)tx] = (uint8_t)(count[(std::size_t)tx] +
                                                           vp.delta[(std::size_t)q]);
                    }
                }
            }
            bool any_boundary = false;
            for (int tx : touched) {
                tot.pairs++;
                if (state[(std::size_t)tx] == 2) {
                    tot.boundary_pairs++;
                    walked[(std::size_t)tx] = 1;
                    any_boundary = true;
                } else {
                    wholesale[(std::size_t)tx] = (uint8_t)(wholesale[(std::size_t)tx] +
                                                           count[(std::size_t)tx]);
                }
            }
            if (any_boundary) {
                const raster::StencilMode mode = zfail ? raster::StencilMode::zfail
                                                       : raster::StencilMode::zpass;
                for (std::size_t k = i; k < j; k++) {
                    const raster::SetupTriangle &p = vp.pieces[(std::size_t)bin[k]];
                    if (p.x_first > p.x_last || p.y_first > p.y_last || p.y_last < Y0 ||
                        p.y_first >= Y1) {
                        continue;
                    }
                    int first = 0, last = 0;
                    if (!piece_columns_in_row(edges[(std::size_t)bin[k]], grid, Y0, Y1, first,
                                              last)) {
                        continue;
                    }
                    first = std::max(first, p.x_first / grid.side);
                    last = std::min(last, p.x_last / grid.side);
                    /* Each run of consecutive boundary tiles in one walk. */
                    for (int tx = first; tx <= last; tx++) {
                        if (state[(std::size_t)tx] != 2) continue;
                        int run_end = tx;
                        while (run_end < last && state[(std::size_t)run_end + 1] == 2) run_end++;
                        raster::SetupTriangle clamped = p;
                        clamped.x_first = std::max(p.x_first, grid.x0(tx));
                        clamped.x_last = std::min(p.x_last, grid.x1(run_end) - 1);
                        rast.walk_stencil(clamped, in.target->depth.data(), result.stencil.data(),
                                          width, height, {Y0, Y1}, mode, tot.walked);
                        tx = run_end;
                    }
                }
            }
            for (int tx : touched) state[(std::size_t)tx] = 0;
            touched.clear();
            i = j;
        }
        for (int tx = 0; tx < grid.tiles_x; tx++) {
            tot.boundary_tiles += walked[(std::size_t)tx];
            const uint8_t add = wholesale[(std::size_t)tx];
            if (add == 0) continue;
            const int X0 = grid.x0(tx), X1 = grid.x1(tx);
            for (int y = Y0; y < Y1; y++) {
                uint8_t *row = result.stencil.data() + (std::size_t)y * (std::size_t)width;
                for (int x = X0; x < X1; x++) row[x] = (uint8_t)(row[x] + add);
            }
            tot.wholesale_pixels += (uint64_t)(X1 - X0) * (uint64_t)(Y1 - Y0);
        }
    });
    for (const RowTotals &t : totals) {
        raster::Rasterizer::add_stencil_counts(t.walked, result.counters);
        /* A tile updated wholesale reads and writes its stencil once. */
        result.counters.stencil_bytes_read += t.wholesale_pixels;
        result.counters.stencil_bytes_written += t.wholesale_pixels;
        result.tile_volume_pairs += t.pairs;
        result.boundary_pairs += t.boundary_pairs;
        result.boundary_tiles += t.boundary_tiles;
    }
    result.tiles = (uint64_t)grid.tiles_x * (uint64_t)grid.tiles_y;
    result.ticks = ticks() - k0;
    result.seconds = now_seconds() - t0;
    return result;
}

} // namespace sv::render
