/*
 * How the depth and stencil passes share the frame between threads
 * (internal to src/render): triangles are set up in chunks of submission
 * order (in parallel), binned to screen bands of kBandRows rows in that
 * order, and each band walked by one thread, so every pixel sees its
 * triangles in submission order at every thread count.
 *
 * Copyright (C) 2026 the shadowvol authors. LGPL-2.1-or-later.
 */
#ifndef SV_RENDER_PASS_BINS_H
#define SV_RENDER_PASS_BINS_H

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>
#include <tbb/partitioner.h>

#include <algorithm>
#include <utility>
#include <vector>

#include "rasterizer.h"

namespace sv::render::detail {

constexpr int kBandRows = 32;     /* rows per screen band */
constexpr int kSetupChunk = 4096; /* triangles per set-up task */

inline int band_count(int height) { return (height + kBandRows - 1) / kBandRows; }

/* Runs BODY(i) for i in [0, n) on the current arena's threads. */
template <class Body> void parallel(int n, Body &&body) {
    tbb::parallel_for(
        tbb::blocked_range<int>(0, n, 1),
        [&](const tbb::blocked_range<int> &r) {
            for (int i = r.begin(); i != r.end(); i++) body(i);
        },
        tbb::simple_partitioner());
}

/* Triangles set up in chunks (in parallel), each chunk binned to bands by
 * the thread that set it up; a band walks the chunks in order and each
 * chunk's pieces in order, so every band sees its triangles in submission
 * order (and no thread bins the whole frame alone). */
struct BinnedTriangles {
    std::vector<std::vector<raster::SetupTriangle>> chunks;
    std::vector<raster::StencilMode> chunk_mode;
    /* chunk_bands[c][b]: chunk c's pieces that reach band b, in order. */
    std::vector<std::vector<std::vector<int>>> chunk_bands;
    raster::PassCounters counters; /* triangle counts */
    /* COUNT empty chunks, keeping their memory (and their bins') for the
     * next set-up: a frame's are as large as the last one's. */
    void clear_chunks(std::size_t count) {
        chunks.resize(count);
        for (auto &c : chunks) c.clear();
        chunk_bands.resize(count);
    }
    /* Bins chunk C's pieces (after its set-up, on the same thread). */
    void bin_chunk(std::size_t c, int height) {
        std::vector<std::vector<int>> &bins = chunk_bands[c];
        bins.resize((std::size_t)band_count(height));
        for (auto &b : bins) b.clear();
        const std::vector<raster::SetupTriangle> &pieces = chunks[c];
        for (std::size_t i = 0; i < pieces.size(); i++) {
            const raster::SetupTriangle &t = pieces[i];
            for (int b = t.y_first / kBandRows; b <= t.y_last / kBandRows; b++) {
                bins[(std::size_t)b].push_back((int)i);
            }
        }
    }
    /* F(chunk, piece) for band B's pieces in submission order. */
    template <class F> void for_each_in_band(int b, F &&f) const {
        for (std::size_t c = 0; c < chunks.size(); c++) {
            for (const int i : chunk_bands[c][(std::size_t)b]) f(c, chunks[c][(std::size_t)i]);
        }
    }
};

inline raster::RowBand band_rows(int b, int height) {
    return {b * kBandRows, std::min(height, (b + 1) * kBandRows)};
}

} // namespace sv::render::detail

#endif
