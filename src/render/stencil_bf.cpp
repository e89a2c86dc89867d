/*
 * The brute-force stencil method ("bf", the reference of every other):
 * the light's double-length vertex buffers through the paper's vertex
 * program, every drawn volume triangle set up (in chunks, in parallel,
 * each chunk binned to screen bands by its thread), and each band's rows
 * walked per pixel against the depth, in submission order.
 *
 * Copyright (C) 2026 the shadowvol authors. LGPL-2.1-or-later.
 */
#include <algorithm>
#include <memory>

#include "frame_math.h"
#include "pass_bins.h"
#include "stencil_pass.h"

namespace sv::render {

using namespace detail;

void detail::brute_force_walk(const StencilPassInputs &in, const BinnedTriangles &bt,
                              StencilPassResult &result) {
    const raster::Rasterizer &rast = *in.rast;
    const int width = in.target->width, height = in.target->height;
    const int num_bands = band_count(height);
    std::vector<raster::RowCounts> rc((std::size_t)num_bands);
    std::unique_ptr<SaturatingCounts> sat;
    if (in.saturate) sat = std::make_unique<SaturatingCounts>(width, height);
    parallel(num_bands, [&](int b) {
        const raster::RowBand band = band_rows(b, height);
        bt.for_each_in_band(b, [&](std::size_t c, const raster::SetupTriangle &t) {
            if (sat) {
                rast.walk_stencil_saturating(t, in.target->depth.data(),
                                             sat->count_for(bt.chunk_mode[c], t.front), width, band,
                                             bt.chunk_mode[c], no_depth_bounds(),
                                             rc[(std::size_t)b]);
            } else {
                rast.walk_stencil(t, in.target->depth.data(), result.stencil.data(), width, height,
                                  band, bt.chunk_mode[c], rc[(std::size_t)b]);
            }
        });
    });
    if (sat) sat->resolve(result.stencil);
    for (const auto &r : rc) raster::Rasterizer::add_stencil_counts(r, result.counters);
}

StencilPassResult stencil_pass_brute_force(const StencilPassInputs &in) {
    StencilPassResult result;
    const std::vector<Volume> &volumes = *in.volumes;
    const raster::Rasterizer &rast = *in.rast;
    const int width = in.target->width, height = in.target->height;
    result.stencil.assign((std::size_t)width * height, 0); /* the clear: not the pass's time */
    const double t0 = now_seconds();
    const uint64_t k0 = ticks();
    const std::vector<VolumeChunk> chunks = volume_chunks(volumes);
    const std::vector<ShadowVertexBuffer> sv_clip = shadow_vertex_buffers(in);
    BinnedTriangles bt;
    bt.clear_chunks(chunks.size());
    std::vector<raster::PassCounters> cc(chunks.size());
    parallel((int)chunks.size(), [&](int c) {
        const VolumeChunk &ch = chunks[(std::size_t)c];
        const Volume &vol = volumes[(std::size_t)ch.volume];
        const auto &cv = sv_clip[(std::size_t)ch.volume];
        /* A piece per triangle, mostly: no copies as the chunk grows. */
        bt.chunks[(std::size_t)c].reserve((std::size_t)(ch.last - ch.first));
        for (int t = ch.first; t < ch.last; t++) {
            const raster::ClipVertex v[3] = {cv[(std::size_t)vol.indices[3 * (std::size_t)t]],
                                             cv[(std::size_t)vol.indices[3 * (std::size_t)t + 1]],
                                             cv[(std::size_t)vol.indices[3 * (std::size_t)t + 2]]};
            rast.setup(v, width, height, 0, cc[(std::size_t)c], bt.chunks[(std::size_t)c]);
        }
        bt.bin_chunk((std::size_t)c, height);
    });
    for (std::size_t c = 0; c < chunks.size(); c++) {
        result.counters.add(cc[c]);
        bt.chunk_mode.push_back(volumes[(std::size_t)chunks[c].volume].zfail
                                    ? raster::StencilMode::zfail
                                    : raster::StencilMode::zpass);
    }
    brute_force_walk(in, bt, result);
    result.ran = StencilMethod::brute_force;
    result.ticks = ticks() - k0;
    result.seconds = now_seconds() - t0;
    return result;
}

} // namespace sv::render
