/*
 * glTF 2.0 loading: the mesh instances of a scene as world-space triangle
 * surfaces (include/shadowvol_gltf.h). tinygltf (Debian's 2.7.0) parses the
 * JSON and fetches the buffers; everything the loader reads from a buffer
 * it has range-checked itself first: tinygltf checks almost none of the
 * offsets, strides, counts and indices it hands over.
 *
 * WHAT IS COMPUTED
 *
 * One GltfSurface per mesh instance (a node with a mesh), in depth-first
 * pre-order of the scene (children in file order). Scene: the file's
 * `scene`, else scene 0, else (no scenes) every root node in node order; a
 * file without nodes gives each mesh once at identity (node_index -1).
 * options.mesh_name keeps only the instances of the mesh(es) of that name,
 * or loads it once at identity when the scene does not use it.
 *
 * Primitives: modes TRIANGLES (4, also when `mode` is absent),
 * TRIANGLE_STRIP (5) and TRIANGLE_FAN (6), indexed (u8, u16, u32) or not
 * (0, 1, 2, ...). Triangle i of a strip is {v_i, v_(i+1+i%2), v_(i+2-i%2)},
 * of a fan {v_(i+1), v_(i+2), v_0} (glTF 2.0 section 3.7.2.1), so every
 * triangle keeps the strip's or fan's facing. Strips and fans of fewer than
 * 3 vertices give no triangle. POINTS and LINE* primitives are skipped with
 * a note. All triangle primitives of an instance are merged into one
 * surface: each primitive appends its own POSITION vertices (all of them,
 * used or not) and its indices are offset by the vertices before it. No
 * 16-bit limit anywhere: indices are u32, a surface may have up to 2^32
 * vertices.
 *
 * Placement, in double, each world coordinate rounded to float once:
 *  - rigid: p' = W p, W = the node's world matrix, the product down the
 *    parent chain of each node's `matrix` or T * R * S (the rotation
 *    quaternion is normalized first: files store it to a few digits).
 *  - skinned (the node has a skin): the pose of the file's joint NODES, as
 *    their stored transforms place them. That is the bind pose only when
 *    the file was saved in it: a character saved mid-animation loads in
 *    that pose, not its bind pose (which the inverse bind matrices imply
 *    but glTF does not store as node transforms). The skinned node's own
 *    transform is ignored (glTF), and p' = sum_k w_k * (world(joint_k) *
 *    inverseBindMatrix_k) p over the vertex's influences (JOINTS_0/WEIGHTS_0,
 *    and JOINTS_1/WEIGHTS_1 when present). Absent inverseBindMatrices mean
 *    identity. The weights are divided by their sum (so the blend stays an
 *    affine combination even when quantized or sloppy weights sum to
 *    0.996); a surface whose sums stray from 1 by more than 0.01 gets a
 *    note. ALL-ZERO WEIGHTS ARE AN ERROR: the vertex has no pose (glTF gives
 *    none; falling back to the node's transform, which glTF says to ignore
 *    for skinned meshes, would put it somewhere arbitrary).
 *
 * Weld guarantee: vertices whose mesh-space positions are bitwise equal
 * (-0.0 taken as +0.0) get bitwise equal world positions. Each surface
 * transforms the first vertex at each distinct position and copies the
 * result to the others, so welding (sv::prepare_surface) joins in world
 * space exactly what it would join in mesh space: the seams of UV and normal
 * splits stay closed after skinning. For skinned meshes this means THE
 * FIRST VERTEX'S WEIGHTS DECIDE for every vertex at that position (the
 * others' weights are validated, then unused). In files where split
 * vertices carry different weights this moves the later ones slightly; the
 * alternative, a crack in the shadow volume, is worse.
 *
 * Winding: a negative determinant mirrors, and would turn every triangle
 * inside out; such triangles get their corners 1 and 2 swapped, so fronts
 * stay outward (counter-clockwise seen from outside). Rigid: the sign of
 * det(W) decides for the whole surface. Skinned: each triangle is decided by
 * the blended matrix of its FIRST CORNER (the one the weld guarantee used
 * for that position): a mirrored joint mirrors only the triangles it
 * carries, and one corner is a deterministic, local rule where a blend of
 * three would have no better claim. A zero determinant flips nothing (the
 * triangle collapses; preparation drops or keeps it as degenerate).
 *
 * Sparse accessors are supported: the base values (zeros when the accessor
 * has no bufferView) with the sparse values written over them.
 *
 * Morph targets are ignored: base positions, with a note.
 *
 * Required extensions that change how geometry is stored or placed (Draco,
 * meshopt, KHR_mesh_quantization, GPU instancing, anything not known to be
 * about materials, textures or lights) are an error: the base data would be
 * wrong or absent.
 *
 * CHECKS (each a GltfError "<path>: <problem>", naming the scene, node,
 * skin, mesh, primitive, accessor, vertex or index concerned)
 *  - the file: cannot be opened or read, is empty, is 4 GiB or more
 *    (tinygltf takes 32-bit lengths), is neither GLB (magic "glTF") nor a
 *    JSON object;
 *  - GLB: version not 2, header shorter than 12 bytes, declared length
 *    larger than the file, no JSON chunk first, any chunk header or chunk
 *    body past the declared length (checked here because tinygltf 2.7.0
 *    forgets the BIN chunk's 8-byte header when it checks the BIN length);
 *  - whatever tinygltf reports (its error text; its warnings go to notes),
 *    and any exception it throws (it can throw std::out_of_range on an
 *    empty GLB buffer);
 *  - required extensions (above);
 *  - nodes: a child or mesh or skin index out of range, a node that is its
 *    own child or the child of two nodes, a cycle, a matrix of other than
 *    16 or a translation / rotation / scale of other than 3 / 4 / 3 numbers,
 *    a non-finite number, a zero quaternion, a matrix whose bottom row is
 *    not (0 0 0 1) (glTF matrices are affine), a world matrix that
 *    overflows double;
 *  - scenes: `scene` out of range, a scene node out of range, listed twice,
 *    or not a root;
 *  - meshes: no primitives, a mode that is not 0..6, no POSITION, a triangle
 *    list whose index count is not a multiple of 3, an index >= the
 *    primitive's vertex count (the index and its position are named), more
 *    than 2^32 vertices in a surface, no triangle at all in the selected
 *    scene, options.mesh_name naming no mesh (the names are listed);
 *  - accessors: index out of range, count 0, the wrong type or component
 *    type (POSITION: FLOAT VEC3, not normalized, so quantized positions are
 *    refused; indices: SCALAR u8/u16/u32; JOINTS_n: VEC4 u8/u16; WEIGHTS_n:
 *    VEC4 float or normalized u8/u16; inverseBindMatrices: MAT4 FLOAT), no
 *    bufferView and not sparse, more than 2^28 components (a sane bound on
 *    what one accessor may make this loader allocate; 2^24 components for a
 *    sparse accessor without bufferView, whose zeros the file does not
 *    pay for), a count whose byte size overflows size_t;
 *  - buffer ranges: a bufferView or buffer index out of range, a bufferView
 *    past the end of its buffer, a byteStride smaller than the element,
 *    accessor.byteOffset + stride * (count - 1) + element size past the end
 *    of the bufferView (stride 0 = tightly packed); the same for both
 *    halves of a sparse accessor, whose indices must also be < count;
 *  - values: a NaN or infinite position in mesh space or after the
 *    transform (the vertex is named), a non-finite inverse bind matrix or
 *    one whose bottom row is not (0 0 0 1);
 *  - skins: no joints, a joint node out of range, fewer inverse bind
 *    matrices than joints, a skinned primitive without JOINTS_0/WEIGHTS_0,
 *    JOINTS_n and WEIGHTS_n counts differing from POSITION's, more than two
 *    influence sets (8 influences), a joint index >= the skin's joint count,
 *    a negative or non-finite weight, all weights zero.
 *  - hostile sizes (issue 17): JSON nested deeper than kGltfMaxJsonDepth
 *    (checked on the bytes before tinygltf parses them); more nodes than
 *    options.max_nodes; more triangles or vertices, summed over the selected
 *    instances and estimated from the accessor counts before any surface is
 *    built, than options.max_triangles / max_vertices (the message gives
 *    the estimated memory and time). An accessor's buffer range is checked
 *    before its values are allocated, so a small file cannot make the
 *    loader allocate more than its bytes justify (sparse accessors without
 *    bufferView: kMaxUnbackedComponents).
 *  - messages: every text quoted from the file (tinygltf's errors, names)
 *    is at most kGltfMaxQuotedBytes and valid UTF-8 (printable_text).
 * Every size computation that could overflow is checked (checked_add,
 * checked_mul). The host is little-endian (CMake requires x86-64), so
 * buffer bytes are read with memcpy as they are.
 *
 * THE FILES: this one holds the entry points and Loader::run, which checks
 * the limits and builds the surfaces; gltf_detail.h lists the others (the
 * file level, nodes, accessors, surfaces, helpers, and src/anim's Reader).
 *
 * Copyright (C) 2026 the shadowvol authors. LGPL-2.1-or-later.
 */
#include "shadowvol_gltf.h"
#include "gltf_detail.h"

#include <algorithm>
#include <climits>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <string>
#include <utility>
#include <vector>

namespace sv {
namespace gltf_detail {

namespace {

/* The size estimate behind options.max_triangles / max_vertices, for the
 * message: bytes and seconds to load and prepare (measured on the 10M-
 * triangle grid: 1.35 GB; about 0.3 us a triangle in Release). */
constexpr double kBytesPerTriangle = 120.0;
constexpr double kBytesPerVertex = 40.0;
constexpr double kSecondsPerTriangle = 0.3e-6;

std::size_t saturating_add(std::size_t a, std::size_t b) {
    return a > SIZE_MAX - b ? SIZE_MAX : a + b;
}

/* Required extensions that cannot change positions, indices or placement:
 * materials, textures, lights, cameras. Any other required extension may
 * store or place geometry in a way this loader does not read. */
bool is_geometry_neutral_extension(const std::string &name) {
    static const char *const kPrefixes[] = {"KHR_materials_", "KHR_texture_", "EXT_texture_",
                                            "MSFT_texture_",  "KHR_lights_",  "KHR_technique",
                                            "EXT_lights_"};
    for (const char *prefix : kPrefixes) {
        if (name.compare(0, std::strlen(prefix), prefix) == 0) {
            return true;
        }
    }
    return false;
}

} // namespace

void Loader::note(const std::string &line) {
    if (std::find(out_.notes.begin(), out_.notes.end(), line) == out_.notes.end()) {
        out_.notes.push_back(line);
    }
}

std::string Loader::mesh_label(int mesh) const {
    const std::string &name = gltf_.meshes[mesh].name;
    return "mesh " + std::to_string(mesh) + (name.empty() ? "" : " " + quoted(name));
}

std::string Loader::node_label(int node) const {
    const std::string &name = gltf_.nodes[node].name;
    return "node " + std::to_string(node) + (name.empty() ? "" : " " + quoted(name));
}

std::string Loader::primitive_label(int mesh, int primitive) const {
    return mesh_label(mesh) + " primitive " + std::to_string(primitive);
}

std::string Loader::vertex_label(int mesh, const MeshGeometry &g, std::size_t vertex) const {
    auto it = std::upper_bound(g.primitive_starts.begin(), g.primitive_starts.end(),
                               std::make_pair(vertex, INT_MAX));
    --it; /* primitive_starts[0].first == 0 <= vertex */
    return primitive_label(mesh, it->second) + " POSITION vertex " +
           std::to_string(vertex - it->first);
}

void Loader::check_required_extensions() const {
    for (const std::string &name : gltf_.extensionsRequired) {
        if (!is_geometry_neutral_extension(name)) {
            fail("requires extension " + name +
                 ", which may store or place geometry in a way this loader does not read");
        }
    }
}

/* Triangles and vertices the instances ask for, from the accessor counts
 * alone (nothing decoded yet; an accessor that does not exist counts 0 and
 * is reported when decoded), against the options' limits. The estimate
 * takes no time worth measuring: one pass over the meshes' primitives. */
void Loader::check_sizes(const std::vector<Instance> &instances) const {
    std::vector<std::pair<std::size_t, std::size_t>> per_mesh(gltf_.meshes.size());
    std::vector<bool> known(gltf_.meshes.size(), false);
    /* An accessor above decode's own bound counts 0: decode names it. */
    auto count_of = [&](int accessor) -> std::size_t {
        if (accessor < 0 || accessor >= static_cast<int>(gltf_.accessors.size())) {
            return 0;
        }
        const std::size_t count = gltf_.accessors[accessor].count;
        return count > kMaxAccessorComponents ? 0 : count;
    };
    std::size_t triangles = 0, vertices = 0;
    for (const Instance &instance : instances) {
        if (!known[instance.mesh]) {
            std::size_t t = 0, v = 0;
            for (const tinygltf::Primitive &prim : gltf_.meshes[instance.mesh].primitives) {
                const int mode = prim.mode == -1 ? TINYGLTF_MODE_TRIANGLES : prim.mode;
                if (mode < TINYGLTF_MODE_TRIANGLES || mode > TINYGLTF_MODE_TRIANGLE_FAN) {
                    continue;
                }
                const auto position = prim.attributes.find("POSITION");
                const std::size_t pv = position == prim.attributes.end()
                                           ? 0
                                           : count_of(position->second);
                const std::size_t corners = prim.indices >= 0 ? count_of(prim.indices) : pv;
                v = saturating_add(v, pv);
                t = saturating_add(t, mode == TINYGLTF_MODE_TRIANGLES ? corners / 3
                                      : corners >= 3                  ? corners - 2
                                                                      : 0);
            }
            per_mesh[instance.mesh] = {t, v};
            known[instance.mesh] = true;
        }
        triangles = saturating_add(triangles, per_mesh[instance.mesh].first);
        vertices = saturating_add(vertices, per_mesh[instance.mesh].second);
    }
    const bool too_many_triangles = options_.max_triangles && triangles > options_.max_triangles;
    const bool too_many_vertices = options_.max_vertices && vertices > options_.max_vertices;
    if (too_many_triangles || too_many_vertices) {
        const double gb =
            (kBytesPerTriangle * double(triangles) + kBytesPerVertex * double(vertices)) / 1e9;
        char estimate[96];
        std::snprintf(estimate, sizeof estimate, "about %.1f GB and %.0f s to load and prepare", gb,
                      kSecondsPerTriangle * double(triangles));
        fail("the scene asks for " + std::to_string(triangles) + " triangles and " +
             std::to_string(vertices) + " vertices in " + std::to_string(instances.size()) +
             " mesh instance(s) (" + estimate + "), more than the limit of " +
             (too_many_triangles ? std::to_string(options_.max_triangles) + " triangles"
                                 : std::to_string(options_.max_vertices) + " vertices") +
             " (shadowvol: --max-triangles N raises it; GltfLoadOptions::max_triangles, "
             "max_vertices)");
    }
}

void Loader::run() {
    check_required_extensions();
    if (options_.max_nodes && gltf_.nodes.size() > options_.max_nodes) {
        fail(std::to_string(gltf_.nodes.size()) + " nodes, more than the limit of " +
             std::to_string(options_.max_nodes) + " (about " +
             std::to_string((gltf_.nodes.size() * 256) >> 20) +
             " MB of transforms; GltfLoadOptions::max_nodes)");
    }
    compute_world_matrices();
    const std::vector<Instance> instances = select_instances();
    check_sizes(instances);
    for (const Instance &instance : instances) {
        GltfSurface surface;
        if (build_surface(instance, surface)) {
            out_.surfaces.push_back(std::move(surface));
        } else {
            note(surface.name + ": no triangles, skipped");
        }
    }
    if (out_.surfaces.empty()) {
        fail(instances.empty() ? "no triangles: the selected scene has no mesh instances"
                               : "no triangles in the selected scene");
    }
}

} // namespace gltf_detail

using gltf_detail::Loader;
using gltf_detail::parse_gltf;
using gltf_detail::read_file;

std::string printable_text(const std::string &s, std::size_t max_bytes) {
    std::string out;
    const std::size_t n = s.size();
    const unsigned char *p = reinterpret_cast<const unsigned char *>(s.data());
    std::size_t i = 0;
    auto escape = [&](unsigned char c) {
        char hex[8];
        std::snprintf(hex, sizeof hex, "\\x%02X", c);
        out += hex;
    };
    while (i < n && i < max_bytes) {
        const unsigned char c = p[i];
        if (c < 0x20 || c == 0x7F) {
            escape(c);
            i++;
            continue;
        }
        if (c < 0x80) {
            out += static_cast<char>(c);
            i++;
            continue;
        }
        /* A well-formed UTF-8 sequence (RFC 3629: no overlong form, no
         * surrogate, at most U+10FFFF), copied whole; else one escaped byte. */
        std::size_t len = c >= 0xC2 && c <= 0xDF   ? 2
                          : c >= 0xE0 && c <= 0xEF ? 3
                          : c >= 0xF0 && c <= 0xF4 ? 4
                                                   : 0;
        bool ok = len > 0 && i + len <= n;
        for (std::size_t k = 1; ok && k < len; k++) {
            ok = (p[i + k] & 0xC0) == 0x80;
        }
        if (ok && len >= 3) {
            const unsigned char c1 = p[i + 1];
            ok = !(c == 0xE0 && c1 < 0xA0) && !(c == 0xED && c1 > 0x9F) &&
                 !(c == 0xF0 && c1 < 0x90) && !(c == 0xF4 && c1 > 0x8F);
        }
        if (!ok) {
            escape(c);
            i++;
            continue;
        }
        out.append(s, i, len);
        i += len;
    }
    if (i < n) {
        out += "... (" + std::to_string(n - i) + " more bytes)";
    }
    return out;
}

GltfModel load_gltf(const std::string &path, const GltfLoadOptions &options) {
    GltfModel out;
    out.path = path;
    const tinygltf::Model gltf = parse_gltf(path, read_file(path), options.external_files,
                                            out.notes);
    Loader(path, gltf, options, out).run();
    return out;
}

GltfModel load_gltf_memory(const unsigned char *bytes, std::size_t size, const std::string &name,
                           const GltfLoadOptions &options) {
    GltfModel out;
    out.path = name;
    const tinygltf::Model gltf = parse_gltf(name, std::vector<unsigned char>(bytes, bytes + size),
                                            options.external_files, out.notes);
    Loader(name, gltf, options, out).run();
    return out;
}

} // namespace sv
