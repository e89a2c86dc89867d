/*
 * The frame of frame.h: depth pass, per light the volumes and their
 * stencil, then the lighting pass.
 *
 * Copyright (C) 2026 the shadowvol authors. LGPL-2.1-or-later.
 */
#include "frame.h"

#include <x86intrin.h>

#include <tbb/blocked_range.h>
#include <tbb/global_control.h>
#include <tbb/info.h>
#include <tbb/parallel_for.h>
#include <tbb/partitioner.h>
#include <tbb/task_arena.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstring>
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

/* A light's constants for the lighting pass, worked out once a frame. */
struct LightTerms {
    const SceneLight *l;
    double cos_outer, cos_inner, inv_range2;
    explicit LightTerms(const SceneLight &light)
        : l(&light), cos_outer(std::cos(light.outer_degrees * kPi / 180.0)),
          cos_inner(std::cos(light.inner_degrees * kPi / 180.0)),
          inv_range2(light.range > 0 ? 1.0 / (light.range * light.range) : 0) {}
};

/* Radiance factor of light T at P with unit normal N (Lambert,
 * attenuation, cone), without the colour. */
double irradiance(const LightTerms &t, const Vec3d &p, const Vec3d &n) {
    const SceneLight &l = *t.l;
    if (l.kind == LightKind::directional) {
        return l.intensity * std::max(0.0, -dot(n, l.direction));
    }
    const Vec3d d = sub(l.position, p);
    const double dist2 = dot(d, d);
    const Vec3d dir = mul(d, 1.0 / std::sqrt(dist2));
    double a = l.intensity * std::max(0.0, dot(n, dir)) / dist2;
    if (l.range > 0) {
        /* KHR_lights_punctual's recommended window. */
        const double q = dist2 * t.inv_range2;
        const double w = std::clamp(1.0 - q * q, 0.0, 1.0);
        a *= w * w;
    }
    if (l.kind == LightKind::spot) {
        const double c = -dot(dir, l.direction);
        const double s = t.cos_inner > t.cos_outer
                             ? std::clamp((c - t.cos_outer) / (t.cos_inner - t.cos_outer), 0.0, 1.0)
                             : (c >= t.cos_outer ? 1.0 : 0.0);
        a *= s * s;
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

const char *fate_name(VolumeFate f) {
    switch (f) {
    case VolumeFate::built: return "built";
    case VolumeFate::reused: return "reused";
    case VolumeFate::out_of_reach: return "out of reach";
    case VolumeFate::out_of_view: return "out of view";
    default: return "no shadow";
    }
}

bool light_reaches_box(const SceneLight &l, const Vec3d &lo, const Vec3d &hi, double scale) {
    if (l.kind == LightKind::directional) return true;
    const Vec3d &L = l.position;
    if (l.range > 0) {
        /* Squared distance from the light to the box. */
        const double dx = std::max({lo.x - L.x, 0.0, L.x - hi.x});
        const double dy = std::max({lo.y - L.y, 0.0, L.y - hi.y});
        const double dz = std::max({lo.z - L.z, 0.0, L.z - hi.z});
        const double r = l.range * scale;
        if (dx * dx + dy * dy + dz * dz >= r * r) return false;
    }
    if (l.kind == LightKind::spot) {
        /* The box's bounding sphere against the cone: outside when the
         * angle from the axis to the sphere's centre, less the angle the
         * sphere subtends, is beyond the outer angle. */
        const Vec3d c = mul(add(lo, hi), 0.5);
        const double r = 0.5 * std::sqrt(dot(sub(hi, lo), sub(hi, lo)));
        const Vec3d v = sub(c, L);
        const double dist = std::sqrt(dot(v, v));
        if (dist <= r) return true;
        const double cos_a = std::clamp(dot(v, l.direction) / dist, -1.0, 1.0);
        const double angle = std::acos(cos_a) - std::asin(r / dist);
        if (angle >= l.outer_degrees * scale * kPi / 180.0) return false;
    }
    return true;
}

bool shadow_may_reach_view(const Mat4d &vp, const Vec3d &lo, const Vec3d &hi, const Vec4 &L,
                           bool with_extrusion) {
    std::array<double, 4> pts[16];
    int n = 0;
    for (int i = 0; i < 8; i++) {
        const double x = (i & 1) ? hi.x : lo.x, y = (i & 2) ? hi.y : lo.y, z = (i & 4) ? hi.z : lo.z;
        pts[n++] = vp.apply(x, y, z, 1.0);
        if (with_extrusion) pts[n++] = vp.apply(x * L.w - L.x, y * L.w - L.y, z * L.w - L.z, 0.0);
    }
    for (int p = 0; p < 5; p++) {
        bool all_out = true;
        for (int i = 0; i < n && all_out; i++) {
            const auto &q = pts[i];
            const double d = p == 0   ? q[2] + q[3]
                             : p == 1 ? q[0] + q[3]
                             : p == 2 ? q[3] - q[0]
                             : p == 3 ? q[1] + q[3]
                                      : q[3] - q[1];
            /* A margin for the rounding of the transform: the rasteriser
             * transforms each vertex on its own. */
            const double scale = std::fabs(q[0]) + std::fabs(q[1]) + std::fabs(q[2]) + std::fabs(q[3]);
            all_out = d < -1e-9 * scale;
        }
        if (all_out) return false;
    }
    return true;
}

bool light_volume_planes(const SceneLight &l, Plane planes[SV_NUM_LIGHT_PLANES], double shrink) {
    auto plane = [](const Vec3d &n, const Vec3d &through) {
        return Plane{(float)n.x, (float)n.y, (float)n.z, (float)-dot(n, through)};
    };
    /* A little larger than the range and the cone, so that rounding the
     * planes to float never cuts into the lit region. */
    constexpr double kGrow = 1 + 1.0 / 4096;
    const Vec3d &L = l.position;
    if (l.kind == LightKind::point) {
        if (!(l.range > 0)) return false;
        const double r = l.range * kGrow * shrink;
        planes[0] = plane({1, 0, 0}, {L.x - r, 0, 0});
        planes[1] = plane({-1, 0, 0}, {L.x + r, 0, 0});
        planes[2] = plane({0, 1, 0}, {0, L.y - r, 0});
        planes[3] = plane({0, -1, 0}, {0, L.y + r, 0});
        planes[4] = plane({0, 0, 1}, {0, 0, L.z - r});
        planes[5] = plane({0, 0, -1}, {0, 0, L.z + r});
        return true;
    }
    if (l.kind != LightKind::spot) return false;
    const Vec3d a = normalized(l.direction);
    const Vec3d helper = std::fabs(a.x) < 0.9 ? Vec3d{1, 0, 0} : Vec3d{0, 1, 0};
    const Vec3d u = normalized(cross(a, helper)), v = cross(a, u);
    const double theta = std::min(l.outer_degrees * kGrow * shrink, 89.999) * kPi / 180.0;
    const double st = std::sin(theta), ct = std::cos(theta);
    /* Side planes through the apex, tilted THETA from the axis: a point at
     * angle phi towards U has n . (x - L) = sin(theta - phi) |x - L|. */
    const Vec3d side[4] = {u, mul(u, -1), v, mul(v, -1)};
    for (int i = 0; i < 4; i++) planes[i] = plane(sub(mul(a, st), mul(side[i], ct)), L);
    planes[4] = plane(a, L); /* the apex plane: the pyramid's other nappe is out */
    if (l.range > 0) {
        planes[5] = plane(mul(a, -1), add(L, mul(a, l.range * kGrow * shrink)));
    } else {
        planes[5] = Plane{0, 0, 0, 1}; /* always in front */
    }
    return true;
}

BoxSide classify_box(const Plane planes[SV_NUM_LIGHT_PLANES], const Vec3d &lo, const Vec3d &hi) {
    bool inside = true;
    for (int i = 0; i < SV_NUM_LIGHT_PLANES; i++) {
        const Plane &p = planes[i];
        const double nearest = p.a * (p.a >= 0 ? lo.x : hi.x) + p.b * (p.b >= 0 ? lo.y : hi.y) +
                               p.c * (p.c >= 0 ? lo.z : hi.z) + p.d;
        const double farthest = p.a * (p.a >= 0 ? hi.x : lo.x) + p.b * (p.b >= 0 ? hi.y : lo.y) +
                                p.c * (p.c >= 0 ? hi.z : lo.z) + p.d;
        if (farthest < 0) return BoxSide::outside;
        if (nearest < 0) inside = false;
    }
    return inside ? BoxSide::inside : BoxSide::straddles;
}

bool pixel_in_light_reach(const Frame &f, const Scene &scene, int li, std::size_t i) {
    const int32_t id = f.target.ids[i];
    if (id < 0) return false;
    int si, t;
    f.decode_id(id, si, t);
    const SceneSurface &s = scene.surfaces[(std::size_t)si];
    const SceneLight &l = scene.lights[(std::size_t)li];
    if (!light_reaches_box(l, s.lo, s.hi)) return false;
    return point_in_light_reach(
        l, visible_point(f, scene, si, t, (int)(i % (std::size_t)f.width), (int)(i / (std::size_t)f.width)));
}

bool point_in_light_reach(const SceneLight &l, const Vec3d &P) {
    if (l.kind == LightKind::directional) return true;
    const Vec3d d = sub(P, l.position);
    const double dist = std::sqrt(dot(d, d));
    if (l.range > 0 && dist >= l.range) return false;
    if (l.kind == LightKind::spot &&
        dot(d, l.direction) <= dist * std::cos(l.outer_degrees * kPi / 180.0)) {
        return false;
    }
    return true;
}

FrameDifference compare_frames(const Scene &scene, const Frame &a, const Frame &b) {
    FrameDifference d;
    if (a.rgb.size() != b.rgb.size() || a.lights.size() != b.lights.size()) {
        d.rgb_bytes = std::max(a.rgb.size(), b.rgb.size());
        d.first_rgb = 0;
        return d;
    }
    for (std::size_t i = 0; i < a.rgb.size(); i++) {
        if (a.rgb[i] == b.rgb[i]) continue;
        if (d.rgb_bytes++ == 0) d.first_rgb = i / 3;
    }
    for (std::size_t li = 0; li < a.lights.size(); li++) {
        const auto &sa = a.lights[li].stencil, &sb = b.lights[li].stencil;
        for (std::size_t i = 0; i < sa.size(); i++) {
            if ((sa[i] == 0) == (sb[i] == 0)) continue;
            if (pixel_in_light_reach(a, scene, (int)li, i)) {
                if (d.mask_in_reach++ == 0) d.first_mask = i;
            } else {
                d.mask_elsewhere++;
            }
        }
    }
    return d;
}

/* What a (light, surface) pair keeps from frame to frame. */
struct VolumeCache::Entry {
    bool valid = false;
    /* The key: the surface's revision, the light, the kernels and the
     * shortcuts that shape the result. */
    uint64_t revision = 0;
    Vec4 light{};
    Plane planes[SV_NUM_LIGHT_PLANES]{};
    bool has_planes = false;
    const sv_variant *variant = nullptr;
    const sv_facing_variant *facing_variant = nullptr;
    unsigned config = 0;
    /* The volume. */
    AlignedVector<uint8_t> facing;        /* calculate_facing's bytes: the lighting pass's */
    AlignedVector<uint8_t> volume_facing; /* after culling */
    bool straddles = false, cull_bits = false;
    int casting = 0;                      /* triangles that cast */
    AlignedVector<int> sil, caps;
    int sil_count = -1, caps_count = -1;  /* -1: not built yet */
    bool dark_cap_dropped = false;
};

VolumeCache::VolumeCache() : entries_(new std::vector<Entry>) {}
VolumeCache::~VolumeCache() { delete entries_; }
void VolumeCache::clear() {
    entries_->clear();
    lights = surfaces = 0;
}

namespace {

constexpr int kBandRows = 32;          /* rows per screen band */
constexpr int kSetupChunk = 4096;      /* triangles per set-up task */

uint64_t ticks() { return __rdtsc(); }

/* Runs BODY(i) for i in [0, n) on the arena's threads. */
template <class Body> void parallel(int n, Body &&body) {
    tbb::parallel_for(tbb::blocked_range<int>(0, n, 1), [&](const tbb::blocked_range<int> &r) {
        for (int i = r.begin(); i != r.end(); i++) body(i);
    }, tbb::simple_partitioner());
}

/* Triangles set up in chunks (in parallel), then binned to bands in
 * submission order, so every band walks its triangles in that order. */
struct BinnedTriangles {
    std::vector<std::vector<raster::SetupTriangle>> chunks;
    std::vector<raster::StencilMode> chunk_mode;
    std::vector<std::vector<std::pair<int, int>>> bands; /* (chunk, piece) */
    raster::PassCounters counters;                       /* triangle counts */
    void bin(int height) {
        bands.assign((std::size_t)((height + kBandRows - 1) / kBandRows), {});
        for (std::size_t c = 0; c < chunks.size(); c++) {
            for (std::size_t i = 0; i < chunks[c].size(); i++) {
                const raster::SetupTriangle &t = chunks[c][i];
                for (int b = t.y_first / kBandRows; b <= t.y_last / kBandRows; b++) {
                    bands[(std::size_t)b].push_back({(int)c, (int)i});
                }
            }
        }
    }
};

raster::RowBand band_rows(int b, int height) {
    return {b * kBandRows, std::min(height, (b + 1) * kBandRows)};
}

} // namespace

Frame render_frame(const Scene &scene, const RenderOptions &opt) {
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
    const Shortcuts &sc = opt.shortcuts;
    const ShortcutFaults &fault = opt.faults;
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
    const int num_surfaces = (int)scene.surfaces.size(), num_lights = (int)scene.lights.size();
    const int num_bands = (opt.height + kBandRows - 1) / kBandRows;

    /* The cache: the caller's (shortcut 6), else one for this frame only. */
    VolumeCache local_cache;
    VolumeCache &cache = (opt.cache && sc.reuse_static) ? *opt.cache : local_cache;
    if (cache.lights != num_lights || cache.surfaces != num_surfaces) {
        cache.clear();
        cache.lights = num_lights;
        cache.surfaces = num_surfaces;
        cache.entries().resize((std::size_t)num_lights * (std::size_t)num_surfaces);
    }

    std::vector<std::vector<raster::ClipVertex>> clip((std::size_t)num_surfaces);
    int32_t next_id = 0;
    for (int si = 0; si < num_surfaces; si++) {
        f.surface_first_id.push_back(next_id);
        next_id += scene.surfaces[(std::size_t)si].prepared.num_triangles();
    }

    arena.execute([&] {
        /* Receivers' vertices in clip space, once. */
        parallel(num_surfaces, [&](int si) {
            const PreparedSurface &p = scene.surfaces[(std::size_t)si].prepared;
            clip[(std::size_t)si].resize((std::size_t)p.num_vertices());
            for (int v = 0; v < p.num_vertices(); v++) {
                const Vec3d q = vertex(p, v);
                clip[(std::size_t)si][(std::size_t)v] = to_clip(f.view_proj, q.x, q.y, q.z, 1.0);
            }
        });

        /* Depth pass: set-up in chunks, then the bands. */
        {
            const double t0 = now_seconds();
            const uint64_t k0 = ticks();
            struct Chunk {
                int surface, first, last;
            };
            std::vector<Chunk> chunks;
            for (int si = 0; si < num_surfaces; si++) {
                const int n = scene.surfaces[(std::size_t)si].prepared.num_triangles();
                for (int t = 0; t < n; t += kSetupChunk) chunks.push_back({si, t, std::min(n, t + kSetupChunk)});
            }
            BinnedTriangles bt;
            bt.chunks.resize(chunks.size());
            std::vector<raster::PassCounters> cc(chunks.size());
            parallel((int)chunks.size(), [&](int c) {
                const Chunk &ch = chunks[(std::size_t)c];
                const PreparedSurface &p = scene.surfaces[(std::size_t)ch.surface].prepared;
                const auto &cv = clip[(std::size_t)ch.surface];
                for (int t = ch.first; t < ch.last; t++) {
                    const raster::ClipVertex v[3] = {cv[(std::size_t)p.indices[3 * (std::size_t)t]],
                                                     cv[(std::size_t)p.indices[3 * (std::size_t)t + 1]],
                                                     cv[(std::size_t)p.indices[3 * (std::size_t)t + 2]]};
                    rast.setup(v, opt.width, opt.height, f.surface_first_id[(std::size_t)ch.surface] + t,
                               cc[(std::size_t)c], bt.chunks[(std::size_t)c]);
                }
            });
            for (const auto &c : cc) f.depth_counters.add(c);
            bt.bin(opt.height);
            std::vector<raster::RowCounts> rc((std::size_t)num_bands);
            parallel(num_bands, [&](int b) {
                const raster::RowBand band = band_rows(b, opt.height);
                for (const auto &[c, i] : bt.bands[(std::size_t)b]) {
                    rast.walk_depth(bt.chunks[(std::size_t)c][(std::size_t)i], f.target, band, rc[(std::size_t)b]);
                }
            });
            for (const auto &r : rc) raster::Rasterizer::add_depth_counts(r, f.depth_counters);
            f.ticks_depth = ticks() - k0;
            f.seconds_depth = now_seconds() - t0;
        }

        /* The (light, surface) jobs: the decisions, and the volumes built
         * or reused. */
        f.lights.resize((std::size_t)num_lights);
        std::vector<std::array<uint64_t, 3>> job_ticks((std::size_t)num_lights * num_surfaces);
        std::vector<Volume> job_volume((std::size_t)num_lights * num_surfaces);
        for (int li = 0; li < num_lights; li++) {
            LightFrame &lf = f.lights[(std::size_t)li];
            lf.light = scene.lights[(std::size_t)li];
            lf.shadow_light = lf.light.shadow_light();
            lf.decisions.resize((std::size_t)num_surfaces);
        }
        const uint64_t k_jobs = ticks();
        parallel(num_lights * num_surfaces, [&](int job) {
            const int li = job / num_surfaces, si = job % num_surfaces;
            LightFrame &lf = f.lights[(std::size_t)li];
            const SceneSurface &s = scene.surfaces[(std::size_t)si];
            const PreparedSurface &p = s.prepared;
            const SceneLight &light = lf.light;
            const Vec4 L = lf.shadow_light;
            VolumeDecision &d = lf.decisions[(std::size_t)si];
            VolumeCache::Entry &e = cache.entries()[(std::size_t)job];
            auto &tk = job_ticks[(std::size_t)job];
            d.surface = si;
            /* 1 and 2: no volume at all. */
            if (sc.light_reach && !light_reaches_box(light, s.lo, s.hi, fault.light_reach_scale)) {
                d.fate = VolumeFate::out_of_reach;
                e.valid = false;
                return;
            }
            if (sc.view_reach && !shadow_may_reach_view(f.view_proj, s.lo, s.hi, L, !fault.view_reach_no_extrusion)) {
                d.fate = VolumeFate::out_of_view;
                return; /* the entry stays for a later frame */
            }
            Plane planes[SV_NUM_LIGHT_PLANES];
            const bool has_planes = (sc.cull_straddling || sc.cull_always) &&
                                    light_volume_planes(light, planes, fault.cull_inside_planes ? 0.5 : 1.0);
            const bool dark_drop = (sc.no_directional_dark_cap && light.kind == LightKind::directional) ||
                                   fault.drop_dark_cap_always;
            const unsigned config = (sc.cull_straddling ? 1u : 0u) | (dark_drop ? 2u : 0u) |
                                    (fault.cull_inside_planes ? 4u : 0u) | (sc.cull_always ? 8u : 0u);
            const bool same_light = e.valid && std::memcmp(&e.light, &L, sizeof L) == 0 &&
                                    e.has_planes == has_planes &&
                                    (!has_planes || std::memcmp(e.planes, planes, sizeof planes) == 0);
            const bool reuse = sc.reuse_static && e.valid && same_light && e.variant == variant &&
                               e.facing_variant == facing_v && e.config == config &&
                               (e.revision == s.revision || fault.reuse_ignores_motion);
            if (!reuse) {
                e = VolumeCache::Entry{};
                e.valid = true;
                e.revision = s.revision;
                e.light = L;
                e.has_planes = has_planes;
                if (has_planes) std::memcpy(e.planes, planes, sizeof planes);
                e.variant = variant;
                e.facing_variant = facing_v;
                e.config = config;
                const int n = p.num_triangles();
                e.facing.assign((std::size_t)n + 1, 1);
                uint64_t k0 = ticks();
                facing_v->calculate_facing(p.planes.data(), n, &L, e.facing.data());
                tk[0] += ticks() - k0;
                e.volume_facing = e.facing;
                k0 = ticks();
                if (has_planes) {
                    const BoxSide side = classify_box(planes, s.lo, s.hi);
                    e.straddles = side != BoxSide::inside;
                    if (e.straddles || sc.cull_always) {
                        /* 3: the culling routine, only here. */
                        const std::vector<Vec4> pos = positions_vec4(p);
                        const Vec3d c = mul(add(s.lo, s.hi), 0.5), x = mul(sub(s.hi, s.lo), 0.5);
                        const Bounds bounds{{(float)c.x, (float)c.y, (float)c.z, 1},
                                            {(float)x.x * (1 + 1e-6f), (float)x.y * (1 + 1e-6f),
                                             (float)x.z * (1 + 1e-6f), 0}};
                        AlignedVector<uint8_t> bits((std::size_t)p.num_vertices() + 1, 0);
                        const int inside = facing_v->calculate_cull_bits(pos.data(), p.num_vertices(), &bounds,
                                                                         planes, bits.data());
                        if (!inside || sc.cull_always) {
                            /* (cull_always: bits all 0 where the routine
                             * found the box inside, as it leaves them.) */
                            e.cull_bits = true;
                            e.casting = n - variant->count_facing_cull(e.volume_facing.data(), n,
                                                                       p.indices.data(), bits.data());
                        }
                    }
                }
                tk[1] += ticks() - k0;
                k0 = ticks();
                if (!e.cull_bits) e.casting = n - variant->count_facing(e.volume_facing.data(), n);
                tk[2] += ticks() - k0;
            }
            d.fate = reuse ? VolumeFate::reused : VolumeFate::built;
            d.straddles = e.straddles;
            d.cull_bits = e.cull_bits;
            if (e.casting == 0) {
                if (!reuse) d.fate = VolumeFate::no_shadow;
                return;
            }
            /* 4: caps only for z-fail. */
            bool zfail;
            if (opt.mode == ModeChoice::zfail) {
                zfail = true;
            } else if (opt.mode == ModeChoice::zpass) {
                zfail = false;
            } else if (!sc.zpass_when_safe) {
                zfail = true;
            } else {
                zfail = !fault.zpass_always && near_plane_may_be_shadowed(scene.camera, aspect, s, light);
            }
            const uint64_t k0 = ticks();
            if (e.sil_count < 0) {
                e.sil.resize(6 * (std::size_t)p.num_sil_edges() + 8);
                e.sil_count = variant->create_sil_triangles(e.sil.data(), e.volume_facing.data(),
                                                            p.sil_edges.data(), p.num_sil_edges());
                d.indices_built += e.sil_count;
            }
            if (zfail && e.caps_count < 0) {
                e.caps.resize(2 * (std::size_t)p.num_indices() + 8);
                int n = variant->create_cap_triangles(e.caps.data(), e.volume_facing.data(),
                                                      p.indices.data(), p.num_indices());
                if (dark_drop) {
                    /* 5: each cap pair is the near cap (3 indices) then the
                     * dark cap (3): keep the near ones. */
                    int k = 0;
                    for (int i = 0; i < n; i += 6) {
                        for (int j = 0; j < 3; j++) e.caps[(std::size_t)(k + j)] = e.caps[(std::size_t)(i + j)];
                        k += 3;
                    }
                    n = k;
                    e.dark_cap_dropped = true;
                }
                e.caps_count = n;
                d.indices_built += n;
            }
            tk[2] += ticks() - k0;
            d.zfail = zfail;
            d.dark_cap_dropped = zfail && e.dark_cap_dropped;
            Volume &vol = job_volume[(std::size_t)job];
            vol.surface = si;
            vol.zfail = zfail;
            vol.silhouette_indices = e.sil_count;
            vol.indices.assign(e.sil.begin(), e.sil.begin() + e.sil_count);
            if (zfail) vol.indices.insert(vol.indices.end(), e.caps.begin(), e.caps.begin() + e.caps_count);
            d.indices_drawn = vol.drawn_indices();
        });
        f.ticks_jobs = ticks() - k_jobs;
        for (int li = 0; li < num_lights; li++) {
            LightFrame &lf = f.lights[(std::size_t)li];
            for (int si = 0; si < num_surfaces; si++) {
                const std::size_t job = (std::size_t)li * num_surfaces + si;
                const VolumeDecision &d = lf.decisions[(std::size_t)si];
                lf.ticks_facing += job_ticks[job][0];
                lf.ticks_culling += job_ticks[job][1];
                lf.ticks_volume += job_ticks[job][2];
                lf.built += d.fate == VolumeFate::built || d.fate == VolumeFate::no_shadow;
                lf.reused += d.fate == VolumeFate::reused;
                lf.out_of_reach += d.fate == VolumeFate::out_of_reach;
                lf.out_of_view += d.fate == VolumeFate::out_of_view;
                lf.culled += d.cull_bits;
                lf.built_indices += d.indices_built;
                Volume &vol = job_volume[job];
                if (vol.indices.empty()) continue;
                lf.zfail_volumes += vol.zfail;
                lf.indices += (int64_t)vol.indices.size();
                lf.drawn_indices += vol.drawn_indices();
                lf.volumes.push_back(std::move(vol));
            }
        }

        /* Per light: the stencil pass, set up per volume, walked per band. */
        for (int li = 0; li < num_lights; li++) {
            LightFrame &lf = f.lights[(std::size_t)li];
            const Vec4 L = lf.shadow_light;
            const double t0 = now_seconds();
            const uint64_t k0 = ticks();
            lf.stencil.assign((std::size_t)opt.width * opt.height, 0);
            struct Chunk {
                int volume, first, last;
            };
            std::vector<Chunk> chunks;
            for (int vi = 0; vi < (int)lf.volumes.size(); vi++) {
                const int n = lf.volumes[(std::size_t)vi].drawn_indices() / 3;
                for (int t = 0; t < n; t += kSetupChunk) chunks.push_back({vi, t, std::min(n, t + kSetupChunk)});
            }
            /* The double-length buffers through the paper's vertex program
             * (the even vertices are the receivers' own, already done). */
            std::vector<std::vector<raster::ClipVertex>> sv_clip(lf.volumes.size());
            parallel((int)lf.volumes.size(), [&](int vi) {
                const Volume &vol = lf.volumes[(std::size_t)vi];
                const PreparedSurface &p = scene.surfaces[(std::size_t)vol.surface].prepared;
                auto &out = sv_clip[(std::size_t)vi];
                out.resize(2 * (std::size_t)p.num_vertices());
                for (int v = 0; v < p.num_vertices(); v++) {
                    out[2 * (std::size_t)v] = clip[(std::size_t)vol.surface][(std::size_t)v];
                    out[2 * (std::size_t)v + 1] = shadow_vertex_to_clip(f.view_proj, p, 2 * v + 1, L);
                }
            });
            BinnedTriangles bt;
            bt.chunks.resize(chunks.size());
            std::vector<raster::PassCounters> cc(chunks.size());
            parallel((int)chunks.size(), [&](int c) {
                const Chunk &ch = chunks[(std::size_t)c];
                const Volume &vol = lf.volumes[(std::size_t)ch.volume];
                const auto &cv = sv_clip[(std::size_t)ch.volume];
                for (int t = ch.first; t < ch.last; t++) {
                    const raster::ClipVertex v[3] = {cv[(std::size_t)vol.indices[3 * (std::size_t)t]],
                                                     cv[(std::size_t)vol.indices[3 * (std::size_t)t + 1]],
                                                     cv[(std::size_t)vol.indices[3 * (std::size_t)t + 2]]};
                    rast.setup(v, opt.width, opt.height, 0, cc[(std::size_t)c], bt.chunks[(std::size_t)c]);
                }
            });
            for (std::size_t c = 0; c < chunks.size(); c++) {
                lf.stencil_counters.add(cc[c]);
                bt.chunk_mode.push_back(lf.volumes[(std::size_t)chunks[c].volume].zfail ? raster::StencilMode::zfail
                                                                                     : raster::StencilMode::zpass);
            }
            bt.bin(opt.height);
            std::vector<raster::RowCounts> rc((std::size_t)num_bands);
            parallel(num_bands, [&](int b) {
                const raster::RowBand band = band_rows(b, opt.height);
                for (const auto &[c, i] : bt.bands[(std::size_t)b]) {
                    rast.walk_stencil(bt.chunks[(std::size_t)c][(std::size_t)i], f.target.depth.data(),
                                      lf.stencil.data(), opt.width, opt.height, band,
                                      bt.chunk_mode[(std::size_t)c], rc[(std::size_t)b]);
                }
            });
            for (const auto &r : rc) raster::Rasterizer::add_stencil_counts(r, lf.stencil_counters);
            lf.ticks_stencil = ticks() - k0;
            lf.seconds_stencil = now_seconds() - t0;
        }
        /* The target's own stencil holds the last light's, as before. */
        if (num_lights > 0) {
            std::copy(f.lights.back().stencil.begin(), f.lights.back().stencil.end(), f.target.stencil.begin());
        }

        /* Lighting: ambient everywhere, each light where its stencil is 0,
         * the visible side of the triangle faces it and the light reaches
         * the surface at all. */
        const uint64_t k0 = ticks();
        f.rgb.assign((std::size_t)opt.width * opt.height * 3, 0);
        std::vector<LightTerms> terms;
        for (int li = 0; li < num_lights; li++) terms.emplace_back(f.lights[(std::size_t)li].light);
        /* Per (light, surface): the facing bytes its volume was built from
         * this frame (or reused: the same surface revision and light), or
         * nothing where the light does not reach the surface. A surface
         * whose volume was skipped out of view has no pixel (and would be
         * left unlit if it had one: the proof would see it). */
        std::vector<const uint8_t *> lit_facing((std::size_t)num_lights * num_surfaces, nullptr);
        for (int li = 0; li < num_lights; li++) {
            const Vec4 L = f.lights[(std::size_t)li].shadow_light;
            for (int si = 0; si < num_surfaces; si++) {
                const SceneSurface &s = scene.surfaces[(std::size_t)si];
                const VolumeCache::Entry &e = cache.entries()[(std::size_t)li * num_surfaces + si];
                if (light_reaches_box(scene.lights[(std::size_t)li], s.lo, s.hi) && e.valid &&
                    e.revision == s.revision && std::memcmp(&e.light, &L, sizeof L) == 0 && !e.facing.empty()) {
                    lit_facing[(std::size_t)li * num_surfaces + si] = e.facing.data();
                }
            }
        }
        parallel(num_bands, [&](int b) {
            const raster::RowBand band = band_rows(b, opt.height);
            for (int py = band.row_begin; py < band.row_end; py++) {
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
                        for (int li = 0; li < num_lights; li++) {
                            const LightFrame &lf = f.lights[(std::size_t)li];
                            const uint8_t *facing = lit_facing[(std::size_t)li * num_surfaces + si];
                            if (lf.stencil[i] != 0 || !facing || !facing[(std::size_t)t]) continue;
                            const double en = irradiance(terms[(std::size_t)li], P, n);
                            for (int c = 0; c < 3; c++) rgb[c] += en * lf.light.color[(std::size_t)c];
                        }
                    }
                    for (int c = 0; c < 3; c++) out[c] = to_display8(rgb[c] * s.albedo[(std::size_t)c]);
                }
            }
        });
        f.ticks_shading = ticks() - k0;
    });
    f.ticks_total = ticks() - k_start;
    return f;
}

} // namespace sv::render
