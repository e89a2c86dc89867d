// The demo scene (models/README.md): a ground, a terrain patch of 105,800
// triangles, pillars and a wall, the project's character with a skin and a
// walk cycle of its own, KHR_lights_punctual lights (a point light with a
// range, two spot lights over the terrain like a car's headlights, a
// directional light) and a perspective camera; one glTF 2.0 binary.
//
// Deterministic: only + - * / sqrt and floor are used (sine and cosine are
// a Taylor series here, not the libm's), the library is compiled with
// -ffp-contract=off, and every number is written with %.9g from a float.

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <limits>
#include <stdexcept>
#include <string>
#include <vector>

#include "model_gen.h"

namespace svgen {
namespace {

constexpr double kPi = 3.14159265358979323846;

// sin(x) by its Taylor series on [-pi, pi] after reduction (error below
// 1e-12), so the file does not depend on the libm.
double dsin(double x) {
    const double twopi = 2 * kPi;
    x -= std::floor(x / twopi + 0.5) * twopi;
    const double x2 = x * x;
    double s = 1.0;
    for (int k = 13; k >= 1; --k) s = 1.0 - s * x2 / double((2 * k) * (2 * k + 1));
    return x * s;
}
double dcos(double x) { return dsin(x + kPi / 2); }

std::string num(double v) {
    char buf[32];
    std::snprintf(buf, sizeof buf, "%.9g", static_cast<double>(static_cast<float>(v)));
    return buf;
}

std::string vec(const double *v, int n) {
    std::string s = "[";
    for (int i = 0; i < n; ++i) s += (i ? "," : "") + num(v[i]);
    return s + "]";
}

struct Quat {
    double x, y, z, w;
};

Quat normalized(Quat q) {
    const double l = std::sqrt(q.x * q.x + q.y * q.y + q.z * q.z + q.w * q.w);
    return {q.x / l, q.y / l, q.z / l, q.w / l};
}

Quat axis_angle(double ax, double ay, double az, double angle) {
    const double s = dsin(angle / 2), c = dcos(angle / 2);
    return normalized({ax * s, ay * s, az * s, c});
}

// The rotation that turns a node's -Z (where cameras and lights look) to
// TARGET - EYE, with its +Y as near world +Y as possible.
Quat look_at(const double eye[3], const double target[3]) {
    double f[3] = {target[0] - eye[0], target[1] - eye[1], target[2] - eye[2]};
    double l = std::sqrt(f[0] * f[0] + f[1] * f[1] + f[2] * f[2]);
    const double z[3] = {-f[0] / l, -f[1] / l, -f[2] / l}; // local +Z = -forward
    // x = up x z
    double x[3] = {1.0 * z[2] - 0.0 * z[1], 0.0 * z[0] - 0.0 * z[2], 0.0 * z[1] - 1.0 * z[0]};
    l = std::sqrt(x[0] * x[0] + x[1] * x[1] + x[2] * x[2]);
    for (double &c : x) c /= l;
    const double y[3] = {z[1] * x[2] - z[2] * x[1], z[2] * x[0] - z[0] * x[2],
                         z[0] * x[1] - z[1] * x[0]};
    // Columns x, y, z of the rotation matrix -> quaternion.
    const double m00 = x[0], m11 = y[1], m22 = z[2];
    const double tr = m00 + m11 + m22;
    Quat q;
    if (tr > 0) {
        const double s = std::sqrt(tr + 1.0) * 2;
        q = {(y[2] - z[1]) / s, (z[0] - x[2]) / s, (x[1] - y[0]) / s, 0.25 * s};
    } else if (m00 > m11 && m00 > m22) {
        const double s = std::sqrt(1.0 + m00 - m11 - m22) * 2;
        q = {0.25 * s, (y[0] + x[1]) / s, (z[0] + x[2]) / s, (y[2] - z[1]) / s};
    } else if (m11 > m22) {
        const double s = std::sqrt(1.0 + m11 - m00 - m22) * 2;
        q = {(y[0] + x[1]) / s, 0.25 * s, (z[1] + y[2]) / s, (z[0] - x[2]) / s};
    } else {
        const double s = std::sqrt(1.0 + m22 - m00 - m11) * 2;
        q = {(z[0] + x[2]) / s, (z[1] + y[2]) / s, 0.25 * s, (x[1] - y[0]) / s};
    }
    return normalized(q);
}

std::string quat_json(Quat q) {
    const double v[4] = {q.x, q.y, q.z, q.w};
    return vec(v, 4);
}

// ------------------------------------------------------------- the buffer --

class Builder {
public:
    std::vector<std::uint8_t> bin;
    std::vector<std::string> views, accessors;

    int view(const void *data, std::size_t bytes, int target) {
        while (bin.size() % 4) bin.push_back(0);
        const std::size_t offset = bin.size();
        const auto *p = static_cast<const std::uint8_t *>(data);
        bin.insert(bin.end(), p, p + bytes);
        std::string v = "{\"buffer\":0,\"byteOffset\":" + std::to_string(offset) +
                        ",\"byteLength\":" + std::to_string(bytes);
        if (target) v += ",\"target\":" + std::to_string(target);
        views.push_back(v + "}");
        return static_cast<int>(views.size() - 1);
    }

    // COMPONENTS floats per element (type TYPE); with min/max when asked.
    int floats(const std::vector<float> &v, int components, const char *type, bool minmax,
               int target = 0) {
        const int bv = view(v.data(), v.size() * 4, target);
        const std::size_t count = v.size() / std::size_t(components);
        std::string a = "{\"bufferView\":" + std::to_string(bv) +
                        ",\"componentType\":5126,\"count\":" + std::to_string(count) +
                        ",\"type\":\"" + type + "\"";
        if (minmax) {
            std::vector<double> lo(components, std::numeric_limits<double>::infinity()),
                hi(components, -std::numeric_limits<double>::infinity());
            for (std::size_t i = 0; i < v.size(); ++i) {
                const int c = int(i % std::size_t(components));
                if (v[i] < lo[c]) lo[c] = v[i];
                if (v[i] > hi[c]) hi[c] = v[i];
            }
            a += ",\"min\":" + vec(lo.data(), components) +
                 ",\"max\":" + vec(hi.data(), components);
        }
        accessors.push_back(a + "}");
        return static_cast<int>(accessors.size() - 1);
    }

    int indices(const std::vector<std::uint32_t> &idx, std::size_t num_vertices) {
        const bool u16 = num_vertices <= 65535;
        std::vector<std::uint8_t> b;
        for (std::uint32_t i : idx)
            for (int k = 0; k < (u16 ? 2 : 4); ++k)
                b.push_back(static_cast<std::uint8_t>(i >> (8 * k)));
        const int bv = view(b.data(), b.size(), 34963);
        accessors.push_back("{\"bufferView\":" + std::to_string(bv) +
                            ",\"componentType\":" + (u16 ? "5123" : "5125") +
                            ",\"count\":" + std::to_string(idx.size()) + ",\"type\":\"SCALAR\"}");
        return static_cast<int>(accessors.size() - 1);
    }

    int u8vec4(const std::vector<std::uint8_t> &v) {
        const int bv = view(v.data(), v.size(), 34962);
        accessors.push_back("{\"bufferView\":" + std::to_string(bv) +
                            ",\"componentType\":5121,\"count\":" + std::to_string(v.size() / 4) +
                            ",\"type\":\"VEC4\"}");
        return static_cast<int>(accessors.size() - 1);
    }
};

// A closed box (8 vertices, 12 triangles, counter-clockwise from outside).
TriMesh box(double x0, double x1, double y0, double y1, double z0, double z1) {
    TriMesh m;
    for (int i = 0; i < 8; ++i) {
        m.positions.push_back(static_cast<float>(i & 1 ? x1 : x0));
        m.positions.push_back(static_cast<float>(i & 2 ? y1 : y0));
        m.positions.push_back(static_cast<float>(i & 4 ? z1 : z0));
    }
    // Faces as quads (a, b, c, d) counter-clockwise seen from outside.
    const std::uint32_t q[6][4] = {{0, 4, 6, 2}, {1, 3, 7, 5}, {0, 1, 5, 4},
                                   {2, 6, 7, 3}, {0, 2, 3, 1}, {4, 5, 7, 6}};
    for (const auto &f : q) m.indices.insert(m.indices.end(), {f[0], f[1], f[2], f[0], f[2], f[3]});
    return m;
}

// The height field: N x N quads of CELL metres from (X0, Z0), gentle hills.
TriMesh terrain(int n, double cell, double x0, double z0) {
    TriMesh m;
    for (int j = 0; j <= n; ++j)
        for (int i = 0; i <= n; ++i) {
            const double x = x0 + cell * i, z = z0 + cell * j;
            // Hills of up to about 2 m, rising from the ground's level over the
            // first 5 m so that the patch meets the ground at its edge.
            const double rise = std::min(1.0, (x - x0) / 5.0);
            const double h = rise * rise *
                             (1.2 * dsin(0.15 * x) * dcos(0.12 * z) +
                              0.45 * dsin(0.4 * x + 0.3 * z) + 0.9);
            m.positions.push_back(static_cast<float>(x));
            m.positions.push_back(static_cast<float>(h));
            m.positions.push_back(static_cast<float>(z));
        }
    const std::uint32_t w = static_cast<std::uint32_t>(n + 1);
    for (std::uint32_t j = 0; j < std::uint32_t(n); ++j)
        for (std::uint32_t i = 0; i < std::uint32_t(n); ++i) {
            const std::uint32_t a = j * w + i, b = a + 1, c = a + w, d = c + 1;
            m.indices.insert(m.indices.end(), {a, c, b, b, c, d}); // +y is the front
        }
    return m;
}

// ------------------------------------------------------------ the skeleton --

struct Joint {
    const char *name;
    int parent;      // joint index, -1: the character's root node
    double local[3]; // translation from the parent (bind pose: no rotation)
};

// Bind pose positions relative to the character's root (the soles at y = 0).
const Joint kJoints[] = {
    {"hips", -1, {0, 0.9, 0}},         {"spine", 0, {0, 0.25, 0}},
    {"head", 1, {0, 0.3, 0}},          {"upper_leg_L", 0, {0.14, -0.05, 0}},
    {"lower_leg_L", 3, {0, -0.42, 0}}, {"upper_leg_R", 0, {-0.14, -0.05, 0}},
    {"lower_leg_R", 5, {0, -0.42, 0}}, {"upper_arm_L", 1, {0.21, 0.225, 0}},
    {"lower_arm_L", 7, {0.32, 0, 0}},  {"upper_arm_R", 1, {-0.21, 0.225, 0}},
    {"lower_arm_R", 9, {-0.32, 0, 0}},
};
constexpr int kNumJoints = sizeof kJoints / sizeof kJoints[0];
enum {
    kHips,
    kSpine,
    kHead,
    kUpperLegL,
    kLowerLegL,
    kUpperLegR,
    kLowerLegR,
    kUpperArmL,
    kLowerArmL,
    kUpperArmR,
    kLowerArmR
};

// Weights in 1/256 steps (exact in float, so each vertex's sum is exactly 1).
double steps(double t) {
    if (t <= 0) return 0;
    if (t >= 1) return 1;
    return std::floor(t * 256 + 0.5) / 256;
}

// Two influences per vertex by where it is: legs below the hips, arms out
// from the shoulders, the head above the neck, the torso between; blended
// across the knees, elbows, hips, shoulders, neck and waist.
void influences(const float *p, std::uint8_t joints[4], float weights[4]) {
    const double x = p[0], y = p[1];
    int j0, j1;
    double t;                  // weight of j1
    if (std::fabs(x) > 0.21) { // arms
        const bool left = x > 0;
        const double a = std::fabs(x) - 0.21;
        if (a < 0.06) {
            j0 = kSpine, j1 = left ? kUpperArmL : kUpperArmR, t = steps(a / 0.06);
        } else {
            j0 = left ? kUpperArmL : kUpperArmR, j1 = left ? kLowerArmL : kLowerArmR,
            t = steps((a - 0.28) / 0.08);
        }
    } else if (y < 0.85) { // legs
        const bool left = x > 0;
        const double b = 0.85 - y;
        if (b < 0.06) {
            j0 = kHips, j1 = left ? kUpperLegL : kUpperLegR, t = steps(b / 0.06);
        } else {
            j0 = left ? kUpperLegL : kUpperLegR, j1 = left ? kLowerLegL : kLowerLegR,
            t = steps((b - 0.37) / 0.08);
        }
    } else if (y > 1.44) { // neck and head
        j0 = kSpine, j1 = kHead, t = steps((y - 1.44) / 0.06);
    } else { // torso
        j0 = kHips, j1 = kSpine, t = steps((y - 1.0) / 0.2);
    }
    joints[0] = static_cast<std::uint8_t>(j0);
    joints[1] = static_cast<std::uint8_t>(j1);
    joints[2] = joints[3] = 0;
    weights[0] = static_cast<float>(1 - t);
    weights[1] = static_cast<float>(t);
    weights[2] = weights[3] = 0;
    if (t == 0) joints[1] = 0; // an unused influence points at joint 0, weight 0
}

void bind_position(int j, double out[3]) {
    out[0] = out[1] = out[2] = 0;
    for (; j >= 0; j = kJoints[j].parent)
        for (int c = 0; c < 3; ++c) out[c] += kJoints[j].local[c];
}

// --------------------------------------------------------------- the JSON --

// EXTRAS: the mesh's "extras" object, or empty for none.
std::string mesh_json(const std::string &name, int pos, int idx, int joints = -1, int weights = -1,
                      const std::string &extras = "") {
    std::string attrs = "\"POSITION\":" + std::to_string(pos);
    if (joints >= 0)
        attrs += ",\"JOINTS_0\":" + std::to_string(joints) +
                 ",\"WEIGHTS_0\":" + std::to_string(weights);
    return "{\"name\":\"" + name + "\",\"primitives\":[{\"attributes\":{" + attrs +
           "},\"indices\":" + std::to_string(idx) + ",\"mode\":4}]" +
           (extras.empty() ? "" : ",\"extras\":" + extras) + "}";
}

std::string translation_json(const double t[3]) { return "\"translation\":" + vec(t, 3); }

} // namespace

DemoSceneInfo demo_scene_info() {
    DemoSceneInfo info;
    info.terrain_quads = 230;
    info.terrain_triangles = 2 * 230 * 230;
    info.character_triangles = 1344;
    info.joints = kNumJoints;
    info.walk_seconds = 1.0;
    return info;
}

std::vector<std::uint8_t> write_demo_scene_glb() {
    Builder b;
    std::vector<std::string> meshes, nodes;
    std::vector<int> roots;
    auto add_node = [&](const std::string &json) {
        nodes.push_back(json);
        return static_cast<int>(nodes.size() - 1);
    };

    // Static geometry.
    auto add_mesh = [&](const std::string &name, const TriMesh &m, const std::string &extras = "") {
        const int pos = b.floats(m.positions, 3, "VEC3", true, 34962);
        const int idx = b.indices(m.indices, m.num_vertices());
        meshes.push_back(mesh_json(name, pos, idx, -1, -1, extras));
        return static_cast<int>(meshes.size() - 1);
    };
    const int ground = add_mesh("ground", box(-12, 11, -0.2, 0, -12, 11));
    const DemoSceneInfo info = demo_scene_info();
    // The terrain is open (a height field, no underside) but the top of a
    // solid nothing stands in: declared ground, it keeps the paper's
    // shadow-volume rule under --caster-rule auto (docs/CASTERS.md, "The
    // ground hint"; the key is sv::kGroundExtrasKey).
    const int terr = add_mesh("terrain", terrain(info.terrain_quads, 0.2, 11, -23),
                              "{\"shadowvol_ground\":true}");
    const int pillar = add_mesh("pillar", box(-0.3, 0.3, 0, 3, -0.3, 0.3));
    const int wall = add_mesh("wall", box(-4, 4, 0, 2.5, -0.15, 0.15));
    roots.push_back(add_node("{\"name\":\"ground\",\"mesh\":" + std::to_string(ground) + "}"));
    roots.push_back(add_node("{\"name\":\"terrain\",\"mesh\":" + std::to_string(terr) + "}"));
    const double pillars[4][3] = {{-4, 0, -4}, {4, 0, -4}, {-4, 0, 4}, {4, 0, 4}};
    for (int i = 0; i < 4; ++i)
        roots.push_back(add_node("{\"name\":\"pillar_" + std::to_string(i + 1) +
                                 "\",\"mesh\":" + std::to_string(pillar) + "," +
                                 translation_json(pillars[i]) + "}"));
    const double wall_at[3] = {-1, 0, -8};
    roots.push_back(add_node("{\"name\":\"wall\",\"mesh\":" + std::to_string(wall) + "," +
                             translation_json(wall_at) + "}"));

    // The character: the same geometry as character_1344, skinned.
    const TriMesh ch = build_character(1);
    std::vector<std::uint8_t> joints;
    std::vector<float> weights;
    for (std::size_t v = 0; v < ch.num_vertices(); ++v) {
        std::uint8_t j[4];
        float w[4];
        influences(&ch.positions[3 * v], j, w);
        joints.insert(joints.end(), j, j + 4);
        weights.insert(weights.end(), w, w + 4);
    }
    const int chpos = b.floats(ch.positions, 3, "VEC3", true, 34962);
    const int chidx = b.indices(ch.indices, ch.num_vertices());
    const int chj = b.u8vec4(joints);
    const int chw = b.floats(weights, 4, "VEC4", false, 34962);
    meshes.push_back(mesh_json("character", chpos, chidx, chj, chw));
    const int chmesh = static_cast<int>(meshes.size() - 1);

    std::vector<float> ibm;
    for (int j = 0; j < kNumJoints; ++j) {
        double p[3];
        bind_position(j, p);
        const double m[16] = {1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, -p[0], -p[1], -p[2], 1};
        for (double e : m) ibm.push_back(static_cast<float>(e));
    }
    const int ibm_acc = b.floats(ibm, 16, "MAT4", false);

    // Nodes: character_root (moves forward), the joints under it, the mesh.
    const int root_index = static_cast<int>(nodes.size());
    const int first_joint = root_index + 1;
    std::string root_children;
    {
        const double at[3] = {0, 0, -2};
        std::string kids;
        for (int j = 0; j < kNumJoints; ++j)
            if (kJoints[j].parent < 0)
                kids += (kids.empty() ? "" : ",") + std::to_string(first_joint + j);
        roots.push_back(add_node("{\"name\":\"character_root\"," + translation_json(at) +
                                 ",\"children\":[" + kids + "]}"));
    }
    for (int j = 0; j < kNumJoints; ++j) {
        std::string kids;
        for (int k = 0; k < kNumJoints; ++k)
            if (kJoints[k].parent == j)
                kids += (kids.empty() ? "" : ",") + std::to_string(first_joint + k);
        add_node(std::string("{\"name\":\"") + kJoints[j].name + "\"," +
                 translation_json(kJoints[j].local) +
                 (kids.empty() ? "" : ",\"children\":[" + kids + "]") + "}");
    }
    roots.push_back(
        add_node("{\"name\":\"character\",\"mesh\":" + std::to_string(chmesh) + ",\"skin\":0}"));
    std::string skin_joints;
    for (int j = 0; j < kNumJoints; ++j)
        skin_joints += (j ? "," : "") + std::to_string(first_joint + j);
    const std::string skins = "[{\"name\":\"character_skin\",\"inverseBindMatrices\":" +
                              std::to_string(ibm_acc) +
                              ",\"skeleton\":" + std::to_string(first_joint + kHips) +
                              ",\"joints\":[" + skin_joints + "]}]";

    // The walk: 1 s. LINEAR rotations of legs, arms and spine; STEP elbows;
    // CUBICSPLINE hip bob; LINEAR root translation (1.2 m forward, +z).
    std::vector<std::string> samplers, channels;
    const int t5 = b.floats({0.0f, 0.25f, 0.5f, 0.75f, 1.0f}, 1, "SCALAR", true);
    const int t2 = b.floats({0.0f, 1.0f}, 1, "SCALAR", true);
    const int tstep = b.floats({0.0f, 0.5f}, 1, "SCALAR", true);
    auto channel = [&](int input, const std::vector<float> &out, const char *type, int comps,
                       const char *interp, int node, const char *path) {
        const int o = b.floats(out, comps, type, false);
        samplers.push_back("{\"input\":" + std::to_string(input) + ",\"output\":" +
                           std::to_string(o) + ",\"interpolation\":\"" + interp + "\"}");
        channels.push_back("{\"sampler\":" + std::to_string(samplers.size() - 1) +
                           ",\"target\":{\"node\":" + std::to_string(node) + ",\"path\":\"" + path +
                           "\"}}");
    };
    auto rotations = [&](double ax, double ay, double az, const std::vector<double> &angles) {
        std::vector<float> out;
        for (double a : angles) {
            const Quat q = axis_angle(ax, ay, az, a);
            out.insert(out.end(), {static_cast<float>(q.x), static_cast<float>(q.y),
                                   static_cast<float>(q.z), static_cast<float>(q.w)});
        }
        return out;
    };
    const std::vector<double> swing = {-0.45, 0, 0.45, 0, -0.45};
    const std::vector<double> swing_r = {0.45, 0, -0.45, 0, 0.45};
    channel(t5, rotations(1, 0, 0, swing), "VEC4", 4, "LINEAR", first_joint + kUpperLegL,
            "rotation");
    channel(t5, rotations(1, 0, 0, swing_r), "VEC4", 4, "LINEAR", first_joint + kUpperLegR,
            "rotation");
    channel(t5, rotations(1, 0, 0, {0.1, 0.6, 0.1, 0.1, 0.1}), "VEC4", 4, "LINEAR",
            first_joint + kLowerLegL, "rotation");
    channel(t5, rotations(1, 0, 0, {0.1, 0.1, 0.1, 0.6, 0.1}), "VEC4", 4, "LINEAR",
            first_joint + kLowerLegR, "rotation");
    channel(t5, rotations(0, 1, 0, {0.35, 0, -0.35, 0, 0.35}), "VEC4", 4, "LINEAR",
            first_joint + kUpperArmL, "rotation");
    channel(t5, rotations(0, 1, 0, {0.35, 0, -0.35, 0, 0.35}), "VEC4", 4, "LINEAR",
            first_joint + kUpperArmR, "rotation");
    channel(t5, rotations(0, 1, 0, {0.08, 0, -0.08, 0, 0.08}), "VEC4", 4, "LINEAR",
            first_joint + kSpine, "rotation");
    channel(tstep, rotations(0, 1, 0, {-0.3, -0.1}), "VEC4", 4, "STEP", first_joint + kLowerArmL,
            "rotation");
    channel(tstep, rotations(0, 1, 0, {0.1, 0.3}), "VEC4", 4, "STEP", first_joint + kLowerArmR,
            "rotation");
    {
        // CUBICSPLINE: per key (in-tangent, value, out-tangent); flat tangents.
        std::vector<float> out;
        const double ys[5] = {0.9, 0.93, 0.9, 0.93, 0.9};
        for (double y : ys) out.insert(out.end(), {0, 0, 0, 0, static_cast<float>(y), 0, 0, 0, 0});
        channel(t5, out, "VEC3", 3, "CUBICSPLINE", first_joint + kHips, "translation");
    }
    channel(t2, {0, 0, -2, 0, 0, -0.8f}, "VEC3", 3, "LINEAR", root_index, "translation");
    std::string anim = "[{\"name\":\"walk\",\"samplers\":[";
    for (std::size_t i = 0; i < samplers.size(); ++i) anim += (i ? "," : "") + samplers[i];
    anim += "],\"channels\":[";
    for (std::size_t i = 0; i < channels.size(); ++i) anim += (i ? "," : "") + channels[i];
    anim += "]}]";

    // Lights (KHR_lights_punctual: they shine along their node's -Z).
    const std::string lights =
        "[{\"name\":\"lamp\",\"type\":\"point\",\"color\":[1,0.949999988,0.850000024],"
        "\"intensity\":22,"
        "\"range\":15},"
        "{\"name\":\"headlight_left\",\"type\":\"spot\",\"color\":[1,1,0.899999976],\"intensity\":"
        "70,"
        "\"range\":20,\"spot\":{\"innerConeAngle\":0.150000006,\"outerConeAngle\":0.300000012}},"
        "{\"name\":\"headlight_right\",\"type\":\"spot\",\"color\":[1,1,0.899999976],\"intensity\":"
        "70,"
        "\"range\":20,\"spot\":{\"innerConeAngle\":0.150000006,\"outerConeAngle\":0.300000012}},"
        "{\"name\":\"sun\",\"type\":\"directional\",\"color\":[1,1,0.949999988],\"intensity\":0.7}"
        "]";
    auto light_node = [&](const char *name, int light, const double eye[3],
                          const double target[3]) {
        return add_node(
            std::string("{\"name\":\"") + name + "\"," + translation_json(eye) +
            ",\"rotation\":" + quat_json(look_at(eye, target)) +
            ",\"extensions\":{\"KHR_lights_punctual\":{\"light\":" + std::to_string(light) + "}}}");
    };
    // Off the character's symmetry plane x = 0: a light exactly in a triangle's
    // plane is refused by the scene (validate_scene), and the midline has some.
    const double lamp[3] = {0.37, 5.1, -0.63}, below[3] = {0.37, 0, -0.629};
    roots.push_back(light_node("lamp", 0, lamp, below));
    const double hl[3] = {13.5, 1.8, -0.8}, hlt[3] = {30, 0, -0.8};
    const double hr[3] = {13.5, 1.8, 0.8}, hrt[3] = {30, 0, 0.8};
    roots.push_back(light_node("headlight_left", 1, hl, hlt));
    roots.push_back(light_node("headlight_right", 2, hr, hrt));
    const double sun[3] = {-20, 40, -15}, sunt[3] = {0, 0, 0};
    roots.push_back(light_node("sun", 3, sun, sunt));
    const double eye[3] = {-7, 6.5, 13}, target[3] = {10, 0, -1};
    roots.push_back(add_node("{\"name\":\"camera\"," + translation_json(eye) + ",\"rotation\":" +
                             quat_json(look_at(eye, target)) + ",\"camera\":0}"));
    const std::string cameras = "[{\"name\":\"camera\",\"type\":\"perspective\",\"perspective\":{"
                                "\"aspectRatio\":1.77777779,"
                                "\"yfov\":0.800000012,\"znear\":0.100000001,\"zfar\":300}}]";

    std::string j;
    j += "{\"asset\":{\"version\":\"2.0\",\"generator\":\"shadowvol generate_models "
         "(tools/generate_models)\"},";
    j += "\"extensionsUsed\":[\"KHR_lights_punctual\"],";
    j += "\"extensions\":{\"KHR_lights_punctual\":{\"lights\":" + lights + "}},";
    j += "\"scene\":0,\"scenes\":[{\"name\":\"demo_scene\",\"nodes\":[";
    for (std::size_t i = 0; i < roots.size(); ++i) j += (i ? "," : "") + std::to_string(roots[i]);
    j += "]}],\"nodes\":[";
    for (std::size_t i = 0; i < nodes.size(); ++i) j += (i ? "," : "") + nodes[i];
    j += "],\"meshes\":[";
    for (std::size_t i = 0; i < meshes.size(); ++i) j += (i ? "," : "") + meshes[i];
    j += "],\"skins\":" + skins + ",\"animations\":" + anim + ",\"cameras\":" + cameras + ",";
    while (b.bin.size() % 4) b.bin.push_back(0);
    j += "\"buffers\":[{\"byteLength\":" + std::to_string(b.bin.size()) + "}],\"bufferViews\":[";
    for (std::size_t i = 0; i < b.views.size(); ++i) j += (i ? "," : "") + b.views[i];
    j += "],\"accessors\":[";
    for (std::size_t i = 0; i < b.accessors.size(); ++i) j += (i ? "," : "") + b.accessors[i];
    j += "]}";
    while (j.size() % 4) j += ' ';

    const std::size_t total = 12 + 8 + j.size() + 8 + b.bin.size();
    std::vector<std::uint8_t> out;
    auto u32 = [&](std::uint32_t v) {
        for (int i = 0; i < 4; ++i) out.push_back(static_cast<std::uint8_t>(v >> (8 * i)));
    };
    out.reserve(total);
    u32(0x46546C67u);
    u32(2);
    u32(static_cast<std::uint32_t>(total));
    u32(static_cast<std::uint32_t>(j.size()));
    u32(0x4E4F534Au);
    out.insert(out.end(), j.begin(), j.end());
    u32(static_cast<std::uint32_t>(b.bin.size()));
    u32(0x004E4942u);
    out.insert(out.end(), b.bin.begin(), b.bin.end());
    return out;
}

} // namespace svgen
