/*
 * Internal to src/gltf (not installed; src/anim reads files through
 * gltf_internal.h): what the files of the static glTF loader share, the
 * Loader class whose members they define, and the bounds, helpers,
 * matrices, glTF names and accessor formats more than one of them needs.
 * The loader's rules and the full list of its checks open gltf_loader.cpp.
 * Its files:
 *   gltf_loader.cpp     the entry points (load_gltf, load_gltf_memory,
 *                       printable_text), Loader::run, the labels of
 *                       messages, required extensions, the size limits;
 *   gltf_file.cpp       reading the file, the GLB layout, the JSON depth,
 *                       tinygltf's parse (fail_file, read_file, parse_gltf);
 *   gltf_nodes.cpp      local and world matrices, the scene's roots, the
 *                       mesh instances to place;
 *   gltf_accessors.cpp  the range-checked accessor decoder;
 *   gltf_surfaces.cpp   triangle primitives, skin attributes, rigid and
 *                       skinned placement (weld guarantee, winding);
 *   gltf_helpers.cpp    quoting, 4x4 matrices, glTF type names and sizes;
 *   gltf_reader.cpp     gltf_internal::Reader, for src/anim.
 *
 * Copyright (C) 2026 the shadowvol authors. LGPL-2.1-or-later.
 */
#ifndef SV_GLTF_DETAIL_H
#define SV_GLTF_DETAIL_H

#include "shadowvol_gltf.h"
#include "gltf_internal.h" /* tinygltf, and the Reader the Loader befriends */

#include <array>
#include <cstddef>
#include <cstdint>
#include <string>
#include <utility>
#include <vector>

namespace sv {
namespace gltf_detail {

using tinygltf::Accessor;

/* The largest number of components one accessor may decode to (2^28
 * doubles, 2 GiB): far above any real mesh, and it keeps a bufferView-less
 * sparse accessor with an absurd count from allocating without bound. */
constexpr std::size_t kMaxAccessorComponents = std::size_t(1) << 28;

// --------------------------------------- small helpers (gltf_helpers.cpp) --

std::string quoted(const std::string &s);

// -------------------------------------------- matrices (gltf_helpers.cpp) --

/* 4x4, column-major as glTF stores it: m[4 * column + row]. Every matrix
 * used here is affine (bottom row 0 0 0 1): node matrices and inverse bind
 * matrices are checked, products and weighted averages keep it. */
using Mat4 = std::array<double, 16>;

Mat4 identity_matrix();
Mat4 multiply(const Mat4 &a, const Mat4 &b);
bool is_affine(const Mat4 &m);
bool all_finite(const double *v, std::size_t n);

// ----------------------------------------- glTF naming (gltf_helpers.cpp) --

const char *component_type_name(int component_type);
const char *type_name(int type);
std::size_t components_in(int type);
std::size_t component_size(int component_type);

/* What one use of an accessor accepts. */
struct ComponentRule {
    int component_type;
    bool normalized;
};

struct AccessorFormat {
    int type;                             /* TINYGLTF_TYPE_* */
    std::array<ComponentRule, 3> allowed; /* the first num_allowed count */
    int num_allowed;
    const char *expected; /* for the message */
};

constexpr int kU8 = TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE;
constexpr int kU16 = TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT;
constexpr int kU32 = TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT;
constexpr int kF32 = TINYGLTF_COMPONENT_TYPE_FLOAT;

const AccessorFormat kPositionFormat = {
    TINYGLTF_TYPE_VEC3,
    {{{kF32, false}}},
    1,
    "FLOAT VEC3 (quantized positions, KHR_mesh_quantization, are not supported)"};
const AccessorFormat kIndexFormat = {TINYGLTF_TYPE_SCALAR,
                                     {{{kU8, false}, {kU16, false}, {kU32, false}}},
                                     3,
                                     "SCALAR UNSIGNED_BYTE, UNSIGNED_SHORT or UNSIGNED_INT"};
const AccessorFormat kJointsFormat = {TINYGLTF_TYPE_VEC4,
                                      {{{kU8, false}, {kU16, false}}},
                                      2,
                                      "VEC4 UNSIGNED_BYTE or UNSIGNED_SHORT"};
const AccessorFormat kWeightsFormat = {TINYGLTF_TYPE_VEC4,
                                       {{{kF32, false}, {kU8, true}, {kU16, true}}},
                                       3,
                                       "VEC4 FLOAT, or normalized UNSIGNED_BYTE or UNSIGNED_SHORT"};
const AccessorFormat kInverseBindFormat = {TINYGLTF_TYPE_MAT4, {{{kF32, false}}}, 1, "MAT4 FLOAT"};

// --------------------------------------------- file level (gltf_file.cpp) --

[[noreturn]] void fail_file(const std::string &path, const std::string &problem);
std::vector<unsigned char> read_file(const std::string &path);
tinygltf::Model parse_gltf(const std::string &path, const std::vector<unsigned char> &bytes,
                           bool external_files, std::vector<std::string> &notes);

// ------------------------------------------------------------- the loader --

/* A mesh to place: node -1 = at identity, no skin. */
struct Instance {
    int mesh;
    int node;
};

/* A surface before placement: every triangle primitive of one mesh
 * appended, positions still in mesh space. */
struct MeshGeometry {
    std::vector<float> positions;  /* xyz per vertex, mesh space */
    std::vector<uint32_t> indices; /* triangles, surface numbering */
    /* For messages: the first surface vertex of each appended primitive,
     * with that primitive's index in the mesh. */
    std::vector<std::pair<std::size_t, int>> primitive_starts;
    /* Skinned only: kMaxInfluences joints and weights per vertex (zeros
     * where a primitive has fewer sets). */
    std::vector<uint32_t> joints;
    std::vector<double> weights;
    int primitives = 0;

    std::size_t num_vertices() const { return positions.size() / 3; }
};

class Loader {
public:
    Loader(const std::string &path, const tinygltf::Model &gltf, const GltfLoadOptions &options,
           GltfModel &out)
        : path_(path), gltf_(gltf), options_(options), out_(out) {}

    void run();
    friend class gltf_internal::Reader; /* gltf_reader.cpp */

private:
    [[noreturn]] void fail(const std::string &problem) const { fail_file(path_, problem); }
    void note(const std::string &line);

    std::string mesh_label(int mesh) const;
    std::string node_label(int node) const;
    std::string primitive_label(int mesh, int primitive) const;
    std::string vertex_label(int mesh, const MeshGeometry &g, std::size_t vertex) const;

    void check_required_extensions() const;
    void check_sizes(const std::vector<Instance> &instances) const;

    /* Node graph (gltf_nodes.cpp): parent_ and world_ for every node, all
     * validated. */
    void compute_world_matrices();
    Mat4 local_matrix(int node) const;
    std::vector<Instance> select_instances() const;
    std::vector<int> scene_roots() const;

    /* Accessors (gltf_accessors.cpp). */
    const Accessor &accessor_at(int index, const std::string &who) const;
    std::vector<double> decode(int index, const AccessorFormat &format,
                               const std::string &who) const;
    const unsigned char *element_span(int view_index, std::size_t byte_offset, std::size_t count,
                                      std::size_t element_size, bool use_view_stride,
                                      const std::string &who, std::size_t *stride) const;
    void apply_sparse(const Accessor &a, const std::string &who, std::vector<double> &values,
                      bool write = true) const;
    void check_sparse_ranges(const Accessor &a, const std::string &who) const;

    /* Surfaces (gltf_surfaces.cpp). */
    bool build_surface(const Instance &instance, GltfSurface &surface);
    /* extras "shadowvol_ground" on MESH or NODE (-1: none) is true; a
     * value that is not a boolean is refused. */
    bool declared_ground(int mesh, int node) const;
    void append_primitive(int mesh, int primitive, bool skinned, MeshGeometry &g);
    void append_skin_attributes(int mesh, int primitive, std::size_t vertices, MeshGeometry &g);
    std::vector<Mat4> joint_matrices(int skin) const;
    void check_skin_weights(int mesh, int skin, const MeshGeometry &g);
    void place_rigid(int mesh, const Mat4 &world, const MeshGeometry &g,
                     GltfSurface &surface) const;
    void place_skinned(int mesh, int skin, const MeshGeometry &g, GltfSurface &surface) const;

    const std::string &path_;
    const tinygltf::Model &gltf_;
    const GltfLoadOptions &options_;
    GltfModel &out_;
    std::vector<int> parent_;
    std::vector<Mat4> world_;
};

} // namespace gltf_detail
} // namespace sv

#endif /* SV_GLTF_DETAIL_H */
