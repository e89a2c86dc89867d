/*
 * The frame of frame.h: depth pass, per light the volumes and their
 * stencil, then the lighting pass.
 *
 * Copyright (C) 2026 the shadowvol authors. LGPL-2.1-or-later.
 */
#include "frame.h"

#include <x86intrin.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <vector>

namespace sv::render {
namespace {

constexpr double kPi = 3.14159265358979323846;

Vec3d sub(const Vec3d &a, const Vec3d &b) { return {a.x - b.x, a.y - b.y, a.z - b.z}; }
Vec3d add(const Vec3d &a, const Vec3d &b) { return {a.x + b.x, a.y + b.y, a.z + b.z}; }
Vec3d mul(const Vec3d &a, double s) { return {a.x * s, a.y * s, a.z * s}; }
Vec3d cross(const Vec3d &a, const Vec3d &b) {
    return {a.y * b.z - a.z * b.y, a.z * b.x - a.x * b.z, a.x * b.y - a.y * b.x};
}
double dot(const Vec3d &a, const Vec3d &b) { return a.x * b.x + a.y * b.y + a.z * b.z; }
Vec3d normalized(const Vec3d &a) { return mul(a, 1.0 / std::sqrt(dot(a, a))); }

double now_seconds() {
    return std::chrono::duration<double>(std::chrono::steady_clock::now().time_since_epoch())
        .count();
}

struct CameraBasis {
    Vec3d f, s, u;
    double tan_half;
};
CameraBasis basis(const Camera &c) {
    CameraBasis b;
    b.f = normalized(sub(c.target, c.eye));
    b.s = normalized(cross(b.f, c.up));
    b.u = cross(b.s, b.f);
    b.tan_half = std::tan(c.fov_y_degrees * kPi / 360.0);
    return b;
}

Vec3d vertex(const PreparedSurface &p, int v) {
    return {p.positions[3 * v], p.positions[3 * v + 1], p.positions[3 * v + 2]};
}

/* Radiance factor of LIGHT at P with unit normal N (Lambert, attenuation,
 * cone), without the colour. */
double irradiance(const SceneLight &l, const Vec3d &p, const Vec3d &n) {
    if (l.kind == LightKind::directional) {
        return l.intensity * std::max(0.0, -dot(n, l.direction));
    }
    const Vec3d d = sub(l.position, p);
    const double dist2 = dot(d, d);
    const Vec3d dir = mul(d, 1.0 / std::sqrt(dist2));
    double a = l.intensity * std::max(0.0, dot(n, dir)) / dist2;
    if (l.range > 0) {
        /* KHR_lights_punctual's recommended window. */
        const double q = dist2 / (l.range * l.range);
        const double w = std::clamp(1.0 - q * q, 0.0, 1.0);
        a *= w * w;
    }
    if (l.kind == LightKind::spot) {
        const double cos_outer = std::cos(l.outer_degrees * kPi / 180.0);
        const double cos_inner = std::cos(l.inner_degrees * kPi / 180.0);
        const double c = -dot(dir, l.direction);
        const double t = cos_inner > cos_outer
                             ? std::clamp((c - cos_outer) / (cos_inner - cos_outer), 0.0, 1.0)
                             : (c >= cos_outer ? 1.0 : 0.0);
        a *= t * t;
    }
    return a;
}

/* Linear radiance to an 8-bit display value: a soft shoulder 1 - e^-1.2x
 * (so several lights overlapping do not wash out one light's shadow) and
 * gamma 2.2, through a table of 1/1024 steps up to 8 (a pow and an exp per
 * channel and pixel were most of the lighting pass). */
uint8_t to_display8(double linear) {
    constexpr int kSteps = 1024, kMax = 8;
    static const std::vector<uint8_t> table = [] {
        std::vector<uint8_t> t(kSteps * kMax + 1);
        for (int i = 0; i <= kSteps * kMax; i++) {
            const double v = 1.0 - std::exp(-1.2 * i / kSteps);
            t[(std::size_t)i] = (uint8_t)std::lround(255.0 * std::pow(v, 1.0 / 2.2));
        }
        return t;
    }();
    const double c = std::clamp(linear, 0.0, (double)kMax);
    return table[(std::size_t)(c * kSteps + 0.5)];
}

} // namespace

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

raster::ClipVertex to_clip(const Mat4d &vp, double x, double y, double z, double w) {
    const std::array<double, 4> c = vp.apply(x, y, z, w);
    return {c[0], c[1], c[2], c[3]};
}

bool near_plane_may_be_shadowed(const Camera &camera, double aspect, const SceneSurface &s,
                                const SceneLight &light) {
    const CameraBasis b = basis(camera);
    const Vec3d centre = add(camera.eye, mul(b.f, camera.near_distance));
    const double hh = camera.near_distance * b.tan_half, hw = hh * aspect;
    const Vec3d c[4] = {add(centre, add(mul(b.s, -hw), mul(b.u, -hh))),
                        add(centre, add(mul(b.s, hw), mul(b.u, -hh))),
                        add(centre, add(mul(b.s, hw), mul(b.u, hh))),
                        add(centre, add(mul(b.s, -hw), mul(b.u, hh)))};
    const bool directional = light.kind == LightKind::directional;
    const Vec3d towards = directional ? mul(light.direction, -1.0) : Vec3d{};
    /* The light's side of the near plane, and a point inside the hull. */
    const double light_side =
        directional ? dot(towards, b.f) : dot(sub(light.position, centre), b.f);
    const double scale = camera.near_distance + std::sqrt(hh * hh + hw * hw);
    if (std::fabs(light_side) <= 1e-9 * scale) return true; /* the hull is flat: be safe */
    const Vec3d inside = directional ? add(centre, mul(towards, scale))
                                     : add(mul(centre, 0.5), mul(light.position, 0.5));
    struct Pl {
        Vec3d n;
        double d;
    } planes[5];
    int np = 0;
    for (int i = 0; i < 4; i++) {
        const Vec3d &p = c[i], &q = c[(i + 1) % 4];
        const Vec3d n = directional ? cross(sub(q, p), towards) : cross(sub(q, p), sub(light.position, p));
        Pl pl{n, -dot(n, p)};
        if (dot(pl.n, inside) + pl.d < 0) pl = {mul(n, -1.0), dot(n, p)};
        planes[np++] = pl;
    }
    {
        Pl pl{b.f, -dot(b.f, centre)};
        if (light_side < 0) pl = {mul(b.f, -1.0), dot(b.f, centre)};
        planes[np++] = pl;
    }
    for (int i = 0; i < np; i++) {
        const Pl &p = planes[i];
        /* The box corner furthest along the normal. */
        const Vec3d far{p.n.x >= 0 ? s.hi.x : s.lo.x, p.n.y >= 0 ? s.hi.y : s.lo.y,
                        p.n.z >= 0 ? s.hi.z : s.lo.z};
        if (dot(p.n, far) + p.d < 0) return false;
    }
    return true;
}

raster::ClipVertex shadow_vertex_to_clip(const Mat4d &vp, const PreparedSurface &p, int sv_index,
                                         const Vec4 &L) {
    const Vec3d q = vertex(p, sv_index >> 1);
    return (sv_index & 1) ? to_clip(vp, q.x * L.w - L.x, q.y * L.w - L.y, q.z * L.w - L.z, 0.0)
                          : to_clip(vp, q.x, q.y, q.z, 1.0);
}

Vec3d camera_ray(const Frame &f, double x, double y) {
    const double nx = (x / f.width) * 2 - 1, ny = 1 - (y / f.height) * 2;
    return add(f.ray_forward, add(mul(f.ray_right, nx), mul(f.ray_up, ny)));
}

Vec3d visible_point(const Frame &f, const Scene &scene, int surface, int triangle, int px,
                    int py) {
    const Vec3d dir = camera_ray(f, px + 0.5, py + 0.5);
    const PreparedSurface &p = scene.surfaces[surface].prepared;
    const int *tri = &p.indices[3 * triangle];
    const Vec3d a = vertex(p, tri[0]);
    const Vec3d n = cross(sub(vertex(p, tri[1]), a), sub(vertex(p, tri[2]), a));
    const double den = dot(n, dir);
    const double t = den != 0 ? dot(n, sub(a, f.camera.eye)) / den : 0;
    return add(f.camera.eye, mul(dir, t));
}

Frame render_frame(const Scene &scene, const RenderOptions &opt) {
    Frame f;
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
    const raster::Rasterizer rast(kernels);
    f.target.resize(opt.width, opt.height);

    /* Receivers' vertices in clip space, once. */
    std::vector<std::vector<raster::ClipVertex>> clip(scene.surfaces.size());
    int32_t next_id = 0;
    for (std::size_t si = 0; si < scene.surfaces.size(); si++) {
        const PreparedSurface &p = scene.surfaces[si].prepared;
        f.surface_first_id.push_back(next_id);
        next_id += p.num_triangles();
        clip[si].resize((std::size_t)p.num_vertices());
        for (int v = 0; v < p.num_vertices(); v++) {
            const Vec3d q = vertex(p, v);
            clip[si][(std::size_t)v] = to_clip(f.view_proj, q.x, q.y, q.z, 1.0);
        }
    }

    /* Depth pass. */
    {
        const double t0 = now_seconds();
        const uint64_t k0 = __rdtsc();
        for (std::size_t si = 0; si < scene.surfaces.size(); si++) {
            const PreparedSurface &p = scene.surfaces[si].prepared;
            for (int t = 0; t < p.num_triangles(); t++) {
                const raster::ClipVertex v[3] = {clip[si][(std::size_t)p.indices[3 * t]],
                                                 clip[si][(std::size_t)p.indices[3 * t + 1]],
                                                 clip[si][(std::size_t)p.indices[3 * t + 2]]};
                rast.draw_depth(f.target, v, f.surface_first_id[si] + t, f.depth_counters);
            }
        }
        f.ticks_depth = __rdtsc() - k0;
        f.seconds_depth = now_seconds() - t0;
    }

    /* Per light: facing, volumes, stencil. The facing bytes stay for the
     * lighting pass. */
    std::vector<std::vector<AlignedVector<uint8_t>>> facing(scene.lights.size());
    for (std::size_t li = 0; li < scene.lights.size(); li++) {
        LightFrame lf;
        lf.light = scene.lights[li];
        lf.shadow_light = lf.light.shadow_light();
        const Vec4 L = lf.shadow_light;
        facing[li].resize(scene.surfaces.size());
        for (std::size_t si = 0; si < scene.surfaces.size(); si++) {
            const PreparedSurface &p = scene.surfaces[si].prepared;
            AlignedVector<uint8_t> &fb = facing[li][si];
            fb.assign((std::size_t)p.num_triangles() + 1, 1);
            uint64_t k0 = __rdtsc();
            facing_v->calculate_facing(p.planes.data(), p.num_triangles(), &L, fb.data());
            lf.ticks_facing += __rdtsc() - k0;
            AlignedVector<uint8_t> work = fb; /* the routines may modify facing */
            Volume vol;
            vol.surface = (int)si;
            vol.indices.resize(sv_shadow_volume_capacity(p.num_indices(), p.num_sil_edges()));
            k0 = __rdtsc();
            const int n = sv_create_shadow_volume(variant, vol.indices.data(), p.indices.data(),
                                                  p.num_indices(), p.sil_edges.data(),
                                                  p.num_sil_edges(), work.data(), nullptr);
            lf.ticks_volume += __rdtsc() - k0;
            if (n <= 0) continue;
            vol.indices.resize((std::size_t)n);
            int sil = 0;
            for (const SilEdge &e : p.sil_edges) sil += fb[(std::size_t)e.p1] != fb[(std::size_t)e.p2];
            vol.silhouette_indices = 6 * sil;
            vol.zfail = opt.mode == ModeChoice::zfail ||
                        (opt.mode == ModeChoice::automatic &&
                         near_plane_may_be_shadowed(scene.camera, aspect, scene.surfaces[si],
                                                    lf.light));
            lf.zfail_volumes += vol.zfail;
            lf.indices += n;
            lf.drawn_indices += vol.drawn_indices();
            lf.volumes.push_back(std::move(vol));
        }

        f.target.clear_stencil();
        const double t0 = now_seconds();
        const uint64_t k0 = __rdtsc();
        std::vector<raster::ClipVertex> sv_clip;
        for (const Volume &vol : lf.volumes) {
            const PreparedSurface &p = scene.surfaces[(std::size_t)vol.surface].prepared;
            /* The double-length buffer through the paper's vertex program
             * (the even vertices are the receivers' own, already done). */
            sv_clip.resize(2 * (std::size_t)p.num_vertices());
            for (int v = 0; v < p.num_vertices(); v++) {
                sv_clip[2 * (std::size_t)v] = clip[(std::size_t)vol.surface][(std::size_t)v];
                sv_clip[2 * (std::size_t)v + 1] = shadow_vertex_to_clip(f.view_proj, p, 2 * v + 1, L);
            }
            const raster::StencilMode mode =
                vol.zfail ? raster::StencilMode::zfail : raster::StencilMode::zpass;
            const int drawn = vol.drawn_indices();
            for (int i = 0; i + 2 < drawn; i += 3) {
                const raster::ClipVertex v[3] = {sv_clip[(std::size_t)vol.indices[(std::size_t)i]],
                                                 sv_clip[(std::size_t)vol.indices[(std::size_t)i + 1]],
                                                 sv_clip[(std::size_t)vol.indices[(std::size_t)i + 2]]};
                rast.draw_stencil(f.target, v, mode, lf.stencil_counters);
            }
        }
        lf.ticks_stencil = __rdtsc() - k0;
        lf.seconds_stencil = now_seconds() - t0;
        lf.stencil.assign(f.target.stencil.begin(), f.target.stencil.end());
        f.lights.push_back(std::move(lf));
    }

    /* Lighting: ambient everywhere, each light where its stencil is 0 and
     * the visible side of the triangle faces it. */
    const uint64_t k0 = __rdtsc();
    f.rgb.assign((std::size_t)opt.width * opt.height * 3, 0);
    for (int py = 0; py < opt.height; py++) {
        for (int px = 0; px < opt.width; px++) {
            const std::size_t i = (std::size_t)py * opt.width + px;
            uint8_t *out = &f.rgb[3 * i];
            const int32_t id = f.target.ids[i];
            if (id < 0) {
                const double sky = 0.30 + 0.25 * (1.0 - (double)py / opt.height);
                out[0] = to_display8(sky * 0.55), out[1] = to_display8(sky * 0.65), out[2] = to_display8(sky);
                continue;
            }
            int si, t;
            f.decode_id(id, si, t);
            const SceneSurface &s = scene.surfaces[(std::size_t)si];
            const Vec3d P = visible_point(f, scene, si, t, px, py);
            const Plane &pl = s.prepared.planes[(std::size_t)t];
            Vec3d n{pl.a, pl.b, pl.c};
            const bool front_seen = dot(n, sub(scene.camera.eye, P)) > 0;
            double rgb[3] = {opt.ambient, opt.ambient, opt.ambient};
            if (s.ground) {
                /* A faint checker, so the ground reads as a plane. */
                const bool odd = ((int)std::floor(P.x * 2) + (int)std::floor(P.z * 2)) & 1;
                for (double &c : rgb) c *= odd ? 0.9 : 1.0;
            }
            if (front_seen) {
                for (std::size_t li = 0; li < f.lights.size(); li++) {
                    const LightFrame &lf = f.lights[li];
                    if (lf.stencil[i] != 0 || !facing[li][(std::size_t)si][(std::size_t)t]) continue;
                    const double e = irradiance(lf.light, P, n);
                    for (int c = 0; c < 3; c++) rgb[c] += e * lf.light.color[(std::size_t)c];
                }
            }
            for (int c = 0; c < 3; c++) out[c] = to_display8(rgb[c] * s.albedo[(std::size_t)c]);
        }
    }
    f.ticks_shading = __rdtsc() - k0;
    return f;
}

} // namespace sv::render
