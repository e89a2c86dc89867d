/*
 * The reach tests of reach.h: where a light can light and a shadow can be
 * seen, worked out per frame, light and surface box before any volume is
 * built.
 *
 * Copyright (C) 2026 the shadowvol authors. LGPL-2.1-or-later.
 */
#include "reach.h"

#include <algorithm>
#include <array>
#include <cmath>

#include "frame_math.h"

namespace sv::render {

using namespace detail;

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

bool shadow_may_reach_view(const Mat4d &view_proj, const Vec3d &lo, const Vec3d &hi, const Vec4 &L,
                           bool with_extrusion) {
    std::array<double, 4> pts[16];
    int n = 0;
    for (int i = 0; i < 8; i++) {
        const double x = (i & 1) ? hi.x : lo.x, y = (i & 2) ? hi.y : lo.y,
                     z = (i & 4) ? hi.z : lo.z;
        pts[n++] = view_proj.apply(x, y, z, 1.0);
        if (with_extrusion)
            pts[n++] = view_proj.apply(x * L.w - L.x, y * L.w - L.y, z * L.w - L.z, 0.0);
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
            const double scale = std::fabs(q[0]) + std::fabs(q[1]) + std::fabs(q[2]) +
                                 std::fabs(q[3]);
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
    const double light_side = directional ? dot(towards, b.f)
                                          : dot(sub(light.position, centre), b.f);
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
        const Vec3d n = directional ? cross(sub(q, p), towards)
                                    : cross(sub(q, p), sub(light.position, p));
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

} // namespace sv::render
