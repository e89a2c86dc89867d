/*
 * The frame's stencils against Mesa's (gl_compare.h).
 *
 * Copyright (C) 2026 the shadowvol authors. LGPL-2.1-or-later.
 */
#include "gl_compare.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <stdexcept>

#include "mesa_stencil.h"

namespace sv::render {
namespace {

/* A depth tie: within 128 float ulps of the stored depth (two depth
 * interpolations in float and double of the same plane differ by a few
 * ulps; a fixed tolerance would excuse metres at a distance). */
constexpr int kDepthTieUlps = 128;
inline double depth_tie(float stored) {
    return kDepthTieUlps * (double)(std::nextafter(stored, 2.0f) - stored);
}
/* Two rasterisers that snap to 1/256 pixel put an edge at most a few
 * 1/256 of a pixel apart (their float and double transforms differ far
 * less); a difference further from every edge is a real one. */
constexpr double kEdgeDistance = 1.0 / 8;

double segment_distance(double px, double py, double ax, double ay, double bx, double by) {
    const double dx = bx - ax, dy = by - ay;
    const double l2 = dx * dx + dy * dy;
    double t = l2 > 0 ? ((px - ax) * dx + (py - ay) * dy) / l2 : 0;
    t = std::clamp(t, 0.0, 1.0);
    const double ex = ax + t * dx - px, ey = ay + t * dy - py;
    return std::sqrt(ex * ex + ey * ey);
}

/* The window triangles of every volume triangle drawn for light LI. */
std::vector<raster::Rasterizer::WindowTriangle> drawn_triangles(const Scene &scene, const Frame &f,
                                                                int li) {
    std::vector<raster::Rasterizer::WindowTriangle> out;
    const raster::Rasterizer rast(&raster::kRowKernelsC);
    const LightFrame &lf = f.lights[(std::size_t)li];
    const Vec4 L = lf.shadow_light;
    for (const Volume &vol : lf.volumes) {
        const PreparedSurface &p = scene.surfaces[(std::size_t)vol.surface].prepared;
        auto clip_of = [&](int sv_index) { return shadow_vertex_to_clip(f.view_proj, p, sv_index, L); };
        for (int i = 0; i + 2 < vol.drawn_indices(); i += 3) {
            const raster::ClipVertex v[3] = {clip_of(vol.indices[(std::size_t)i]),
                                             clip_of(vol.indices[(std::size_t)i + 1]),
                                             clip_of(vol.indices[(std::size_t)i + 2])};
            for (const auto &w : rast.window_triangles(v, f.width, f.height)) out.push_back(w);
        }
    }
    return out;
}

} // namespace

GlComparison classify_differences(const Scene &scene, const Frame &f, int light,
                                  const std::vector<uint8_t> &ours,
                                  const std::vector<uint8_t> &theirs,
                                  const std::vector<float> &their_depth) {
    GlComparison g;
    g.cls.assign(ours.size(), 0);
    std::vector<std::size_t> diff;
    for (std::size_t i = 0; i < ours.size(); i++) {
        if (ours[i] != theirs[i]) diff.push_back(i);
    }
    g.differing = diff.size();
    if (diff.empty()) return g;
    const auto tris = drawn_triangles(scene, f, light);
    for (std::size_t i : diff) {
        const double px = (double)(i % (std::size_t)f.width) + 0.5;
        const double py = (double)(i / (std::size_t)f.width) + 0.5;
        double nearest = HUGE_VAL, gap_ulps = HUGE_VAL;
        bool tie = false;
        for (const auto &t : tris) {
            const double x0 = std::min({t.x[0], t.x[1], t.x[2]}), x1 = std::max({t.x[0], t.x[1], t.x[2]});
            const double y0 = std::min({t.y[0], t.y[1], t.y[2]}), y1 = std::max({t.y[0], t.y[1], t.y[2]});
            if (px < x0 - 1 || px > x1 + 1 || py < y0 - 1 || py > y1 + 1) continue;
            for (int e = 0; e < 3; e++) {
                const int k = (e + 1) % 3;
                nearest = std::min(nearest, segment_distance(px, py, t.x[e], t.y[e], t.x[k], t.y[k]));
            }
            /* Inside: barycentric depth. */
            const double d = (t.x[1] - t.x[0]) * (t.y[2] - t.y[0]) - (t.x[2] - t.x[0]) * (t.y[1] - t.y[0]);
            if (d == 0) continue;
            const double b1 = ((px - t.x[0]) * (t.y[2] - t.y[0]) - (t.x[2] - t.x[0]) * (py - t.y[0])) / d;
            const double b2 = ((t.x[1] - t.x[0]) * (py - t.y[0]) - (px - t.x[0]) * (t.y[1] - t.y[0])) / d;
            if (b1 < 0 || b2 < 0 || b1 + b2 > 1) continue;
            const double z = t.z[0] + b1 * (t.z[1] - t.z[0]) + b2 * (t.z[2] - t.z[0]);
            gap_ulps = std::min(gap_ulps, std::fabs(z - f.target.depth[i]) / depth_tie(f.target.depth[i]) * kDepthTieUlps);
            if (std::fabs(z - f.target.depth[i]) <= depth_tie(f.target.depth[i]) ||
                (i < their_depth.size() && std::fabs(z - their_depth[i]) <= depth_tie(their_depth[i]))) {
                tie = true;
            }
        }
        const uint8_t c = tie ? 2 : nearest <= kEdgeDistance ? 1 : 3;
        if (c == 1) g.max_edge_distance = std::max(g.max_edge_distance, nearest);
        g.cls[i] = c;
        if (c == 3 && g.first_other.size() < 8) {
            char b[160];
            std::snprintf(b, sizeof b, "pixel (%zu, %zu): nearest volume edge %.4f px, nearest volume depth %.0f float ulps away",
                          i % (std::size_t)f.width, i / (std::size_t)f.width, nearest, gap_ulps);
            g.first_other.push_back(b);
        }
        (c == 1 ? g.on_edge : c == 2 ? g.depth_tie : g.other)++;
    }
    return g;
}

std::vector<GlComparison> compare_with_mesa(const Scene &scene, const Frame &f,
                                            std::string *renderer, std::string *note) {
    std::string why;
    const std::unique_ptr<gl::MesaContext> ctx = gl::MesaContext::create(f.width, f.height, 1, &why);
    if (!ctx) {
        *note = "no Mesa GL context (" + why + "): the comparison with OpenGL was skipped";
        return {};
    }
    *renderer = ctx->describe();
    std::vector<AlignedVector<Vec4>> buffers;
    for (const SceneSurface &s : scene.surfaces) buffers.push_back(shadow_vertices(s.prepared));
    std::vector<GlComparison> out;
    for (std::size_t li = 0; li < f.lights.size(); li++) {
        const LightFrame &lf = f.lights[li];
        gl::MesaStencilJob job;
        job.width = f.width;
        job.height = f.height;
        std::copy(f.view_proj.m, f.view_proj.m + 16, job.view_proj);
        job.light = lf.shadow_light;
        for (const SceneSurface &s : scene.surfaces) {
            gl::MesaMesh m;
            m.positions = s.prepared.positions.data();
            m.num_vertices = s.prepared.num_vertices();
            m.indices = s.prepared.indices.data();
            m.num_indices = s.prepared.num_indices();
            job.receivers.push_back(m);
        }
        for (const Volume &vol : lf.volumes) {
            gl::MesaVolume v;
            v.shadow_vertices = buffers[(std::size_t)vol.surface].data();
            v.num_shadow_vertices = (int)buffers[(std::size_t)vol.surface].size();
            v.indices = vol.indices.data();
            v.num_indices = vol.drawn_indices();
            v.zfail = vol.zfail;
            job.volumes.push_back(v);
        }
        /* Twice, timing the faster: the first draw in a context pays for
         * llvmpipe compiling its shaders and stencil states (measured:
         * over a millisecond with nothing to draw). */
        gl::MesaStencilResult r = ctx->run(job);
        const gl::MesaStencilResult again = ctx->run(job);
        if (again.stencil != r.stencil) throw std::runtime_error("Mesa drew a different stencil the second time");
        r.stencil_pass_seconds = std::min(r.stencil_pass_seconds, again.stencil_pass_seconds);
        r.depth_pass_seconds = std::min(r.depth_pass_seconds, again.depth_pass_seconds);
        GlComparison g = classify_differences(scene, f, (int)li, lf.stencil, r.stencil, r.depth);
        g.mesa_depth_seconds = r.depth_pass_seconds;
        g.mesa_stencil_seconds = r.stencil_pass_seconds;
        g.mesa_stencil = r.stencil;
        out.push_back(std::move(g));
    }
    return out;
}

} // namespace sv::render
