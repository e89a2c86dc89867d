/*
 * The glTF loader's surfaces: one mesh instance's triangle primitives
 * merged (strips and fans turned into triangles, points and lines skipped),
 * its skin attributes read and validated, and its vertices placed in world
 * space, rigid or skinned, under the weld guarantee and the winding rule
 * that open gltf_loader.cpp.
 *
 * Copyright (C) 2026 the shadowvol authors. LGPL-2.1-or-later.
 */
#include "gltf_detail.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <string>
#include <utility>
#include <vector>

namespace sv {
namespace gltf_detail {

namespace {

/* Indices are u32: a surface holds at most 2^32 vertices. */
constexpr std::uint64_t kMaxSurfaceVertices = std::uint64_t(1) << 32;

/* JOINTS_0/WEIGHTS_0 and JOINTS_1/WEIGHTS_1: up to 8 influences a vertex. */
constexpr int kMaxInfluenceSets = 2;
constexpr int kMaxInfluences = 4 * kMaxInfluenceSets;

/* Weight sums farther than this from 1 get a note (u8 weights are off by
 * at most 4 * 0.5 / 255 = 0.008). */
constexpr double kWeightSumTolerance = 0.01;

/* Formats a double the way a person wants to read it in a message. */
std::string number_text(double v) {
    char text[32];
    std::snprintf(text, sizeof text, "%.9g", v);
    return text;
}

/* Determinant of the upper-left 3x3 (the linear part): its sign tells
 * whether the transform mirrors. */
double linear_determinant(const Mat4 &m) {
    return m[0] * (m[5] * m[10] - m[9] * m[6]) - m[4] * (m[1] * m[10] - m[9] * m[2]) +
           m[8] * (m[1] * m[6] - m[5] * m[2]);
}

/* p' = M p for an affine M, rounded to float once per coordinate. */
std::array<float, 3> transform_point(const Mat4 &m, const float p[3]) {
    const double x = p[0], y = p[1], z = p[2];
    std::array<float, 3> r;
    for (int row = 0; row < 3; row++) {
        r[row] = static_cast<float>(m[row] * x + m[4 + row] * y + m[8 + row] * z + m[12 + row]);
    }
    return r;
}

const char *mode_name(int mode) {
    switch (mode) {
    case TINYGLTF_MODE_POINTS: return "POINTS";
    case TINYGLTF_MODE_LINE: return "LINES";
    case TINYGLTF_MODE_LINE_LOOP: return "LINE_LOOP";
    case TINYGLTF_MODE_LINE_STRIP: return "LINE_STRIP";
    case TINYGLTF_MODE_TRIANGLES: return "TRIANGLES";
    case TINYGLTF_MODE_TRIANGLE_STRIP: return "TRIANGLE_STRIP";
    case TINYGLTF_MODE_TRIANGLE_FAN: return "TRIANGLE_FAN";
    default: return "invalid mode";
    }
}

/* Appends the triangles of one primitive's corner list, offset by `base`. */
void append_triangles(int mode, const std::vector<uint32_t> &corners, uint32_t base,
                      std::vector<uint32_t> &out) {
    const std::size_t n = corners.size();
    if (mode == TINYGLTF_MODE_TRIANGLES) {
        for (std::size_t i = 0; i < n; i++) {
            out.push_back(base + corners[i]);
        }
    } else if (mode == TINYGLTF_MODE_TRIANGLE_STRIP) {
        for (std::size_t i = 0; i + 2 < n; i++) {
            const std::size_t odd = i % 2;
            out.push_back(base + corners[i]);
            out.push_back(base + corners[i + 1 + odd]);
            out.push_back(base + corners[i + 2 - odd]);
        }
    } else { /* TRIANGLE_FAN */
        for (std::size_t i = 0; i + 2 < n; i++) {
            out.push_back(base + corners[i + 1]);
            out.push_back(base + corners[i + 2]);
            out.push_back(base + corners[0]);
        }
    }
}

/* first[v]: the first vertex whose mesh-space position has the same bits
 * as v's, -0.0 taken as +0.0 (the weld guarantee's "same position"). */
std::vector<uint32_t> first_vertex_at_same_position(const std::vector<float> &positions) {
    const std::size_t n = positions.size() / 3;
    auto key = [&](std::size_t v, int axis) {
        float f = positions[3 * v + axis];
        if (f == 0.0f) {
            f = 0.0f;
        }
        uint32_t bits;
        std::memcpy(&bits, &f, sizeof bits);
        return bits;
    };
    std::vector<uint32_t> order(n);
    for (std::size_t v = 0; v < n; v++) {
        order[v] = static_cast<uint32_t>(v);
    }
    /* Sorted by position, ties by vertex number: the first of a run is the
     * lowest-numbered vertex at that position. */
    std::sort(order.begin(), order.end(), [&](uint32_t a, uint32_t b) {
        for (int axis = 0; axis < 3; axis++) {
            const uint32_t ka = key(a, axis), kb = key(b, axis);
            if (ka != kb) {
                return ka < kb;
            }
        }
        return a < b;
    });
    std::vector<uint32_t> first(n);
    for (std::size_t i = 0; i < n; i++) {
        const bool same_as_previous = i > 0 && key(order[i], 0) == key(order[i - 1], 0) &&
                                      key(order[i], 1) == key(order[i - 1], 1) &&
                                      key(order[i], 2) == key(order[i - 1], 2);
        first[order[i]] = same_as_previous ? first[order[i - 1]] : order[i];
    }
    return first;
}

void flip_triangle(std::vector<uint32_t> &indices, std::size_t triangle) {
    std::swap(indices[3 * triangle + 1], indices[3 * triangle + 2]);
}

} // namespace

void Loader::append_skin_attributes(int mesh, int primitive, std::size_t vertices,
                                    MeshGeometry &g) {
    const tinygltf::Primitive &prim = gltf_.meshes[mesh].primitives[primitive];
    const std::string label = primitive_label(mesh, primitive);
    const std::size_t first = g.joints.size();
    g.joints.resize(first + vertices * kMaxInfluences, 0);
    g.weights.resize(first + vertices * kMaxInfluences, 0.0);
    for (int set = 0;; set++) {
        const std::string joints_name = "JOINTS_" + std::to_string(set);
        const std::string weights_name = "WEIGHTS_" + std::to_string(set);
        const auto joints_it = prim.attributes.find(joints_name);
        const auto weights_it = prim.attributes.find(weights_name);
        const bool has_joints = joints_it != prim.attributes.end();
        const bool has_weights = weights_it != prim.attributes.end();
        if (!has_joints && !has_weights) {
            if (set == 0) {
                fail(label + ": the node has a skin but the primitive has no JOINTS_0/WEIGHTS_0");
            }
            return;
        }
        if (has_joints != has_weights) {
            fail(label + ": " +
                 (has_joints ? joints_name + " without " + weights_name
                             : weights_name + " without " + joints_name));
        }
        if (set >= kMaxInfluenceSets) {
            fail(label + ": " + joints_name + ": more than " + std::to_string(kMaxInfluences) +
                 " influences per vertex are not supported");
        }
        const std::vector<double> joints = decode(joints_it->second, kJointsFormat,
                                                  label + " " + joints_name);
        const std::vector<double> weights = decode(weights_it->second, kWeightsFormat,
                                                   label + " " + weights_name);
        if (joints.size() != 4 * vertices || weights.size() != 4 * vertices) {
            fail(label + ": " + joints_name + " / " + weights_name + " count differs from " +
                 "POSITION's (" + std::to_string(vertices) + ")");
        }
        for (std::size_t v = 0; v < vertices; v++) {
            for (std::size_t k = 0; k < 4; k++) {
                const std::size_t slot = first + v * kMaxInfluences + 4 * std::size_t(set) + k;
                g.joints[slot] = static_cast<uint32_t>(joints[4 * v + k]);
                g.weights[slot] = weights[4 * v + k];
            }
        }
    }
}

void Loader::append_primitive(int mesh, int primitive, bool skinned, MeshGeometry &g) {
    const tinygltf::Primitive &prim = gltf_.meshes[mesh].primitives[primitive];
    const std::string label = primitive_label(mesh, primitive);
    const int mode = prim.mode == -1 ? TINYGLTF_MODE_TRIANGLES : prim.mode;
    if (mode < TINYGLTF_MODE_POINTS || mode > TINYGLTF_MODE_TRIANGLE_FAN) {
        fail(label + ": mode " + std::to_string(mode) + " is not a glTF primitive mode (0..6)");
    }
    if (mode < TINYGLTF_MODE_TRIANGLES) {
        note(label + ": " + mode_name(mode) + " primitive skipped (no triangles)");
        return;
    }
    if (!prim.targets.empty()) {
        note(label + ": " + std::to_string(prim.targets.size()) +
             " morph target(s) ignored (base positions used)");
    }
    const auto position_it = prim.attributes.find("POSITION");
    if (position_it == prim.attributes.end()) {
        fail(label + " has no POSITION attribute");
    }
    const std::vector<double> positions = decode(position_it->second, kPositionFormat,
                                                 label + " POSITION");
    const std::size_t vertices = positions.size() / 3;
    const std::size_t base = g.num_vertices();
    /* (64-bit arithmetic: on 32-bit x86 size_t holds no 2^32.) */
    if ((std::uint64_t)vertices > kMaxSurfaceVertices - (std::uint64_t)base) {
        fail(label + ": the surface would have more than 2^32 vertices");
    }
    for (std::size_t v = 0; v < vertices; v++) {
        const double *p = &positions[3 * v];
        if (!all_finite(p, 3)) {
            fail(label + " POSITION vertex " + std::to_string(v) + " is not finite (" +
                 number_text(p[0]) + ", " + number_text(p[1]) + ", " + number_text(p[2]) + ")");
        }
    }

    std::vector<uint32_t> corners;
    if (prim.indices >= 0) {
        const std::vector<double> indices = decode(prim.indices, kIndexFormat, label + " indices");
        corners.reserve(indices.size());
        for (std::size_t i = 0; i < indices.size(); i++) {
            if (!(indices[i] < double(vertices))) {
                fail(label + ": index " + std::to_string(i) + " is " +
                     std::to_string(static_cast<uint64_t>(indices[i])) +
                     ", out of range: POSITION has " + std::to_string(vertices) + " vertices");
            }
            corners.push_back(static_cast<uint32_t>(indices[i]));
        }
    } else {
        corners.resize(vertices);
        for (std::size_t v = 0; v < vertices; v++) {
            corners[v] = static_cast<uint32_t>(v);
        }
    }
    if (mode == TINYGLTF_MODE_TRIANGLES && corners.size() % 3 != 0) {
        fail(label + ": TRIANGLES with " + std::to_string(corners.size()) +
             " indices, not a multiple of 3");
    }

    g.primitive_starts.emplace_back(base, primitive);
    g.positions.reserve(g.positions.size() + positions.size());
    for (double c : positions) {
        g.positions.push_back(static_cast<float>(c)); /* exact: they were floats */
    }
    append_triangles(mode, corners, static_cast<uint32_t>(base), g.indices);
    if (skinned) {
        append_skin_attributes(mesh, primitive, vertices, g);
    }
    g.primitives++;
}

void Loader::place_rigid(int mesh, const Mat4 &world, const MeshGeometry &g,
                         GltfSurface &surface) const {
    const std::vector<uint32_t> first = first_vertex_at_same_position(g.positions);
    surface.positions.resize(g.positions.size());
    for (std::size_t v = 0; v < g.num_vertices(); v++) {
        float *out = &surface.positions[3 * v];
        if (first[v] != v) { /* first[v] < v: already placed */
            std::copy_n(&surface.positions[3 * std::size_t(first[v])], 3, out);
            continue;
        }
        const std::array<float, 3> p = transform_point(world, &g.positions[3 * v]);
        if (!std::isfinite(p[0]) || !std::isfinite(p[1]) || !std::isfinite(p[2])) {
            fail(vertex_label(mesh, g, v) + " is not finite in world space (the transform "
                                            "overflows float)");
        }
        std::copy(p.begin(), p.end(), out);
    }
    surface.indices = g.indices;
    if (linear_determinant(world) < 0.0) {
        for (std::size_t t = 0; t < surface.num_triangles(); t++) {
            flip_triangle(surface.indices, t);
        }
        surface.flipped_triangles = surface.num_triangles();
    }
}

/* world(joint_j) * inverseBindMatrix_j for each joint of the skin. */
std::vector<Mat4> Loader::joint_matrices(int skin) const {
    const tinygltf::Skin &s = gltf_.skins[skin];
    const std::string label = "skin " + std::to_string(skin) +
                              (s.name.empty() ? "" : " " + quoted(s.name));
    if (s.joints.empty()) {
        fail(label + " has no joints");
    }
    std::vector<double> inverse_bind;
    if (s.inverseBindMatrices >= 0) {
        inverse_bind = decode(s.inverseBindMatrices, kInverseBindFormat,
                              label + " inverseBindMatrices");
        if (inverse_bind.size() < 16 * s.joints.size()) {
            fail(label + " inverseBindMatrices: " + std::to_string(inverse_bind.size() / 16) +
                 " matrices for " + std::to_string(s.joints.size()) + " joints");
        }
    }
    std::vector<Mat4> matrices(s.joints.size());
    for (std::size_t j = 0; j < s.joints.size(); j++) {
        const int node = s.joints[j];
        if (node < 0 || node >= static_cast<int>(gltf_.nodes.size())) {
            fail(label + ": joint " + std::to_string(j) + " is node " + std::to_string(node) +
                 ", which does not exist");
        }
        Mat4 ibm = identity_matrix();
        if (!inverse_bind.empty()) {
            std::copy_n(&inverse_bind[16 * j], 16, ibm.begin());
            if (!all_finite(ibm.data(), 16)) {
                fail(label + ": inverse bind matrix " + std::to_string(j) + " is not finite");
            }
            if (!is_affine(ibm)) {
                fail(label + ": inverse bind matrix " + std::to_string(j) +
                     " bottom row is not (0 0 0 1)");
            }
        }
        matrices[j] = multiply(world_[node], ibm);
    }
    return matrices;
}

/* Every vertex's influences, used or not: joints in range, weights finite,
 * non-negative and not all zero. Notes sums far from 1 (they are divided
 * by their sum when blending). */
void Loader::check_skin_weights(int mesh, int skin, const MeshGeometry &g) {
    const std::size_t num_joints = gltf_.skins[skin].joints.size();
    std::size_t off_sum = 0, first_off = 0;
    double first_off_sum = 0.0;
    for (std::size_t v = 0; v < g.num_vertices(); v++) {
        double sum = 0.0;
        for (int k = 0; k < kMaxInfluences; k++) {
            const std::size_t slot = v * kMaxInfluences + k;
            const double w = g.weights[slot];
            if (!std::isfinite(w) || w < 0.0) {
                fail(vertex_label(mesh, g, v) + ": skin weight " + std::to_string(k) + " is " +
                     number_text(w) + " (must be finite and >= 0)");
            }
            if (g.joints[slot] >= num_joints) {
                fail(vertex_label(mesh, g, v) + ": joint index " + std::to_string(g.joints[slot]) +
                     " is out of range (skin " + std::to_string(skin) + " has " +
                     std::to_string(num_joints) + " joints)");
            }
            sum += w;
        }
        if (!(sum > 0.0)) {
            fail(vertex_label(mesh, g, v) + ": all skin weights are zero (the vertex has no "
                                            "bind pose)");
        }
        if (std::fabs(sum - 1.0) > kWeightSumTolerance) {
            if (off_sum++ == 0) {
                first_off = v;
                first_off_sum = sum;
            }
        }
    }
    if (off_sum > 0) {
        note(mesh_label(mesh) + ": " + std::to_string(off_sum) +
             " vertices have skin weights that do not sum to 1 (first: " +
             vertex_label(mesh, g, first_off) + ", sum " + number_text(first_off_sum) +
             "); each was divided by its sum");
    }
}

void Loader::place_skinned(int mesh, int skin, const MeshGeometry &g, GltfSurface &surface) const {
    const std::vector<Mat4> joints = joint_matrices(skin);
    const std::vector<uint32_t> first = first_vertex_at_same_position(g.positions);
    std::vector<bool> mirrors(g.num_vertices(), false); /* meaningful at first[v] == v */
    surface.positions.resize(g.positions.size());
    for (std::size_t v = 0; v < g.num_vertices(); v++) {
        float *out = &surface.positions[3 * v];
        if (first[v] != v) { /* the first vertex's weights decide */
            std::copy_n(&surface.positions[3 * std::size_t(first[v])], 3, out);
            continue;
        }
        const double *w = &g.weights[v * kMaxInfluences];
        const uint32_t *j = &g.joints[v * kMaxInfluences];
        double sum = 0.0;
        for (int k = 0; k < kMaxInfluences; k++) {
            sum += w[k];
        }
        Mat4 blend{}; /* bottom row: sum of (w_k / sum) * (0 0 0 1) = (0 0 0 1) */
        for (int k = 0; k < kMaxInfluences; k++) {
            if (w[k] == 0.0) {
                continue;
            }
            const double wk = w[k] / sum;
            for (int e = 0; e < 16; e++) {
                blend[e] += wk * joints[j[k]][e];
            }
        }
        mirrors[v] = linear_determinant(blend) < 0.0;
        const std::array<float, 3> p = transform_point(blend, &g.positions[3 * v]);
        if (!std::isfinite(p[0]) || !std::isfinite(p[1]) || !std::isfinite(p[2])) {
            fail(vertex_label(mesh, g, v) + " is not finite in world space (the skinning "
                                            "overflows float)");
        }
        std::copy(p.begin(), p.end(), out);
    }
    surface.indices = g.indices;
    for (std::size_t t = 0; t < surface.num_triangles(); t++) {
        if (mirrors[first[surface.indices[3 * t]]]) {
            flip_triangle(surface.indices, t);
            surface.flipped_triangles++;
        }
    }
}

bool Loader::declared_ground(int mesh, int node) const {
    auto says = [this](const tinygltf::Value &extras, const std::string &label) {
        if (!extras.IsObject() || !extras.Has(kGroundExtrasKey)) return false;
        const tinygltf::Value &v = extras.Get(kGroundExtrasKey);
        if (!v.IsBool())
            fail(label + ": extras \"" + kGroundExtrasKey + "\" must be true or false");
        return v.Get<bool>();
    };
    const bool by_mesh = says(gltf_.meshes[mesh].extras, mesh_label(mesh));
    const bool by_node = node >= 0 && says(gltf_.nodes[node].extras, node_label(node));
    return by_mesh || by_node;
}

/* Builds one instance's surface; false when it has no triangle (only
 * points or lines, or strips too short). */
bool Loader::build_surface(const Instance &instance, GltfSurface &surface) {
    const tinygltf::Mesh &mesh = gltf_.meshes[instance.mesh];
    if (mesh.primitives.empty()) {
        fail(mesh_label(instance.mesh) + " has no primitives");
    }
    const int skin = instance.node >= 0 ? gltf_.nodes[instance.node].skin : -1;
    MeshGeometry g;
    for (std::size_t p = 0; p < mesh.primitives.size(); p++) {
        append_primitive(instance.mesh, static_cast<int>(p), skin >= 0, g);
    }

    /* Names come from the file: printable and bounded (they are printed). */
    surface.name = (mesh.name.empty() ? "mesh#" + std::to_string(instance.mesh)
                                      : printable_text(mesh.name));
    if (instance.node >= 0) {
        const std::string &node_name = gltf_.nodes[instance.node].name;
        surface.name += " @ " + (node_name.empty() ? "node#" + std::to_string(instance.node)
                                                   : printable_text(node_name));
    }
    surface.mesh_index = instance.mesh;
    surface.node_index = instance.node;
    surface.primitives = g.primitives;
    surface.skinned = skin >= 0;
    surface.declared_ground = declared_ground(instance.mesh, instance.node);
    if (g.indices.empty()) {
        return false;
    }
    if (skin >= 0) {
        check_skin_weights(instance.mesh, skin, g);
        place_skinned(instance.mesh, skin, g, surface);
    } else {
        const Mat4 world = instance.node >= 0 ? world_[instance.node] : identity_matrix();
        place_rigid(instance.mesh, world, g, surface);
    }
    surface.mirrored = surface.flipped_triangles > 0;
    return true;
}

} // namespace gltf_detail
} // namespace sv
