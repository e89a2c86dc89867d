/*
 * Poses in time (include/shadowvol_anim.h): sampling, node transforms,
 * skinning dispatch, surfaces, lights and cameras at a pose.
 *
 * Interpolation (glTF 2.0 section 3.11 and its Appendix C), in double:
 *  - the frame time is clamped to the animation's [start, end]; before a
 *    sampler's first key it holds the first value, after its last key the
 *    last value;
 *  - between keys k and k+1, u = (t - t_k) / (t_(k+1) - t_k);
 *  - STEP: value k;
 *  - LINEAR: (1 - u) v_k + u v_(k+1); rotations by slerp on the shorter arc
 *    (v_(k+1) negated when the dot product is negative), with a plain
 *    normalized lerp when the keys are within 0.9995 of each other (the
 *    sine of the angle is too small to divide by);
 *  - CUBICSPLINE: the Hermite spline
 *      p(u) = (2u^3 - 3u^2 + 1) v_k + (u^3 - 2u^2 + u) dt b_k
 *           + (-2u^3 + 3u^2) v_(k+1) + (u^3 - u^2) dt a_(k+1)
 *    with b_k the out-tangent of key k, a_(k+1) the in-tangent of key k+1,
 *    dt = t_(k+1) - t_k;
 *  - rotations (4 components) come out normalized whatever the mode (a
 *    spline through unit quaternions leaves the unit sphere; a zero result,
 *    possible only with wild tangents, falls back to key k's value).
 * A node's local matrix is T * R * S with load_gltf's formula; nodes no
 * channel drives keep the file's local matrix bit for bit, so pose_at(-1)
 * gives load_gltf's world matrices exactly.
 *
 * Copyright (C) 2026 the shadowvol authors. LGPL-2.1-or-later.
 */
#include "shadowvol_anim.h"

#include <algorithm>
#include <cmath>
#include <cstring>

namespace sv {

namespace {

constexpr double kPi = 3.14159265358979323846;

/* load_gltf's T * R * S (src/gltf/gltf_nodes.cpp, local_matrix). */
Mat4d trs_matrix(const double t[3], const double q_in[4], const double s[3]) {
    const double norm = std::sqrt(q_in[0] * q_in[0] + q_in[1] * q_in[1] + q_in[2] * q_in[2] +
                                  q_in[3] * q_in[3]);
    const double x = q_in[0] / norm, y = q_in[1] / norm, z = q_in[2] / norm, w = q_in[3] / norm;
    const double r[3][3] = {
        {1.0 - 2.0 * (y * y + z * z), 2.0 * (x * y - z * w), 2.0 * (x * z + y * w)},
        {2.0 * (x * y + z * w), 1.0 - 2.0 * (x * x + z * z), 2.0 * (y * z - x * w)},
        {2.0 * (x * z - y * w), 2.0 * (y * z + x * w), 1.0 - 2.0 * (x * x + y * y)}};
    Mat4d m;
    for (int col = 0; col < 3; col++) {
        for (int row = 0; row < 3; row++) {
            m.m[4 * col + row] = r[row][col] * s[col];
        }
    }
    m.m[12] = t[0];
    m.m[13] = t[1];
    m.m[14] = t[2];
    return m;
}

bool normalize4(double *q) {
    const double n = std::sqrt(q[0] * q[0] + q[1] * q[1] + q[2] * q[2] + q[3] * q[3]);
    if (!(n > 0.0) || !std::isfinite(n)) return false;
    for (int c = 0; c < 4; c++) q[c] /= n;
    return true;
}

void slerp(const float *a_in, const float *b_in, double u, double *out) {
    double a[4], b[4];
    for (int c = 0; c < 4; c++) {
        a[c] = a_in[c];
        b[c] = b_in[c];
    }
    normalize4(a); /* keys are not zero: checked at load */
    normalize4(b);
    double d = a[0] * b[0] + a[1] * b[1] + a[2] * b[2] + a[3] * b[3];
    if (d < 0.0) { /* the shorter arc */
        for (double &c : b) c = -c;
        d = -d;
    }
    if (d > 0.9995) {
        for (int c = 0; c < 4; c++) out[c] = a[c] + u * (b[c] - a[c]);
    } else {
        const double theta = std::acos(d);
        const double sn = std::sin(theta);
        const double s0 = std::sin((1.0 - u) * theta) / sn, s1 = std::sin(u * theta) / sn;
        for (int c = 0; c < 4; c++) out[c] = s0 * a[c] + s1 * b[c];
    }
}

void copy_value(const float *v, int n, double *out) {
    for (int c = 0; c < n; c++) out[c] = v[c];
}

void lerp(const float *a, const float *b, double u, int n, double *out) {
    for (int c = 0; c < n; c++) out[c] = (1.0 - u) * a[c] + u * double(b[c]);
}

} // namespace

void sample(const AnimSampler &s, double t, double *out) {
    const int n = s.components;
    const std::size_t keys = s.input.size();
    const bool cubic = s.interp == AnimSampler::Interp::cubicspline;
    const std::size_t stride = std::size_t(n) * (cubic ? 3 : 1);
    auto value = [&](std::size_t k) { return &s.output[k * stride + (cubic ? n : 0)]; };
    if (keys == 0) {
        for (int c = 0; c < n; c++) out[c] = 0.0;
        if (n == 4) out[3] = 1.0;
        return;
    }
    std::size_t k = 0;
    if (!(t > s.input.front())) { /* also NaN: the first value */
        copy_value(value(0), n, out);
    } else if (t >= s.input.back()) {
        k = keys - 1;
        copy_value(value(k), n, out);
    } else {
        k = std::size_t(std::upper_bound(s.input.begin(), s.input.end(), t) - s.input.begin()) - 1;
        const double t0 = s.input[k], t1 = s.input[k + 1];
        const double dt = t1 - t0;
        const double u = (t - t0) / dt;
        switch (s.interp) {
        case AnimSampler::Interp::step: copy_value(value(k), n, out); break;
        case AnimSampler::Interp::linear:
            if (n == 4) {
                slerp(value(k), value(k + 1), u, out);
            } else {
                lerp(value(k), value(k + 1), u, n, out);
            }
            break;
        case AnimSampler::Interp::cubicspline: {
            const float *v0 = value(k), *v1 = value(k + 1);
            const float *b0 = &s.output[k * stride + 2 * n]; /* out-tangent of k */
            const float *a1 = &s.output[(k + 1) * stride];   /* in-tangent of k+1 */
            const double u2 = u * u, u3 = u2 * u;
            const double h00 = 2 * u3 - 3 * u2 + 1, h10 = u3 - 2 * u2 + u;
            const double h01 = -2 * u3 + 3 * u2, h11 = u3 - u2;
            for (int c = 0; c < n; c++) {
                out[c] = h00 * v0[c] + h10 * dt * b0[c] + h01 * v1[c] + h11 * dt * a1[c];
            }
            break;
        }
        }
    }
    if (n == 4 && !normalize4(out)) {
        copy_value(value(k), n, out);
        normalize4(out);
    }
}

Pose pose_at(const AnimatedAsset &asset, int animation, double time_seconds) {
    const std::size_t n = asset.nodes.size();
    if (animation < -1 || animation >= static_cast<int>(asset.animations.size())) {
        throw GltfError(asset.path + ": animation " + std::to_string(animation) +
                        " does not exist (" + std::to_string(asset.animations.size()) +
                        " animations)");
    }
    std::vector<Mat4d> local(n);
    for (std::size_t i = 0; i < n; i++) local[i] = asset.nodes[i].rest_local;
    if (animation >= 0) {
        const Animation &a = asset.animations[animation];
        double t = time_seconds;
        if (!(t >= a.start)) t = a.start; /* NaN too */
        if (t > a.end) t = a.end;
        struct Trs {
            double t[3], r[4], s[3];
        };
        std::vector<Trs> trs(n);
        std::vector<char> driven(n, 0);
        for (const AnimChannel &c : a.channels) {
            if (c.path == AnimChannel::Path::weights) continue;
            const AnimNode &node = asset.nodes[c.node];
            Trs &x = trs[c.node];
            if (!driven[c.node]) {
                std::memcpy(x.t, node.translation, sizeof x.t);
                std::memcpy(x.r, node.rotation, sizeof x.r);
                std::memcpy(x.s, node.scale, sizeof x.s);
                driven[c.node] = 1;
            }
            double v[4];
            sample(a.samplers[c.sampler], t, v);
            switch (c.path) {
            case AnimChannel::Path::translation: std::memcpy(x.t, v, sizeof x.t); break;
            case AnimChannel::Path::rotation: std::memcpy(x.r, v, sizeof x.r); break;
            case AnimChannel::Path::scale: std::memcpy(x.s, v, sizeof x.s); break;
            case AnimChannel::Path::weights: break;
            }
        }
        for (std::size_t i = 0; i < n; i++) {
            if (driven[i]) local[i] = trs_matrix(trs[i].t, trs[i].r, trs[i].s);
        }
    }
    Pose p;
    p.world.resize(n);
    for (int i : asset.node_order) {
        const int parent = asset.nodes[i].parent;
        p.world[i] = parent < 0 ? local[i] : p.world[parent] * local[i];
    }
    return p;
}

// -------------------------------------------------------------- skinning --

const SkinningKernel *skinning_kernels(int *count) { return sv_skin_variants(count); }

const SkinningKernel *best_skinning_kernel() {
    int n;
    const SkinningKernel *k = skinning_kernels(&n);
    const unsigned isa = sv_cpu_isa();
    const SkinningKernel *best = &k[0];
    for (int i = 0; i < n; i++) {
        if ((k[i].isa & isa) == k[i].isa) best = &k[i];
    }
    return best;
}

const SkinningKernel *skinning_kernel_by_name(const char *name) {
    return sv_skin_variant_by_name(name);
}

void joint_matrices(const AnimatedAsset &asset, int skin, const Pose &pose, const Mat4d &root,
                    float *out) {
    const AnimSkin &s = asset.skins[skin];
    for (std::size_t j = 0; j < s.joints.size(); j++) {
        const Mat4d m = (root * pose.world[s.joints[j]]) * s.inverse_bind[j];
        for (int e = 0; e < 16; e++) out[16 * j + e] = static_cast<float>(m.m[e]);
    }
}

void pose_surface(const AnimatedAsset &asset, const AnimatedSurface &surface, const Pose &pose,
                  const Mat4d &root, float *out, const SkinningKernel *k) {
    const std::size_t nv = surface.rest_positions.size() / 3;
    const float *rest = surface.rest_positions.data();
    if (surface.skin >= 0) {
        AlignedVector<float> jm(16 * asset.skins[surface.skin].joints.size());
        joint_matrices(asset, surface.skin, pose, root, jm.data());
        if (!k) k = best_skinning_kernel();
        k->fn(jm.data(), rest, surface.joints.data(), surface.weights.data(), surface.influences,
              nv, out);
        return;
    }
    const Mat4d m = surface.node_index >= 0 ? root * pose.world[surface.node_index] : root;
    for (std::size_t v = 0; v < nv; v++) {
        const double x = rest[3 * v], y = rest[3 * v + 1], z = rest[3 * v + 2];
        for (int r = 0; r < 3; r++) {
            out[3 * v + r] = static_cast<float>(m.m[r] * x + m.m[4 + r] * y + m.m[8 + r] * z +
                                                m.m[12 + r]);
        }
    }
}

PreparedSurface prepared_at(const AnimatedSurface &surface, const float *positions) {
    PreparedSurface p = surface.prepared;
    std::copy(positions, positions + p.positions.size(), p.positions.begin());
    const int *ix = p.indices.data();
    for (int t = 0; t < p.num_triangles(); t++) {
        p.planes[t] = triangle_plane(&positions[3 * ix[3 * t]], &positions[3 * ix[3 * t + 1]],
                                     &positions[3 * ix[3 * t + 2]]);
    }
    return p;
}

// ------------------------------------------------------ lights and cameras --

namespace {

Vec3d unit(const std::array<double, 4> &v, const Vec3d &fallback) {
    const double n = std::sqrt(v[0] * v[0] + v[1] * v[1] + v[2] * v[2]);
    if (!(n > 0.0) || !std::isfinite(n)) return fallback;
    return Vec3d{v[0] / n, v[1] / n, v[2] / n};
}

} // namespace

SceneLight light_at(const AnimatedAsset &asset, int light, const Pose &pose, const Mat4d &root) {
    const AnimLight &a = asset.lights.at(static_cast<std::size_t>(light));
    const Mat4d m = root * pose.world[a.node];
    SceneLight s = a.light;
    const auto p = m.apply(0, 0, 0, 1);
    s.position = Vec3d{p[0], p[1], p[2]};
    /* A zero direction (a node scaled to 0) stays zero: validate_scene
     * refuses it rather than this guessing one. */
    s.direction = unit(m.apply(0, 0, -1, 0), Vec3d{0, 0, 0});
    return s;
}

Camera camera_at(const AnimatedAsset &asset, int camera, const Pose &pose, const Mat4d &root,
                 double *aspect_out) {
    const AnimCamera &a = asset.cameras.at(static_cast<std::size_t>(camera));
    const Mat4d m = root * pose.world[a.node];
    Camera c;
    const auto e = m.apply(0, 0, 0, 1);
    c.eye = Vec3d{e[0], e[1], e[2]};
    const Vec3d f = unit(m.apply(0, 0, -1, 0), Vec3d{0, 0, -1});
    c.target = Vec3d{c.eye.x + f.x, c.eye.y + f.y, c.eye.z + f.z};
    c.up = unit(m.apply(0, 1, 0, 0), Vec3d{0, 1, 0});
    c.fov_y_degrees = a.yfov_radians * 180.0 / kPi;
    c.near_distance = a.znear;
    if (aspect_out) *aspect_out = a.aspect;
    return c;
}

} // namespace sv
