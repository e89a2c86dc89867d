/*
 * The volume faces of volume_faces.h.
 *
 * Copyright (C) 2026 the shadowvol authors. LGPL-2.1-or-later.
 */
#include "volume_faces.h"

#include <algorithm>
#include <cmath>

#include "row_kernels.h"

namespace sv::render {
namespace {

double segment_distance(double px, double py, double ax, double ay, double bx, double by) {
    const double dx = bx - ax, dy = by - ay;
    const double l2 = dx * dx + dy * dy;
    double t = l2 > 0 ? ((px - ax) * dx + (py - ay) * dy) / l2 : 0;
    t = std::clamp(t, 0.0, 1.0);
    const double ex = ax + t * dx - px, ey = ay + t * dy - py;
    return std::sqrt(ex * ex + ey * ey);
}

} // namespace

double depth_tie_width(float stored) {
    return kDepthTieUlps * (double)(std::nextafter(stored, 2.0f) - stored);
}

std::vector<raster::Rasterizer::WindowTriangle> drawn_volume_triangles(const Scene &scene,
                                                                       const Frame &f, int li) {
    std::vector<raster::Rasterizer::WindowTriangle> out;
    const raster::Rasterizer rast(&raster::kRowKernelsC);
    const LightFrame &lf = f.lights[(std::size_t)li];
    const Vec4 L = lf.shadow_light;
    for (const Volume &vol : lf.volumes) {
        const PreparedSurface &p = scene.surfaces[(std::size_t)vol.surface].prepared;
        auto clip_of = [&](int sv_index) {
            return volume_vertex_to_clip(f.view_proj, p, vol, sv_index, L);
        };
        for (int i = 0; i + 2 < vol.drawn_indices(); i += 3) {
            const raster::ClipVertex v[3] = {clip_of(vol.indices[(std::size_t)i]),
                                             clip_of(vol.indices[(std::size_t)i + 1]),
                                             clip_of(vol.indices[(std::size_t)i + 2])};
            for (const auto &w : rast.window_triangles(v, f.width, f.height)) out.push_back(w);
        }
    }
    return out;
}

FaceProximity face_proximity(const std::vector<raster::Rasterizer::WindowTriangle> &tris,
                             const Frame &f, std::size_t pixel, float depth) {
    const std::size_t row = pixel / (std::size_t)f.width, column = pixel % (std::size_t)f.width;
    const double px = (double)column + 0.5;
    const double py = (double)row + 0.5;
    FaceProximity r{HUGE_VAL, HUGE_VAL};
    for (const auto &t : tris) {
        const double x0 = std::min({t.x[0], t.x[1], t.x[2]}),
                     x1 = std::max({t.x[0], t.x[1], t.x[2]});
        const double y0 = std::min({t.y[0], t.y[1], t.y[2]}),
                     y1 = std::max({t.y[0], t.y[1], t.y[2]});
        if (px < x0 - 1 || px > x1 + 1 || py < y0 - 1 || py > y1 + 1) continue;
        for (int e = 0; e < 3; e++) {
            const int k = (e + 1) % 3;
            r.nearest_edge = std::min(r.nearest_edge,
                                      segment_distance(px, py, t.x[e], t.y[e], t.x[k], t.y[k]));
        }
        /* Inside: barycentric depth. */
        const double d = (t.x[1] - t.x[0]) * (t.y[2] - t.y[0]) -
                         (t.x[2] - t.x[0]) * (t.y[1] - t.y[0]);
        if (d == 0) continue;
        const double b1 = ((px - t.x[0]) * (t.y[2] - t.y[0]) - (t.x[2] - t.x[0]) * (py - t.y[0])) /
                          d;
        const double b2 = ((t.x[1] - t.x[0]) * (py - t.y[0]) - (px - t.x[0]) * (t.y[1] - t.y[0])) /
                          d;
        if (b1 < 0 || b2 < 0 || b1 + b2 > 1) continue;
        const double z = t.z[0] + b1 * (t.z[1] - t.z[0]) + b2 * (t.z[2] - t.z[0]);
        r.gap_ulps = std::min(r.gap_ulps,
                              std::fabs(z - depth) / depth_tie_width(depth) * kDepthTieUlps);
    }
    return r;
}

} // namespace sv::render
