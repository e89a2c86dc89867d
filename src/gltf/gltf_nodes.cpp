/*
 * The glTF loader's node graph: each node's local matrix (its `matrix`, or
 * T * R * S with the quaternion normalized), validated; the world matrices
 * down the parent chains (one parent at most, no cycle, finite); the
 * scene's roots; and the mesh instances to place, in depth-first pre-order
 * of the scene (the rules open gltf_loader.cpp).
 *
 * Copyright (C) 2026 the shadowvol authors. LGPL-2.1-or-later.
 */
#include "gltf_detail.h"

#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

namespace sv {
namespace gltf_detail {

Mat4 Loader::local_matrix(int node) const {
    const tinygltf::Node &n = gltf_.nodes[node];
    if (!n.matrix.empty()) {
        if (n.matrix.size() != 16) {
            fail(node_label(node) + ": matrix has " + std::to_string(n.matrix.size()) +
                 " numbers, not 16");
        }
        Mat4 m;
        std::copy(n.matrix.begin(), n.matrix.end(), m.begin());
        if (!all_finite(m.data(), 16)) {
            fail(node_label(node) + ": matrix is not finite");
        }
        if (!is_affine(m)) {
            fail(node_label(node) + ": matrix bottom row is not (0 0 0 1)");
        }
        return m;
    }
    if (!n.translation.empty() && n.translation.size() != 3) {
        fail(node_label(node) + ": translation has " + std::to_string(n.translation.size()) +
             " numbers, not 3");
    }
    if (!n.rotation.empty() && n.rotation.size() != 4) {
        fail(node_label(node) + ": rotation has " + std::to_string(n.rotation.size()) +
             " numbers, not 4");
    }
    if (!n.scale.empty() && n.scale.size() != 3) {
        fail(node_label(node) + ": scale has " + std::to_string(n.scale.size()) +
             " numbers, not 3");
    }
    const double t[3] = {n.translation.empty() ? 0.0 : n.translation[0],
                         n.translation.empty() ? 0.0 : n.translation[1],
                         n.translation.empty() ? 0.0 : n.translation[2]};
    double q[4] = {0.0, 0.0, 0.0, 1.0}; /* x y z w */
    if (!n.rotation.empty()) {
        std::copy(n.rotation.begin(), n.rotation.end(), q);
    }
    const double s[3] = {n.scale.empty() ? 1.0 : n.scale[0], n.scale.empty() ? 1.0 : n.scale[1],
                         n.scale.empty() ? 1.0 : n.scale[2]};
    if (!all_finite(t, 3) || !all_finite(q, 4) || !all_finite(s, 3)) {
        fail(node_label(node) + ": translation, rotation or scale is not finite");
    }
    const double norm = std::sqrt(q[0] * q[0] + q[1] * q[1] + q[2] * q[2] + q[3] * q[3]);
    if (!(norm > 0.0) || !std::isfinite(norm)) {
        fail(node_label(node) + ": rotation quaternion is zero");
    }
    const double x = q[0] / norm, y = q[1] / norm, z = q[2] / norm, w = q[3] / norm;
    /* Rotation matrix of a unit quaternion, rows as written. */
    const double r[3][3] = {
        {1.0 - 2.0 * (y * y + z * z), 2.0 * (x * y - z * w), 2.0 * (x * z + y * w)},
        {2.0 * (x * y + z * w), 1.0 - 2.0 * (x * x + z * z), 2.0 * (y * z - x * w)},
        {2.0 * (x * z - y * w), 2.0 * (y * z + x * w), 1.0 - 2.0 * (x * x + y * y)}};
    /* T * R * S: column j of R scaled by s[j], then the translation. */
    Mat4 m = identity_matrix();
    for (int col = 0; col < 3; col++) {
        for (int row = 0; row < 3; row++) {
            m[4 * col + row] = r[row][col] * s[col];
        }
    }
    m[12] = t[0];
    m[13] = t[1];
    m[14] = t[2];
    return m;
}

void Loader::compute_world_matrices() {
    const int num_nodes = static_cast<int>(gltf_.nodes.size());
    const int num_meshes = static_cast<int>(gltf_.meshes.size());
    const int num_skins = static_cast<int>(gltf_.skins.size());
    parent_.assign(gltf_.nodes.size(), -1);
    for (int n = 0; n < num_nodes; n++) {
        const tinygltf::Node &node = gltf_.nodes[n];
        if (node.mesh < -1 || node.mesh >= num_meshes) {
            fail(node_label(n) + ": mesh " + std::to_string(node.mesh) + " does not exist (" +
                 std::to_string(num_meshes) + " meshes)");
        }
        if (node.skin < -1 || node.skin >= num_skins) {
            fail(node_label(n) + ": skin " + std::to_string(node.skin) + " does not exist (" +
                 std::to_string(num_skins) + " skins)");
        }
        for (int child : node.children) {
            if (child < 0 || child >= num_nodes) {
                fail(node_label(n) + ": child node " + std::to_string(child) + " does not exist (" +
                     std::to_string(num_nodes) + " nodes)");
            }
            if (child == n) {
                fail(node_label(n) + " is its own child (a cycle)");
            }
            if (parent_[child] != -1) {
                fail(node_label(child) + " is a child of both node " +
                     std::to_string(parent_[child]) + " and node " + std::to_string(n) +
                     " (glTF nodes have at most one parent)");
            }
            parent_[child] = n;
        }
    }

    /* With one parent at most, the graph is a forest plus components that
     * contain a cycle; walking down from the roots reaches exactly the
     * forest. An explicit stack: a chain of 100k nodes must not overflow
     * the call stack. */
    world_.assign(gltf_.nodes.size(), identity_matrix());
    std::vector<int> stack;
    std::size_t reached = 0;
    for (int n = num_nodes - 1; n >= 0; n--) {
        if (parent_[n] == -1) {
            stack.push_back(n);
        }
    }
    while (!stack.empty()) {
        const int n = stack.back();
        stack.pop_back();
        reached++;
        const Mat4 local = local_matrix(n);
        world_[n] = parent_[n] == -1 ? local : multiply(world_[parent_[n]], local);
        if (!all_finite(world_[n].data(), 16)) {
            fail(node_label(n) + ": world matrix is not finite (the chain of transforms "
                                 "overflows)");
        }
        const std::vector<int> &children = gltf_.nodes[n].children;
        for (auto it = children.rbegin(); it != children.rend(); ++it) {
            stack.push_back(*it);
        }
    }
    if (reached != gltf_.nodes.size()) {
        std::vector<bool> seen(gltf_.nodes.size(), false);
        for (int n = 0; n < num_nodes; n++) {
            /* Unreached nodes hang from a cycle: climb to it. */
            if (parent_[n] == -1) {
                continue;
            }
            int m = n;
            while (!seen[m]) {
                seen[m] = true;
                m = parent_[m];
                if (m == -1) {
                    break;
                }
            }
            if (m != -1) {
                fail("node hierarchy has a cycle through " + node_label(m));
            }
        }
        fail("node hierarchy has a cycle"); /* not reached: one was found above */
    }
}

std::vector<int> Loader::scene_roots() const {
    const int num_nodes = static_cast<int>(gltf_.nodes.size());
    if (gltf_.scenes.empty()) {
        if (gltf_.defaultScene >= 0) {
            fail("scene " + std::to_string(gltf_.defaultScene) + " does not exist (no scenes)");
        }
        std::vector<int> roots;
        for (int n = 0; n < num_nodes; n++) {
            if (parent_[n] == -1) {
                roots.push_back(n);
            }
        }
        return roots;
    }
    const int scene = gltf_.defaultScene >= 0 ? gltf_.defaultScene : 0;
    if (scene >= static_cast<int>(gltf_.scenes.size())) {
        fail("scene " + std::to_string(scene) + " does not exist (" +
             std::to_string(gltf_.scenes.size()) + " scenes)");
    }
    const std::vector<int> &roots = gltf_.scenes[scene].nodes;
    std::vector<bool> listed(gltf_.nodes.size(), false);
    for (int n : roots) {
        const std::string who = "scene " + std::to_string(scene) + ": node " + std::to_string(n);
        if (n < 0 || n >= num_nodes) {
            fail(who + " does not exist (" + std::to_string(num_nodes) + " nodes)");
        }
        if (listed[n]) {
            fail(who + " is listed twice");
        }
        if (parent_[n] != -1) {
            fail(who + " is not a root (it is a child of node " + std::to_string(parent_[n]) + ")");
        }
        listed[n] = true;
    }
    return roots;
}

std::vector<Instance> Loader::select_instances() const {
    /* Which meshes are wanted: all, or those named options.mesh_name. */
    std::vector<bool> wanted(gltf_.meshes.size(), options_.mesh_name.empty());
    if (!options_.mesh_name.empty()) {
        bool found = false;
        for (std::size_t m = 0; m < gltf_.meshes.size(); m++) {
            if (gltf_.meshes[m].name == options_.mesh_name) {
                wanted[m] = true;
                found = true;
            }
        }
        if (!found) {
            std::string names;
            for (std::size_t m = 0; m < gltf_.meshes.size(); m++) {
                const std::string &name = gltf_.meshes[m].name;
                names += (m ? ", " : "") +
                         (name.empty() ? "mesh#" + std::to_string(m) : quoted(name));
            }
            fail("no mesh named " + quoted(options_.mesh_name) +
                 "; the meshes are: " + (names.empty() ? std::string("(none)") : names));
        }
    }

    std::vector<Instance> instances;
    if (!gltf_.nodes.empty()) {
        /* Depth-first pre-order, children in file order. */
        const std::vector<int> roots = scene_roots();
        std::vector<int> stack(roots.rbegin(), roots.rend());
        while (!stack.empty()) {
            const int n = stack.back();
            stack.pop_back();
            const tinygltf::Node &node = gltf_.nodes[n];
            if (node.mesh >= 0 && wanted[node.mesh]) {
                instances.push_back({node.mesh, n});
            }
            for (auto it = node.children.rbegin(); it != node.children.rend(); ++it) {
                stack.push_back(*it);
            }
        }
    }
    /* No nodes at all, or a named mesh the scene does not use: each wanted
     * mesh once, at identity. */
    if (gltf_.nodes.empty() || (instances.empty() && !options_.mesh_name.empty())) {
        for (std::size_t m = 0; m < gltf_.meshes.size(); m++) {
            if (wanted[m]) {
                instances.push_back({static_cast<int>(m), -1});
            }
        }
    }
    return instances;
}

} // namespace gltf_detail
} // namespace sv
