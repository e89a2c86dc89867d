/*
 * The frame's stencils against Mesa's (gl_compare.h).
 *
 * Copyright (C) 2026 the shadowvol authors. LGPL-2.1-or-later.
 */
#include "gl_compare.h"

#include <algorithm>
#include <memory>
#include <cmath>
#include <cstdio>
#include <stdexcept>

#include "mesa_stencil.h"
#include "volume_faces.h"

namespace sv::render {

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
    const auto tris = drawn_volume_triangles(scene, f, light);
    for (std::size_t i : diff) {
        const FaceProximity ours_p = face_proximity(tris, f, i, f.target.depth[i]);
        double gap_ulps = ours_p.gap_ulps;
        if (i < their_depth.size())
            gap_ulps = std::min(gap_ulps, face_proximity(tris, f, i, their_depth[i]).gap_ulps);
        const double nearest = ours_p.nearest_edge;
        const bool tie = gap_ulps <= kDepthTieUlps;
        const uint8_t c = tie ? 2 : nearest <= kEdgeDistance ? 1 : 3;
        if (c == 1) g.max_edge_distance = std::max(g.max_edge_distance, nearest);
        g.cls[i] = c;
        if (c == 3 && g.first_other.size() < 8) {
            char b[160];
            std::snprintf(b, sizeof b,
                          "pixel (%zu, %zu): nearest volume edge %.4f px, nearest volume depth "
                          "%.0f float ulps away",
                          i % (std::size_t)f.width, i / (std::size_t)f.width, nearest, gap_ulps);
            g.first_other.push_back(b);
        }
        (c == 1 ? g.on_edge : c == 2 ? g.depth_tie : g.other)++;
    }
    return g;
}

gl::MesaMesh mesa_receiver(const SceneSurface &s) {
    gl::MesaMesh m;
    m.positions = s.prepared.positions.data();
    m.num_vertices = s.prepared.num_vertices();
    m.indices = s.prepared.indices.data();
    m.num_indices = s.prepared.num_indices();
    return m;
}

std::vector<gl::MesaVolume> mesa_volumes(const LightFrame &lf,
                                         const std::vector<AlignedVector<Vec4>> &buffers) {
    std::vector<gl::MesaVolume> out;
    for (const Volume &vol : lf.volumes) {
        gl::MesaVolume v;
        v.shadow_vertices = buffers[(std::size_t)vol.surface].data();
        v.num_shadow_vertices = (int)buffers[(std::size_t)vol.surface].size();
        if (!vol.extruded.empty()) {
            /* Seed 002's volume: an extruded vertex at a finite point (the
             * seed's range) is drawn as it is (w = 1); one at infinity
             * (w = 0) is the buffer's (x, y, z, 0), which the program
             * extrudes from the light as the seed's program did. */
            auto own = std::make_shared<AlignedVector<Vec4>>(buffers[(std::size_t)vol.surface]);
            for (std::size_t k = 0; k < vol.extruded.size() && 2 * k + 1 < own->size(); k++) {
                if (vol.extruded[k].w == 1.0f) (*own)[2 * k + 1] = vol.extruded[k];
            }
            v.shadow_vertices = own->data();
            v.own_vertices = std::move(own);
        }
        v.indices = vol.indices.data();
        v.num_indices = vol.drawn_indices();
        v.zfail = vol.zfail;
        out.push_back(v);
    }
    return out;
}

std::vector<GlComparison> compare_with_mesa(const Scene &scene, const Frame &f,
                                            std::string *renderer, std::string *note, int threads,
                                            int *lp_threads) {
    std::string why;
    const std::unique_ptr<gl::MesaContext> ctx = gl::MesaContext::create(f.width, f.height, threads,
                                                                         &why);
    if (!ctx) {
        *note = "no Mesa GL context (" + why + "): the comparison with OpenGL was skipped";
        return {};
    }
    *renderer = ctx->describe();
    if (lp_threads) *lp_threads = ctx->lp_num_threads();
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
        for (const SceneSurface &s : scene.surfaces) job.receivers.push_back(mesa_receiver(s));
        job.volumes = mesa_volumes(lf, buffers);
        /* Twice, timing the faster: the first draw in a context pays for
         * llvmpipe compiling its shaders and stencil states (measured:
         * over a millisecond with nothing to draw). */
        gl::MesaStencilResult r = ctx->run(job);
        const gl::MesaStencilResult again = ctx->run(job);
        if (again.stencil != r.stencil)
            throw std::runtime_error("Mesa drew a different stencil the second time");
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
