/*
 * The small vector arithmetic, clocks and camera basis the frame's passes
 * share (internal to src/render). Everything in double: the frame's
 * geometry is computed once per vertex, triangle or pixel in double and
 * rounded only where the rasteriser takes its input.
 *
 * Copyright (C) 2026 the shadowvol authors. LGPL-2.1-or-later.
 */
#ifndef SV_RENDER_FRAME_MATH_H
#define SV_RENDER_FRAME_MATH_H

#include <x86intrin.h>

#include <chrono>
#include <cmath>
#include <cstdint>

#include "shadowvol_scene.h"

namespace sv::render::detail {

constexpr double kPi = 3.14159265358979323846;

inline Vec3d sub(const Vec3d &a, const Vec3d &b) { return {a.x - b.x, a.y - b.y, a.z - b.z}; }
inline Vec3d add(const Vec3d &a, const Vec3d &b) { return {a.x + b.x, a.y + b.y, a.z + b.z}; }
inline Vec3d mul(const Vec3d &a, double s) { return {a.x * s, a.y * s, a.z * s}; }
inline Vec3d cross(const Vec3d &a, const Vec3d &b) {
    return {a.y * b.z - a.z * b.y, a.z * b.x - a.x * b.z, a.x * b.y - a.y * b.x};
}
inline double dot(const Vec3d &a, const Vec3d &b) { return a.x * b.x + a.y * b.y + a.z * b.z; }
inline Vec3d normalized(const Vec3d &a) { return mul(a, 1.0 / std::sqrt(dot(a, a))); }

/* Vertex V of a prepared surface, widened to double. */
inline Vec3d vertex(const PreparedSurface &p, int v) {
    return {p.positions[3 * v], p.positions[3 * v + 1], p.positions[3 * v + 2]};
}

inline double now_seconds() {
    return std::chrono::duration<double>(std::chrono::steady_clock::now().time_since_epoch())
        .count();
}
inline uint64_t ticks() { return __rdtsc(); }

/* The camera's unit forward, side and up vectors and tan(fov_y / 2). */
struct CameraBasis {
    Vec3d f, s, u;
    double tan_half;
};
inline CameraBasis basis(const Camera &c) {
    CameraBasis b;
    b.f = normalized(sub(c.target, c.eye));
    b.s = normalized(cross(b.f, c.up));
    b.u = cross(b.s, b.f);
    b.tan_half = std::tan(c.fov_y_degrees * kPi / 360.0);
    return b;
}

} // namespace sv::render::detail

#endif
