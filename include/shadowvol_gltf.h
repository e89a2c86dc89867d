/*
 * shadowvol: glTF 2.0 loading (.gltf and .glb, through Debian's tinygltf).
 * Turns the mesh instances of a scene into triangle surfaces in world space,
 * ready for sv::prepare_surface (shadowvol_mesh.h).
 *
 * Copyright (C) 2026 the shadowvol authors. LGPL-2.1-or-later.
 */
#ifndef SHADOWVOL_GLTF_H
#define SHADOWVOL_GLTF_H

#include <cstddef>
#include <cstdint>
#include <stdexcept>
#include <string>
#include <vector>

namespace sv {

struct GltfLoadOptions {
    /* Empty: every mesh instance of the scene (below). Otherwise only the
     * instances of the mesh with this name; when the scene does not use
     * that mesh it is loaded once with the identity transform. An unknown
     * name is an error that lists the mesh names. */
    std::string mesh_name;

    /* Hostile sizes (issue 17): a small file can ask for any amount of work
     * (10^4 instances of a character are 13M triangles from 176 KB). Before
     * any surface is built, the loader estimates from the accessor counts
     * the triangles and vertices of every selected instance, and refuses
     * the file (GltfError naming the counts, the estimated memory and time,
     * and the limit) when either exceeds its limit. Defaults: 2^24
     * triangles and 2^25 vertices (about 2.5 GB and 10 s to load and
     * prepare on one core), 2^20 nodes. 0 = no limit. */
    std::size_t max_triangles = kDefaultMaxTriangles;
    std::size_t max_vertices = kDefaultMaxVertices;
    std::size_t max_nodes = kDefaultMaxNodes;
    /* false: buffers and images named by a file uri are refused (only data:
     * URIs and the GLB's BIN chunk are read): for input that must not make
     * the loader open other files (the fuzz targets). */
    bool external_files = true;

    static constexpr std::size_t kDefaultMaxTriangles = std::size_t(1) << 24;
    static constexpr std::size_t kDefaultMaxVertices = std::size_t(1) << 25;
    static constexpr std::size_t kDefaultMaxNodes = std::size_t(1) << 20;
};

/* JSON nested deeper than this (arrays and objects, in a .gltf or in a
 * GLB's JSON chunk) is refused before tinygltf parses it: tinygltf parses
 * values recursively, and 17,500 levels of [[[...]]] (40 KB) overflowed
 * its stack. glTF itself needs about 8 levels. */
constexpr int kGltfMaxJsonDepth = 128;

/* What one message quotes of the file's text (tinygltf's errors, names):
 * at most this many bytes, with every byte that is not part of valid
 * UTF-8, and every control character, written as \xNN. */
constexpr std::size_t kGltfMaxQuotedBytes = 300;

/* S made safe to print: valid UTF-8, no control characters (\xNN instead),
 * cut after MAX_BYTES input bytes with "... (N more bytes)". Idempotent on
 * its own output. */
std::string printable_text(const std::string &s, std::size_t max_bytes = kGltfMaxQuotedBytes);

/* One mesh instance (a node with a mesh, or a mesh loaded on its own):
 * all its triangle primitives merged into one surface. */
/* The extras key (on a glTF mesh or node) that declares a surface the top
 * of a solid never seen from below: GltfSurface::declared_ground. */
constexpr const char *kGroundExtrasKey = "shadowvol_ground";

struct GltfSurface {
    std::string name; /* "<mesh name or mesh#i> @ <node name or node#j>";
                              just the mesh part when loaded at identity */
    int mesh_index = -1;
    int node_index = -1;   /* -1: loaded at identity (no node) */
    int primitives = 0;    /* triangle primitives merged (modes 4, 5, 6) */
    bool mirrored = false; /* some triangle's winding was flipped back
                              (flipped_triangles > 0). Rigid: the node's
                              world transform has a negative determinant,
                              and every triangle was flipped. Skinned: the
                              blended matrix of a triangle's first corner
                              decides, triangle by triangle. */
    std::size_t flipped_triangles = 0;
    bool skinned = false; /* placed by its skin's joints, in the pose the
                              file's joint NODES have (their stored
                              transforms): the bind pose only when the file
                              was saved in it; a character saved mid-
                              animation loads in that pose. The skinned
                              node's own transform is ignored (glTF) */
    /* Its mesh or node says "shadowvol_ground": true in its extras: the
     * top of a solid never seen from below (shadowvol_casters.h). */
    bool declared_ground = false;
    /* World-space positions, x y z per vertex, computed in double and
     * rounded to float once. Vertices whose mesh-space positions are
     * bitwise equal (-0.0 == +0.0) get bitwise equal world positions, so
     * welding finds in world space exactly what it finds in mesh space:
     * the first vertex at a position is transformed (skinned: with its own
     * weights) and the others copy it. Every coordinate is finite. */
    std::vector<float> positions;
    /* Triangles (3 per triangle), counter-clockwise seen from the front in
     * world space; strips and fans converted; each index < vertex count. */
    std::vector<uint32_t> indices;

    std::size_t num_vertices() const { return positions.size() / 3; }
    std::size_t num_triangles() const { return indices.size() / 3; }
};

struct GltfModel {
    std::string path;
    /* In depth-first pre-order of the scene; never empty, and each has at
     * least one triangle (instances without any are left out, with a
     * note). */
    std::vector<GltfSurface> surfaces;
    /* What was ignored or adjusted, one line each:
     * primitives of other modes (points, lines), instances without
     * triangles, morph targets, skin weights that did not sum to 1,
     * tinygltf warnings. */
    std::vector<std::string> notes;
};

/* Malformed or unusable input. what() is "<path>: <problem>", naming the
 * mesh / primitive / accessor / vertex concerned. */
class GltfError : public std::runtime_error {
public:
    using std::runtime_error::runtime_error;
};

/* Loads a .gltf (JSON) or .glb (binary) file; the format is chosen by the
 * file's first bytes ("glTF" magic), not by its name.
 * Scene: the file's `scene`, else scene 0, else (no scenes) every root
 * node; a file without nodes loads each mesh once at identity.
 * Throws GltfError; see the implementation's header comment for the list of
 * checks. Never reads outside a buffer. */
GltfModel load_gltf(const std::string &path, const GltfLoadOptions &options = {});

/* The same from bytes in memory; NAME stands for the path in messages, and
 * file uris are relative to its folder (when options.external_files). */
GltfModel load_gltf_memory(const unsigned char *bytes, std::size_t size, const std::string &name,
                           const GltfLoadOptions &options = {});

} // namespace sv

#endif /* SHADOWVOL_GLTF_H */
