/*
 * load_animated_gltf and find_animation (include/shadowvol_anim.h).
 *
 * The file goes through the static loader's reader (src/gltf/gltf_internal.h)
 * first, so it gets every check load_gltf makes with the same words: file,
 * GLB, tinygltf, required extensions, the node graph and its transforms,
 * meshes, accessors, buffer ranges, skins and their weights. Then the checks
 * of this file (each a GltfError "<path>: <problem>"):
 *  - nodes: a camera or KHR_lights_punctual light index out of range, a
 *    light reference without an integer "light";
 *  - skins: a skeleton node out of range (and the inverse bind matrices of
 *    every skin, used or not);
 *  - animations: a channel whose node is missing or out of range, whose
 *    path is not translation / rotation / scale / weights, whose sampler is
 *    out of range, that targets a node with a matrix (glTF forbids it), or
 *    that repeats another channel's node and path; a sampler shared by
 *    channels of different paths; a sampler whose interpolation is not
 *    LINEAR / STEP / CUBICSPLINE, whose input is not FLOAT SCALAR, not
 *    finite or not strictly increasing, whose output is not FLOAT VEC3
 *    (translation, scale) or FLOAT / normalized integer VEC4 (rotation),
 *    has other than keys (LINEAR, STEP) or 3 * keys (CUBICSPLINE) elements,
 *    is not finite, or holds a zero rotation quaternion (a key's value;
 *    tangents may be zero);
 *  - lights: a type other than point / spot / directional, a colour of
 *    other than 3 finite numbers >= 0, a negative or non-finite intensity
 *    or range, a spot with innerConeAngle < 0, outerConeAngle outside
 *    (0, pi/2], or outer < inner;
 *  - cameras: a type other than perspective / orthographic; perspective:
 *    yfov not in (0, pi), znear <= 0, zfar neither absent (0) nor > znear,
 *    an aspectRatio <= 0 when given, anything non-finite.
 * Morph targets ("weights" channels, primitives with targets) are not
 * supported: notes say so, and poses use the base mesh.
 *
 * Copyright (C) 2026 the shadowvol authors. LGPL-2.1-or-later.
 */
#include "shadowvol_anim.h"

#include "gltf_internal.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <utility>

namespace sv {

namespace {

using gltf_internal::Mat4;
using gltf_internal::MeshData;
using gltf_internal::Reader;

constexpr double kPi = 3.14159265358979323846;

std::string quoted(const std::string &s) { return "'" + s + "'"; }

std::string num(double v) {
    char text[32];
    std::snprintf(text, sizeof text, "%.9g", v);
    return text;
}

Mat4d to_mat4d(const Mat4 &m) {
    Mat4d r;
    std::copy(m.begin(), m.end(), r.m);
    return r;
}

double linear_determinant(const double *m) {
    return m[0] * (m[5] * m[10] - m[9] * m[6]) - m[4] * (m[1] * m[10] - m[9] * m[2]) +
           m[8] * (m[1] * m[6] - m[5] * m[2]);
}

const char *path_name(AnimChannel::Path p) {
    switch (p) {
    case AnimChannel::Path::translation: return "translation";
    case AnimChannel::Path::rotation: return "rotation";
    case AnimChannel::Path::scale: return "scale";
    case AnimChannel::Path::weights: return "weights";
    }
    return "?";
}

class AnimLoader {
public:
    explicit AnimLoader(const std::string &path) : r_(path) { out_.path = path; }
    AnimLoader(const unsigned char *bytes, std::size_t size, const std::string &name)
        : r_(bytes, size, name) {
        out_.path = name;
    }
    AnimatedAsset run();

private:
    [[noreturn]] void fail(const std::string &problem) const { r_.fail(problem); }
    void load_nodes();
    void load_skins();
    void load_animations();
    void load_sampler(const std::string &label, const tinygltf::AnimationSampler &s, int components,
                      AnimSampler &out);
    void check_lights();
    void check_cameras();
    void place_lights_and_cameras();
    void load_surfaces();
    std::string light_label(int light) const;
    std::string camera_label(int camera) const;

    Reader r_;
    AnimatedAsset out_;
    std::vector<bool> orthographic_noted_;
};

// ------------------------------------------------------------------ nodes --

void AnimLoader::load_nodes() {
    r_.check_nodes();
    const tinygltf::Model &model = r_.model();
    const int num_nodes = static_cast<int>(model.nodes.size());
    const int num_cameras = static_cast<int>(model.cameras.size());
    const int num_lights = static_cast<int>(model.lights.size());
    out_.nodes.resize(model.nodes.size());
    for (int i = 0; i < num_nodes; i++) {
        const tinygltf::Node &g = model.nodes[i];
        AnimNode &a = out_.nodes[i];
        a.name = g.name;
        a.parent = r_.parent()[i];
        a.children = g.children;
        a.mesh = g.mesh;
        a.skin = g.skin;
        if (g.camera < -1 || g.camera >= num_cameras) {
            fail(r_.node_label(i) + ": camera " + std::to_string(g.camera) + " does not exist (" +
                 std::to_string(num_cameras) + " cameras)");
        }
        a.camera = g.camera;
        const auto ext = g.extensions.find("KHR_lights_punctual");
        if (ext != g.extensions.end()) {
            const tinygltf::Value &v = ext->second;
            if (!v.IsObject() || !v.Has("light") || !v.Get("light").IsInt()) {
                fail(r_.node_label(i) + ": KHR_lights_punctual has no integer \"light\"");
            }
            const int light = v.Get("light").GetNumberAsInt();
            if (light < 0 || light >= num_lights) {
                fail(r_.node_label(i) + ": KHR_lights_punctual light " + std::to_string(light) +
                     " does not exist (" + std::to_string(num_lights) + " lights)");
            }
            a.light = light;
        }
        a.has_matrix = !g.matrix.empty();
        if (a.has_matrix) {
            std::copy(g.matrix.begin(), g.matrix.end(), a.matrix.m);
        } else {
            for (int c = 0; c < 3; c++) {
                if (!g.translation.empty()) a.translation[c] = g.translation[c];
                if (!g.scale.empty()) a.scale[c] = g.scale[c];
            }
            if (!g.rotation.empty()) {
                const double *q = g.rotation.data();
                const double n = std::sqrt(q[0] * q[0] + q[1] * q[1] + q[2] * q[2] + q[3] * q[3]);
                for (int c = 0; c < 4; c++) a.rotation[c] = q[c] / n; /* n > 0: checked */
            }
        }
        a.rest_local = to_mat4d(r_.local_matrix(i));
    }
    out_.scene_roots = r_.scene_roots();
    /* Parents before children: every root (node order), depth first. */
    std::vector<int> stack;
    for (int n = num_nodes - 1; n >= 0; n--) {
        if (out_.nodes[n].parent == -1) stack.push_back(n);
    }
    while (!stack.empty()) {
        const int n = stack.back();
        stack.pop_back();
        out_.node_order.push_back(n);
        const std::vector<int> &ch = out_.nodes[n].children;
        for (auto it = ch.rbegin(); it != ch.rend(); ++it) stack.push_back(*it);
    }
}

// ------------------------------------------------------------------ skins --

void AnimLoader::load_skins() {
    const tinygltf::Model &model = r_.model();
    for (std::size_t s = 0; s < model.skins.size(); s++) {
        const tinygltf::Skin &g = model.skins[s];
        AnimSkin skin;
        skin.name = g.name;
        skin.joints = g.joints;
        for (const Mat4 &m : r_.inverse_bind_matrices(static_cast<int>(s))) {
            skin.inverse_bind.push_back(to_mat4d(m));
        }
        if (g.skeleton < -1 || g.skeleton >= static_cast<int>(model.nodes.size())) {
            fail("skin " + std::to_string(s) + (g.name.empty() ? "" : " " + quoted(g.name)) +
                 ": skeleton node " + std::to_string(g.skeleton) + " does not exist (" +
                 std::to_string(model.nodes.size()) + " nodes)");
        }
        skin.skeleton = g.skeleton;
        out_.skins.push_back(std::move(skin));
    }
}

// ------------------------------------------------------------- animations --

void AnimLoader::load_sampler(const std::string &label, const tinygltf::AnimationSampler &s,
                              int components, AnimSampler &out) {
    if (s.interpolation == "LINEAR") {
        out.interp = AnimSampler::Interp::linear;
    } else if (s.interpolation == "STEP") {
        out.interp = AnimSampler::Interp::step;
    } else if (s.interpolation == "CUBICSPLINE") {
        out.interp = AnimSampler::Interp::cubicspline;
    } else {
        fail(label + ": interpolation " + quoted(s.interpolation) +
             " is not LINEAR, STEP or CUBICSPLINE");
    }
    out.components = components;

    const std::string in_who = label + " input";
    const tinygltf::Accessor &ia = r_.accessor(s.input, in_who);
    if (ia.type != TINYGLTF_TYPE_SCALAR || ia.componentType != TINYGLTF_COMPONENT_TYPE_FLOAT ||
        ia.normalized) {
        fail(in_who + " (accessor " + std::to_string(s.input) + ") is " + Reader::format_text(ia) +
             ", expected FLOAT SCALAR (key times in seconds)");
    }
    const std::vector<double> times = r_.decode(s.input, in_who);
    for (std::size_t k = 0; k < times.size(); k++) {
        if (!std::isfinite(times[k])) {
            fail(in_who + ": key " + std::to_string(k) + " time is not finite");
        }
        if (k > 0 && !(times[k] > times[k - 1])) {
            fail(in_who + ": key " + std::to_string(k) + " time " + num(times[k]) +
                 " is not after key " + std::to_string(k - 1) + " time " + num(times[k - 1]) +
                 " (key times must increase strictly)");
        }
    }

    const std::string out_who = label + " output";
    const tinygltf::Accessor &oa = r_.accessor(s.output, out_who);
    bool format_ok = false;
    const char *expected = "";
    if (components == 3) {
        expected = "FLOAT VEC3";
        format_ok = oa.type == TINYGLTF_TYPE_VEC3 &&
                    oa.componentType == TINYGLTF_COMPONENT_TYPE_FLOAT && !oa.normalized;
    } else {
        expected = "FLOAT VEC4, or normalized BYTE, UNSIGNED_BYTE, SHORT or UNSIGNED_SHORT VEC4";
        const int ct = oa.componentType;
        format_ok = oa.type == TINYGLTF_TYPE_VEC4 &&
                    ((ct == TINYGLTF_COMPONENT_TYPE_FLOAT && !oa.normalized) ||
                     (oa.normalized && (ct == TINYGLTF_COMPONENT_TYPE_BYTE ||
                                        ct == TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE ||
                                        ct == TINYGLTF_COMPONENT_TYPE_SHORT ||
                                        ct == TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT)));
    }
    if (!format_ok) {
        fail(out_who + " (accessor " + std::to_string(s.output) + ") is " +
             Reader::format_text(oa) + ", expected " + expected + " for " +
             (components == 3 ? "translation or scale" : "rotation"));
    }
    const bool cubic = out.interp == AnimSampler::Interp::cubicspline;
    const std::size_t expected_count = times.size() * (cubic ? 3 : 1);
    if (oa.count != expected_count) {
        fail(out_who + " (accessor " + std::to_string(s.output) + ") has " +
             std::to_string(oa.count) + " elements, expected " + std::to_string(expected_count) +
             " (" + std::to_string(times.size()) + " keys" +
             (cubic ? " x 3: in-tangent, value, out-tangent" : "") + ")");
    }
    const std::vector<double> values = r_.decode(s.output, out_who);
    const std::size_t per_key = std::size_t(components) * (cubic ? 3 : 1);
    for (std::size_t k = 0; k < times.size(); k++) {
        const double *v = &values[k * per_key];
        for (std::size_t c = 0; c < per_key; c++) {
            if (!std::isfinite(v[c]) || !std::isfinite(static_cast<float>(v[c]))) {
                fail(out_who + ": key " + std::to_string(k) + " is not finite (in float)");
            }
        }
        if (components == 4) {
            const double *q = v + (cubic ? 4 : 0);
            const double n2 = q[0] * q[0] + q[1] * q[1] + q[2] * q[2] + q[3] * q[3];
            if (!(n2 > 0.0)) {
                fail(out_who + ": key " + std::to_string(k) +
                     " rotation quaternion is zero (no rotation has length 0)");
            }
        }
    }
    out.input.assign(times.begin(), times.end());
    out.output.resize(values.size());
    for (std::size_t i = 0; i < values.size(); i++) {
        out.output[i] = static_cast<float>(values[i]);
    }
}

void AnimLoader::load_animations() {
    const tinygltf::Model &model = r_.model();
    const int num_nodes = static_cast<int>(model.nodes.size());
    for (std::size_t ai = 0; ai < model.animations.size(); ai++) {
        const tinygltf::Animation &g = model.animations[ai];
        Animation an;
        an.name = g.name.empty() ? "animation#" + std::to_string(ai) : g.name;
        const std::string label = "animation " + std::to_string(ai) +
                                  (g.name.empty() ? "" : " " + quoted(g.name));
        const int num_samplers = static_cast<int>(g.samplers.size());
        std::vector<int> components(g.samplers.size(), 0); /* 0: no pose channel uses it */
        std::vector<std::string> first_user(g.samplers.size());
        std::size_t morph_channels = 0;
        for (std::size_t ci = 0; ci < g.channels.size(); ci++) {
            const tinygltf::AnimationChannel &c = g.channels[ci];
            const std::string clabel = label + " channel " + std::to_string(ci);
            if (c.target_node < 0 || c.target_node >= num_nodes) {
                fail(clabel + ": target node " +
                     (c.target_node < 0 ? std::string("is missing")
                                        : std::to_string(c.target_node) + " does not exist (" +
                                              std::to_string(num_nodes) + " nodes)"));
            }
            AnimChannel ch;
            ch.node = c.target_node;
            ch.sampler = c.sampler;
            if (c.target_path == "translation") {
                ch.path = AnimChannel::Path::translation;
            } else if (c.target_path == "rotation") {
                ch.path = AnimChannel::Path::rotation;
            } else if (c.target_path == "scale") {
                ch.path = AnimChannel::Path::scale;
            } else if (c.target_path == "weights") {
                ch.path = AnimChannel::Path::weights;
            } else {
                fail(clabel + ": target path " + quoted(c.target_path) +
                     " is not translation, rotation, scale or weights");
            }
            if (c.sampler < 0 || c.sampler >= num_samplers) {
                fail(clabel + ": sampler " + std::to_string(c.sampler) + " does not exist (" +
                     std::to_string(num_samplers) + " samplers)");
            }
            if (ch.path == AnimChannel::Path::weights) {
                morph_channels++;
                continue;
            }
            if (out_.nodes[ch.node].has_matrix) {
                fail(clabel + ": targets " + r_.node_label(ch.node) +
                     ", which has a matrix (glTF: an animated node has translation, rotation "
                     "and scale)");
            }
            for (std::size_t k = 0; k < an.channels.size(); k++) {
                if (an.channels[k].node == ch.node && an.channels[k].path == ch.path) {
                    fail(clabel + ": " + r_.node_label(ch.node) + " " + path_name(ch.path) +
                         " is animated twice (glTF: each target once per animation)");
                }
            }
            const int want = ch.path == AnimChannel::Path::rotation ? 4 : 3;
            int &have = components[ch.sampler];
            if (have != 0 && have != want) {
                fail(clabel + ": sampler " + std::to_string(ch.sampler) + " drives " +
                     path_name(ch.path) + " here and " + first_user[ch.sampler] +
                     " elsewhere (different value types)");
            }
            if (have == 0) first_user[ch.sampler] = path_name(ch.path);
            have = want;
            an.channels.push_back(ch);
        }
        if (morph_channels > 0) {
            r_.note(label + ": " + std::to_string(morph_channels) +
                    " channel(s) animate morph target weights: not supported, ignored (poses "
                    "use the base mesh)");
        }
        an.samplers.resize(g.samplers.size());
        bool any = false;
        for (int si = 0; si < num_samplers; si++) {
            if (components[si] == 0) continue; /* unused, or morph weights only */
            load_sampler(label + " sampler " + std::to_string(si), g.samplers[si], components[si],
                         an.samplers[si]);
            const AnimSampler &s = an.samplers[si];
            if (!any || s.input.front() < an.start) an.start = s.input.front();
            if (!any || s.input.back() > an.end) an.end = s.input.back();
            any = true;
        }
        out_.animations.push_back(std::move(an));
    }
}

// ------------------------------------------------------ lights and cameras --

std::string AnimLoader::light_label(int light) const {
    const std::string &name = r_.model().lights[light].name;
    return "KHR_lights_punctual light " + std::to_string(light) +
           (name.empty() ? "" : " " + quoted(name));
}

std::string AnimLoader::camera_label(int camera) const {
    const std::string &name = r_.model().cameras[camera].name;
    return "camera " + std::to_string(camera) + (name.empty() ? "" : " " + quoted(name));
}

void AnimLoader::check_lights() {
    const tinygltf::Model &model = r_.model();
    for (int i = 0; i < static_cast<int>(model.lights.size()); i++) {
        const tinygltf::Light &l = model.lights[i];
        const std::string label = light_label(i);
        if (l.type != "point" && l.type != "spot" && l.type != "directional") {
            fail(label + ": type " + quoted(l.type) + " is not point, spot or directional");
        }
        if (!l.color.empty()) {
            bool ok = l.color.size() == 3;
            for (double c : l.color) ok = ok && std::isfinite(c) && c >= 0.0;
            if (!ok) fail(label + ": color must be 3 finite numbers >= 0");
        }
        if (!std::isfinite(l.intensity) || l.intensity < 0.0) {
            fail(label + ": intensity " + num(l.intensity) + " must be finite and >= 0");
        }
        if (!std::isfinite(l.range) || l.range < 0.0) {
            fail(label + ": range " + num(l.range) +
                 (l.range < 0.0 ? " is negative" : " is not finite") +
                 " (a range is > 0; absent means unlimited)");
        }
        if (l.type == "spot") {
            const double inner = l.spot.innerConeAngle, outer = l.spot.outerConeAngle;
            if (!std::isfinite(inner) || !std::isfinite(outer)) {
                fail(label + ": spot cone angles are not finite");
            }
            if (inner < 0.0) {
                fail(label + ": spot innerConeAngle " + num(inner) + " is negative");
            }
            if (!(outer > 0.0) || outer > kPi / 2) {
                fail(label + ": spot outerConeAngle " + num(outer) +
                     " is outside (0, pi/2] (radians)");
            }
            if (outer < inner) {
                fail(label + ": spot outerConeAngle " + num(outer) +
                     " is smaller than innerConeAngle " + num(inner));
            }
        }
    }
}

void AnimLoader::check_cameras() {
    const tinygltf::Model &model = r_.model();
    for (int i = 0; i < static_cast<int>(model.cameras.size()); i++) {
        const tinygltf::Camera &c = model.cameras[i];
        const std::string label = camera_label(i);
        if (c.type == "orthographic") continue;
        if (c.type != "perspective") {
            fail(label + ": type " + quoted(c.type) + " is not perspective or orthographic");
        }
        const tinygltf::PerspectiveCamera &p = c.perspective;
        if (!std::isfinite(p.yfov) || !(p.yfov > 0.0) || !(p.yfov < kPi)) {
            fail(label + ": yfov " + num(p.yfov) + " is not in (0, pi) (radians)");
        }
        if (!std::isfinite(p.znear) || !(p.znear > 0.0)) {
            fail(label + ": znear " + num(p.znear) + " must be finite and > 0");
        }
        if (!std::isfinite(p.zfar) || (p.zfar != 0.0 && !(p.zfar > p.znear))) {
            fail(label + ": zfar " + num(p.zfar) + " must be > znear " + num(p.znear) +
                 " (or absent: infinite)");
        }
        if (!std::isfinite(p.aspectRatio) || p.aspectRatio < 0.0) {
            fail(label + ": aspectRatio " + num(p.aspectRatio) + " must be finite and > 0");
        }
    }
}

void AnimLoader::place_lights_and_cameras() {
    const tinygltf::Model &model = r_.model();
    std::vector<int> stack(out_.scene_roots.rbegin(), out_.scene_roots.rend());
    while (!stack.empty()) {
        const int n = stack.back();
        stack.pop_back();
        const AnimNode &node = out_.nodes[n];
        if (node.light >= 0) {
            const tinygltf::Light &l = model.lights[node.light];
            AnimLight a;
            a.node = n;
            a.index = node.light;
            a.name = l.name.empty() ? "light#" + std::to_string(node.light) : l.name;
            SceneLight &s = a.light;
            s.kind = l.type == "point"  ? LightKind::point
                     : l.type == "spot" ? LightKind::spot
                                        : LightKind::directional;
            s.position = Vec3d{0, 0, 0};
            s.direction = Vec3d{0, 0, -1};
            s.range = l.type == "directional" ? 0.0 : l.range;
            if (s.kind == LightKind::spot) {
                s.inner_degrees = l.spot.innerConeAngle * 180.0 / kPi;
                s.outer_degrees = l.spot.outerConeAngle * 180.0 / kPi;
            }
            if (l.color.size() == 3) {
                for (int c = 0; c < 3; c++) s.color[c] = static_cast<float>(l.color[c]);
            }
            s.intensity = l.intensity;
            out_.lights.push_back(a);
        }
        if (node.camera >= 0) {
            const tinygltf::Camera &c = model.cameras[node.camera];
            if (c.type == "orthographic") {
                r_.note(camera_label(node.camera) + " on " + r_.node_label(n) +
                        ": orthographic cameras are not supported, left out");
            } else {
                AnimCamera a;
                a.node = n;
                a.index = node.camera;
                a.name = c.name.empty() ? "camera#" + std::to_string(node.camera) : c.name;
                a.yfov_radians = c.perspective.yfov;
                a.znear = c.perspective.znear;
                a.zfar = c.perspective.zfar;
                a.aspect = c.perspective.aspectRatio;
                out_.cameras.push_back(a);
            }
        }
        for (auto it = node.children.rbegin(); it != node.children.rend(); ++it) {
            stack.push_back(*it);
        }
    }
}

// --------------------------------------------------------------- surfaces --

void AnimLoader::load_surfaces() {
    const tinygltf::Model &model = r_.model();
    const Pose rest = pose_at(out_, -1, 0.0);
    for (const auto &instance : r_.instances()) {
        const int mesh = instance.first, node = instance.second;
        const int skin = node >= 0 ? model.nodes[node].skin : -1;
        MeshData md = r_.mesh(mesh, skin);

        AnimatedSurface s;
        const std::string &mesh_name = model.meshes[mesh].name;
        s.name = mesh_name.empty() ? "mesh#" + std::to_string(mesh) : mesh_name;
        if (node >= 0) {
            const std::string &node_name = model.nodes[node].name;
            s.name += " @ " + (node_name.empty() ? "node#" + std::to_string(node) : node_name);
        }
        if (md.indices.empty()) {
            r_.note(s.name + ": no triangles, skipped");
            continue;
        }
        s.mesh_index = mesh;
        s.node_index = node;
        s.skin = skin;
        s.declared_ground = r_.declared_ground(mesh, node);

        auto prepare = [&](const std::vector<uint32_t> &indices) {
            try {
                return prepare_surface(md.positions.data(), md.num_vertices(), indices.data(),
                                       indices.size());
            } catch (const PrepareError &e) {
                fail(s.name + ": " + e.what());
            }
        };
        s.prepared = prepare(md.indices);
        const int welded = s.prepared.num_vertices();
        /* first[w]: the first input vertex of welded vertex w. */
        std::vector<uint32_t> first(welded, UINT32_MAX);
        for (std::size_t v = 0; v < s.prepared.remap.size(); v++) {
            uint32_t &f = first[s.prepared.remap[v]];
            if (f == UINT32_MAX) f = static_cast<uint32_t>(v);
        }
        s.rest_positions = s.prepared.positions;

        /* Which triangles the file's pose mirrors (load_gltf's rule). */
        std::vector<bool> flip(md.indices.size() / 3, false);
        if (skin < 0) {
            const Mat4d world = node >= 0 ? rest.world[node] : Mat4d();
            if (linear_determinant(world.m) < 0.0) flip.assign(flip.size(), true);
        } else {
            const AnimSkin &sk = out_.skins[skin];
            std::vector<Mat4d> jm(sk.joints.size());
            for (std::size_t j = 0; j < jm.size(); j++) {
                jm[j] = rest.world[sk.joints[j]] * sk.inverse_bind[j];
            }
            std::vector<bool> mirrors(welded, false);
            for (int w = 0; w < welded; w++) {
                const double *wt = &md.weights[8 * std::size_t(first[w])];
                const uint32_t *jt = &md.joints[8 * std::size_t(first[w])];
                double sum = 0.0;
                for (int k = 0; k < 8; k++) sum += wt[k];
                double blend[16] = {0};
                for (int k = 0; k < 8; k++) {
                    if (wt[k] == 0.0) continue;
                    const double wk = wt[k] / sum;
                    for (int e = 0; e < 16; e++) blend[e] += wk * jm[jt[k]].m[e];
                }
                mirrors[w] = linear_determinant(blend) < 0.0;
            }
            for (std::size_t t = 0; t < flip.size(); t++) {
                flip[t] = mirrors[s.prepared.remap[md.indices[3 * t]]];
            }
        }
        s.flipped_triangles = static_cast<std::size_t>(std::count(flip.begin(), flip.end(), true));
        s.mirrored = s.flipped_triangles > 0;
        if (s.mirrored) {
            for (std::size_t t = 0; t < flip.size(); t++) {
                if (flip[t]) std::swap(md.indices[3 * t + 1], md.indices[3 * t + 2]);
            }
            s.prepared = prepare(md.indices); /* same welding; windings flipped */
        }

        if (skin >= 0) {
            s.influences = 4 * md.influence_sets;
            const std::size_t inf = std::size_t(s.influences);
            s.joints.resize(inf * welded);
            s.weights.resize(inf * welded);
            for (int w = 0; w < welded; w++) {
                const double *wt = &md.weights[8 * std::size_t(first[w])];
                const uint32_t *jt = &md.joints[8 * std::size_t(first[w])];
                double sum = 0.0;
                for (int k = 0; k < 8; k++) sum += wt[k];
                for (std::size_t k = 0; k < inf; k++) {
                    s.joints[inf * w + k] = static_cast<uint16_t>(jt[k]); /* < 65536: u8/u16 */
                    s.weights[inf * w + k] = static_cast<float>(wt[k] / sum);
                }
            }
        }

        /* At rest: the file's pose. */
        std::vector<float> posed(s.rest_positions.size());
        pose_surface(out_, s, rest, Mat4d(), posed.data());
        for (float c : posed) {
            if (!std::isfinite(c)) {
                fail(s.name + ": a vertex is not finite at the file's pose (the transform "
                              "overflows float)");
            }
        }
        s.prepared = prepared_at(s, posed.data());
        out_.surfaces.push_back(std::move(s));
    }
    if (!model.meshes.empty() && out_.surfaces.empty()) {
        r_.note("no surface with triangles in the selected scene");
    }
}

AnimatedAsset AnimLoader::run() {
    load_nodes();
    load_skins();
    check_lights();
    check_cameras();
    load_animations();
    place_lights_and_cameras();
    load_surfaces();
    out_.notes = r_.notes();
    return std::move(out_);
}

} // namespace

AnimatedAsset load_animated_gltf(const std::string &path) {
    AnimLoader loader(path);
    return loader.run();
}

AnimatedAsset load_animated_gltf_memory(const unsigned char *bytes, std::size_t size,
                                        const std::string &name) {
    AnimLoader loader(bytes, size, name);
    return loader.run();
}

int find_animation(const AnimatedAsset &asset, const std::string &name_or_index) {
    const int n = static_cast<int>(asset.animations.size());
    for (int i = 0; i < n; i++) {
        if (asset.animations[i].name == name_or_index) return i;
    }
    if (!name_or_index.empty() && name_or_index.size() < 10 &&
        std::all_of(name_or_index.begin(), name_or_index.end(),
                    [](char c) { return c >= '0' && c <= '9'; })) {
        const int i = std::atoi(name_or_index.c_str());
        if (i < n) return i;
    }
    std::string names;
    for (int i = 0; i < n; i++) {
        names += (i ? ", " : "") + std::to_string(i) + " " + quoted(asset.animations[i].name);
    }
    throw GltfError(asset.path + ": no animation " + quoted(name_or_index) +
                    (n == 0 ? "; the file has no animations" : "; the animations are: " + names));
}

} // namespace sv
