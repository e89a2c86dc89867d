/*
 * The overlays of view_overlays.h.
 *
 * Copyright (C) 2026 the shadowvol authors. LGPL-2.1-or-later.
 */
#include "view_overlays.h"

#include <algorithm>
#include <cmath>
#include <cstdlib>

namespace svcli {
namespace {

void plot(sv::render::Image &image, int x, int y, uint8_t r, uint8_t g, uint8_t b) {
    if (x < 0 || y < 0 || x >= image.width || y >= image.height) return;
    uint8_t *p = image.at(x, y);
    p[0] = r, p[1] = g, p[2] = b;
}

/* The segment from (X0, Y0) to (X1, Y1) in pixels, clipped to a margin
 * around the image first so that a far endpoint costs nothing. */
void line(sv::render::Image &image, double x0, double y0, double x1, double y1, uint8_t r,
          uint8_t g, uint8_t b) {
    const double lo_x = -1, lo_y = -1, hi_x = image.width, hi_y = image.height;
    /* Liang-Barsky against the rectangle. */
    double t0 = 0, t1 = 1;
    const double dx = x1 - x0, dy = y1 - y0;
    const double p[4] = {-dx, dx, -dy, dy};
    const double q[4] = {x0 - lo_x, hi_x - x0, y0 - lo_y, hi_y - y0};
    for (int k = 0; k < 4; k++) {
        if (p[k] == 0) {
            if (q[k] < 0) return;
            continue;
        }
        const double t = q[k] / p[k];
        if (p[k] < 0)
            t0 = std::max(t0, t);
        else
            t1 = std::min(t1, t);
        if (t0 > t1) return;
    }
    const double ax = x0 + t0 * dx, ay = y0 + t0 * dy, bx = x0 + t1 * dx, by = y0 + t1 * dy;
    const int steps = (int)std::ceil(std::max(std::abs(bx - ax), std::abs(by - ay))) + 1;
    for (int s = 0; s <= steps; s++) {
        const double t = (double)s / steps;
        plot(image, (int)std::floor(ax + t * (bx - ax)), (int)std::floor(ay + t * (by - ay)), r, g,
             b);
    }
}

} // namespace

void overlay_stencil_counts(sv::render::Image &image, const sv::render::Frame &frame, int light) {
    if (light < 0 || light >= (int)frame.lights.size()) return;
    image = sv::render::stencil_image(frame.lights[(std::size_t)light].stencil, image);
}

void overlay_boundary_tiles(sv::render::Image &image, const sv::render::Frame &frame, int light,
                            int tile) {
    if (light < 0 || light >= (int)frame.lights.size() || tile <= 0) return;
    const std::vector<uint8_t> &mask = frame.lights[(std::size_t)light].stencil_boundary_tiles;
    const int cols = (frame.width + tile - 1) / tile, rows = (frame.height + tile - 1) / tile;
    if (mask.size() != (std::size_t)cols * rows) return;
    for (int ty = 0; ty < rows; ty++) {
        for (int tx = 0; tx < cols; tx++) {
            if (!mask[(std::size_t)ty * cols + tx]) continue;
            const int x0 = tx * tile, y0 = ty * tile;
            const int x1 = std::min(frame.width, x0 + tile) - 1;
            const int y1 = std::min(frame.height, y0 + tile) - 1;
            for (int x = x0; x <= x1; x++) {
                plot(image, x, y0, 255, 200, 0);
                plot(image, x, y1, 255, 200, 0);
            }
            for (int y = y0; y <= y1; y++) {
                plot(image, x0, y, 255, 200, 0);
                plot(image, x1, y, 255, 200, 0);
            }
        }
    }
}

int64_t overlay_volume_wireframe(sv::render::Image &image, const sv::render::Frame &frame,
                                 const sv::Scene &scene, int light, int64_t max_edges) {
    if (light < 0 || light >= (int)frame.lights.size()) return 0;
    const sv::render::LightFrame &lf = frame.lights[(std::size_t)light];
    int64_t edges = 0;
    /* Clip space to pixels, the segment first cut where w is small (behind
     * the eye, or a point at infinity seen edge-on). */
    const double kMinW = 1e-6;
    auto draw = [&](const sv::raster::ClipVertex &a, const sv::raster::ClipVertex &b, bool cap) {
        sv::raster::ClipVertex p = a, q = b;
        if (p.w < kMinW && q.w < kMinW) return;
        if (p.w < kMinW || q.w < kMinW) {
            const double t = (kMinW - p.w) / (q.w - p.w);
            sv::raster::ClipVertex m = {p.x + t * (q.x - p.x), p.y + t * (q.y - p.y),
                                        p.z + t * (q.z - p.z), kMinW};
            (p.w < kMinW ? p : q) = m;
        }
        auto px = [&](const sv::raster::ClipVertex &v, double &x, double &y) {
            x = (v.x / v.w + 1) * 0.5 * frame.width;
            y = (1 - v.y / v.w) * 0.5 * frame.height;
        };
        double x0, y0, x1, y1;
        px(p, x0, y0);
        px(q, x1, y1);
        if (!std::isfinite(x0) || !std::isfinite(y0) || !std::isfinite(x1) || !std::isfinite(y1))
            return;
        if (cap)
            line(image, x0, y0, x1, y1, 255, 140, 40);
        else
            line(image, x0, y0, x1, y1, 80, 255, 255);
    };
    for (const sv::render::Volume &v : lf.volumes) {
        const sv::PreparedSurface &p = scene.surfaces[(std::size_t)v.surface].prepared;
        const int drawn = v.drawn_indices();
        for (int i = 0; i + 2 < drawn && edges < max_edges; i += 3) {
            sv::raster::ClipVertex c[3];
            for (int k = 0; k < 3; k++) {
                c[k] = sv::render::volume_vertex_to_clip(frame.view_proj, p, v,
                                                         v.indices[(std::size_t)i + k],
                                                         lf.shadow_light);
            }
            const bool cap = i >= v.silhouette_indices;
            for (int k = 0; k < 3; k++) draw(c[k], c[(k + 1) % 3], cap);
            edges += 3;
        }
    }
    return edges;
}

} // namespace svcli
