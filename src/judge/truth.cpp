/*
 * Ray-cast truth (truth.h).
 *
 * Copyright (C) 2026 the shadowvol authors. LGPL-2.1-or-later.
 */
#include "truth.h"
#include "volume_faces.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <thread>

#include "ray_triangles.h"

namespace sv::render {

/* Mismatches looked at on the 7 x 7 grid, at most, per light. */
constexpr int kMaxRefined = 2000;

class SceneRays {
public:
    RayTriangles tris; /* triangle k = frame id k */
};

namespace {

Vec3d sub(const Vec3d &a, const Vec3d &b) { return {a.x - b.x, a.y - b.y, a.z - b.z}; }
double dot(const Vec3d &a, const Vec3d &b) { return a.x * b.x + a.y * b.y + a.z * b.z; }

inline Point3 cross3(const Point3 &a, const Point3 &b) {
    return {a.y * b.z - a.z * b.y, a.z * b.x - a.x * b.z, a.x * b.y - a.y * b.x};
}
inline double dot3(const Point3 &a, const Point3 &b) { return a.x * b.x + a.y * b.y + a.z * b.z; }

/* Moller-Trumbore: the s where P + s R meets triangle T of RT, or NaN. */
inline double ray_hit(const RayTriangles &rt, uint32_t t, const Point3 &p, const Point3 &r) {
    const Point3 &e1 = rt.e1[t], &e2 = rt.e2[t];
    const Point3 pv = cross3(r, e2);
    const double det = dot3(e1, pv);
    if (det == 0) return NAN;
    const double inv = 1.0 / det;
    const Point3 tv{p.x - rt.a[t].x, p.y - rt.a[t].y, p.z - rt.a[t].z};
    const double u = dot3(tv, pv) * inv;
    if (u < 0 || u > 1) return NAN;
    const Point3 qv = cross3(tv, e1);
    const double v = dot3(r, qv) * inv;
    if (v < 0 || u + v > 1) return NAN;
    return dot3(e2, qv) * inv;
}

/* Does P + s R, s in (s_min, s_max), cross a triangle other than SKIP? */
bool blocked(const RayTriangles &rt, const Point3 &p, const Point3 &r, double s_min, double s_max,
             uint32_t skip) {
    bool hit = false;
    rt.for_each_candidate(p, r, s_max, [&](uint32_t t) {
        if (t == skip) return true;
        const double s = ray_hit(rt, t, p, r);
        hit = s > s_min && s < s_max; /* false for NaN */
        return !hit;
    });
    return hit;
}

} // namespace

TruthCaster::TruthCaster(const Scene &scene) : scene_(scene), rays_(new SceneRays) {
    double size = 0;
    for (const SceneSurface &s : scene.surfaces) {
        const PreparedSurface &p = s.prepared;
        auto pt = [&](int v) {
            return Point3{p.positions[3 * v], p.positions[3 * v + 1], p.positions[3 * v + 2]};
        };
        for (int t = 0; t < p.num_triangles(); t++) {
            rays_->tris.add(pt(p.indices[3 * t]), pt(p.indices[3 * t + 1]),
                            pt(p.indices[3 * t + 2]));
        }
        size = std::max({size, s.hi.x - s.lo.x, s.hi.y - s.lo.y, s.hi.z - s.lo.z});
    }
    rays_->tris.build(1e-9 * std::max(size, 1.0));
}

TruthCaster::~TruthCaster() = default;

namespace {

/* One pixel in 16, spread over rows and columns. */
inline bool primary_sample(int x, int y) { return (x + 5 * y) % 16 == 0; }

/* Does the depth pass show one triangle over the 3 x 3 pixels around
 * (x, y) (those inside the frame)? */
bool off_depth_edges(const Frame &f, int x, int y) {
    const int32_t id = f.target.ids[(std::size_t)y * f.width + x];
    for (int dy = -1; dy <= 1; dy++) {
        for (int dx = -1; dx <= 1; dx++) {
            const int nx = x + dx, ny = y + dy;
            if (nx < 0 || ny < 0 || nx >= f.width || ny >= f.height) continue;
            if (f.target.ids[(std::size_t)ny * f.width + nx] != id) return false;
        }
    }
    return true;
}

} // namespace

bool TruthCaster::primary_ray_agrees(const Frame &f, int x, int y) const {
    const int32_t id = f.target.ids[(std::size_t)y * f.width + x];
    const Vec3d d = camera_ray(f, x + 0.5, y + 0.5);
    const Point3 o{f.camera.eye.x, f.camera.eye.y, f.camera.eye.z}, r{d.x, d.y, d.z};
    /* d has unit length along the view axis: s is the view depth. */
    double best = HUGE_VAL, s_id = NAN;
    int32_t best_id = -1;
    rays_->tris.for_each_candidate(o, r, HUGE_VAL, [&](uint32_t t) {
        const double s = ray_hit(rays_->tris, t, o, r);
        if (!(s >= f.camera.near_distance)) return true;
        if ((int32_t)t == id) s_id = s;
        if (s < best) best = s, best_id = (int32_t)t;
        return true;
    });
    if (best_id == id) return true;
    if (id < 0 || best_id < 0) return false;
    return std::fabs(s_id - best) <= 1e-6 * best; /* false for NaN: the ray missed ID */
}

uint8_t TruthCaster::light_class(const Frame &f, const std::vector<std::vector<uint8_t>> &facing,
                                 const LightFrame &lf, int si, int t, const Vec3d &P,
                                 uint64_t *rays) const {
    const Vec4 &L = lf.shadow_light;
    const Plane &pl = scene_.surfaces[(std::size_t)si].prepared.planes[(std::size_t)t];
    const Vec3d nrm{pl.a, pl.b, pl.c};
    if (!facing[(std::size_t)si][(std::size_t)t] || dot(nrm, sub(f.camera.eye, P)) <= 0)
        return kTruthDark;
    /* Beyond the range or outside the cone the light gives nothing: dark,
     * whatever lies between (and the frame's shortcuts may leave another
     * stencil there: frame.h). */
    if (!point_in_light_reach(lf.light, P)) return kTruthDark;
    const Point3 p{P.x, P.y, P.z};
    Point3 r;
    double s_max;
    if (L.w == 0) {
        r = {L.x, L.y, L.z};
        s_max = HUGE_VAL;
    } else {
        r = {L.x - P.x, L.y - P.y, L.z - P.z};
        s_max = 1.0;
    }
    (*rays)++;
    const uint32_t id = (uint32_t)(f.surface_first_id[(std::size_t)si] + t);
    return blocked(rays_->tris, p, r, 1e-9, s_max, id) ? kTruthShadowed : kTruthLit;
}

std::vector<std::vector<uint8_t>> TruthCaster::facing_bytes(const Vec4 &L) const {
    std::vector<std::vector<uint8_t>> facing(scene_.surfaces.size());
    for (std::size_t si = 0; si < scene_.surfaces.size(); si++) {
        const PreparedSurface &p = scene_.surfaces[si].prepared;
        facing[si].assign((std::size_t)p.num_triangles() + 1, 1);
        sv_calculate_facing_c_ref(p.planes.data(), p.num_triangles(), &L, facing[si].data());
    }
    return facing;
}

uint8_t TruthCaster::classify_point(const Frame &f, int light, double x, double y) const {
    const LightFrame &lf = f.lights[(std::size_t)light];
    return classify_point(f, facing_bytes(lf.shadow_light), lf, x, y);
}

uint8_t TruthCaster::classify_point(const Frame &f, const std::vector<std::vector<uint8_t>> &facing,
                                    const LightFrame &lf, double x, double y) const {
    const Vec3d d = camera_ray(f, x, y);
    const Point3 o{f.camera.eye.x, f.camera.eye.y, f.camera.eye.z}, r{d.x, d.y, d.z};
    /* The nearest triangle the camera ray meets beyond the near plane
     * (d has unit length along the view axis, so s is the view depth). */
    double best = HUGE_VAL;
    int32_t best_id = -1;
    rays_->tris.for_each_candidate(o, r, HUGE_VAL, [&](uint32_t t) {
        const double s = ray_hit(rays_->tris, t, o, r);
        if (s >= f.camera.near_distance && s < best) best = s, best_id = (int32_t)t;
        return true;
    });
    if (best_id < 0) return kTruthNone;
    int si, t;
    f.decode_id(best_id, si, t);
    const Vec3d P{o.x + best * r.x, o.y + best * r.y, o.z + best * r.z};
    uint64_t rays = 0;
    return light_class(f, facing, lf, si, t, P, &rays);
}

uint8_t TruthCaster::classify_stored_depth(const Frame &f,
                                           const std::vector<std::vector<uint8_t>> &facing,
                                           const LightFrame &lf, int x, int y) const {
    const std::size_t i = (std::size_t)y * f.width + x;
    const int32_t id = f.target.ids[i];
    if (id < 0) return kTruthNone;
    /* Window depth back to view distance through the infinite projection:
     * z_ndc = ((eps - 1) z + (eps - 2) n) / -z, so -z = (2 - eps) n /
     * (1 - eps - z_ndc). */
    const double z_ndc = 2.0 * f.target.depth[i] - 1.0;
    const double den = 1.0 - kInfiniteFarEpsilon - z_ndc;
    if (!(den > 0)) return kTruthNone;
    const double dist = (2.0 - kInfiniteFarEpsilon) * f.camera.near_distance / den;
    const Vec3d d = camera_ray(f, x + 0.5, y + 0.5);
    const Vec3d P{f.camera.eye.x + dist * d.x, f.camera.eye.y + dist * d.y,
                  f.camera.eye.z + dist * d.z};
    int si, t;
    f.decode_id(id, si, t);
    uint64_t rays = 0;
    return light_class(f, facing, lf, si, t, P, &rays);
}

Comparison TruthCaster::compare(const Frame &f, int light, const Truth &truth) const {
    const LightFrame &lf = f.lights[(std::size_t)light];
    const std::vector<std::vector<uint8_t>> facing = facing_bytes(lf.shadow_light);
    int looked_at = 0;
    uint64_t ties = 0;
    std::vector<raster::Rasterizer::WindowTriangle> faces;
    bool faces_ready = false;
    Comparison result = compare_with_stencil(
        truth, f.lights[(std::size_t)light].stencil, f.width, f.height, [&](int x, int y) {
            /* A frame with this many unexplained mismatches fails anyway. */
            if (++looked_at > kMaxRefined) return false;
            /* The point the depth test used: the camera ray at the stored
             * depth. For a receiver seen edge-on, the depth of its snapped
             * triangle can lie well off the exact one. */
            const std::size_t px = (std::size_t)y * f.width + x;
            const uint8_t at_depth = classify_stored_depth(f, facing, lf, x, y);
            if (at_depth != kTruthNone && (at_depth == kTruthLit) != (truth.cls[px] == kTruthLit)) {
                return true;
            }
            bool lit = false, shadow = false;
            for (int j = 0; j < 7; j++) {
                for (int i = 0; i < 7; i++) {
                    const uint8_t c = classify_point(f, facing, lf, x - 1 + (i + 0.5) * 3 / 7.0,
                                                     y - 1 + (j + 0.5) * 3 / 7.0);
                    if (c == kTruthNone) continue;
                    (c == kTruthLit ? lit : shadow) = true;
                    if (lit && shadow) return true;
                }
            }
            /* A volume face through the receiver. */
            if (!faces_ready) {
                faces = drawn_volume_triangles(scene_, f, light);
                faces_ready = true;
            }
            if (face_proximity(faces, f, px, f.target.depth[px]).gap_ulps <= kDepthTieUlps) {
                ties++;
                return true;
            }
            return false;
        });
    result.depth_tie_mismatches = ties;
    result.primary_checked = truth.primary_checked;
    result.primary_disagreements = truth.primary_disagreements;
    result.off_boundary_mismatches += truth.primary_disagreements;
    for (int p : truth.first_primary_disagreements) {
        if (result.first_off_boundary.size() < 16) result.first_off_boundary.push_back(p);
    }
    return result;
}

Truth TruthCaster::cast(const Frame &f, int light, int threads) const {
    const auto t0 = std::chrono::steady_clock::now();
    Truth out;
    const std::size_t n = (std::size_t)f.width * f.height;
    out.cls.assign(n, kTruthNone);
    const LightFrame &lf = f.lights[(std::size_t)light];
    const Vec4 L = lf.shadow_light;
    /* Facing as the volumes saw it: the reference's bytes (every variant
     * gives the same). */
    const std::vector<std::vector<uint8_t>> facing = facing_bytes(L);
    std::vector<uint64_t> rays((std::size_t)std::max(threads, 1), 0);
    std::vector<uint64_t> checked(rays.size(), 0);
    std::vector<std::vector<int>> disagree(rays.size());
    auto work = [&](int k, int step) {
        for (int py = k; py < f.height; py += step) {
            for (int px = 0; px < f.width; px++) {
                const std::size_t i = (std::size_t)py * f.width + px;
                const int32_t id = f.target.ids[i];
                if (id < 0) continue;
                int si, t;
                f.decode_id(id, si, t);
                const Vec3d P = visible_point(f, scene_, si, t, px, py);
                out.cls[i] = light_class(f, facing, lf, si, t, P, &rays[(std::size_t)k]);
                if (primary_sample(px, py) && off_depth_edges(f, px, py)) {
                    checked[(std::size_t)k]++;
                    if (!primary_ray_agrees(f, px, py)) disagree[(std::size_t)k].push_back((int)i);
                }
            }
        }
    };
    const int nt = std::max(threads, 1);
    std::vector<std::thread> pool;
    for (int k = 1; k < nt; k++) pool.emplace_back(work, k, nt);
    work(0, nt);
    for (std::thread &th : pool) th.join();
    for (uint64_t r : rays) out.rays += r;
    for (std::size_t k = 0; k < rays.size(); k++) {
        out.primary_checked += checked[k];
        out.primary_disagreements += disagree[k].size();
        for (int p : disagree[k]) out.first_primary_disagreements.push_back(p);
    }
    std::sort(out.first_primary_disagreements.begin(), out.first_primary_disagreements.end());
    if (out.first_primary_disagreements.size() > 16) out.first_primary_disagreements.resize(16);
    out.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    return out;
}

bool on_boundary(const Truth &truth, int width, int height, int x, int y) {
    const uint8_t c = truth.cls[(std::size_t)y * width + x];
    const bool shadow = c != kTruthLit;
    for (int dy = -1; dy <= 1; dy++) {
        for (int dx = -1; dx <= 1; dx++) {
            const int nx = x + dx, ny = y + dy;
            if (nx < 0 || ny < 0 || nx >= width || ny >= height) continue;
            const uint8_t o = truth.cls[(std::size_t)ny * width + nx];
            if (o != kTruthNone && (o != kTruthLit) != shadow) return true;
        }
    }
    return false;
}

Comparison compare_with_stencil(const Truth &truth, const std::vector<uint8_t> &stencil, int width,
                                int height, const std::function<bool(int x, int y)> &refine) {
    Comparison c;
    for (int y = 0; y < height; y++) {
        for (int x = 0; x < width; x++) {
            const std::size_t i = (std::size_t)y * width + x;
            const uint8_t t = truth.cls[i];
            if (t != kTruthLit && t != kTruthShadowed) continue;
            c.compared++;
            (t == kTruthLit ? c.lit : c.shadowed)++;
            bool boundary = on_boundary(truth, width, height, x, y);
            const bool mismatch = (stencil[i] != 0) != (t == kTruthShadowed);
            bool subpixel = false;
            if (mismatch && !boundary && refine) boundary = subpixel = refine(x, y);
            c.boundary += boundary;
            if (!mismatch) continue;
            c.mismatches++;
            if (boundary) {
                c.boundary_mismatches++;
                c.subpixel_boundary_mismatches += subpixel;
            } else {
                c.off_boundary_mismatches++;
                if (c.first_off_boundary.size() < 16) c.first_off_boundary.push_back((int)i);
            }
        }
    }
    return c;
}

} // namespace sv::render
