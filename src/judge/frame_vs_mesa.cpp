/*
 * Our frame against Mesa's (frame_vs_mesa.h).
 *
 * Copyright (C) 2026 the shadowvol authors. LGPL-2.1-or-later.
 */
#include "frame_vs_mesa.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <stdexcept>
#include <utility>

#include "gl_compare.h"
#include "mesa_frame.h"
#include "shading_pass.h"

namespace sv::render {

namespace {

constexpr double kPi = 3.14159265358979323846;

gl::MesaFrameLight mesa_light(const LightFrame &lf,
                              const std::vector<AlignedVector<Vec4>> &buffers) {
    const SceneLight &l = lf.light;
    gl::MesaFrameLight m;
    m.kind = l.kind == LightKind::point ? 0 : l.kind == LightKind::spot ? 1 : 2;
    m.position[0] = (float)l.position.x, m.position[1] = (float)l.position.y,
    m.position[2] = (float)l.position.z;
    m.direction[0] = (float)l.direction.x, m.direction[1] = (float)l.direction.y,
    m.direction[2] = (float)l.direction.z;
    for (int c = 0; c < 3; c++) m.color[c] = l.color[(std::size_t)c];
    m.intensity = (float)l.intensity;
    m.inv_range2 = l.range > 0 ? (float)(1.0 / (l.range * l.range)) : 0.0f;
    m.cos_outer = (float)std::cos(l.outer_degrees * kPi / 180.0);
    m.cos_inner = (float)std::cos(l.inner_degrees * kPi / 180.0);
    m.shadow_light = lf.shadow_light;
    m.volumes = mesa_volumes(lf, buffers);
    return m;
}

/* The ground's checker at pixel (X, Y) of surface SI, triangle T: odd? */
bool checker_odd_at(const Scene &scene, const Frame &f, int si, int t, int x, int y) {
    const Vec3d p = visible_point(f, scene, si, t, x, y);
    return (((int64_t)std::floor(p.x * 2) + (int64_t)std::floor(p.z * 2)) & 1) != 0;
}

/* Does pixel I's 3x3 neighbourhood show another triangle, another
 * shadow-mask value of some light, or (on the ground) a line of its
 * checker? */
bool near_an_edge(const Scene &scene, const Frame &f, std::size_t i) {
    const int w = f.width, h = f.height;
    const int x = (int)(i % (std::size_t)w), y = (int)(i / (std::size_t)w);
    int si = -1, t = -1;
    f.decode_id(f.target.ids[i], si, t);
    const bool ground = scene.surfaces[(std::size_t)si].ground;
    const bool odd = ground && checker_odd_at(scene, f, si, t, x, y);
    for (int dy = -1; dy <= 1; dy++) {
        for (int dx = -1; dx <= 1; dx++) {
            const int nx = x + dx, ny = y + dy;
            if (nx < 0 || ny < 0 || nx >= w || ny >= h) continue;
            const std::size_t j = (std::size_t)ny * w + nx;
            if (f.target.ids[j] != f.target.ids[i]) return true;
            for (const LightFrame &lf : f.lights) {
                if ((lf.stencil[j] == 0) != (lf.stencil[i] == 0)) return true;
            }
            if (ground && checker_odd_at(scene, f, si, t, nx, ny) != odd) return true;
        }
    }
    return false;
}

} // namespace

MesaFrameComparison compare_frame_with_mesa(const Scene &scene, const Frame &f, double ambient,
                                            int threads, int runs, std::string *note) {
    MesaFrameComparison out;
    std::string why;
    const std::unique_ptr<gl::MesaContext> ctx = gl::MesaContext::create(f.width, f.height, threads,
                                                                         &why);
    if (!ctx) {
        *note = "no Mesa GL context (" + why + "): Mesa's frame was not drawn";
        return out;
    }
    out.ran = true;
    out.renderer = ctx->describe();
    out.lp_num_threads = ctx->lp_num_threads();
    std::vector<AlignedVector<Vec4>> buffers;
    for (const SceneSurface &s : scene.surfaces) buffers.push_back(shadow_vertices(s.prepared));
    gl::MesaFrameJob job;
    job.width = f.width;
    job.height = f.height;
    std::copy(f.view_proj.m, f.view_proj.m + 16, job.view_proj);
    job.ambient = (float)ambient;
    for (const SceneSurface &s : scene.surfaces) {
        gl::MesaFrameSurface m;
        m.mesh = mesa_receiver(s);
        for (int c = 0; c < 3; c++) m.albedo[c] = s.albedo[(std::size_t)c];
        m.ground = s.ground;
        job.surfaces.push_back(m);
    }
    for (const LightFrame &lf : f.lights) job.lights.push_back(mesa_light(lf, buffers));

    /* A warm-up (llvmpipe compiles its shaders and states on first use)
     * that reads back the depth and every light's stencil, then RUNS timed
     * frames, the minimum kept; then one more with a wait after each pass
     * for the per-pass times. */
    job.read_stencils = true;
    const gl::MesaFrameResult read = ctx->run_frame(job);
    job.read_stencils = false;
    /* Per light, where Mesa's stencil differs from ours: on a volume's
     * edge (1), at a depth tie (2) or neither (3). */
    std::vector<std::vector<uint8_t>> stencil_class;
    for (std::size_t li = 0; li < f.lights.size() && li < read.stencils.size(); li++) {
        GlComparison g = classify_differences(scene, f, (int)li, f.lights[li].stencil,
                                              read.stencils[li], read.depth);
        out.stencil_other += g.other;
        stencil_class.push_back(std::move(g.cls));
    }
    auto stencil_excuses = [&](std::size_t i) {
        for (const auto &c : stencil_class) {
            if (c[i] == 1 || c[i] == 2) return true;
        }
        return false;
    };
    gl::MesaFrameResult r;
    out.runs = std::max(runs, 1);
    out.total_seconds = 1e30;
    for (int i = 0; i < out.runs; i++) {
        r = ctx->run_frame(job);
        out.total_seconds = std::min(out.total_seconds, r.total_seconds);
    }
    job.time_each_pass = true;
    const gl::MesaFrameResult passes = ctx->run_frame(job);
    out.depth_seconds = passes.depth_seconds;
    out.stencil_seconds = passes.stencil_seconds;
    out.lighting_seconds = passes.lighting_seconds;

    const std::size_t n = (std::size_t)f.width * f.height;
    out.mesa_rgb = f.rgb;
    for (std::size_t i = 0; i < n; i++) {
        if (!r.covered[i]) continue;
        int diff = 0;
        for (int c = 0; c < 3; c++) {
            const uint8_t v = display_byte(r.radiance[3 * i + (std::size_t)c]);
            out.mesa_rgb[3 * i + (std::size_t)c] = v;
            diff = std::max(diff, std::abs((int)v - (int)f.rgb[3 * i + (std::size_t)c]));
        }
        if (f.target.ids[i] < 0) continue;
        out.compared++;
        if (diff <= kFrameTolerance) {
            out.equal++;
        } else if (near_an_edge(scene, f, i) || stencil_excuses(i)) {
            out.on_edge++;
        } else {
            out.other++;
            out.max_difference_other = std::max(out.max_difference_other, diff);
            if (out.first_other.size() < 4) {
                const uint8_t *o = &f.rgb[3 * i], *m = &out.mesa_rgb[3 * i];
                char b[200];
                std::snprintf(b, sizeof b,
                              "pixel (%zu, %zu), triangle id %d: ours %d %d %d, Mesa's %d %d %d",
                              i % (std::size_t)f.width, i / (std::size_t)f.width,
                              (int)f.target.ids[i], o[0], o[1], o[2], m[0], m[1], m[2]);
                out.first_other.push_back(b);
            }
        }
    }
    return out;
}

} // namespace sv::render
