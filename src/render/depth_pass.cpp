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

namespace {

/* A run of one surface's vertices: the unit of the per-vertex work spread
 * over threads (the demo's terrain alone holds most of a frame's
 * vertices, so one task per surface left it on one thread). */
struct VertexRun {
    int surface, first, last;
};
constexpr int kVertexRun = 8192;

std::vector<VertexRun> vertex_runs(const Scene &scene) {
    std::vector<VertexRun> runs;
    for (int si = 0; si < (int)scene.surfaces.size(); si++) {
        const int n = scene.surfaces[(std::size_t)si].prepared.num_vertices();
        for (int v = 0; v < n; v += kVertexRun)
            runs.push_back({si, v, std::min(n, v + kVertexRun)});
    }
    return runs;
}

} // namespace

ClipVertices receivers_to_clip(const Scene &scene, const Mat4d &view_proj) {
    const int num_surfaces = (int)scene.surfaces.size();
    ClipVertices clip((std::size_t)num_surfaces);
    for (int si = 0; si < num_surfaces; si++) {
        clip[(std::size_t)si].resize(
            (std::size_t)scene.surfaces[(std::size_t)si].prepared.num_vertices());
    }
    const std::vector<VertexRun> runs = vertex_runs(scene);
    parallel((int)runs.size(), [&](int r) {
        const VertexRun &run = runs[(std::size_t)r];
        const PreparedSurface &p = scene.surfaces[(std::size_t)run.surface].prepared;
        for (int v = run.first; v < run.last; v++) {
            const Vec3d q = vertex(p, v);
            clip[(std::size_t)run.surface][(std::size_t)v] = to_clip(view_proj, q.x, q.y, q.z, 1.0);
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
    for (int si = 0; si < num_surfaces; si++) {
        window[(std::size_t)si].resize(clip[(std::size_t)si].size());
    }
    const std::vector<VertexRun> runs = vertex_runs(scene);
    parallel((int)runs.size(), [&](int r) {
        const VertexRun &run = runs[(std::size_t)r];
        const auto &cv = clip[(std::size_t)run.surface];
        auto &wv = window[(std::size_t)run.surface];
        for (int v = run.first; v < run.last; v++) {
            wv[(std::size_t)v] = raster::window_vertex(cv[(std::size_t)v], width, height);
        }
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
        bt.bin_chunk((std::size_t)c, height);
    });
    for (const auto &c : cc) result.counters.add(c);
    const int num_bands = band_count(height);
    std::vector<raster::RowCounts> rc((std::size_t)num_bands);
    parallel(num_bands, [&](int b) {
        const raster::RowBand band = band_rows(b, height);
        bt.for_each_in_band(b, [&](std::size_t, const raster::SetupTriangle &t) {
            rast.walk_depth(t, target, band, rc[(std::size_t)b]);
        });
    });
    for (const auto &r : rc) raster::Rasterizer::add_depth_counts(r, result.counters);
    result.ticks = ticks() - k0;
    result.seconds = now_seconds() - t0;
    return result;
}

} // namespace sv::render
