/*
 * Ray-cast truth (truth.h).
 *
 * Copyright (C) 2026 the shadowvol authors. LGPL-2.1-or-later.
 */
#include "truth.h"

#include <chrono>
#include <cmath>
#include <thread>

#include "ray_triangles.h"

namespace sv::render {

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

/* Does P + s R, s in (s_min, s_max), cross a triangle other than SKIP? */
bool blocked(const RayTriangles &rt, const Point3 &p, const Point3 &r, double s_min,
             double s_max, uint32_t skip) {
    bool hit = false;
    rt.for_each_candidate(p, r, s_max, [&](uint32_t t) {
        if (t == skip) return true;
        const Point3 &e1 = rt.e1[t], &e2 = rt.e2[t];
        const Point3 pv = cross3(r, e2);
        const double det = dot3(e1, pv);
        if (det == 0) return true;
        const double inv = 1.0 / det;
        const Point3 tv{p.x - rt.a[t].x, p.y - rt.a[t].y, p.z - rt.a[t].z};
        const double u = dot3(tv, pv) * inv;
        if (u < 0 || u > 1) return true;
        const Point3 qv = cross3(tv, e1);
        const double v = dot3(r, qv) * inv;
        if (v < 0 || u + v > 1) return true;
        const double s = dot3(e2, qv) * inv;
        if (s > s_min && s < s_max) {
            hit = true;
            return false;
        }
        return true;
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
            rays_->tris.add(pt(p.indices[3 * t]), pt(p.indices[3 * t + 1]), pt(p.indices[3 * t + 2]));
        }
        size = std::max({size, s.hi.x - s.lo.x, s.hi.y - s.lo.y, s.hi.z - s.lo.z});
    }
    rays_->tris.build(1e-9 * std::max(size, 1.0));
}

TruthCaster::~TruthCaster() = default;

Truth TruthCaster::cast(const Frame &f, int light, int threads) const {
    const auto t0 = std::chrono::steady_clock::now();
    Truth out;
    const std::size_t n = (std::size_t)f.width * f.height;
    out.cls.assign(n, kTruthNone);
    const LightFrame &lf = f.lights[(std::size_t)light];
    const Vec4 L = lf.shadow_light;
    /* Facing as the volumes saw it: the reference's bytes (every variant
     * gives the same). */
    std::vector<std::vector<uint8_t>> facing(scene_.surfaces.size());
    for (std::size_t si = 0; si < scene_.surfaces.size(); si++) {
        const PreparedSurface &p = scene_.surfaces[si].prepared;
        facing[si].assign((std::size_t)p.num_triangles() + 1, 1);
        sv_calculate_facing_c_ref(p.planes.data(), p.num_triangles(), &L, facing[si].data());
    }
    std::vector<uint64_t> rays((std::size_t)std::max(threads, 1), 0);
    auto work = [&](int k, int step) {
        for (int py = k; py < f.height; py += step) {
            for (int px = 0; px < f.width; px++) {
                const std::size_t i = (std::size_t)py * f.width + px;
                const int32_t id = f.target.ids[i];
                if (id < 0) continue;
                int si, t;
                f.decode_id(id, si, t);
                const Vec3d P = visible_point(f, scene_, si, t, px, py);
                const Plane &pl = scene_.surfaces[(std::size_t)si].prepared.planes[(std::size_t)t];
                const Vec3d nrm{pl.a, pl.b, pl.c};
                if (!facing[(std::size_t)si][(std::size_t)t] || dot(nrm, sub(f.camera.eye, P)) <= 0) {
                    out.cls[i] = kTruthDark;
                    continue;
                }
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
                rays[(std::size_t)k]++;
                out.cls[i] = blocked(rays_->tris, p, r, 1e-9, s_max, (uint32_t)id) ? kTruthShadowed
                                                                                  : kTruthLit;
            }
        }
    };
    const int nt = std::max(threads, 1);
    std::vector<std::thread> pool;
    for (int k = 1; k < nt; k++) pool.emplace_back(work, k, nt);
    work(0, nt);
    for (std::thread &th : pool) th.join();
    for (uint64_t r : rays) out.rays += r;
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

Comparison compare_with_stencil(const Truth &truth, const std::vector<uint8_t> &stencil,
                                int width, int height) {
    Comparison c;
    for (int y = 0; y < height; y++) {
        for (int x = 0; x < width; x++) {
            const std::size_t i = (std::size_t)y * width + x;
            const uint8_t t = truth.cls[i];
            if (t != kTruthLit && t != kTruthShadowed) continue;
            c.compared++;
            (t == kTruthLit ? c.lit : c.shadowed)++;
            const bool boundary = on_boundary(truth, width, height, x, y);
            c.boundary += boundary;
            if ((stencil[i] != 0) == (t == kTruthShadowed)) continue;
            c.mismatches++;
            if (boundary) {
                c.boundary_mismatches++;
            } else {
                c.off_boundary_mismatches++;
                if (c.first_off_boundary.size() < 16) c.first_off_boundary.push_back((int)i);
            }
        }
    }
    return c;
}

} // namespace sv::render
