/*
 * gltf_internal::Reader (gltf_internal.h): the static loader's file
 * checks, node graph, accessor decoder and merged triangle primitives, with
 * their checks and words, as the animated-scene loader (src/anim) reads a
 * file through them.
 *
 * Copyright (C) 2026 the shadowvol authors. LGPL-2.1-or-later.
 */
#include "gltf_internal.h"
#include "gltf_detail.h"

#include <algorithm>
#include <memory>
#include <string>
#include <utility>
#include <vector>

namespace sv {
namespace gltf_internal {

using namespace gltf_detail; /* the Loader and what it shares */

struct Reader::Impl {
    std::string path;
    GltfLoadOptions options; /* none: every mesh instance */
    GltfModel out;           /* only its notes are used */
    tinygltf::Model model;
    std::unique_ptr<Loader> loader;
};

Reader::Reader(const std::string &path) : impl_(new Impl) {
    impl_->path = path;
    impl_->out.path = path;
    impl_->model = parse_gltf(path, read_file(path), impl_->options.external_files,
                              impl_->out.notes);
    impl_->loader.reset(new Loader(impl_->path, impl_->model, impl_->options, impl_->out));
    impl_->loader->check_required_extensions();
}

Reader::Reader(const unsigned char *bytes, std::size_t size, const std::string &name)
    : impl_(new Impl) {
    impl_->path = name;
    impl_->out.path = name;
    impl_->options.external_files = false;
    impl_->model = parse_gltf(name, std::vector<unsigned char>(bytes, bytes + size), false,
                              impl_->out.notes);
    impl_->loader.reset(new Loader(impl_->path, impl_->model, impl_->options, impl_->out));
    impl_->loader->check_required_extensions();
}

Reader::~Reader() = default;

const tinygltf::Model &Reader::model() const { return impl_->model; }
const std::string &Reader::path() const { return impl_->path; }
std::vector<std::string> &Reader::notes() { return impl_->out.notes; }
void Reader::note(const std::string &line) { impl_->loader->note(line); }
void Reader::fail(const std::string &problem) const { impl_->loader->fail(problem); }
std::string Reader::node_label(int node) const { return impl_->loader->node_label(node); }
std::string Reader::mesh_label(int mesh) const { return impl_->loader->mesh_label(mesh); }

void Reader::check_nodes() { impl_->loader->compute_world_matrices(); }
const std::vector<int> &Reader::parent() const { return impl_->loader->parent_; }
const std::vector<Mat4> &Reader::world() const { return impl_->loader->world_; }
Mat4 Reader::local_matrix(int node) const { return impl_->loader->local_matrix(node); }
bool Reader::declared_ground(int mesh, int node) const {
    return impl_->loader->declared_ground(mesh, node);
}
std::vector<int> Reader::scene_roots() const {
    return impl_->model.nodes.empty() ? std::vector<int>{} : impl_->loader->scene_roots();
}

std::vector<std::pair<int, int>> Reader::instances() const {
    std::vector<std::pair<int, int>> out;
    for (const Instance &i : impl_->loader->select_instances()) {
        out.emplace_back(i.mesh, i.node);
    }
    return out;
}

const tinygltf::Accessor &Reader::accessor(int index, const std::string &who) const {
    return impl_->loader->accessor_at(index, who);
}

std::string Reader::format_text(const tinygltf::Accessor &a) {
    return std::string(a.normalized ? "normalized " : "") + component_type_name(a.componentType) +
           " " + type_name(a.type);
}

std::vector<double> Reader::decode(int index, const std::string &who) const {
    const Accessor &a = accessor(index, who);
    const int ct = a.componentType;
    const bool readable = ct == TINYGLTF_COMPONENT_TYPE_BYTE || ct == kU8 ||
                          ct == TINYGLTF_COMPONENT_TYPE_SHORT || ct == kU16 || ct == kU32 ||
                          ct == kF32;
    if (!readable || components_in(a.type) == 0) {
        fail(who + " (accessor " + std::to_string(index) + ") is " + format_text(a) +
             ", not a glTF accessor format");
    }
    /* The accessor's own format: decode() then checks only count, sizes and
     * byte ranges. */
    const AccessorFormat own = {a.type, {{{ct, a.normalized}}}, 1, ""};
    return impl_->loader->decode(index, own, who);
}

MeshData Reader::mesh(int mesh, int skin) {
    Loader &loader = *impl_->loader;
    const tinygltf::Mesh &m = impl_->model.meshes[mesh];
    if (m.primitives.empty()) {
        fail(mesh_label(mesh) + " has no primitives");
    }
    MeshGeometry g;
    MeshData d;
    for (std::size_t p = 0; p < m.primitives.size(); p++) {
        const int primitives_before = g.primitives;
        loader.append_primitive(mesh, static_cast<int>(p), skin >= 0, g);
        if (skin >= 0 && g.primitives > primitives_before) {
            const auto &attributes = m.primitives[p].attributes;
            d.influence_sets = std::max(d.influence_sets, attributes.count("JOINTS_1") ? 2 : 1);
        }
    }
    if (skin >= 0 && !g.indices.empty()) {
        loader.check_skin_weights(mesh, skin, g);
    }
    d.positions = std::move(g.positions);
    d.indices = std::move(g.indices);
    d.primitives = g.primitives;
    d.joints = std::move(g.joints);
    d.weights = std::move(g.weights);
    return d;
}

std::vector<Mat4> Reader::inverse_bind_matrices(int skin) const {
    const tinygltf::Skin &s = impl_->model.skins[skin];
    const std::string label = "skin " + std::to_string(skin) +
                              (s.name.empty() ? "" : " " + quoted(s.name));
    if (s.joints.empty()) {
        fail(label + " has no joints");
    }
    std::vector<double> inverse_bind;
    if (s.inverseBindMatrices >= 0) {
        inverse_bind = impl_->loader->decode(s.inverseBindMatrices, kInverseBindFormat,
                                             label + " inverseBindMatrices");
        if (inverse_bind.size() < 16 * s.joints.size()) {
            fail(label + " inverseBindMatrices: " + std::to_string(inverse_bind.size() / 16) +
                 " matrices for " + std::to_string(s.joints.size()) + " joints");
        }
    }
    std::vector<Mat4> matrices(s.joints.size(), identity_matrix());
    for (std::size_t j = 0; j < s.joints.size(); j++) {
        const int node = s.joints[j];
        if (node < 0 || node >= static_cast<int>(impl_->model.nodes.size())) {
            fail(label + ": joint " + std::to_string(j) + " is node " + std::to_string(node) +
                 ", which does not exist");
        }
        if (!inverse_bind.empty()) {
            std::copy_n(&inverse_bind[16 * j], 16, matrices[j].begin());
            if (!all_finite(matrices[j].data(), 16)) {
                fail(label + ": inverse bind matrix " + std::to_string(j) + " is not finite");
            }
            if (!is_affine(matrices[j])) {
                fail(label + ": inverse bind matrix " + std::to_string(j) +
                     " bottom row is not (0 0 0 1)");
            }
        }
    }
    return matrices;
}

} // namespace gltf_internal
} // namespace sv
