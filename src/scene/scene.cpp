/*
 * The static scene of include/shadowvol_scene.h: matrices, placement of
 * glTF surfaces, the ground, the automatic camera and lights, and the
 * checks that keep a bad scene from becoming a silent wrong picture.
 *
 * Copyright (C) 2026 the shadowvol authors. LGPL-2.1-or-later.
 */
#include "shadowvol_scene.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>

#include "shadowvol_gltf.h"

namespace sv {
namespace {

constexpr double kPi = 3.14159265358979323846;

Vec3d sub(const Vec3d &a, const Vec3d &b) { return {a.x - b.x, a.y - b.y, a.z - b.z}; }
Vec3d cross(const Vec3d &a, const Vec3d &b) {
    return {a.y * b.z - a.z * b.y, a.z * b.x - a.x * b.z, a.x * b.y - a.y * b.x};
}
double dot(const Vec3d &a, const Vec3d &b) { return a.x * b.x + a.y * b.y + a.z * b.z; }
double length(const Vec3d &a) { return std::sqrt(dot(a, a)); }
Vec3d normalized(const Vec3d &a) {
    const double l = length(a);
    return {a.x / l, a.y / l, a.z / l};
}
bool finite(const Vec3d &a) {
    return std::isfinite(a.x) && std::isfinite(a.y) && std::isfinite(a.z);
}
std::string fmt(const Vec3d &a) {
    char b[96];
    std::snprintf(b, sizeof b, "(%g, %g, %g)", a.x, a.y, a.z);
    return b;
}

/* Parity of the crossings of a ray from P with the surface's triangles:
 * inside a closed surface when odd. The ray's direction is fixed and
 * irrational-looking so it rarely grazes an edge; good enough for a note. */
bool inside_closed_surface(const SceneSurface &s, const Vec3d &p) {
    const PrepareReport &r = s.prepared.report;
    if (r.boundary_edges || r.non_manifold_edges || r.same_direction_edges ||
        s.prepared.num_triangles() == 0) {
        return false;
    }
    const Vec3d dir = normalized({0.5773, 0.8017, 0.1543});
    const float *pos = s.prepared.positions.data();
    const int *idx = s.prepared.indices.data();
    int crossings = 0;
    for (int t = 0; t < s.prepared.num_triangles(); t++) {
        const float *a = pos + 3 * idx[3 * t], *b = pos + 3 * idx[3 * t + 1],
                    *c = pos + 3 * idx[3 * t + 2];
        const Vec3d e1{b[0] - (double)a[0], b[1] - (double)a[1], b[2] - (double)a[2]};
        const Vec3d e2{c[0] - (double)a[0], c[1] - (double)a[1], c[2] - (double)a[2]};
        const Vec3d pv = cross(dir, e2);
        const double det = dot(e1, pv);
        if (det == 0) continue;
        const Vec3d tv{p.x - a[0], p.y - a[1], p.z - a[2]};
        const double u = dot(tv, pv) / det;
        if (u < 0 || u > 1) continue;
        const Vec3d qv = cross(tv, e1);
        const double v = dot(dir, qv) / det;
        if (v < 0 || u + v > 1) continue;
        if (dot(e2, qv) / det > 0) crossings++;
    }
    return crossings % 2 == 1;
}

/* Colours for successive surfaces: muted, distinguishable. */
const std::array<float, 3> kPalette[] = {
    {0.85f, 0.55f, 0.35f}, {0.45f, 0.65f, 0.85f}, {0.60f, 0.80f, 0.45f},
    {0.85f, 0.75f, 0.40f}, {0.75f, 0.50f, 0.75f}, {0.50f, 0.80f, 0.75f},
};

} // namespace

void update_bounds(SceneSurface &s) {
    const std::vector<float> &p = s.prepared.positions;
    const double inf = std::numeric_limits<double>::infinity();
    s.lo = {inf, inf, inf};
    s.hi = {-inf, -inf, -inf};
    for (std::size_t i = 0; i + 2 < p.size(); i += 3) {
        s.lo = {std::min(s.lo.x, (double)p[i]), std::min(s.lo.y, (double)p[i + 1]),
                std::min(s.lo.z, (double)p[i + 2])};
        s.hi = {std::max(s.hi.x, (double)p[i]), std::max(s.hi.y, (double)p[i + 1]),
                std::max(s.hi.z, (double)p[i + 2])};
    }
    if (p.empty()) s.lo = s.hi = {};
}

void check_placement(const std::string &path, const Placement &pl) {
    if (!finite(pl.translation) || !std::isfinite(pl.yaw_degrees) || !std::isfinite(pl.scale)) {
        throw SceneError(path + ": the placement has a number that is not finite");
    }
    if (!(pl.scale > 0)) throw SceneError(path + ": the scale must be above 0");
}

Mat4d placement_matrix(const Placement &pl) {
    const double yaw = pl.yaw_degrees * kPi / 180.0;
    const double c = std::cos(yaw), s = std::sin(yaw);
    Mat4d m; /* column-major: p' = t + scale * R_y(yaw) p */
    m.m[0] = pl.scale * c, m.m[1] = 0, m.m[2] = -pl.scale * s, m.m[3] = 0;
    m.m[4] = 0, m.m[5] = pl.scale, m.m[6] = 0, m.m[7] = 0;
    m.m[8] = pl.scale * s, m.m[9] = 0, m.m[10] = pl.scale * c, m.m[11] = 0;
    m.m[12] = pl.translation.x, m.m[13] = pl.translation.y, m.m[14] = pl.translation.z, m.m[15] = 1;
    return m;
}

Mat4d Mat4d::operator*(const Mat4d &b) const {
    Mat4d r;
    for (int c = 0; c < 4; c++) {
        for (int row = 0; row < 4; row++) {
            double s = 0;
            for (int k = 0; k < 4; k++) s += at(row, k) * b.at(k, c);
            r.m[c * 4 + row] = s;
        }
    }
    return r;
}

std::array<double, 4> Mat4d::apply(double x, double y, double z, double w) const {
    std::array<double, 4> r;
    for (int row = 0; row < 4; row++) {
        r[row] = ((at(row, 0) * x + at(row, 1) * y) + at(row, 2) * z) + at(row, 3) * w;
    }
    return r;
}

Mat4d infinite_projection(double fov_y_degrees, double aspect, double near_distance) {
    const double f = 1.0 / std::tan(fov_y_degrees * kPi / 360.0);
    Mat4d p;
    for (double &v : p.m) v = 0;
    p.m[0] = f / aspect;
    p.m[5] = f;
    p.m[10] = kInfiniteFarEpsilon - 1;
    p.m[14] = (kInfiniteFarEpsilon - 2) * near_distance;
    p.m[11] = -1;
    return p;
}

Mat4d look_at(const Vec3d &eye, const Vec3d &target, const Vec3d &up) {
    const Vec3d f = normalized(sub(target, eye));
    const Vec3d s = normalized(cross(f, up));
    const Vec3d u = cross(s, f);
    Mat4d v;
    v.m[0] = s.x, v.m[4] = s.y, v.m[8] = s.z, v.m[12] = -dot(s, eye);
    v.m[1] = u.x, v.m[5] = u.y, v.m[9] = u.z, v.m[13] = -dot(u, eye);
    v.m[2] = -f.x, v.m[6] = -f.y, v.m[10] = -f.z, v.m[14] = dot(f, eye);
    v.m[3] = 0, v.m[7] = 0, v.m[11] = 0, v.m[15] = 1;
    return v;
}

Vec4 SceneLight::shadow_light() const {
    if (kind == LightKind::directional) {
        return {(float)-direction.x, (float)-direction.y, (float)-direction.z, 0.0f};
    }
    return {(float)position.x, (float)position.y, (float)position.z, 1.0f};
}

std::string SceneLight::describe() const {
    char b[256];
    switch (kind) {
    case LightKind::point:
        std::snprintf(b, sizeof b, "point %s%s", fmt(position).c_str(),
                      range > 0 ? (" range " + std::to_string(range)).c_str() : "");
        break;
    case LightKind::spot:
        std::snprintf(b, sizeof b, "spot %s towards %s cone %g..%g deg", fmt(position).c_str(),
                      fmt(direction).c_str(), inner_degrees, outer_degrees);
        break;
    case LightKind::directional:
        std::snprintf(b, sizeof b, "directional towards %s", fmt(direction).c_str());
        break;
    }
    return b;
}

void Scene::bounds(Vec3d &lo, Vec3d &hi, bool with_ground) const {
    const double inf = std::numeric_limits<double>::infinity();
    lo = {inf, inf, inf};
    hi = {-inf, -inf, -inf};
    bool any = false;
    for (const SceneSurface &s : surfaces) {
        if ((s.ground && !with_ground) || s.prepared.num_vertices() == 0) continue;
        any = true;
        lo = {std::min(lo.x, s.lo.x), std::min(lo.y, s.lo.y), std::min(lo.z, s.lo.z)};
        hi = {std::max(hi.x, s.hi.x), std::max(hi.y, s.hi.y), std::max(hi.z, s.hi.z)};
    }
    if (!any) lo = hi = {};
}

int64_t Scene::triangles() const {
    int64_t n = 0;
    for (const SceneSurface &s : surfaces) n += s.prepared.num_triangles();
    return n;
}

void add_model(Scene &scene, const std::string &path, const Placement &pl) {
    check_placement(path, pl);
    const GltfModel model = load_gltf(path);
    const double yaw = pl.yaw_degrees * kPi / 180.0;
    const double c = std::cos(yaw), s = std::sin(yaw);
    for (const std::string &n : model.notes) scene.notes.push_back(path + ": " + n);
    for (const GltfSurface &g : model.surfaces) {
        std::vector<float> pos(g.positions.size());
        for (std::size_t i = 0; i + 2 < pos.size(); i += 3) {
            const double x = g.positions[i], y = g.positions[i + 1], z = g.positions[i + 2];
            /* R_y(yaw): x' = c x + s z, z' = -s x + c z. Bitwise-equal
             * inputs give bitwise-equal outputs, so welding is unchanged. */
            const double wx = pl.translation.x + pl.scale * (c * x + s * z);
            const double wy = pl.translation.y + pl.scale * y;
            const double wz = pl.translation.z + pl.scale * (-s * x + c * z);
            pos[i] = (float)wx, pos[i + 1] = (float)wy, pos[i + 2] = (float)wz;
            if (!std::isfinite(pos[i]) || !std::isfinite(pos[i + 1]) ||
                !std::isfinite(pos[i + 2])) {
                throw SceneError(path + ": " + g.name + ": a placed vertex is not finite in float");
            }
        }
        SceneSurface surf;
        surf.name = path.substr(path.find_last_of('/') + 1) + ": " + g.name;
        surf.declared_ground = g.declared_ground;
        surf.prepared = prepare_surface(pos.data(), g.num_vertices(), g.indices.data(),
                                        g.indices.size());
        surf.albedo = kPalette[scene.surfaces.size() % (sizeof kPalette / sizeof kPalette[0])];
        update_bounds(surf);
        scene.surfaces.push_back(std::move(surf));
    }
}

void add_ground(Scene &scene) {
    Vec3d lo, hi;
    scene.bounds(lo, hi, false);
    const double cx = (lo.x + hi.x) / 2, cz = (lo.z + hi.z) / 2;
    const double radius = std::max({(hi.x - lo.x) / 2, (hi.z - lo.z) / 2, (hi.y - lo.y) / 2});
    const double half = std::max(4 * radius, 0.5);
    const float y = (float)lo.y;
    const float x0 = (float)(cx - half), x1 = (float)(cx + half);
    const float z0 = (float)(cz - half), z1 = (float)(cz + half);
    /* Counter-clockwise seen from above (+y): front faces up. */
    const float pos[] = {x0, y, z1, x1, y, z1, x1, y, z0, x0, y, z0};
    const uint32_t idx[] = {0, 1, 2, 0, 2, 3};
    SceneSurface g;
    g.name = "ground";
    g.ground = true;
    /* The top of the solid below it: everything else stands on or above
     * its plane (y is the scene's lowest point), so the paper's rule is
     * exact for it (docs/CASTERS.md, "The ground hint"). */
    g.declared_ground = true;
    g.albedo = {0.72f, 0.72f, 0.70f};
    g.prepared = prepare_surface(pos, 4, idx, 6);
    update_bounds(g);
    scene.surfaces.push_back(std::move(g));
}

Camera frame_camera(const Scene &scene, double aspect) {
    Vec3d lo, hi;
    scene.bounds(lo, hi, false);
    const Vec3d c{(lo.x + hi.x) / 2, (lo.y + hi.y) / 2, (lo.z + hi.z) / 2};
    /* The bounding sphere, enlarged so the shadows beside it are in view. */
    const double r = std::max(1.6 * length(sub(hi, c)), 1e-3);
    Camera cam;
    const double half_fov = cam.fov_y_degrees * kPi / 360.0;
    const double fit = std::min(std::tan(half_fov), std::tan(half_fov) * aspect);
    const double dist = r / std::sin(std::atan(fit));
    const Vec3d dir = normalized({0.0, 0.55, 1.0}); /* front and above */
    cam.target = {c.x, c.y - 0.15 * r, c.z};
    cam.eye = {cam.target.x + dist * dir.x, cam.target.y + dist * dir.y,
               cam.target.z + dist * dir.z};
    cam.near_distance = std::max(dist - 2 * r, dist * 0.01);
    cam.near_distance = std::min(cam.near_distance, dist * 0.25);
    return cam;
}

double fitting_near_distance(const Scene &scene, const Camera &camera) {
    Vec3d lo, hi;
    scene.bounds(lo, hi, true);
    const Vec3d e = camera.eye;
    const Vec3d c{(lo.x + hi.x) / 2, (lo.y + hi.y) / 2, (lo.z + hi.z) / 2};
    const double dx = std::max({lo.x - e.x, 0.0, e.x - hi.x});
    const double dy = std::max({lo.y - e.y, 0.0, e.y - hi.y});
    const double dz = std::max({lo.z - e.z, 0.0, e.z - hi.z});
    const double outside = std::sqrt(dx * dx + dy * dy + dz * dz);
    const double radius = std::max(length(sub(hi, c)), 1e-30);
    if (outside == 0) return 0.01 * radius;
    return std::max(0.5 * outside, 1e-3 * length(sub(c, e)));
}

std::vector<SceneLight> default_lights(const Scene &scene) {
    Vec3d lo, hi;
    scene.bounds(lo, hi, false);
    const Vec3d c{(lo.x + hi.x) / 2, (lo.y + hi.y) / 2, (lo.z + hi.z) / 2};
    const double r = std::max(length(sub(hi, c)), 1e-3);
    SceneLight point;
    point.kind = LightKind::point;
    /* In front, left and above: the surfaces are lit where the camera sees
     * them, and their shadows fall behind and to the right, on the ground
     * the raised camera looks down on. */
    point.position = {c.x - 1.2 * r, hi.y + 1.6 * r, c.z + 1.0 * r};
    point.color = {1.0f, 0.92f, 0.80f};
    const Vec3d to_centre = sub(c, point.position);
    point.intensity = dot(to_centre, to_centre); /* irradiance 1 at the centre */
    SceneLight sun;
    sun.kind = LightKind::directional;
    sun.direction = normalized({-0.55, -1.0, -0.45}); /* travels down, left and back */
    sun.color = {0.70f, 0.80f, 1.0f};
    sun.intensity = 0.6;
    return {point, sun};
}

SceneLight auto_light(const Scene &scene, LightKind kind) {
    Vec3d lo, hi;
    scene.bounds(lo, hi, false);
    const Vec3d c{(lo.x + hi.x) / 2, (lo.y + hi.y) / 2, (lo.z + hi.z) / 2};
    const double r = std::max({hi.x - lo.x, hi.y - lo.y, hi.z - lo.z, 1e-3});
    SceneLight l;
    l.kind = kind;
    switch (kind) {
    case LightKind::point: l.position = {c.x - 0.8 * r, hi.y + 0.9 * r, c.z + 0.7 * r}; break;
    case LightKind::spot:
        l.position = {c.x + 0.7 * r, hi.y + 1.1 * r, c.z + 0.4 * r};
        l.direction = normalized(sub({c.x, lo.y, c.z}, l.position));
        l.inner_degrees = 20;
        l.outer_degrees = 40;
        break;
    case LightKind::directional:
        l.direction = normalized({0.4, -1, -0.5});
        l.intensity = 1;
        return l;
    }
    const Vec3d d = sub(c, l.position);
    l.intensity = dot(d, d);
    return l;
}

void validate_scene(Scene &scene) {
    if (scene.triangles() == 0) throw SceneError("the scene has no triangles to render");
    const Camera &cam = scene.camera;
    if (!finite(cam.eye) || !finite(cam.target) || !finite(cam.up) ||
        !std::isfinite(cam.fov_y_degrees) || !std::isfinite(cam.near_distance)) {
        throw SceneError("the camera has a number that is not finite");
    }
    const Vec3d view = sub(cam.target, cam.eye);
    if (length(view) == 0) throw SceneError("the camera's eye equals its target");
    if (length(cross(normalized(view), cam.up)) < 1e-9) {
        throw SceneError("the camera's up direction is parallel to its view direction");
    }
    if (!(cam.fov_y_degrees > 0 && cam.fov_y_degrees < 180)) {
        throw SceneError("the field of view must be above 0 and below 180 degrees");
    }
    if (!(cam.near_distance > 0)) throw SceneError("the near distance must be above 0");
    for (std::size_t li = 0; li < scene.lights.size(); li++) {
        SceneLight &l = scene.lights[li];
        const std::string who = "light " + std::to_string(li) + " (" + l.describe() + ")";
        if (!finite(l.position) || !finite(l.direction) || !std::isfinite(l.range) ||
            !std::isfinite(l.inner_degrees) || !std::isfinite(l.outer_degrees) ||
            !std::isfinite(l.intensity)) {
            throw SceneError(who + ": a number is not finite");
        }
        /* The routines take the light in float: a coordinate beyond
         * float's range would become infinite there. */
        const Vec4 Lf = l.shadow_light();
        if (!std::isfinite(Lf.x) || !std::isfinite(Lf.y) || !std::isfinite(Lf.z)) {
            throw SceneError(who + ": a coordinate is beyond float's range (3.4e38)");
        }
        if (l.range < 0) throw SceneError(who + ": the range must be 0 (unlimited) or above");
        if (l.kind != LightKind::point) {
            if (length(l.direction) == 0) throw SceneError(who + ": the direction is zero");
            l.direction = normalized(l.direction);
        }
        if (l.kind == LightKind::spot &&
            !(l.inner_degrees >= 0 && l.inner_degrees <= l.outer_degrees && l.outer_degrees < 90)) {
            throw SceneError(who + ": cone angles need 0 <= inner <= outer < 90 degrees");
        }
        if (l.kind == LightKind::directional) continue;
        const Vec4 L = l.shadow_light();
        for (const SceneSurface &s : scene.surfaces) {
            const std::vector<float> &p = s.prepared.positions;
            for (std::size_t i = 0; i + 2 < p.size(); i += 3) {
                if (p[i] == L.x && p[i + 1] == L.y && p[i + 2] == L.z) {
                    throw SceneError(who + ": the light is exactly at a vertex of " + s.name +
                                     " (its shadow has no direction there)");
                }
            }
            int on_plane = 0;
            for (const Plane &pl : s.prepared.planes) {
                const float d = pl.a * L.x + pl.b * L.y + pl.c * L.z + pl.d;
                if (d == 0.0f && (pl.a != 0 || pl.b != 0 || pl.c != 0)) on_plane++;
            }
            if (on_plane) {
                /* Such a triangle counts as not facing (the facing test is
                 * strict) and casts a flat prism in its own plane; from a
                 * light inside the triangle that prism is the whole plane,
                 * and its coincident faces make the stencil count anything:
                 * refused rather than drawn wrong. */
                throw SceneError(who + " lies exactly on the plane of " + std::to_string(on_plane) +
                                 " triangle(s) of " + s.name + ": move it off that plane");
            }
            if (inside_closed_surface(s, l.position)) {
                scene.notes.push_back(who + " is inside the closed surface " + s.name +
                                      ": everything outside it is in its shadow");
            }
        }
    }
    for (const SceneSurface &s : scene.surfaces) {
        if (inside_closed_surface(s, cam.eye)) {
            scene.notes.push_back("the camera is inside the closed surface " + s.name +
                                  ": it sees that surface's inside, which no light reaches");
        }
    }
}

} // namespace sv
