/*
 * The frame of frame.h: render_frame runs the passes in order (depth,
 * volumes, per light its stencil, shading), each in a file of its own;
 * here too the frame's small geometry (clip space, camera rays, the
 * visible point) that the passes and the judges share.
 *
 * Copyright (C) 2026 the shadowvol authors. LGPL-2.1-or-later.
 */
#include "frame.h"

#include <tbb/global_control.h>
#include <tbb/info.h>
#include <tbb/task_arena.h>

#include <algorithm>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

#include "depth_pass.h"
#include "extruded_volumes.h"
#include "frame_math.h"
#include "frame_scratch.h"
#include "pass_bins.h"
#include "shading_pass.h"
#include "stencil_pass.h"
#include "tile_depth_range.h"
#include "volume_pass.h"

namespace sv::render {

using namespace detail;

const char *mode_name(ModeChoice m) {
    switch (m) {
    case ModeChoice::zpass: return "zpass";
    case ModeChoice::zfail: return "zfail";
    default: return "auto";
    }
}

uint64_t frame_bytes(int width, int height, int lights) {
    const uint64_t px = (uint64_t)width * (uint64_t)height, l = (uint64_t)std::max(lights, 1);
    /* The target (depth, ids, stencil: 9), per light its stencil (1) and
     * truth classes (1), the Mesa judge's read-back and classes (6 per
     * light, one light at a time: 6), the shaded image and the PNG panels
     * (3 each: the shaded copy, and per light its stencil, truth and
     * difference panels plus the side-by-side copies of each: 3 + 18 l). */
    return px * (9 + 2 * l + 6 + 3 + 3 + 18 * l);
}

void Frame::decode_id(int32_t id, int &surface, int &triangle) const {
    const auto it = std::upper_bound(surface_first_id.begin(), surface_first_id.end(), id);
    surface = (int)(it - surface_first_id.begin()) - 1;
    triangle = id - surface_first_id[surface];
}

raster::ClipVertex to_clip(const Mat4d &view_proj, double x, double y, double z, double w) {
    const std::array<double, 4> c = view_proj.apply(x, y, z, w);
    return {c[0], c[1], c[2], c[3]};
}

raster::ClipVertex shadow_vertex_to_clip(const Mat4d &view_proj, const PreparedSurface &p,
                                         int sv_index, const Vec4 &L) {
    const Vec3d q = vertex(p, sv_index >> 1);
    return (sv_index & 1)
               ? to_clip(view_proj, q.x * L.w - L.x, q.y * L.w - L.y, q.z * L.w - L.z, 0.0)
               : to_clip(view_proj, q.x, q.y, q.z, 1.0);
}

raster::ClipVertex volume_vertex_to_clip(const Mat4d &view_proj, const PreparedSurface &p,
                                         const Volume &vol, int sv_index, const Vec4 &L) {
    if ((sv_index & 1) && !vol.extruded.empty()) {
        const Vec4 &e = vol.extruded[(std::size_t)(sv_index >> 1)];
        return to_clip(view_proj, e.x, e.y, e.z, e.w);
    }
    return shadow_vertex_to_clip(view_proj, p, sv_index, L);
}

Vec3d camera_ray(const Frame &f, double x, double y) {
    const double nx = (x / f.width) * 2 - 1, ny = 1 - (y / f.height) * 2;
    return add(f.ray_forward, add(mul(f.ray_right, nx), mul(f.ray_up, ny)));
}

Vec3d visible_point(const Frame &f, const Scene &scene, int surface, int triangle, int px, int py) {
    const Vec3d dir = camera_ray(f, px + 0.5, py + 0.5);
    const PreparedSurface &p = scene.surfaces[surface].prepared;
    const int *tri = &p.indices[3 * triangle];
    const Vec3d a = vertex(p, tri[0]);
    const Vec3d n = cross(sub(vertex(p, tri[1]), a), sub(vertex(p, tri[2]), a));
    const double den = dot(n, dir);
    const double t = den != 0 ? dot(n, sub(a, f.camera.eye)) / den : 0;
    return add(f.camera.eye, mul(dir, t));
}

const char *fate_name(VolumeFate f) {
    switch (f) {
    case VolumeFate::built: return "built";
    case VolumeFate::reused: return "reused";
    case VolumeFate::out_of_reach: return "out of reach";
    case VolumeFate::out_of_view: return "out of view";
    default: return "no shadow";
    }
}

FrameScratch::FrameScratch() : buffers_(new Buffers) {}
FrameScratch::~FrameScratch() { delete buffers_; }

Frame render_frame(const Scene &scene, const RenderOptions &opt) {
    if (opt.width < 1 || opt.height < 1 || opt.width > kMaxFrameSide ||
        opt.height > kMaxFrameSide || (int64_t)opt.width * opt.height > kMaxFramePixels) {
        throw std::invalid_argument("render_frame: a " + std::to_string(opt.width) + "x" +
                                    std::to_string(opt.height) + " frame is outside 1.." +
                                    std::to_string(kMaxFrameSide) + " per side");
    }
    const uint64_t k_start = ticks();
    const int threads = opt.threads > 0 ? opt.threads : tbb::info::default_concurrency();
    /* More threads than cores only when asked (the tests of identical
     * bytes at every count): oneTBB caps its workers at the cores. */
    tbb::global_control allow(tbb::global_control::max_allowed_parallelism,
                              (std::size_t)std::max(threads, tbb::info::default_concurrency()));
    tbb::task_arena arena(threads);
    Frame f;
    f.threads = threads;
    f.width = opt.width;
    f.height = opt.height;
    f.camera = scene.camera;
    const double aspect = (double)opt.width / opt.height;
    f.view_proj = infinite_projection(scene.camera.fov_y_degrees, aspect,
                                      scene.camera.near_distance) *
                  look_at(scene.camera.eye, scene.camera.target, scene.camera.up);
    const raster::RowKernels *kernels = opt.kernels ? opt.kernels : raster::row_kernels_best();
    const sv_variant *variant = opt.variant ? opt.variant : sv_best_variant();
    const sv_facing_variant *facing_v = opt.facing ? opt.facing : sv_best_facing_variant();
    {
        const CameraBasis b = basis(scene.camera);
        f.ray_forward = b.f;
        f.ray_right = mul(b.s, b.tan_half * aspect);
        f.ray_up = mul(b.u, b.tan_half);
    }
    f.kernels = kernels->name;
    f.variant = variant->name;
    f.stencil_method = stencil_method_name(opt.stencil);
    const raster::Rasterizer rast(kernels);
    f.target.allocate(opt.width, opt.height); /* cleared below, band by band */
    int32_t next_id = 0;
    for (const SceneSurface &s : scene.surfaces) {
        f.surface_first_id.push_back(next_id);
        next_id += s.prepared.num_triangles();
    }
    /* The cache: the caller's (shortcut 6), else one for this frame only. */
    VolumeCache local_cache;
    VolumeCache &cache = (opt.cache && opt.shortcuts.reuse_static) ? *opt.cache : local_cache;
    FrameScratch local_scratch;
    FrameScratch::Buffers &scratch = opt.scratch ? opt.scratch->buffers() : local_scratch.buffers();
    scratch.surface_triangles.begin_frame();

    arena.execute([&] {
        parallel(band_count(f.height), [&](int b) {
            const raster::RowBand band = band_rows(b, f.height);
            f.target.clear_rows(band.row_begin, band.row_end);
        });
        const ClipVertices clip = receivers_to_clip(scene, f.view_proj);
        const DepthPassResult depth = depth_pass(scene, clip, f.surface_first_id, rast, f.target,
                                                 scratch.depth_bins, scratch.depth_window);
        f.depth_counters = depth.counters;
        f.ticks_depth = depth.ticks;
        f.seconds_depth = depth.seconds;

        VolumePassInputs vin;
        vin.scene = &scene;
        vin.view_proj = f.view_proj;
        vin.aspect = aspect;
        vin.mode = opt.mode;
        vin.caster_rule = opt.caster_rule;
        vin.general_build = opt.general_build;
        vin.ground_hints = opt.ground_hints;
        /* The general kernels of the paper's variant's instruction set. */
        vin.general_variant = sv_general_variant_for_isa(variant->isa);
        vin.shortcuts = opt.shortcuts;
        vin.faults = opt.faults;
        vin.variant = variant;
        vin.facing = facing_v;
        f.ticks_jobs = volume_pass(vin, cache, f.lights);
        if (opt.volume == VolumeSource::extrude) use_extruded_volumes(scene, opt, f.lights);

        /* hier's tile depth ranges: the same depth for every light. Their
         * time counts in the first light's stencil pass. */
        detail::TileGrid tile_grid;
        detail::TileGrid auto_tile_grid; /* auto: the first light that takes hier computes it */
        uint64_t grid_ticks = 0;
        double grid_seconds = 0;
        const bool share_grid = opt.stencil == StencilMethod::hierarchical && !f.lights.empty() &&
                                valid_stencil_tile(opt.stencil_tile); /* else the pass says why */
        if (share_grid) {
            const double g0 = now_seconds();
            const uint64_t gk0 = ticks();
            tile_grid = detail::tile_depth_ranges(f.target.depth.data(), f.width, f.height,
                                                  opt.stencil_tile);
            grid_ticks = ticks() - gk0;
            grid_seconds = now_seconds() - g0;
        }
        for (LightFrame &lf : f.lights) {
            StencilPassInputs sin;
            sin.scene = &scene;
            sin.receivers = &clip;
            sin.volumes = &lf.volumes;
            sin.light = lf.shadow_light;
            sin.view_proj = f.view_proj;
            sin.rast = &rast;
            sin.target = &f.target;
            sin.tile = opt.stencil_tile;
            sin.faults = opt.stencil_faults;
            sin.saturate = opt.stencil_saturate;
            if (share_grid) sin.tile_grid = &tile_grid;
            sin.tile_grid_for_auto = &auto_tile_grid;
            sin.rule = opt.stencil_rule;
            sin.surface_triangles = &scratch.surface_triangles;
            StencilPassResult st = stencil_pass(opt.stencil, sin);
            st.ticks += grid_ticks;
            st.seconds += grid_seconds;
            grid_ticks = 0;
            grid_seconds = 0;
            lf.stencil = std::move(st.stencil);
            lf.stencil_boundary_tiles = std::move(st.boundary_tile_mask);
            lf.stencil_psv_lines = st.psv_lines;
            lf.stencil_coverage_rows = st.coverage_rows;
            lf.stencil_coverage_pixels = st.coverage_pixels;
            lf.stencil_counters = st.counters;
            lf.ticks_stencil = st.ticks;
            lf.seconds_stencil = st.seconds;
            lf.stencil_ran = st.ran;
            lf.stencil_load = st.load;
        }
        /* The target's own stencil holds the last light's, as before. */
        if (!f.lights.empty()) {
            std::copy(f.lights.back().stencil.begin(), f.lights.back().stencil.end(),
                      f.target.stencil.begin());
        }

        const uint64_t k0 = ticks();
        ShadingResult shaded = shading_pass(scene, f, lit_facing(scene, f.lights, cache),
                                            opt.ambient, kernels->isa, scratch.shade_triangles);
        f.rgb = std::move(shaded.rgb);
        f.ticks_shading = ticks() - k0;
        f.shading_divider_lanes = shaded.divider_lanes;
    });
    f.ticks_total = ticks() - k_start;
    return f;
}

} // namespace sv::render
