/*
 * Internal to shadowvol (not installed): what the animated-scene loader
 * (src/anim) shares with the static glTF loader (src/gltf/gltf_loader.cpp
 * and the files src/gltf/gltf_detail.h lists; Reader is defined in
 * gltf_reader.cpp), so that both read a file with the same checks and the
 * same words: the file and GLB checks, tinygltf, the node graph and its
 * transforms, the scene's mesh instances, the range-checked accessor
 * decoder, and the merged triangle primitives of a mesh with their skin
 * attributes.
 *
 * Every failure throws GltfError "<path>: <problem>" as load_gltf does.
 *
 * Copyright (C) 2026 the shadowvol authors. LGPL-2.1-or-later.
 */
#ifndef SV_GLTF_INTERNAL_H
#define SV_GLTF_INTERNAL_H

#include "shadowvol_gltf.h"

/* The configuration src/gltf/tinygltf_build.cpp compiles tinygltf with:
 * the header's inline parts (TinyGLTF's default image callbacks) must agree
 * between the translation units. */
#ifndef TINYGLTF_NO_STB_IMAGE
#define TINYGLTF_NO_STB_IMAGE
#endif
#ifndef TINYGLTF_NO_STB_IMAGE_WRITE
#define TINYGLTF_NO_STB_IMAGE_WRITE
#endif
#ifndef TINYGLTF_NO_EXTERNAL_IMAGE
#define TINYGLTF_NO_EXTERNAL_IMAGE
#endif
#include <tiny_gltf.h>

#include <array>
#include <cstddef>
#include <cstdint>
#include <memory>
#include <string>
#include <utility>
#include <vector>

namespace sv {
namespace gltf_internal {

/* 4x4 column-major, m[4 * column + row], as glTF stores it. */
using Mat4 = std::array<double, 16>;

/* One mesh's triangle primitives merged, as load_gltf merges them (points
 * and lines skipped with a note, strips and fans converted, morph targets
 * noted and ignored), positions in mesh space. */
struct MeshData {
    std::vector<float> positions;  /* xyz per vertex */
    std::vector<uint32_t> indices; /* 3 per triangle, < vertex count */
    int primitives = 0;
    /* Skinned only (skin >= 0): influence sets used by some primitive (1:
     * JOINTS_0/WEIGHTS_0 only, 2: also JOINTS_1/WEIGHTS_1), and 8 joints
     * and weights per vertex (zeros where a primitive has fewer sets).
     * Validated as load_gltf does: joints < the skin's joint count, weights
     * finite, >= 0 and not all zero (sums far from 1 noted). */
    int influence_sets = 0;
    std::vector<uint32_t> joints;
    std::vector<double> weights;

    std::size_t num_vertices() const { return positions.size() / 3; }
};

class Reader {
public:
    /* Reads and parses PATH (load_gltf's file, GLB and tinygltf checks) and
     * checks its required extensions. */
    explicit Reader(const std::string &path);
    /* The same from SIZE bytes in memory, NAME standing for the path in
     * messages; external files (buffers by URI) are refused (the fuzz
     * targets read so). */
    Reader(const unsigned char *bytes, std::size_t size, const std::string &name);
    ~Reader();
    Reader(const Reader &) = delete;
    Reader &operator=(const Reader &) = delete;

    const tinygltf::Model &model() const;
    const std::string &path() const;
    /* Notes so far (tinygltf's warnings, skipped primitives, ...). */
    std::vector<std::string> &notes();
    void note(const std::string &line); /* once per distinct line */
    [[noreturn]] void fail(const std::string &problem) const;

    std::string node_label(int node) const; /* "node 3 'name'" */
    std::string mesh_label(int mesh) const; /* "mesh 0 'name'" */

    /* Validates the node graph as load_gltf does (mesh and skin indices,
     * children, one parent, no cycle, matrix or TRS well formed and finite,
     * no zero quaternion, affine matrices, finite world matrices). After
     * it: parent() and world() (the file's pose). */
    void check_nodes();
    const std::vector<int> &parent() const;
    const std::vector<Mat4> &world() const;
    /* The node's own transform, exactly as load_gltf computes it. */
    Mat4 local_matrix(int node) const;
    /* The scene's root nodes (load_gltf's choice of scene). check_nodes()
     * first. */
    std::vector<int> scene_roots() const;
    /* The mesh instances load_gltf places: (mesh, node) in depth-first
     * pre-order of the scene; node -1 = at identity (a file without
     * nodes). check_nodes() first. */
    std::vector<std::pair<int, int>> instances() const;
    /* GltfSurface::declared_ground of MESH placed by NODE (-1: none). */
    bool declared_ground(int mesh, int node) const;

    /* Every component of accessor INDEX (count * components values) after
     * checking every byte range it reads; WHO names the user in messages.
     * Component types BYTE, UNSIGNED_BYTE, SHORT, UNSIGNED_SHORT,
     * UNSIGNED_INT and FLOAT (normalized integers as glTF says); the
     * caller checks type and component type against what it expects. */
    std::vector<double> decode(int index, const std::string &who) const;
    /* The accessor, range-checked. */
    const tinygltf::Accessor &accessor(int index, const std::string &who) const;
    /* "normalized UNSIGNED_SHORT VEC4" */
    static std::string format_text(const tinygltf::Accessor &a);

    /* Mesh MESH's triangle primitives; SKIN >= 0 also reads and validates
     * their skin attributes against that skin. */
    MeshData mesh(int mesh, int skin);

    /* Skin SKIN's inverse bind matrices (identity when absent), one per
     * joint, checked as load_gltf checks them (joints present and in
     * range, enough matrices, finite, affine). */
    std::vector<Mat4> inverse_bind_matrices(int skin) const;

private:
    struct Impl;
    std::unique_ptr<Impl> impl_;
};

} // namespace gltf_internal
} // namespace sv

#endif /* SV_GLTF_INTERNAL_H */
