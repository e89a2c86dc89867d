/*
 * The hierarchical stencil method ("hier"; seed 004, Aila and
 * Akenine-Moeller, "A Hierarchical Shadow Volume Algorithm", 2004,
 * sections 3-5 and appendix A), exact against brute force:
 *
 *  - the screen in tiles (RenderOptions::stencil_tile, kDefaultStencilTile
 *    by default; the seed's are 8x8) with
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
 * The receiver's own caps by coverage (beyond the seed). In z-fail such a
 * cap's count is its delta at every pixel centre it covers, whatever the
 * depth, so its pieces need no test at all: each band adds their covered
 * spans (Rasterizer::covered_spans, the pixels the walks would test) as
 * differences along its rows and a running sum gives each pixel theirs.
 * What is left of the volume is classified and walked as above, with the
 * edges between the receiver's pieces and the others (CAP_SEGMENTS: where
 * the receiver's triangles do not close among themselves) as open edges:
 * the tiles they meet are boundary tiles. In any other tile the rest's
 * count is constant, by the argument above, and the caps' count is exact
 * per pixel, so the sum is brute force's. A dense mesh in z-fail is mostly
 * caps (the koala under a point light: 88% of its pieces), and its caps
 * then cost a few integer operations per row instead of a walk with a
 * depth read per pixel. Taken only where every triangle of the receiver's
 * own kept its flag (VolumePieces::caps_by_coverage) and not under
 * saturation.
 *
 * The z-pass form (derived here; the seed gives z-fail): a pixel's z-pass
 * count is the deltas of the pieces in front of it, so in a tile no piece
 * crosses, the pieces in front of the whole box count (front faces +1,
 * back faces -1) where they cover the sample point, and those behind it
 * do not; z-fail counts those behind (back +1, front -1), appendix A.
 *
 * Under seed 002's saturating operations (StencilPassInputs::saturate)
 * no tile is updated wholesale: a saturating count is no sum modulo 256,
 * and its two halves, the increments and the decrements, are not constant
 * over a tile that no piece crosses (only their difference is: a closed
 * edge between a back and a front piece moves both), so a tile where a
 * piece counts is walked per pixel into both. Tiles where no piece counts
 * (missed, or every piece on the side where its test never changes the
 * count) are still skipped: exact for any operation. So hier stays equal
 * to bf, and its saving under saturation is the tiles no piece counts in.
 * The seed's S_min/S_max would need the same care: a saturating update of
 * a tile's range is [min(255, S_min + k), min(255, S_max + k)] for its
 * increments, not a sum.
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
#include <memory>
#include <stdexcept>
#include <string>
#include <utility>

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
    bool add(const std::vector<SegmentLine> &segs, int begin, int end, const TileGrid &g, int Y0,
             int Y1) {
        if (end - begin > 4) return false;
        for (int si = begin; si < end; si++) {
            if (segment_columns_in_row(segs[(std::size_t)si], g, Y0, Y1, first[n], last[n])) n++;
        }
        return true;
    }
    bool meet(int tx) const {
        bool hit = false;
        for (int i = 0; i < n; i++) hit |= tx >= first[i] && tx <= last[i];
        return hit;
    }
};

/* Tiles per side of a coarse tile: seed 004's test one level up, so a
 * long sliver in front of or behind a coarse tile's box decides its
 * fine tiles without testing each. */
constexpr int kCoarse = 4;

struct RowTotals {
    raster::RowCounts walked;
    uint64_t pairs = 0, boundary_pairs = 0, boundary_tiles = 0, wholesale_pixels = 0;
    uint64_t psv_lines = 0, coverage_rows = 0, coverage_pixels = 0;
};

/* The receiver's own caps of a band's rows by coverage: each covered
 * span adds its delta at its first pixel and takes it back one past its
 * last, in a row of differences (modulo 256, as the stencil); a running
 * sum along the row then gives every pixel the sum of the deltas of the
 * spans over it. */
class CoverageRows {
public:
    /* DIFF, LO, HI: storage kept from band to band (BandScratch). DIFF
     * is all zeros between bands (resolve clears what add wrote), so it is
     * only grown here, not cleared: most bands of most passes add nothing. */
    CoverageRows(int row_begin, int row_end, int width, std::vector<uint8_t> &diff,
                 std::vector<int> &lo, std::vector<int> &hi)
        : row_begin_(row_begin), width_(width), diff_(diff), lo_(lo), hi_(hi) {
        const std::size_t rows = (std::size_t)(row_end - row_begin);
        if (diff_.size() < rows * (std::size_t)(width + 1)) {
            diff_.resize(rows * (std::size_t)(width + 1), 0);
        }
        lo_.assign(rows, width);
        hi_.assign(rows, -1);
    }
    void add(const raster::Rasterizer::CoveredSpan &s, uint8_t delta) {
        const std::size_t r = (std::size_t)(s.y - row_begin_);
        uint8_t *d = diff_.data() + r * (std::size_t)(width_ + 1);
        d[s.x_begin] = (uint8_t)(d[s.x_begin] + delta);
        d[s.x_end] = (uint8_t)(d[s.x_end] - delta);
        lo_[r] = std::min(lo_[r], s.x_begin);
        hi_[r] = std::max(hi_[r], s.x_end);
    }
    /* Adds the sums to STENCIL's rows; returns the pixels it ran over. */
    uint64_t resolve(uint8_t *stencil) {
        uint64_t pixels = 0;
        for (std::size_t r = 0; r < lo_.size(); r++) {
            if (hi_[r] < 0) continue;
            uint8_t *d = diff_.data() + r * (std::size_t)(width_ + 1);
            uint8_t *row = stencil + ((std::size_t)row_begin_ + r) * (std::size_t)width_;
            uint8_t sum = 0;
            /* The sum is 0 again at HI (every span has ended by then); every
             * entry ADD wrote, [lo, hi], is cleared. */
            for (int x = lo_[r]; x < hi_[r]; x++) {
                sum = (uint8_t)(sum + d[x]);
                d[x] = 0;
                row[x] = (uint8_t)(row[x] + sum);
            }
            d[hi_[r]] = 0;
            pixels += (uint64_t)(hi_[r] - lo_[r]);
        }
        return pixels;
    }

private:
    int row_begin_, width_;
    std::vector<uint8_t> &diff_;
    std::vector<int> &lo_, &hi_;
};

/* What one piece needs in one fine row of a band, computed when first
 * asked for (and kept for stage 2). */
struct FineRow {
    bool reached;
    int first, last;
    RowExtent extent;
};

/* The columns its open edges (and, for the receiver's own triangle, its
 * unclosed edges) may meet in a fine row: stage 1's, per piece. */
struct FineSegments {
    bool open_whole, cap_whole;
    SegmentColumns open, cap;
};

/* A band's working buffers, kept by each thread from band to band and
 * frame to frame: a pass over a dense mesh asks for tens of megabytes of
 * them, and fresh pages cost the kernel more than the pass's own work. */
struct BandScratch {
    std::vector<uint8_t> state, count, wholesale, walked, psv_seen, fine_known;
    std::vector<std::size_t> touched, walkable;
    std::vector<FineRow> fine_rows;
    std::vector<raster::Rasterizer::CoveredSpan> spans;
    std::vector<uint8_t> coverage_diff;
    std::vector<int> coverage_lo, coverage_hi;
};

/* Tiles per cache line of the seed's PSV buffer (StencilPassResult). */
constexpr int kPsvLineTiles = 128;

} // namespace

void detail::check_stencil_tile(int side) {
    if (!valid_stencil_tile(side)) {
        throw std::invalid_argument("stencil tile side " + std::to_string(side) +
                                    ": 4, 8, 16 or 32");
    }
}

StencilPassResult stencil_pass_hierarchical(const StencilPassInputs &in) {
    check_stencil_tile(in.tile);
    StencilPassResult result;
    const int width = in.target->width, height = in.target->height;
    result.stencil.assign((std::size_t)width * height, 0); /* the clear: not the pass's time */
    const double t0 = now_seconds();
    const uint64_t k0 = ticks();
    hierarchical_stencil(in, set_up_pieces(in), result);
    result.ticks = ticks() - k0;
    result.seconds = now_seconds() - t0;
    return result;
}

void detail::hierarchical_stencil(const StencilPassInputs &in, PieceSetup &&setup,
                                  StencilPassResult &result) {
    check_stencil_tile(in.tile);
    const raster::Rasterizer &rast = *in.rast;
    const int width = in.target->width, height = in.target->height;
    TileGrid own_grid;
    const TileGrid *given = in.tile_grid;
    if (!given && in.tile_grid_for_auto && in.tile_grid_for_auto->side == in.tile &&
        in.tile_grid_for_auto->width == width && in.tile_grid_for_auto->height == height) {
        given = in.tile_grid_for_auto; /* an earlier light's */
    }
    if (!given) {
        /* Computed here, into auto's frame-wide slot where there is one. */
        TileGrid &into = in.tile_grid_for_auto ? *in.tile_grid_for_auto : own_grid;
        into = tile_depth_ranges(in.target->depth.data(), width, height, in.tile);
        given = &into;
    }
    const TileGrid &grid = *given;
    if (grid.side != in.tile || grid.width != width || grid.height != height) {
        throw std::invalid_argument("stencil_pass_hierarchical: the tile grid given is not the "
                                    "frame's at the pass's tile side");
    }
    const TileGrid coarse = coarser_grid(grid, kCoarse);
    const VolumePieces vp = finish_volume_pieces(in, std::move(setup));
    result.counters = vp.counters;
    /* The receiver's caps are taken by coverage where VolumePieces allows
     * it, not under saturation (two counts, not one sum of deltas). */
    const bool coverage_allowed = !in.saturate;
    /* Pieces binned to bands (a row of coarse tiles) by their extent, in
     * submission order (so a volume's pieces are consecutive in every
     * band). */
    std::vector<std::vector<int>> bands((std::size_t)coarse.tiles_y);
    for (int q = 0; q < (int)vp.pieces.size(); q++) {
        const raster::PieceExtent &e = vp.extents[(std::size_t)q];
        int first = 0, last = 0;
        tile_span(e.min_y, e.max_y, coarse.side, coarse.tiles_y, first, last);
        for (int cy = first; cy <= last; cy++) bands[(std::size_t)cy].push_back(q);
    }
    std::vector<PieceEdges> edges;
    edges.reserve(vp.pieces.size());
    for (std::size_t q = 0; q < vp.extents.size(); q++) edges.emplace_back(vp.extents[q]);
    std::vector<SegmentLine> open_lines, cap_lines;
    open_lines.reserve(vp.open_segments.size());
    for (const VolumePieces::Segment &sg : vp.open_segments)
        open_lines.emplace_back(sg.x0, sg.y0, sg.x1, sg.y1);
    cap_lines.reserve(vp.cap_segments.size());
    for (const VolumePieces::Segment &sg : vp.cap_segments)
        cap_lines.emplace_back(sg.x0, sg.y0, sg.x1, sg.y1);
    /* The faults are about the fine tiles' tests: the coarse level stays
     * out of their way. */
    const bool use_coarse = !in.faults.tile_box_test_too_tight && !in.faults.sample_outside_tile;
    std::vector<RowTotals> totals((std::size_t)coarse.tiles_y);
    std::unique_ptr<SaturatingCounts> sat;
    if (in.saturate) sat = std::make_unique<SaturatingCounts>(width, height);
    result.boundary_tile_mask.assign((std::size_t)grid.tiles_x * (std::size_t)grid.tiles_y, 0);
    parallel(coarse.tiles_y, [&](int cy) {
        const std::vector<int> &bin = bands[(std::size_t)cy];
        RowTotals &tot = totals[(std::size_t)cy];
        const int ty0 = cy * kCoarse, ty1 = std::min(grid.tiles_y, ty0 + kCoarse);
        const int band_rows = ty1 - ty0;
        const std::size_t nx = (std::size_t)grid.tiles_x;
        /* Per tile of the band (row r, column tx at r * nx + tx), for the
         * volume at hand: 0 untouched, 1 counted, 2 boundary; its sampled
         * count. Across volumes: the counts to add wholesale, and whether
         * any volume walked it. */
        const std::size_t n = nx * (std::size_t)band_rows;
        static thread_local BandScratch scratch;
        std::vector<uint8_t> &state = scratch.state, &count = scratch.count,
                             &wholesale = scratch.wholesale, &walked = scratch.walked;
        state.assign(n, 0);
        count.assign(n, 0);
        wholesale.assign(n, 0);
        walked.assign(n, 0);
        std::vector<std::size_t> &touched = scratch.touched;
        touched.clear();
        const std::size_t psv_per_row = (nx + kPsvLineTiles - 1) / kPsvLineTiles;
        std::vector<uint8_t> &psv_seen = scratch.psv_seen;
        psv_seen.assign(psv_per_row * (std::size_t)band_rows, 0);
        bool row_boundary[kCoarse] = {};
        const int band_y0 = grid.y0(ty0), band_y1 = grid.y1(ty1 - 1);
        CoverageRows coverage(band_y0, band_y1, width, scratch.coverage_diff, scratch.coverage_lo,
                              scratch.coverage_hi);
        std::vector<raster::Rasterizer::CoveredSpan> &spans = scratch.spans;
        auto touch = [&](std::size_t t) {
            if (state[t] == 0) {
                state[t] = 1;
                count[t] = 0;
                touched.push_back(t);
            }
        };
        /* The rows' data, and whether each was computed (bit 0) and its
         * segments' columns (bit 1): the flags cleared per volume, the data
         * (larger) written only where asked for. */
        std::vector<FineRow> &fine_rows = scratch.fine_rows;
        std::vector<uint8_t> &fine_known = scratch.fine_known;
        constexpr uint8_t kRowKnown = 1;
        for (std::size_t i = 0; i < bin.size();) {
            const int vol = vp.volume[(std::size_t)bin[i]];
            std::size_t j = i;
            while (j < bin.size() && vp.volume[(std::size_t)bin[j]] == vol) j++;
            const bool zfail = vp.zfail[(std::size_t)vol];
            /* Per piece of the volume and fine row: kept for stage 2. */
            if (fine_rows.size() < (j - i) * (std::size_t)kCoarse)
                fine_rows.resize((j - i) * (std::size_t)kCoarse);
            fine_known.assign((j - i) * (std::size_t)kCoarse, 0);
            /* The pieces stage 2 may walk (not those taken by coverage,
             * nor the receiver's in z-pass, which fail everywhere): on a
             * dense mesh in z-fail a tenth of the volume, scanned once per
             * boundary row. */
            std::vector<std::size_t> &walkable = scratch.walkable;
            walkable.clear();
            for (std::size_t k = i; k < j; k++) {
                const int q = bin[k];
                const raster::SetupTriangle &p = vp.pieces[(std::size_t)q];
                const raster::PieceExtent &e = vp.extents[(std::size_t)q];
                const bool receiver = vp.receiver[(std::size_t)q] != 0;
                const uint8_t open = vp.open[(std::size_t)q];
                const uint8_t delta = vp.delta[(std::size_t)q];
                const bool by_coverage = receiver && coverage_allowed &&
                                         vp.caps_by_coverage[(std::size_t)vol] != 0;
                if (!receiver || (zfail && !by_coverage)) walkable.push_back(k);
                FineRow *fine = &fine_rows[(k - i) * (std::size_t)kCoarse];
                uint8_t *known = &fine_known[(k - i) * (std::size_t)kCoarse];
                auto fine_row = [&](int r) -> const FineRow & {
                    FineRow &f = fine[r];
                    if (known[r] & kRowKnown) return f;
                    known[r] |= kRowKnown;
                    const int ty = ty0 + r;
                    f.reached = piece_columns_in_row(edges[(std::size_t)q], grid, grid.y0(ty),
                                                     grid.y1(ty), f.first, f.last, &f.extent);
                    return f;
                };
                /* ... and the columns its segments may meet there. */
                FineSegments segments[kCoarse];
                unsigned segments_known = 0;
                auto fine_segments = [&](int r) -> const FineSegments & {
                    FineSegments &f = segments[r];
                    if (segments_known >> r & 1) return f;
                    segments_known |= 1u << r;
                    f.open.n = 0;
                    f.cap.n = 0;
                    f.cap_whole = false;
                    const int ty = ty0 + r;
                    f.open_whole = (open & kOpenWhole) != 0;
                    if (open && !f.open_whole) {
                        f.open_whole = !f.open.add(open_lines, vp.open_first[(std::size_t)q],
                                                   vp.open_first[(std::size_t)q + 1], grid,
                                                   grid.y0(ty), grid.y1(ty));
                    }
                    if (receiver) {
                        f.cap_whole = !f.cap.add(cap_lines, vp.cap_first[(std::size_t)q],
                                                 vp.cap_first[(std::size_t)q + 1], grid,
                                                 grid.y0(ty), grid.y1(ty));
                    }
                    return f;
                };
                /* One fine tile: the seed's stage 1 test. */
                auto classify_fine = [&](int r, int tx, const FineRow &f, const FineSegments &sg) {
                    const std::size_t t = (std::size_t)r * nx + (std::size_t)tx;
                    if (state[t] == 2) return;
                    TileSide side = TileSide::behind;
                    if (!receiver) {
                        side = classify_in_row(p, e, grid, tx, ty0 + r, f.extent, in.faults);
                        if (side == TileSide::misses) return;
                    } else if (sg.cap_whole || sg.cap.meet(tx)) {
                        /* The receiver's own triangle fails its test at every
                         * pixel it covers: "behind" in every tile, except
                         * where an edge at which the receiver's triangles do
                         * not close meets the tile (the other pieces on it may
                         * count otherwise). */
                        side = TileSide::crosses;
                    }
                    touch(t);
                    if (side == TileSide::crosses) {
                        state[t] = 2;
                        return;
                    }
                    if ((side == TileSide::behind) != zfail) return; /* does not count */
                    if (in.saturate || sg.open_whole || sg.open.meet(tx)) {
                        state[t] = 2;
                        return;
                    }
                    int sx = 0, sy = 0;
                    tile_sample(grid, tx, ty0 + r, in.faults, sx, sy);
                    if (covers_pixel(p, sx, sy)) count[t] = (uint8_t)(count[t] + delta);
                };
                if (by_coverage) {
                    /* Its count is its delta wherever it covers a pixel
                     * centre (its test fails at each): the band's rows
                     * take it by coverage, and stage 2 never walks it. The
                     * edges where the receiver's pieces meet the others
                     * are open edges of what is left of the volume: the
                     * tiles they meet are boundary tiles. */
                    spans.clear();
                    raster::Rasterizer::covered_spans(p, {band_y0, band_y1}, spans);
                    for (raster::Rasterizer::CoveredSpan &sp : spans) {
                        if (in.faults.cap_spans_short && sp.x_end - sp.x_begin > 1) sp.x_end--;
                        coverage.add(sp, delta);
                    }
                    tot.coverage_rows += spans.size();
                    if (vp.cap_first[(std::size_t)q] == vp.cap_first[(std::size_t)q + 1] ||
                        in.faults.cap_edges_not_boundary) {
                        continue;
                    }
                    for (int r = 0; r < band_rows; r++) {
                        const FineRow &f = fine_row(r);
                        if (!f.reached) continue;
                        const FineSegments &sg = fine_segments(r);
                        for (int tx = f.first; tx <= f.last; tx++) {
                            if (!sg.cap_whole && !sg.cap.meet(tx)) continue;
                            const std::size_t t = (std::size_t)r * nx + (std::size_t)tx;
                            touch(t);
                            state[t] = 2;
                        }
                    }
                    continue;
                }
                int cfirst = 0, clast = 0;
                RowExtent cextent{};
                if (!piece_columns_in_row(edges[(std::size_t)q], coarse, coarse.y0(cy),
                                          coarse.y1(cy), cfirst, clast, &cextent)) {
                    continue;
                }
                /* The coarse tiles an open edge (or the receiver's unclosed
                 * edge) may meet are left to the fine tiles. */
                bool coarse_whole = (open & kOpenWhole) != 0;
                SegmentColumns copen, ccap;
                if (use_coarse && open && !coarse_whole) {
                    coarse_whole = !copen.add(open_lines, vp.open_first[(std::size_t)q],
                                              vp.open_first[(std::size_t)q + 1], coarse,
                                              coarse.y0(cy), coarse.y1(cy));
                }
                if (use_coarse && receiver && !coarse_whole) {
                    coarse_whole = !ccap.add(cap_lines, vp.cap_first[(std::size_t)q],
                                             vp.cap_first[(std::size_t)q + 1], coarse,
                                             coarse.y0(cy), coarse.y1(cy));
                }
                for (int cx = cfirst; cx <= clast; cx++) {
                    const int tx_lo = cx * kCoarse,
                              tx_hi = std::min(grid.tiles_x - 1, tx_lo + kCoarse - 1);
                    if (use_coarse && !coarse_whole && !copen.meet(cx) && !ccap.meet(cx)) {
                        /* Seed 004's test one level up: a piece in front of
                         * or behind the coarse tile's box is so for each of
                         * its tiles (their boxes lie inside it). */
                        const TileSide side = receiver ? TileSide::behind
                                                       : classify_in_row(p, e, coarse, cx, cy,
                                                                         cextent, in.faults, false);
                        if (side == TileSide::misses) continue;
                        if (side != TileSide::crosses &&
                            ((side == TileSide::behind) != zfail || !in.saturate)) {
                            if ((side == TileSide::behind) != zfail) continue; /* no count */
                            /* It counts where it covers a tile's sample (the
                             * tile's first pixel): none when one edge leaves
                             * every sample of the block outside. */
                            if (!covers_any_sample(p, grid, tx_lo, tx_hi, ty0, ty1 - 1)) continue;
                            for (int r = 0; r < band_rows; r++) {
                                for (int tx = tx_lo; tx <= tx_hi; tx++) {
                                    const std::size_t t = (std::size_t)r * nx + (std::size_t)tx;
                                    if (state[t] == 2 ||
                                        !covers_pixel(p, grid.x0(tx), grid.y0(ty0 + r))) {
                                        continue;
                                    }
                                    touch(t);
                                    count[t] = (uint8_t)(count[t] + delta);
                                }
                            }
                            continue;
                        }
                    }
                    for (int r = 0; r < band_rows; r++) {
                        const FineRow &f = fine_row(r);
                        if (!f.reached) continue;
                        const FineSegments &sg = fine_segments(r);
                        for (int tx = std::max(f.first, tx_lo); tx <= std::min(f.last, tx_hi);
                             tx++) {
                            classify_fine(r, tx, f, sg);
                        }
                    }
                }
            }
            for (std::size_t t : touched) {
                const std::size_t line = (t / nx) * psv_per_row + (t % nx) / kPsvLineTiles;
                tot.psv_lines += psv_seen[line] == 0;
                psv_seen[line] = 1;
            }
            std::fill(psv_seen.begin(), psv_seen.end(), 0);
            for (std::size_t t : touched) {
                tot.pairs++;
                if (state[t] == 2) {
                    tot.boundary_pairs++;
                    walked[t] = 1;
                    row_boundary[t / nx] = true;
                } else {
                    wholesale[t] = (uint8_t)(wholesale[t] + count[t]);
                }
            }
            const raster::StencilMode mode = zfail ? raster::StencilMode::zfail
                                                   : raster::StencilMode::zpass;
            for (int r = 0; r < band_rows; r++) {
                if (!row_boundary[r]) continue;
                row_boundary[r] = false;
                const int ty = ty0 + r, Y0 = grid.y0(ty), Y1 = grid.y1(ty);
                const uint8_t *row_state = state.data() + (std::size_t)r * nx;
                for (const std::size_t k : walkable) {
                    const int q = bin[k];
                    const raster::SetupTriangle &p = vp.pieces[(std::size_t)q];
                    if (p.x_first > p.x_last || p.y_first > p.y_last || p.y_last < Y0 ||
                        p.y_first >= Y1) {
                        continue;
                    }
                    const bool receiver = vp.receiver[(std::size_t)q] != 0;
                    const std::size_t fr = (k - i) * (std::size_t)kCoarse + (std::size_t)r;
                    FineRow &f = fine_rows[fr];
                    if (!(fine_known[fr] & kRowKnown)) {
                        fine_known[fr] |= kRowKnown;
                        f.reached = piece_columns_in_row(edges[(std::size_t)q], grid, Y0, Y1,
                                                         f.first, f.last, &f.extent);
                    }
                    if (!f.reached) continue;
                    const RowExtent &row_extent = f.extent;
                    int first = f.first, last = f.last;
                    first = std::max(first, p.x_first / grid.side);
                    last = std::min(last, p.x_last / grid.side);
                    /* In a boundary tile, a piece that neither crosses the box
                     * nor counts in the volume's mode adds nothing at any of
                     * its pixels: only the others are walked. */
                    auto walks = [&](int tx) {
                        if (row_state[tx] != 2) return false;
                        if (receiver) return true;
                        const TileSide side = classify_in_row(p, vp.extents[(std::size_t)q], grid,
                                                              tx, ty, row_extent, in.faults, false);
                        if (side == TileSide::misses) return false;
                        return side == TileSide::crosses || (side == TileSide::behind) == zfail;
                    };
                    /* Each run of consecutive tiles to walk in one walk. */
                    for (int tx = first; tx <= last; tx++) {
                        if (!walks(tx)) continue;
                        int run_end = tx;
                        while (run_end < last && walks(run_end + 1)) run_end++;
                        raster::SetupTriangle clamped = p;
                        clamped.x_first = std::max(p.x_first, grid.x0(tx));
                        clamped.x_last = std::min(p.x_last, grid.x1(run_end) - 1);
                        if (sat) {
                            rast.walk_stencil_saturating(clamped, in.target->depth.data(),
                                                         sat->count_for(mode, p.front), width,
                                                         {Y0, Y1}, mode, no_depth_bounds(),
                                                         tot.walked);
                        } else {
                            rast.walk_stencil(clamped, in.target->depth.data(),
                                              result.stencil.data(), width, height, {Y0, Y1}, mode,
                                              tot.walked);
                        }
                        tx = run_end + 1; /* run_end + 1 does not walk (or is past LAST) */
                    }
                }
            }
            for (std::size_t t : touched) state[t] = 0;
            touched.clear();
            i = j;
        }
        for (int r = 0; r < band_rows; r++) {
            const int ty = ty0 + r, Y0 = grid.y0(ty), Y1 = grid.y1(ty);
            for (int tx = 0; tx < grid.tiles_x; tx++) {
                const std::size_t t = (std::size_t)r * nx + (std::size_t)tx;
                tot.boundary_tiles += walked[t];
                result.boundary_tile_mask[(std::size_t)ty * nx + (std::size_t)tx] = walked[t];
                const uint8_t add = wholesale[t];
                if (add == 0) continue;
                const int X0 = grid.x0(tx), X1 = grid.x1(tx);
                for (int y = Y0; y < Y1; y++) {
                    uint8_t *row = result.stencil.data() + (std::size_t)y * (std::size_t)width;
                    for (int x = X0; x < X1; x++) row[x] = (uint8_t)(row[x] + add);
                }
                tot.wholesale_pixels += (uint64_t)(X1 - X0) * (uint64_t)(Y1 - Y0);
            }
        }
        tot.coverage_pixels += coverage.resolve(result.stencil.data());
    });
    if (sat) sat->resolve(result.stencil);
    for (const RowTotals &t : totals) {
        raster::Rasterizer::add_stencil_counts(t.walked, result.counters);
        /* A tile updated wholesale reads and writes its stencil once. */
        result.counters.stencil_bytes_read += t.wholesale_pixels;
        result.counters.stencil_bytes_written += t.wholesale_pixels;
        result.tile_volume_pairs += t.pairs;
        result.boundary_pairs += t.boundary_pairs;
        result.boundary_tiles += t.boundary_tiles;
        result.psv_lines += t.psv_lines;
        result.coverage_rows += t.coverage_rows;
        result.coverage_pixels += t.coverage_pixels;
        /* The running sum reads and writes each pixel's stencil once. */
        result.counters.stencil_bytes_read += t.coverage_pixels;
        result.counters.stencil_bytes_written += t.coverage_pixels;
    }
    result.tiles = (uint64_t)grid.tiles_x * (uint64_t)grid.tiles_y;
    result.ran = StencilMethod::hierarchical;
}

} // namespace sv::render
