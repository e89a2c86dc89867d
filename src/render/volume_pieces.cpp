/*
 * The volumes' pieces for the classifying stencil methods
 * (volume_pieces.h): set-up in chunks of triangles in parallel as the
 * brute-force method does (set_up_pieces), then per volume its open edges
 * and the receiver's caps (finish_volume_pieces).
 *
 * Copyright (C) 2026 the shadowvol authors. LGPL-2.1-or-later.
 */
#include "volume_pieces.h"

#include <algorithm>
#include <cmath>

#include "frame_math.h"
#include "open_edges.h"
#include "pass_bins.h"
#include "surface_triangles.h"

namespace sv::render::detail {
namespace {

/* Signed distance of V to clip plane P (>= 0 inside), as the rasteriser's. */
inline double plane_distance(int p, const raster::ClipVertex &v) {
    switch (p) {
    case 0: return v.z + v.w;
    case 1: return v.x + v.w;
    case 2: return v.w - v.x;
    case 3: return v.y + v.w;
    default: return v.w - v.y;
    }
}

/* The part of segment A-B inside the view, in window pixels: 1, or 0 when
 * none is, or -1 when it cannot be projected (a point at w = 0 left). */
int visible_segment(const raster::ClipVertex &a, const raster::ClipVertex &b, int width, int height,
                    VolumePieces::Segment &out, int first_plane = 0) {
    double t0 = 0, t1 = 1;
    for (int p = first_plane; p < 5; p++) {
        const double da = plane_distance(p, a), db = plane_distance(p, b);
        if (da < 0 && db < 0) return 0;
        if (da < 0) t0 = std::max(t0, da / (da - db));
        if (db < 0) t1 = std::min(t1, da / (da - db));
    }
    if (t0 > t1) return 0;
    auto window = [&](double t, double &x, double &y) {
        const double cx = a.x + t * (b.x - a.x), cy = a.y + t * (b.y - a.y),
                     cw = a.w + t * (b.w - a.w);
        if (!(cw > 0)) return false;
        x = (cx / cw + 1) * 0.5 * width;
        y = (1 - cy / cw) * 0.5 * height;
        return std::isfinite(x) && std::isfinite(y);
    };
    return window(t0, out.x0, out.y0) && window(t1, out.x1, out.y1) ? 1 : -1;
}

} // namespace

PieceSetup set_up_pieces(const StencilPassInputs &in) {
    const std::vector<Volume> &volumes = *in.volumes;
    const raster::Rasterizer &rast = *in.rast;
    const int width = in.target->width, height = in.target->height;
    PieceSetup ps;
    ps.chunks = volume_chunks(volumes);
    ps.sv_clip = shadow_vertex_buffers(in);
    const std::vector<VolumeChunk> &chunks = ps.chunks;
    const std::vector<ShadowVertexBuffer> &sv_clip = ps.sv_clip;
    std::vector<PieceSetup::ChunkOut> &co = ps.chunk_out;
    co.resize(chunks.size());
    std::vector<std::vector<uint8_t>> &degenerate = ps.degenerate, &near_cut = ps.near_cut;
    degenerate.resize(volumes.size());
    near_cut.resize(volumes.size());
    for (std::size_t vi = 0; vi < volumes.size(); vi++) {
        degenerate[vi].assign((std::size_t)volumes[vi].drawn_indices() / 3, 0);
        near_cut[vi].assign((std::size_t)volumes[vi].drawn_indices() / 3, 0);
    }
    parallel((int)chunks.size(), [&](int c) {
        const VolumeChunk &ch = chunks[(std::size_t)c];
        const Volume &vol = volumes[(std::size_t)ch.volume];
        const auto &cv = sv_clip[(std::size_t)ch.volume];
        PieceSetup::ChunkOut &o = co[(std::size_t)c];
        /* A piece per triangle, mostly (a clipped one may give more): no
         * copies as the vectors grow. */
        o.pieces.reserve((std::size_t)(ch.last - ch.first));
        o.extents.reserve((std::size_t)(ch.last - ch.first));
        o.triangle.reserve((std::size_t)(ch.last - ch.first));
        for (int t = ch.first; t < ch.last; t++) {
            const raster::ClipVertex v[3] = {cv[(std::size_t)vol.indices[3 * (std::size_t)t]],
                                             cv[(std::size_t)vol.indices[3 * (std::size_t)t + 1]],
                                             cv[(std::size_t)vol.indices[3 * (std::size_t)t + 2]]};
            const uint64_t degenerate_before = o.counters.triangles_degenerate;
            rast.setup(v, width, height, 0, o.counters, o.pieces, &o.extents);
            o.triangle.resize(o.pieces.size(), t);
            degenerate[(std::size_t)ch.volume][(std::size_t)t] = o.counters.triangles_degenerate !=
                                                                 degenerate_before;
            /* Cut by the near plane (or wholly behind it): the cut edge is
             * an edge of no other triangle. */
            near_cut[(std::size_t)ch.volume][(std::size_t)t] = v[0].z + v[0].w < 0 ||
                                                               v[1].z + v[1].w < 0 ||
                                                               v[2].z + v[2].w < 0;
        }
    });
    return ps;
}

VolumePieces finish_volume_pieces(const StencilPassInputs &in, PieceSetup &&ps) {
    const Scene &scene = *in.scene;
    const std::vector<Volume> &volumes = *in.volumes;
    const int width = in.target->width, height = in.target->height;
    const Vec4 L = in.light;
    const std::vector<VolumeChunk> &chunks = ps.chunks;
    const std::vector<ShadowVertexBuffer> &sv_clip = ps.sv_clip;
    const std::vector<PieceSetup::ChunkOut> &co = ps.chunk_out;
    const std::vector<std::vector<uint8_t>> &degenerate = ps.degenerate, &near_cut = ps.near_cut;
    std::vector<std::vector<uint8_t>> open_tri(volumes.size());
    parallel((int)volumes.size(), [&](int vi) {
        const Volume &vol = volumes[(std::size_t)vi];
        open_tri[(std::size_t)vi] = triangles_on_open_edges(vol.indices.data(),
                                                            vol.drawn_indices() / 3,
                                                            degenerate[(std::size_t)vi], L.w == 0);
    });
    /* Per volume: which triangles are the receiver's own, and the edges
     * where those do not close among themselves. */
    std::vector<std::vector<uint8_t>> on_receiver(volumes.size()), cap_open(volumes.size());
    /* The receivers' triangles grouped (surface_triangles.h): the
     * caller's, kept from light to light and frame to frame, else this
     * pass's own. Fetched here, one thread, before the volumes' tasks
     * read them. */
    SurfaceTrianglesCache own_groupings;
    SurfaceTrianglesCache &groupings = in.surface_triangles ? *in.surface_triangles : own_groupings;
    groupings.fit((int)scene.surfaces.size());
    std::vector<const SurfaceTriangles *> grouped(volumes.size(), nullptr);
    for (std::size_t vi = 0; vi < volumes.size(); vi++) {
        const Volume &vol = volumes[vi];
        const int n = vol.drawn_indices() / 3;
        bool any = false; /* a triangle of the surface's vertices alone */
        for (int t = 0; t < n && !any; t++) {
            const int *i = &vol.indices[3 * (std::size_t)t];
            any = ((i[0] | i[1] | i[2]) & 1) == 0;
        }
        if (!any) continue;
        grouped[vi] = &groupings.get(vol.surface,
                                     scene.surfaces[(std::size_t)vol.surface].prepared);
    }
    parallel((int)volumes.size(), [&](int vi) {
        const Volume &vol = volumes[(std::size_t)vi];
        const int n = vol.drawn_indices() / 3;
        auto &mine = on_receiver[(std::size_t)vi];
        mine.assign((std::size_t)n, 0);
        const SurfaceTriangles *surface_triangles = grouped[(std::size_t)vi];
        if (!surface_triangles) return;
        std::vector<uint8_t> skip((std::size_t)n, 1);
        for (int t = 0; t < n; t++) {
            const int *i = &vol.indices[3 * (std::size_t)t];
            if (((i[0] | i[1] | i[2]) & 1) != 0) continue;
            const bool found = surface_triangles->contains(i[0] / 2, i[1] / 2, i[2] / 2);
            mine[(std::size_t)t] = found;
            skip[(std::size_t)t] = !found || degenerate[(std::size_t)vi][(std::size_t)t];
        }
        cap_open[(std::size_t)vi] = triangles_on_open_edges(vol.indices.data(), n, skip, false);
    });
    VolumePieces vp;
    vp.closed.assign(volumes.size(), 1);
    vp.zfail.resize(volumes.size());
    vp.caps_by_coverage.assign(volumes.size(), 0);
    vp.first_piece.assign(volumes.size() + 1, 0);
    for (std::size_t vi = 0; vi < volumes.size(); vi++) {
        vp.zfail[vi] = volumes[vi].zfail;
        vp.caps_by_coverage[vi] = volumes[vi].zfail ? 1 : 0;
        const auto &o = open_tri[vi];
        const auto &nc = near_cut[vi];
        for (std::size_t t = 0; t < o.size(); t++) {
            if ((o[t] || nc[t]) && !degenerate[vi][t]) vp.closed[vi] = 0;
        }
    }
    std::size_t total = 0;
    for (const PieceSetup::ChunkOut &o : co) total += o.pieces.size();
    vp.pieces.reserve(total);
    vp.extents.reserve(total);
    vp.volume.reserve(total);
    vp.delta.reserve(total);
    vp.open.reserve(total);
    vp.receiver.reserve(total);
    vp.open_first.reserve(total + 1);
    vp.cap_first.reserve(total + 1);
    for (std::size_t c = 0; c < chunks.size(); c++) {
        const int vi = chunks[c].volume;
        const PieceSetup::ChunkOut &o = co[c];
        vp.counters.add(o.counters);
        const bool zfail = volumes[(std::size_t)vi].zfail;
        for (std::size_t i = 0; i < o.pieces.size(); i++) {
            const std::size_t t = (std::size_t)o.triangle[i];
            vp.pieces.push_back(o.pieces[i]);
            vp.extents.push_back(o.extents[i]);
            vp.volume.push_back(vi);
            /* z-pass: front +1, back -1; z-fail: back +1, front -1. */
            vp.delta.push_back((!zfail == o.pieces[i].front) ? 1 : 255);
            const uint8_t edges = open_tri[(std::size_t)vi][t];
            const bool cut = near_cut[(std::size_t)vi][t] != 0;
            bool whole = false;
            const std::size_t first_segment = vp.open_segments.size();
            const int *ix = &volumes[(std::size_t)vi].indices[3 * t];
            const auto &cv = sv_clip[(std::size_t)vi];
            for (int k = 0; k < 3 && edges && !whole; k++) {
                if (!(edges >> k & 1)) continue;
                VolumePieces::Segment seg{};
                const int seen = visible_segment(cv[(std::size_t)ix[k]],
                                                 cv[(std::size_t)ix[(k + 1) % 3]], width, height,
                                                 seg);
                if (seen > 0) vp.open_segments.push_back(seg);
                whole |= seen < 0;
            }
            if (cut && !whole) {
                /* The near plane's cut: from the point where one edge leaves
                 * the near side to where another comes back (each computed
                 * from its inside end, as the clipper does). */
                raster::ClipVertex ends[2];
                int found = 0;
                for (int k = 0; k < 3; k++) {
                    const raster::ClipVertex &a = cv[(std::size_t)ix[k]],
                                             &b = cv[(std::size_t)ix[(k + 1) % 3]];
                    const double da = a.z + a.w, db = b.z + b.w;
                    if ((da >= 0) == (db >= 0) || found == 2) continue;
                    /* From the end on the near plane's inside. */
                    const raster::ClipVertex &p0 = da >= 0 ? a : b, &p1 = da >= 0 ? b : a;
                    const double d0 = da >= 0 ? da : db, d1 = da >= 0 ? db : da;
                    const double u = d0 / (d0 - d1);
                    ends[found++] = {p0.x + u * (p1.x - p0.x), p0.y + u * (p1.y - p0.y),
                                     p0.z + u * (p1.z - p0.z), p0.w + u * (p1.w - p0.w)};
                }
                /* On the near plane by construction: only the side planes
                 * clip it (a test against the near plane could lose it to
                 * rounding). */
                VolumePieces::Segment seg{};
                const int seen = found == 2
                                     ? visible_segment(ends[0], ends[1], width, height, seg, 1)
                                     : -1;
                if (seen > 0) vp.open_segments.push_back(seg);
                whole |= seen < 0;
            }
            if (whole) vp.open_segments.resize(first_segment);
            const bool any_open = edges || cut;
            vp.open.push_back(whole ? kOpenWhole : any_open ? 1 : 0);
            vp.open_first.push_back((int)first_segment);
            /* The receiver's own triangle, and its edges that are open among
             * the receiver's triangles (not projectable: not used). */
            const bool on_surface = on_receiver[(std::size_t)vi][t] != 0;
            bool receiver = on_surface;
            const std::size_t first_cap = vp.cap_segments.size();
            const uint8_t cap_edges = receiver ? cap_open[(std::size_t)vi][t] : 0;
            if (cap_edges) {
                for (int k = 0; k < 3; k++) {
                    if (!(cap_edges >> k & 1)) continue;
                    VolumePieces::Segment seg{};
                    const int seen = visible_segment(cv[(std::size_t)ix[k]],
                                                     cv[(std::size_t)ix[(k + 1) % 3]], width,
                                                     height, seg);
                    if (seen > 0) vp.cap_segments.push_back(seg);
                    receiver &= seen >= 0;
                }
            }
            if (!receiver) vp.cap_segments.resize(first_cap);
            if (on_surface && !receiver) vp.caps_by_coverage[(std::size_t)vi] = 0;
            vp.receiver.push_back(receiver ? 1 : 0);
            vp.cap_first.push_back((int)first_cap);
        }
        vp.first_piece[(std::size_t)vi + 1] = (int)vp.pieces.size();
    }
    vp.open_first.push_back((int)vp.open_segments.size());
    vp.cap_first.push_back((int)vp.cap_segments.size());
    /* The records stay where they are (moving a vector keeps its buffer). */
    vp.piece_chunks.reserve(ps.chunk_out.size());
    vp.extent_chunks.reserve(ps.chunk_out.size());
    for (PieceSetup::ChunkOut &o : ps.chunk_out) {
        vp.piece_chunks.push_back(std::move(o.pieces));
        vp.extent_chunks.push_back(std::move(o.extents));
    }
    /* Volumes with no chunk (no drawn triangle) start where the last ended. */
    for (std::size_t vi = 1; vi <= volumes.size(); vi++) {
        vp.first_piece[vi] = std::max(vp.first_piece[vi], vp.first_piece[vi - 1]);
    }
    return vp;
}

VolumePieces set_up_volume_pieces(const StencilPassInputs &in) {
    return finish_volume_pieces(in, set_up_pieces(in));
}

} // namespace sv::render::detail
