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

/* Triangles set up in chunks (in parallel), then binned to bands in
 * submission order, so every band walks its triangles in that order. */
struct BinnedTriangles {
    std::vector<std::vector<raster::SetupTriangle>> chunks;
    std::vector<raster::StencilMode> chunk_mode;
    std::vector<std::vector<std::pair<int, int>>> bands; /* (chunk, piece) */
    raster::PassCounters counters;                       /* triangle counts */
    /* Empties every chunk, keeping its memory for the next set-up. */
    void clear_chunks(std::size_t count) {
        chunks.resize(count);
        for (auto &c : chunks) c.clear();
    }
    void bin(int height) {
        /* The bands' lists are emptied, not freed: a frame's bins are as
         * large as the last one's. */
        bands.resize((std::size_t)band_count(height));
        for (auto &b : bands) b.clear();
        for (std::size_t c = 0; c < chunks.size(); c++) {
            for (std::size_t i = 0; i < chunks[c].size(); i++) {
                const raster::SetupTriangle &t = chunks[c][i];
                for (int b = t.y_first / kBandRows; b <= t.y_last / kBandRows; b++) {
                    bands[(std::size_t)b].push_back({(int)c, (int)i});
                }
            }
        }
    }
};

inline raster::RowBand band_rows(int b, int height) {
    return {b * kBandRows, std::min(height, (b + 1) * kBandRows)};
}

} // namespace sv::render::detail

#endif
