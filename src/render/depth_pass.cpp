/*
 * The depth pass of depth_pass.h.
 *
 * Copyright (C) 2026 the shadowvol authors. LGPL-2.1-or-later.
 */
#include "depth_pass.h"

#include <algorithm>

#include "frame.h"
#include "frame_math.h"
#include "pass_bins.h"

namespace sv::render {

using namespace detail;

ClipVertices receivers_to_clip(const Scene &scene, const Mat4d &view_proj) {
    const int num_surfaces = (int)scene.surfaces.size();
    ClipVertices clip((std::size_t)num_surfaces);
    parallel(num_surfaces, [&](int si) {
        const PreparedSurface &p = scene.surfaces[(std::size_t)si].prepared;
        clip[(std::size_t)si].resize((std::size_t)p.num_vertices());
        for (int v = 0; v < p.num_vertices(); v++) {
            const Vec3d q = vertex(p, v);
            clip[(std::size_t)si][(std::size_t)v] = to_clip(view_proj, q.x, q.y, q.z, 1.0);
        }
    });
    return clip;
}

DepthPassResult depth_pass(const Scene &scene, const ClipVertices &clip,
                           const std::vector<int32_t> &surface_first_id,
                           const raster::Rasterizer &rast, raster::Target &target,
                           BinnedTriangles &bt, WindowVertices &window) {
    DepthPassResult result;
    const double t0 = now_seconds();
    const uint64_t k0 = ticks();
    const int width = target.width, height = target.height;
    const int num_surfaces = (int)scene.surfaces.size();
    struct Chunk {
        int surface, first, last;
    };
    std::vector<Chunk> chunks;
    for (int si = 0; si < num_surfaces; si++) {
        const int n = scene.surfaces[(std::size_t)si].prepared.num_triangles();
        for (int t = 0; t < n; t += kSetupChunk)
            chunks.push_back({si, t, std::min(n, t + kSetupChunk)});
    }
    /* Each vertex snapped once (a corner is shared by about six
     * triangles): set-up then clips and snaps only the triangles that
     * cross a plane of the view volume. */
    window.resize((std::size_t)num_surfaces);
    parallel(num_surfaces, [&](int si) {
        const auto &cv = clip[(std::size_t)si];
        auto &wv = window[(std::size_t)si];
        wv.resize(cv.size());
        for (std::size_t v = 0; v < cv.size(); v++)
            wv[v] = raster::window_vertex(cv[v], width, height);
    });
    bt.clear_chunks(chunks.size());
    std::vector<raster::PassCounters> cc(chunks.size());
    parallel((int)chunks.size(), [&](int c) {
        const Chunk &ch = chunks[(std::size_t)c];
        const PreparedSurface &p = scene.surfaces[(std::size_t)ch.surface].prepared;
        const auto &cv = clip[(std::size_t)ch.surface];
        const auto &wv = window[(std::size_t)ch.surface];
        for (int t = ch.first; t < ch.last; t++) {
            const int *i = &p.indices[3 * (std::size_t)t];
            const raster::ClipVertex v[3] = {cv[(std::size_t)i[0]], cv[(std::size_t)i[1]],
                                             cv[(std::size_t)i[2]]};
            const raster::WindowVertex w[3] = {wv[(std::size_t)i[0]], wv[(std::size_t)i[1]],
                                               wv[(std::size_t)i[2]]};
            rast.setup_shared(v, w, width, height, surface_first_id[(std::size_t)ch.surface] + t,
                              cc[(std::size_t)c], bt.chunks[(std::size_t)c]);
        }
    });
    for (const auto &c : cc) result.counters.add(c);
    bt.bin(height);
    const int num_bands = band_count(height);
    std::vector<raster::RowCounts> rc((std::size_t)num_bands);
    parallel(num_bands, [&](int b) {
        const raster::RowBand band = band_rows(b, height);
        for (const auto &[c, i] : bt.bands[(std::size_t)b]) {
            rast.walk_depth(bt.chunks[(std::size_t)c][(std::size_t)i], target, band,
                            rc[(std::size_t)b]);
        }
    });
    for (const auto &r : rc) raster::Rasterizer::add_depth_counts(r, result.counters);
    result.ticks = ticks() - k0;
    result.seconds = now_seconds() - t0;
    return result;
}

} // namespace sv::render
