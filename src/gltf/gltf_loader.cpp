/*
 * glTF 2.0 loading: the mesh instances of a scene as world-space triangle
 * surfaces (include/shadowvol_gltf.h). tinygltf (Debian's 2.7.0) parses the
 * JSON and fetches the buffers; everything this file reads from a buffer it
 * has range-checked itself first: tinygltf checks almost none of the
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
 * Copyright (C) 2026 the shadowvol authors. LGPL-2.1-or-later.
 */
#include "shadowvol_gltf.h"
#include "gltf_internal.h" /* src/anim reads files through Reader (end of file) */

/* The same configuration as src/gltf/tinygltf_build.cpp, which compiles
 * tinygltf: the header's inline parts (TinyGLTF's default image callbacks)
 * must agree between the two translation units. */
#define TINYGLTF_NO_STB_IMAGE
#define TINYGLTF_NO_STB_IMAGE_WRITE
#define TINYGLTF_NO_EXTERNAL_IMAGE
#include <tiny_gltf.h>

#include <algorithm>
#include <array>
#include <cerrno>
#include <climits>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <memory>
#include <string>
#include <utility>
#include <vector>

namespace sv {

namespace {

using tinygltf::Accessor;

/* The largest number of components one accessor may decode to (2^28
 * doubles, 2 GiB): far above any real mesh, and it keeps a bufferView-less
 * sparse accessor with an absurd count from allocating without bound. */
constexpr std::size_t kMaxAccessorComponents = std::size_t(1) << 28;

/* A sparse accessor without bufferView has zeros for a base: nothing in the
 * file pays for its count, so it gets a tighter bound (16M components,
 * 128 MB of doubles: 5.6M VEC3 positions). */
constexpr std::size_t kMaxUnbackedComponents = std::size_t(1) << 24;

/* Indices are u32: a surface holds at most 2^32 vertices. */
constexpr std::uint64_t kMaxSurfaceVertices = std::uint64_t(1) << 32;

/* JOINTS_0/WEIGHTS_0 and JOINTS_1/WEIGHTS_1: up to 8 influences a vertex. */
constexpr int kMaxInfluenceSets = 2;
constexpr int kMaxInfluences = 4 * kMaxInfluenceSets;

/* Weight sums farther than this from 1 get a note (u8 weights are off by
 * at most 4 * 0.5 / 255 = 0.008). */
constexpr double kWeightSumTolerance = 0.01;

// ---------------------------------------------------------- small helpers --

bool checked_add(std::size_t a, std::size_t b, std::size_t *sum) {
    if (a > SIZE_MAX - b) {
        return false;
    }
    *sum = a + b;
    return true;
}

bool checked_mul(std::size_t a, std::size_t b, std::size_t *product) {
    if (a != 0 && b > SIZE_MAX / a) {
        return false;
    }
    *product = a * b;
    return true;
}

std::string quoted(const std::string &s) { return "'" + printable_text(s) + "'"; }

/* Formats a double the way a person wants to read it in a message. */
std::string number_text(double v) {
    char text[32];
    std::snprintf(text, sizeof text, "%.9g", v);
    return text;
}

// ---------------------------------------------------------------- matrices --

/* 4x4, column-major as glTF stores it: m[4 * column + row]. Every matrix
 * used here is affine (bottom row 0 0 0 1): node matrices and inverse bind
 * matrices are checked, products and weighted averages keep it. */
using Mat4 = std::array<double, 16>;

Mat4 identity_matrix() {
    Mat4 m{};
    m[0] = m[5] = m[10] = m[15] = 1.0;
    return m;
}

Mat4 multiply(const Mat4 &a, const Mat4 &b) {
    Mat4 r{};
    for (int col = 0; col < 4; col++) {
        for (int row = 0; row < 4; row++) {
            double s = 0.0;
            for (int k = 0; k < 4; k++) {
                s += a[4 * k + row] * b[4 * col + k];
            }
            r[4 * col + row] = s;
        }
    }
    return r;
}

/* Determinant of the upper-left 3x3 (the linear part): its sign tells
 * whether the transform mirrors. */
double linear_determinant(const Mat4 &m) {
    return m[0] * (m[5] * m[10] - m[9] * m[6]) - m[4] * (m[1] * m[10] - m[9] * m[2]) +
           m[8] * (m[1] * m[6] - m[5] * m[2]);
}

bool is_affine(const Mat4 &m) {
    return m[3] == 0.0 && m[7] == 0.0 && m[11] == 0.0 && m[15] == 1.0;
}

bool all_finite(const double *v, std::size_t n) {
    for (std::size_t i = 0; i < n; i++) {
        if (!std::isfinite(v[i])) {
            return false;
        }
    }
    return true;
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

// ------------------------------------------------------------ glTF naming --

const char *component_type_name(int component_type) {
    switch (component_type) {
    case TINYGLTF_COMPONENT_TYPE_BYTE: return "BYTE";
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE: return "UNSIGNED_BYTE";
    case TINYGLTF_COMPONENT_TYPE_SHORT: return "SHORT";
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT: return "UNSIGNED_SHORT";
    case TINYGLTF_COMPONENT_TYPE_INT: return "INT";
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT: return "UNSIGNED_INT";
    case TINYGLTF_COMPONENT_TYPE_FLOAT: return "FLOAT";
    case TINYGLTF_COMPONENT_TYPE_DOUBLE: return "DOUBLE";
    default: return "unknown component type";
    }
}

const char *type_name(int type) {
    switch (type) {
    case TINYGLTF_TYPE_SCALAR: return "SCALAR";
    case TINYGLTF_TYPE_VEC2: return "VEC2";
    case TINYGLTF_TYPE_VEC3: return "VEC3";
    case TINYGLTF_TYPE_VEC4: return "VEC4";
    case TINYGLTF_TYPE_MAT2: return "MAT2";
    case TINYGLTF_TYPE_MAT3: return "MAT3";
    case TINYGLTF_TYPE_MAT4: return "MAT4";
    default: return "unknown type";
    }
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

/* Components per element; 0 for an unknown type. (Only the types accepted
 * by some AccessorFormat below reach the decoder, and none of them needs
 * the column padding glTF gives small MAT2/MAT3 elements.) */
std::size_t components_in(int type) {
    switch (type) {
    case TINYGLTF_TYPE_SCALAR: return 1;
    case TINYGLTF_TYPE_VEC2: return 2;
    case TINYGLTF_TYPE_VEC3: return 3;
    case TINYGLTF_TYPE_VEC4: return 4;
    case TINYGLTF_TYPE_MAT2: return 4;
    case TINYGLTF_TYPE_MAT3: return 9;
    case TINYGLTF_TYPE_MAT4: return 16;
    default: return 0;
    }
}

std::size_t component_size(int component_type) {
    switch (component_type) {
    case TINYGLTF_COMPONENT_TYPE_BYTE:
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE: return 1;
    case TINYGLTF_COMPONENT_TYPE_SHORT:
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT: return 2;
    case TINYGLTF_COMPONENT_TYPE_INT:
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT:
    case TINYGLTF_COMPONENT_TYPE_FLOAT: return 4;
    case TINYGLTF_COMPONENT_TYPE_DOUBLE: return 8;
    default: return 0;
    }
}

/* One component as a double. Every component type an AccessorFormat
 * accepts (u8, u16, u32, float) is exact in a double, so one decoder serves
 * indices, joints, weights, positions and matrices. Normalized integers
 * follow glTF 2.0 section 3.11 (c / 255, c / 65535; signed: max(c / 127,
 * -1), max(c / 32767, -1)). */
double read_component(const unsigned char *p, int component_type, bool normalized) {
    switch (component_type) {
    case TINYGLTF_COMPONENT_TYPE_BYTE: {
        int8_t v;
        std::memcpy(&v, p, sizeof v);
        return normalized ? std::max(v / 127.0, -1.0) : v;
    }
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE: {
        uint8_t v;
        std::memcpy(&v, p, sizeof v);
        return normalized ? v / 255.0 : v;
    }
    case TINYGLTF_COMPONENT_TYPE_SHORT: {
        int16_t v;
        std::memcpy(&v, p, sizeof v);
        return normalized ? std::max(v / 32767.0, -1.0) : v;
    }
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT: {
        uint16_t v;
        std::memcpy(&v, p, sizeof v);
        return normalized ? v / 65535.0 : v;
    }
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT: {
        uint32_t v;
        std::memcpy(&v, p, sizeof v);
        return v;
    }
    case TINYGLTF_COMPONENT_TYPE_FLOAT: {
        float v;
        std::memcpy(&v, p, sizeof v);
        return v;
    }
    default: return 0.0; /* unreachable: AccessorFormat admits none other */
    }
}

/* What one use of an accessor accepts. */
struct ComponentRule {
    int component_type;
    bool normalized;
};

struct AccessorFormat {
    int type;                               /* TINYGLTF_TYPE_* */
    std::array<ComponentRule, 3> allowed;   /* the first num_allowed count */
    int num_allowed;
    const char *expected;                   /* for the message */
};

constexpr int kU8 = TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE;
constexpr int kU16 = TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT;
constexpr int kU32 = TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT;
constexpr int kF32 = TINYGLTF_COMPONENT_TYPE_FLOAT;

const AccessorFormat kPositionFormat = {
    TINYGLTF_TYPE_VEC3, {{{kF32, false}}}, 1,
    "FLOAT VEC3 (quantized positions, KHR_mesh_quantization, are not supported)"};
const AccessorFormat kIndexFormat = {
    TINYGLTF_TYPE_SCALAR, {{{kU8, false}, {kU16, false}, {kU32, false}}}, 3,
    "SCALAR UNSIGNED_BYTE, UNSIGNED_SHORT or UNSIGNED_INT"};
const AccessorFormat kJointsFormat = {
    TINYGLTF_TYPE_VEC4, {{{kU8, false}, {kU16, false}}}, 2,
    "VEC4 UNSIGNED_BYTE or UNSIGNED_SHORT"};
const AccessorFormat kWeightsFormat = {
    TINYGLTF_TYPE_VEC4, {{{kF32, false}, {kU8, true}, {kU16, true}}}, 3,
    "VEC4 FLOAT, or normalized UNSIGNED_BYTE or UNSIGNED_SHORT"};
const AccessorFormat kInverseBindFormat = {
    TINYGLTF_TYPE_MAT4, {{{kF32, false}}}, 1, "MAT4 FLOAT"};

/* Required extensions that cannot change positions, indices or placement:
 * materials, textures, lights, cameras. Any other required extension may
 * store or place geometry in a way this loader does not read. */
bool is_geometry_neutral_extension(const std::string &name) {
    static const char *const kPrefixes[] = {"KHR_materials_", "KHR_texture_", "EXT_texture_",
                                            "MSFT_texture_", "KHR_lights_", "KHR_technique",
                                            "EXT_lights_"};
    for (const char *prefix : kPrefixes) {
        if (name.compare(0, std::strlen(prefix), prefix) == 0) {
            return true;
        }
    }
    return false;
}

/* tinygltf insists on decoding images; shadow volumes need none. */
bool ignore_image(tinygltf::Image *, const int, std::string *, std::string *, int, int,
                  const unsigned char *, int, void *) {
    return true;
}

// ------------------------------------------------------------- file level --

/* A whole message's bound: a few quoted texts and the words around them. */
constexpr std::size_t kMaxMessageBytes = 4 * kGltfMaxQuotedBytes;

[[noreturn]] void fail_file(const std::string &path, const std::string &problem) {
    throw GltfError(printable_text(path, kGltfMaxQuotedBytes) + ": " +
                    printable_text(problem, kMaxMessageBytes));
}

/* The deepest nesting of arrays and objects in JSON text, stopping at the
 * first byte that goes past LIMIT (*at gets its offset); strings (with
 * their escapes) skipped. Malformed text is tinygltf's to report. */
int json_depth(const unsigned char *p, std::size_t n, int limit, std::size_t *at) {
    int depth = 0, deepest = 0;
    bool in_string = false;
    for (std::size_t i = 0; i < n; i++) {
        const unsigned char c = p[i];
        if (in_string) {
            if (c == '\\') {
                i++;
            } else if (c == '"') {
                in_string = false;
            }
        } else if (c == '"') {
            in_string = true;
        } else if (c == '[' || c == '{') {
            if (++depth > deepest) {
                deepest = depth;
                if (deepest > limit) {
                    *at = i;
                    return deepest;
                }
            }
        } else if (c == ']' || c == '}') {
            depth--;
        }
    }
    return deepest;
}

void check_json_depth(const std::string &path, const unsigned char *p, std::size_t n,
                      std::size_t offset, const char *where) {
    std::size_t at = 0;
    if (json_depth(p, n, kGltfMaxJsonDepth, &at) > kGltfMaxJsonDepth) {
        fail_file(path, std::string(where) + " nests arrays and objects more than " +
                            std::to_string(kGltfMaxJsonDepth) + " deep (at byte " +
                            std::to_string(offset + at) +
                            "); refused before parsing (glTF needs about 8 levels)");
    }
}

/* The whole file. Read here rather than by tinygltf so that a missing or
 * unreadable file is one clear error, and so that the bytes are checked
 * (GLB layout) before tinygltf sees them. */
std::vector<unsigned char> read_file(const std::string &path) {
    errno = 0;
    std::unique_ptr<std::FILE, int (*)(std::FILE *)> file(std::fopen(path.c_str(), "rb"),
                                                          &std::fclose);
    if (!file) {
        fail_file(path, std::string("cannot open: ") + std::strerror(errno));
    }
    std::vector<unsigned char> bytes;
    unsigned char chunk[1 << 16];
    for (;;) {
        const std::size_t n = std::fread(chunk, 1, sizeof chunk, file.get());
        bytes.insert(bytes.end(), chunk, chunk + n);
        if (bytes.size() > UINT_MAX) {
            fail_file(path, "file is 4 GiB or larger (tinygltf reads at most 2^32 - 1 bytes)");
        }
        if (n < sizeof chunk) {
            break;
        }
    }
    if (std::ferror(file.get())) {
        fail_file(path, std::string("cannot read: ") + std::strerror(errno));
    }
    if (bytes.empty()) {
        fail_file(path, "empty file (not a glTF file)");
    }
    return bytes;
}

bool has_glb_magic(const std::vector<unsigned char> &bytes) {
    return bytes.size() >= 4 && std::memcmp(bytes.data(), "glTF", 4) == 0;
}

uint32_t read_u32le(const unsigned char *p) {
    uint32_t v;
    std::memcpy(&v, p, sizeof v);
    return v;
}

/* Checks the GLB container: 12-byte header (magic, version 2, length),
 * then chunks of (length, type, body) that all end within the declared
 * length, the first one JSON. Returns the declared length: the bytes that
 * go to tinygltf. Bytes past it are ignored with a note. */
uint32_t check_glb_layout(const std::string &path, const std::vector<unsigned char> &bytes,
                          std::vector<std::string> &notes) {
    const std::size_t size = bytes.size();
    if (size < 12) {
        fail_file(path, "truncated GLB: the header needs 12 bytes, the file has " +
                            std::to_string(size));
    }
    const uint32_t version = read_u32le(bytes.data() + 4);
    const uint32_t length = read_u32le(bytes.data() + 8);
    if (version != 2) {
        fail_file(path, "GLB version " + std::to_string(version) + " is not supported (only 2)");
    }
    if (length > size) {
        fail_file(path, "truncated GLB: the header declares " + std::to_string(length) +
                            " bytes, the file has " + std::to_string(size));
    }
    if (length < 20) {
        fail_file(path, "truncated GLB: no room for the JSON chunk (declared length " +
                            std::to_string(length) + ")");
    }
    std::size_t pos = 12;
    for (int chunk = 0; pos < length; chunk++) {
        if (length - pos < 8) {
            fail_file(path, "truncated GLB: chunk " + std::to_string(chunk) + " header at byte " +
                                std::to_string(pos) + " runs past the declared length " +
                                std::to_string(length));
        }
        const uint32_t chunk_length = read_u32le(bytes.data() + pos);
        const uint32_t chunk_type = read_u32le(bytes.data() + pos + 4);
        if (chunk == 0 && chunk_type != 0x4E4F534Au) { /* "JSON" */
            fail_file(path, "GLB: the first chunk is not JSON");
        }
        if (chunk_length > length - pos - 8) {
            fail_file(path, "truncated GLB: chunk " + std::to_string(chunk) + " at byte " +
                                std::to_string(pos) + " declares " + std::to_string(chunk_length) +
                                " bytes, only " + std::to_string(length - pos - 8) + " remain");
        }
        pos += 8 + std::size_t(chunk_length);
    }
    if (length < size) {
        notes.push_back("GLB: " + std::to_string(size - length) +
                        " bytes after the declared length ignored");
    }
    return length;
}

/* A JSON glTF starts with '{' after an optional UTF-8 byte order mark and
 * white space; anything else is not worth handing to a JSON parser. */
bool looks_like_json_object(const std::vector<unsigned char> &bytes) {
    std::size_t i = 0;
    if (bytes.size() >= 3 && bytes[0] == 0xEF && bytes[1] == 0xBB && bytes[2] == 0xBF) {
        i = 3;
    }
    while (i < bytes.size() &&
           (bytes[i] == ' ' || bytes[i] == '\t' || bytes[i] == '\n' || bytes[i] == '\r')) {
        i++;
    }
    return i < bytes.size() && bytes[i] == '{';
}

void add_tinygltf_lines(const std::string &text, std::vector<std::string> &notes) {
    std::size_t start = 0;
    while (start < text.size()) {
        std::size_t end = text.find('\n', start);
        if (end == std::string::npos) {
            end = text.size();
        }
        if (end > start) {
            notes.push_back("tinygltf: " + printable_text(text.substr(start, end - start)));
        }
        start = end + 1;
    }
}

std::string trimmed(std::string s) {
    while (!s.empty() && (s.back() == '\n' || s.back() == ' ' || s.back() == '\r')) {
        s.pop_back();
    }
    return s;
}

/* For options.external_files = false: no file exists. */
bool no_file_exists(const std::string &, void *) { return false; }
bool no_file_read(std::vector<unsigned char> *, std::string *err, const std::string &name,
                  void *) {
    if (err) *err += "external file " + name + " refused (external files are off)\n";
    return false;
}

/* Parses the file with tinygltf: GLB or JSON by the magic, external
 * buffers relative to the file's folder. */
tinygltf::Model parse_gltf(const std::string &path, const std::vector<unsigned char> &bytes,
                           bool external_files, std::vector<std::string> &notes) {
    if (bytes.empty()) {
        fail_file(path, "empty file (not a glTF file)");
    }
    if (bytes.size() > UINT_MAX) {
        fail_file(path, "file is 4 GiB or larger (tinygltf reads at most 2^32 - 1 bytes)");
    }
    std::string base_dir = std::filesystem::path(path).parent_path().string();
    if (base_dir.empty()) {
        base_dir = ".";
    }

    tinygltf::TinyGLTF parser;
    parser.SetImageLoader(&ignore_image, nullptr);
    if (!external_files) {
        parser.SetFsCallbacks({&no_file_exists, &tinygltf::ExpandFilePath, &no_file_read,
                               &tinygltf::WriteWholeFile, nullptr});
    }
    tinygltf::Model model;
    std::string err, warn;
    bool ok = false;
    try {
        if (has_glb_magic(bytes)) {
            const uint32_t length = check_glb_layout(path, bytes, notes);
            /* check_glb_layout: the JSON chunk (header at 12) lies within length */
            check_json_depth(path, bytes.data() + 20, read_u32le(bytes.data() + 12), 20,
                             "the GLB's JSON chunk");
            ok = parser.LoadBinaryFromMemory(&model, &err, &warn, bytes.data(), length, base_dir);
        } else if (looks_like_json_object(bytes)) {
            check_json_depth(path, bytes.data(), bytes.size(), 0, "the JSON");
            ok = parser.LoadASCIIFromString(&model, &err, &warn,
                                            reinterpret_cast<const char *>(bytes.data()),
                                            static_cast<unsigned int>(bytes.size()), base_dir);
        } else {
            fail_file(path, "not a glTF file (neither the GLB magic \"glTF\" nor a JSON object)");
        }
    } catch (const GltfError &) {
        throw;
    } catch (const std::exception &e) {
        fail_file(path, std::string("tinygltf failed: ") + e.what());
    }
    add_tinygltf_lines(warn, notes);
    if (!ok) {
        /* tinygltf echoes input (a whole data: URI, bytes that are not
         * UTF-8): each of its lines quoted within the bound. */
        std::string text;
        std::vector<std::string> lines;
        add_tinygltf_lines(trimmed(err), lines);
        for (const std::string &line : lines) {
            text += (text.empty() ? "" : "; ") + line.substr(std::strlen("tinygltf: "));
        }
        fail_file(path, "tinygltf: " + (text.empty() ? std::string("failed") : text));
    }
    /* tinygltf sometimes reports a problem and goes on (e.g. a buffer
     * without uri in a JSON file); what it loaded is still range-checked
     * below, so keep its words as a note. */
    add_tinygltf_lines(err, notes);
    return model;
}

// -------------------------------------------------------------- the loader --

/* The size estimate behind options.max_triangles / max_vertices, for the
 * message: bytes and seconds to load and prepare (measured on the 10M-
 * triangle grid: 1.35 GB; about 0.3 us a triangle in Release). */
constexpr double kBytesPerTriangle = 120.0;
constexpr double kBytesPerVertex = 40.0;
constexpr double kSecondsPerTriangle = 0.3e-6;

std::size_t saturating_add(std::size_t a, std::size_t b) {
    return a > SIZE_MAX - b ? SIZE_MAX : a + b;
}

/* A mesh to place: node -1 = at identity, no skin. */
struct Instance {
    int mesh;
    int node;
};

/* A surface before placement: every triangle primitive of one mesh
 * appended, positions still in mesh space. */
struct MeshGeometry {
    std::vector<float> positions;         /* xyz per vertex, mesh space */
    std::vector<uint32_t> indices;        /* triangles, surface numbering */
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
    friend class gltf_internal::Reader; /* at the end of this file */

private:
    [[noreturn]] void fail(const std::string &problem) const { fail_file(path_, problem); }
    void note(const std::string &line);

    std::string mesh_label(int mesh) const;
    std::string node_label(int node) const;
    std::string primitive_label(int mesh, int primitive) const;
    std::string vertex_label(int mesh, const MeshGeometry &g, std::size_t vertex) const;

    void check_required_extensions() const;
    void check_sizes(const std::vector<Instance> &instances) const;

    /* Node graph: parent_ and world_ for every node, all validated. */
    void compute_world_matrices();
    Mat4 local_matrix(int node) const;
    std::vector<Instance> select_instances() const;
    std::vector<int> scene_roots() const;

    /* Accessors. */
    const Accessor &accessor_at(int index, const std::string &who) const;
    std::vector<double> decode(int index, const AccessorFormat &format,
                               const std::string &who) const;
    const unsigned char *element_span(int view_index, std::size_t byte_offset, std::size_t count,
                                      std::size_t element_size, bool use_view_stride,
                                      const std::string &who, std::size_t *stride) const;
    void apply_sparse(const Accessor &a, const std::string &who, std::vector<double> &values,
                      bool write = true) const;
    void check_sparse_ranges(const Accessor &a, const std::string &who) const;

    /* Surfaces. */
    bool build_surface(const Instance &instance, GltfSurface &surface);
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

// ------------------------------------------------------------------ nodes --

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
                fail(node_label(n) + ": child node " + std::to_string(child) +
                     " does not exist (" + std::to_string(num_nodes) + " nodes)");
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
            fail(who + " is not a root (it is a child of node " + std::to_string(parent_[n]) +
                 ")");
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
                names += (m ? ", " : "") + (name.empty() ? "mesh#" + std::to_string(m)
                                                         : quoted(name));
            }
            fail("no mesh named " + quoted(options_.mesh_name) + "; the meshes are: " +
                 (names.empty() ? std::string("(none)") : names));
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

// -------------------------------------------------------------- accessors --

const Accessor &Loader::accessor_at(int index, const std::string &who) const {
    if (index < 0 || index >= static_cast<int>(gltf_.accessors.size())) {
        fail(who + ": accessor " + std::to_string(index) + " does not exist (" +
             std::to_string(gltf_.accessors.size()) + " accessors)");
    }
    return gltf_.accessors[index];
}

/* The address of element 0 of `count` elements of element_size bytes, at
 * byte_offset in bufferView view_index, after checking that all of them lie
 * inside the bufferView and the bufferView inside its buffer. *stride gets
 * the distance between elements: the bufferView's byteStride when
 * use_view_stride and it is set, else element_size (tightly packed).
 * count >= 1 (the callers check). */
const unsigned char *Loader::element_span(int view_index, std::size_t byte_offset,
                                          std::size_t count, std::size_t element_size,
                                          bool use_view_stride, const std::string &who,
                                          std::size_t *stride) const {
    if (view_index < 0 || view_index >= static_cast<int>(gltf_.bufferViews.size())) {
        fail(who + ": bufferView " + std::to_string(view_index) + " does not exist (" +
             std::to_string(gltf_.bufferViews.size()) + " bufferViews)");
    }
    const tinygltf::BufferView &view = gltf_.bufferViews[view_index];
    const std::string view_name = "bufferView " + std::to_string(view_index);
    if (view.buffer < 0 || view.buffer >= static_cast<int>(gltf_.buffers.size())) {
        fail(who + ": " + view_name + ": buffer " + std::to_string(view.buffer) +
             " does not exist (" + std::to_string(gltf_.buffers.size()) + " buffers)");
    }
    const std::vector<unsigned char> &data = gltf_.buffers[view.buffer].data;
    std::size_t view_end;
    if (!checked_add(view.byteOffset, view.byteLength, &view_end) || view_end > data.size()) {
        fail(who + ": " + view_name + " (bytes " + std::to_string(view.byteOffset) + " + " +
             std::to_string(view.byteLength) + ") runs past the end of buffer " +
             std::to_string(view.buffer) + " (" + std::to_string(data.size()) +
             " bytes): truncated or missing buffer data");
    }
    *stride = element_size;
    if (use_view_stride && view.byteStride != 0) {
        if (view.byteStride < element_size) {
            fail(who + ": " + view_name + " byteStride " + std::to_string(view.byteStride) +
                 " is smaller than the element (" + std::to_string(element_size) + " bytes)");
        }
        *stride = view.byteStride;
    }
    if (byte_offset >= view.byteLength) {
        fail(who + ": byteOffset " + std::to_string(byte_offset) + " is past the end of " +
             view_name + " (" + std::to_string(view.byteLength) + " bytes)");
    }
    /* byte_offset + stride * (count - 1) + element_size <= byteLength */
    std::size_t span, end;
    if (!checked_mul(*stride, count - 1, &span) || !checked_add(span, element_size, &span) ||
        !checked_add(byte_offset, span, &end) || end > view.byteLength) {
        fail(who + ": " + std::to_string(count) + " elements of " + std::to_string(element_size) +
             " bytes, stride " + std::to_string(*stride) + ", at byteOffset " +
             std::to_string(byte_offset) + " run past the end of " + view_name + " (" +
             std::to_string(view.byteLength) + " bytes)");
    }
    return data.data() + view.byteOffset + byte_offset;
}

/* Checks a sparse accessor's counts, types and both byte ranges (before
 * the accessor's values are allocated); apply_sparse then reads them. */
void Loader::check_sparse_ranges(const Accessor &a, const std::string &who) const {
    std::vector<double> none;
    apply_sparse(a, who, none, false);
}

/* Writes a sparse accessor's values over the base values (WRITE false:
 * only the checks of the ranges). */
void Loader::apply_sparse(const Accessor &a, const std::string &who,
                          std::vector<double> &values, bool write) const {
    const std::string sparse_who = who + " (sparse)";
    const int sparse_count = a.sparse.count;
    if (sparse_count < 1 || std::size_t(sparse_count) > a.count) {
        fail(sparse_who + ": count " + std::to_string(sparse_count) + " is not in 1.." +
             std::to_string(a.count));
    }
    const int index_type = a.sparse.indices.componentType;
    if (index_type != kU8 && index_type != kU16 && index_type != kU32) {
        fail(sparse_who + ": indices are " + component_type_name(index_type) +
             ", expected UNSIGNED_BYTE, UNSIGNED_SHORT or UNSIGNED_INT");
    }
    if (a.sparse.indices.byteOffset < 0 || a.sparse.values.byteOffset < 0) {
        fail(sparse_who + ": negative byteOffset");
    }
    const std::size_t count = std::size_t(sparse_count);
    const std::size_t components = components_in(a.type);
    const std::size_t value_size = components * component_size(a.componentType);
    std::size_t index_stride, value_stride;
    const unsigned char *index_bytes =
        element_span(a.sparse.indices.bufferView, std::size_t(a.sparse.indices.byteOffset), count,
                     component_size(index_type), false, sparse_who + " indices", &index_stride);
    const unsigned char *value_bytes =
        element_span(a.sparse.values.bufferView, std::size_t(a.sparse.values.byteOffset), count,
                     value_size, false, sparse_who + " values", &value_stride);
    if (!write) {
        return;
    }
    const std::size_t csize = component_size(a.componentType);
    for (std::size_t i = 0; i < count; i++) {
        const double target = read_component(index_bytes + i * index_stride, index_type, false);
        if (!(target < double(a.count))) {
            fail(sparse_who + ": index " + std::to_string(i) + " is " +
                 std::to_string(static_cast<uint64_t>(target)) +
                 ", not below the accessor's count " + std::to_string(a.count));
        }
        const std::size_t element = static_cast<std::size_t>(target);
        for (std::size_t c = 0; c < components; c++) {
            values[element * components + c] = read_component(
                value_bytes + i * value_stride + c * csize, a.componentType, a.normalized);
        }
    }
}

/* Every component of accessor `index`, count * components values, after
 * checking its format against `format` and every byte range it reads. */
std::vector<double> Loader::decode(int index, const AccessorFormat &format,
                                   const std::string &who) const {
    const Accessor &a = accessor_at(index, who);
    const std::string label = who + " (accessor " + std::to_string(index) + ")";

    bool format_ok = a.type == format.type;
    if (format_ok) {
        format_ok = false;
        for (int i = 0; i < format.num_allowed; i++) {
            if (a.componentType == format.allowed[i].component_type &&
                a.normalized == format.allowed[i].normalized) {
                format_ok = true;
            }
        }
    }
    if (!format_ok) {
        fail(label + " is " + (a.normalized ? "normalized " : "") +
             component_type_name(a.componentType) + " " + type_name(a.type) + ", expected " +
             format.expected);
    }
    if (a.count == 0) {
        fail(label + ": count is 0");
    }
    const std::size_t components = components_in(a.type);
    const std::size_t csize = component_size(a.componentType);
    std::size_t total;
    if (!checked_mul(a.count, components, &total) || total > kMaxAccessorComponents) {
        fail(label + ": count " + std::to_string(a.count) + " is too large (more than " +
             std::to_string(kMaxAccessorComponents) + " components)");
    }

    if (a.bufferView < 0 && !a.sparse.isSparse) {
        fail(label + " has no bufferView (and is not sparse)");
    }
    if (a.bufferView < 0 && total > kMaxUnbackedComponents) {
        fail(label + ": sparse, without bufferView, and count " + std::to_string(a.count) +
             " is too large (more than " + std::to_string(kMaxUnbackedComponents) +
             " components of zeros)");
    }
    /* The range first, then the allocation: a 380-byte file claiming 89M
     * VEC3 elements must fail here, not after allocating 2 GB. */
    std::size_t stride = 0;
    const unsigned char *first = nullptr;
    if (a.bufferView >= 0) {
        first = element_span(a.bufferView, a.byteOffset, a.count, components * csize, true, label,
                             &stride);
    }
    if (a.sparse.isSparse) {
        check_sparse_ranges(a, label);
    }
    std::vector<double> values(total, 0.0);
    if (a.bufferView >= 0) {
        for (std::size_t e = 0; e < a.count; e++) {
            const unsigned char *element = first + e * stride;
            for (std::size_t c = 0; c < components; c++) {
                values[e * components + c] =
                    read_component(element + c * csize, a.componentType, a.normalized);
            }
        }
    }
    if (a.sparse.isSparse) {
        apply_sparse(a, label, values);
    }
    return values;
}

// --------------------------------------------------------------- surfaces --

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
            fail(label + ": " + (has_joints ? joints_name + " without " + weights_name
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
    const std::vector<double> positions =
        decode(position_it->second, kPositionFormat, label + " POSITION");
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
        const std::vector<double> indices =
            decode(prim.indices, kIndexFormat, label + " indices");
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

void Loader::place_skinned(int mesh, int skin, const MeshGeometry &g,
                           GltfSurface &surface) const {
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
                const std::size_t pv =
                    position == prim.attributes.end() ? 0 : count_of(position->second);
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
        std::snprintf(estimate, sizeof estimate, "about %.1f GB and %.0f s to load and prepare",
                      gb, kSecondsPerTriangle * double(triangles));
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

} // namespace

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
        std::size_t len = c >= 0xC2 && c <= 0xDF ? 2 : c >= 0xE0 && c <= 0xEF ? 3
                          : c >= 0xF0 && c <= 0xF4                          ? 4
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
    const tinygltf::Model gltf =
        parse_gltf(name, std::vector<unsigned char>(bytes, bytes + size), options.external_files,
                   out.notes);
    Loader(name, gltf, options, out).run();
    return out;
}

} // namespace sv

// ------------------------------------------ shared with src/anim (internal) --

namespace sv {
namespace gltf_internal {

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
    impl_->model = parse_gltf(path, read_file(path), impl_->options.external_files, impl_->out.notes);
    impl_->loader.reset(new Loader(impl_->path, impl_->model, impl_->options, impl_->out));
    impl_->loader->check_required_extensions();
}

Reader::Reader(const unsigned char *bytes, std::size_t size, const std::string &name) : impl_(new Impl) {
    impl_->path = name;
    impl_->out.path = name;
    impl_->options.external_files = false;
    impl_->model = parse_gltf(name, std::vector<unsigned char>(bytes, bytes + size), false, impl_->out.notes);
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
            d.influence_sets = std::max(d.influence_sets,
                                        attributes.count("JOINTS_1") ? 2 : 1);
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
