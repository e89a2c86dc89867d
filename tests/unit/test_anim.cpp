// Scenes in time from glTF (include/shadowvol_anim.h, src/anim/).
//
//  - AnimSample: interpolation against hand-computed values (LINEAR, STEP,
//    CUBICSPLINE with its tangents, slerp with the shorter-arc sign flip,
//    the near-parallel lerp), clamping before the first and after the last
//    key, rotations normalized.
//  - AnimFile: files written here (JSON with a base64 data: buffer): a node
//    hierarchy driven by an animation, a skinned mesh with one and with two
//    influence sets, lights and cameras on nodes, the file's pose equal to
//    load_gltf's, a mirrored node, morph targets and "weights" channels
//    reported, find_animation; and one clean GltfError for each malformed
//    file (sampler input not increasing, output of the wrong length or
//    type, zero quaternions, joints beyond the skin, missing nodes, bad
//    lights and cameras, non-finite numbers).
//  - AnimSkinning: every kernel the CPU runs against the C reference, bit
//    for bit (the stated bound is 0 ulps: docs/ANIMATION.md), on random
//    data of every influence count and many lengths, with guards after the
//    output.
//  - AnimCharacters: the real characters of ../shared/models (Fox,
//    CesiumMan, RobotExpressive, RiggedFigure; a NOTE when the folder is
//    absent): every animation found by name and by index and posed at
//    several times (finite, bounded, moving), kernels bit-identical to the
//    C reference there too, topology equal to load_gltf + prepare_surface,
//    the rest pose equal to load_gltf's, and the kernels' rdtsc ticks per
//    vertex printed (no timing assertion).
//
// Copyright (C) 2026 the shadowvol authors. LGPL-2.1-or-later.
#include "shadowvol_anim.h"
#include "shadowvol_gltf.h"
#include "shadowvol_mesh.h"
#include "test_support.h"

#include <gtest/gtest.h>

#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <limits>
#include <string>
#include <vector>

namespace {

namespace fs = std::filesystem;

constexpr double kPi = 3.14159265358979323846;
constexpr int kU8 = 5121, kU16 = 5123, kFloat = 5126;

// ================================================================ sampling

sv::AnimSampler make_sampler(sv::AnimSampler::Interp interp, int components,
                             std::vector<float> input, std::vector<float> output) {
    sv::AnimSampler s;
    s.interp = interp;
    s.components = components;
    s.input = std::move(input);
    s.output = std::move(output);
    return s;
}

void expect_near3(const double *v, double x, double y, double z, double tol = 1e-12) {
    EXPECT_NEAR(v[0], x, tol);
    EXPECT_NEAR(v[1], y, tol);
    EXPECT_NEAR(v[2], z, tol);
}

TEST(AnimSample, LinearClampsAndInterpolates) {
    const auto s = make_sampler(sv::AnimSampler::Interp::linear, 3, {0, 1, 3},
                                {0, 0, 0, 1, 2, 3, 3, 2, 1});
    double v[4];
    sv::sample(s, 0.5, v);
    expect_near3(v, 0.5, 1, 1.5);
    sv::sample(s, 2.0, v); // halfway between keys 1 and 2
    expect_near3(v, 2, 2, 2);
    sv::sample(s, 1.0, v); // exactly on a key
    expect_near3(v, 1, 2, 3, 0);
    sv::sample(s, -5.0, v); // before the first key: its value
    expect_near3(v, 0, 0, 0, 0);
    sv::sample(s, 99.0, v); // after the last: its value
    expect_near3(v, 3, 2, 1, 0);
    sv::sample(s, std::nan(""), v); // NaN: the first value, never garbage
    expect_near3(v, 0, 0, 0, 0);
}

TEST(AnimSample, StepHoldsUntilTheNextKey) {
    const auto s = make_sampler(sv::AnimSampler::Interp::step, 3, {0, 1, 2},
                                {1, 1, 1, 2, 2, 2, 3, 3, 3});
    double v[4];
    sv::sample(s, 0.999, v);
    expect_near3(v, 1, 1, 1, 0);
    sv::sample(s, 1.0, v);
    expect_near3(v, 2, 2, 2, 0);
    sv::sample(s, 1.5, v);
    expect_near3(v, 2, 2, 2, 0);
    sv::sample(s, 7, v);
    expect_near3(v, 3, 3, 3, 0);
}

TEST(AnimSample, CubicSplineUsesTheTangents) {
    // Keys at 0 and 2 (dt = 2): v0 = 0, out-tangent b0 = (4, 0, 0); v1 = (1,
    // 2, 3), in-tangent a1 = (0, 0, 8). Unused tangents are set to junk.
    const auto s = make_sampler(sv::AnimSampler::Interp::cubicspline, 3, {0, 2},
                                {9, 9, 9, /**/ 0, 0, 0, /**/ 4, 0, 0,   // key 0: a, v, b
                                 0, 0, 8, /**/ 1, 2, 3, /**/ 9, 9, 9}); // key 1
    double v[4];
    // u = 0.5: h00 = 0.5, h10 = 0.125, h01 = 0.5, h11 = -0.125
    //   p = 0.5 v0 + 0.125 * 2 * b0 + 0.5 v1 - 0.125 * 2 * a1
    sv::sample(s, 1.0, v);
    expect_near3(v, 0.5 + 1.0, 1.0, 1.5 - 2.0);
    // u = 0.25: h00 = 0.84375, h10 = 0.140625, h01 = 0.15625, h11 = -0.046875
    sv::sample(s, 0.5, v);
    expect_near3(v, 0.140625 * 2 * 4 + 0.15625, 0.15625 * 2, 0.15625 * 3 - 0.046875 * 2 * 8);
    // Clamped: the key values, not the tangents.
    sv::sample(s, -1, v);
    expect_near3(v, 0, 0, 0, 0);
    sv::sample(s, 3, v);
    expect_near3(v, 1, 2, 3, 0);
}

std::vector<float> quat_z(double degrees) {
    const double h = degrees * kPi / 360.0;
    return {0, 0, float(std::sin(h)), float(std::cos(h))};
}

TEST(AnimSample, SlerpTakesTheShorterArc) {
    std::vector<float> out = quat_z(0);
    const std::vector<float> q90 = quat_z(90);
    out.insert(out.end(), q90.begin(), q90.end());
    const auto s = make_sampler(sv::AnimSampler::Interp::linear, 4, {0, 1}, out);
    double v[4];
    sv::sample(s, 0.5, v); // 45 degrees about z
    EXPECT_NEAR(v[0], 0, 1e-7);
    EXPECT_NEAR(v[1], 0, 1e-7);
    EXPECT_NEAR(v[2], std::sin(22.5 * kPi / 180), 1e-7);
    EXPECT_NEAR(v[3], std::cos(22.5 * kPi / 180), 1e-7);
    sv::sample(s, 0.25, v); // slerp, not lerp: 22.5 degrees exactly
    EXPECT_NEAR(v[2], std::sin(11.25 * kPi / 180), 1e-7);
    EXPECT_NEAR(v[3], std::cos(11.25 * kPi / 180), 1e-7);

    // The same rotation stored as -q: the shorter arc is still 45 degrees
    // (a naive slerp would turn the long way, through 225 degrees).
    std::vector<float> neg = quat_z(0);
    for (float c : q90) neg.push_back(-c);
    const auto s2 = make_sampler(sv::AnimSampler::Interp::linear, 4, {0, 1}, neg);
    sv::sample(s2, 0.5, v);
    EXPECT_NEAR(v[2], std::sin(22.5 * kPi / 180), 1e-7);
    EXPECT_NEAR(v[3], std::cos(22.5 * kPi / 180), 1e-7);

    // Nearly equal keys: the normalized lerp branch, still unit length.
    std::vector<float> close = quat_z(10);
    const std::vector<float> q11 = quat_z(10.5);
    close.insert(close.end(), q11.begin(), q11.end());
    const auto s3 = make_sampler(sv::AnimSampler::Interp::linear, 4, {0, 1}, close);
    sv::sample(s3, 0.5, v);
    EXPECT_NEAR(std::hypot(std::hypot(v[0], v[1]), std::hypot(v[2], v[3])), 1.0, 1e-15);
    EXPECT_NEAR(v[2], std::sin(10.25 * kPi / 360), 1e-6);
}

TEST(AnimSample, RotationsComeOutNormalized) {
    // STEP with a key of length 2; CUBICSPLINE between unit keys with big
    // tangents leaves the unit sphere before normalization.
    const auto s = make_sampler(sv::AnimSampler::Interp::step, 4, {0, 1}, {0, 0, 0, 2, 0, 0, 3, 4});
    double v[4];
    sv::sample(s, 0.2, v);
    EXPECT_DOUBLE_EQ(v[3], 1.0);
    sv::sample(s, 1.5, v);
    EXPECT_DOUBLE_EQ(v[2], 0.6);
    EXPECT_DOUBLE_EQ(v[3], 0.8);
    std::vector<float> out = {0, 0, 0, 0, 0, 0, 0, 1, 5, 5, 5, 5};
    const std::vector<float> k1 = {0, 0, 0, 0, 0, 0, 1, 0, 0, 0, 0, 0};
    out.insert(out.end(), k1.begin(), k1.end());
    const auto c = make_sampler(sv::AnimSampler::Interp::cubicspline, 4, {0, 1}, out);
    sv::sample(c, 0.3, v);
    EXPECT_NEAR(v[0] * v[0] + v[1] * v[1] + v[2] * v[2] + v[3] * v[3], 1.0, 1e-14);
}

// ============================================================ glTF writer

std::string base64(const std::string &in) {
    static const char kTable[] = "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
    std::string out;
    std::size_t i = 0;
    for (; i + 2 < in.size(); i += 3) {
        const uint32_t v = uint32_t(uint8_t(in[i])) << 16 | uint32_t(uint8_t(in[i + 1])) << 8 |
                           uint8_t(in[i + 2]);
        for (int s = 18; s >= 0; s -= 6) out += kTable[(v >> s) & 63];
    }
    if (i + 1 == in.size()) {
        const uint32_t v = uint32_t(uint8_t(in[i])) << 16;
        out += kTable[v >> 18];
        out += kTable[(v >> 12) & 63];
        out += "==";
    } else if (i + 2 == in.size()) {
        const uint32_t v = uint32_t(uint8_t(in[i])) << 16 | uint32_t(uint8_t(in[i + 1])) << 8;
        out += kTable[v >> 18];
        out += kTable[(v >> 12) & 63];
        out += kTable[(v >> 6) & 63];
        out += '=';
    }
    return out;
}

// A glTF document from JSON fragments, one vector per top-level array, the
// binary data in one base64 buffer.
struct Doc {
    std::string bin;
    std::vector<std::string> views, accessors, meshes, nodes, skins, scenes, animations, cameras,
        lights;

    int add(const void *data, std::size_t bytes, int component_type, std::size_t count,
            const std::string &type, const std::string &extra = "") {
        while (bin.size() % 4) bin += '\0';
        const std::size_t offset = bin.size();
        bin.append(static_cast<const char *>(data), bytes);
        views.push_back("{\"buffer\":0,\"byteOffset\":" + std::to_string(offset) +
                        ",\"byteLength\":" + std::to_string(bytes) + "}");
        accessors.push_back("{\"bufferView\":" + std::to_string(views.size() - 1) +
                            ",\"componentType\":" + std::to_string(component_type) + ",\"count\":" +
                            std::to_string(count) + ",\"type\":\"" + type + "\"" + extra + "}");
        return int(accessors.size()) - 1;
    }
    int floats(const std::vector<float> &v, const std::string &type, std::size_t per) {
        return add(v.data(), 4 * v.size(), kFloat, v.size() / per, type);
    }
    int u8(const std::vector<uint8_t> &v, const std::string &type, std::size_t per,
           bool normalized = false) {
        return add(v.data(), v.size(), kU8, v.size() / per, type,
                   normalized ? ",\"normalized\":true" : "");
    }
    int u16(const std::vector<uint16_t> &v, const std::string &type, std::size_t per) {
        return add(v.data(), 2 * v.size(), kU16, v.size() / per, type);
    }
    int node(const std::string &body) {
        nodes.push_back("{" + body + "}");
        return int(nodes.size()) - 1;
    }

    std::string json() const {
        std::string j = "{\"asset\":{\"version\":\"2.0\"},";
        auto array = [&j](const char *name, const std::vector<std::string> &items) {
            if (items.empty()) return;
            j += std::string("\"") + name + "\":[";
            for (std::size_t i = 0; i < items.size(); i++) j += (i ? "," : "") + items[i];
            j += "],";
        };
        array("scenes", scenes);
        array("nodes", nodes);
        array("meshes", meshes);
        array("skins", skins);
        array("animations", animations);
        array("cameras", cameras);
        array("accessors", accessors);
        array("bufferViews", views);
        if (!lights.empty()) {
            j += "\"extensionsUsed\":[\"KHR_lights_punctual\"],\"extensions\":{"
                 "\"KHR_lights_punctual\":{\"lights\":[";
            for (std::size_t i = 0; i < lights.size(); i++) j += (i ? "," : "") + lights[i];
            j += "]}},";
        }
        if (!bin.empty()) {
            j += "\"buffers\":[{\"byteLength\":" + std::to_string(bin.size()) +
                 ",\"uri\":\"data:application/octet-stream;base64," + base64(bin) + "\"}],";
        }
        j.back() = '}';
        return j;
    }
};

// A closed tetrahedron, counter-clockwise seen from outside, plus a copy of
// vertex 0 (a UV-seam split: it must weld to vertex 0).
const std::vector<float> kTetra = {0, 0, 0, 1, 0, 0, 0, 1, 0, 0, 0, 1, 0, 0, 0};
const std::vector<uint16_t> kTetraIndices = {0, 2, 1, 4, 1, 3, 0, 3, 2, 1, 2, 3};

// The test rig, valid as built; each malformed case changes one part.
struct Rig {
    // Animation 0 "wave": node 2's rotation about z, 0 -> 90 degrees over
    // [0, 2] (LINEAR), and node 1's translation (STEP).
    std::vector<float> times = {0, 1, 2};
    std::vector<float> rotations; // 4 per key
    std::string rotation_interp = "LINEAR";
    std::string rotation_type = "VEC4";
    int rotation_components = 4;
    std::string channel_target = "\"node\":2"; // of the rotation channel
    std::string channel_path = "rotation";
    std::vector<float> translations = {0, 0, 0, 0, 0.5f, 0, 0, 1, 0};
    // The mesh: skinned to joints 1 and 2 (JOINTS_0 as u8).
    std::vector<uint8_t> joints; // 4 per vertex
    std::vector<float> weights;  // 4 per vertex
    bool second_set = false;     // JOINTS_1 / WEIGHTS_1 too
    std::string node2_extra;     // more members of node 2
    std::string light_point =
        "{\"type\":\"point\",\"range\":5,\"intensity\":3,\"color\":[1,0.5,0.25]}";
    std::string light_spot =
        "{\"type\":\"spot\",\"spot\":{\"innerConeAngle\":0.2,\"outerConeAngle\":0.5}}";
    std::string camera = "{\"type\":\"perspective\",\"perspective\":{\"yfov\":0.8,\"znear\":0.1,"
                         "\"aspectRatio\":1.5}}";
    std::string extra_animation; // another animation, when not empty
    std::string mesh_extra;      // more members of the primitive

    Rig() {
        for (double deg : {0.0, 45.0, 90.0}) {
            const std::vector<float> q = quat_z(deg);
            rotations.insert(rotations.end(), q.begin(), q.end());
        }
        // vertices 0, 4: joint 1 (node 1) only; 1: half and half; 2, 3: joint 2.
        joints = {0, 0, 0, 0, 0, 1, 0, 0, 1, 0, 0, 0, 1, 0, 0, 0, 0, 0, 0, 0};
        weights = {1, 0, 0, 0, 0.5f, 0.5f, 0, 0, 1, 0, 0, 0, 1, 0, 0, 0, 1, 0, 0, 0};
    }

    Doc doc() const {
        Doc d;
        const int pos = d.floats(kTetra, "VEC3", 3);
        const int idx = d.u16(kTetraIndices, "SCALAR", 1);
        const int j0 = d.u8(joints, "VEC4", 4);
        const int w0 = d.floats(weights, "VEC4", 4);
        std::string attributes = "\"POSITION\":" + std::to_string(pos) +
                                 ",\"JOINTS_0\":" + std::to_string(j0) +
                                 ",\"WEIGHTS_0\":" + std::to_string(w0);
        if (second_set) {
            // Second set: vertex 3 gets 0.25 of joint 0 (node 1) in its
            // fourth slot of set 1; its first set is scaled to 0.75.
            std::vector<uint8_t> j1(20, 0);
            std::vector<float> w1(20, 0.0f);
            w1[4 * 3 + 3] = 0.25f;
            const int aj = d.u8(j1, "VEC4", 4), aw = d.floats(w1, "VEC4", 4);
            attributes += ",\"JOINTS_1\":" + std::to_string(aj) +
                          ",\"WEIGHTS_1\":" + std::to_string(aw);
        }
        d.meshes.push_back("{\"name\":\"tetra\",\"primitives\":[{\"attributes\":{" + attributes +
                           "},\"indices\":" + std::to_string(idx) + mesh_extra + "}]}");
        // The joints' bind pose: node 1 at the origin, node 2 at (0, 1, 0).
        const std::vector<float> ibm = {1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, 0,  0, 1,
                                        1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, -1, 0, 1};
        const int ib = d.floats(ibm, "MAT4", 16);
        d.skins.push_back("{\"name\":\"rig\",\"joints\":[1,2],\"inverseBindMatrices\":" +
                          std::to_string(ib) + ",\"skeleton\":1}");
        d.node("\"name\":\"root\",\"translation\":[10,0,0],\"children\":[1,3,4,5,6]");   // 0
        d.node("\"name\":\"hip\",\"children\":[2]");                                     // 1
        d.node("\"name\":\"arm\",\"translation\":[0,1,0]" + node2_extra);                // 2
        d.node("\"name\":\"body\",\"mesh\":0,\"skin\":0,\"translation\":[100,100,100]"); // 3
        d.node(
            "\"name\":\"lamp\",\"translation\":[0,3,0],\"rotation\":[-0.70710678,0,0,0.70710678],"
            "\"extensions\":{\"KHR_lights_punctual\":{\"light\":1}}");   // 4: spot aimed down
        d.node("\"name\":\"eye\",\"translation\":[0,1,5],\"camera\":0"); // 5
        d.node("\"name\":\"bulb\",\"translation\":[1,2,3],"
               "\"extensions\":{\"KHR_lights_punctual\":{\"light\":0}}"); // 6
        d.scenes.push_back("{\"nodes\":[0]}");
        d.lights = {light_point, light_spot, "{\"type\":\"directional\"}"};
        d.cameras = {camera};
        const int tin = d.floats(times, "SCALAR", 1);
        const int rot = d.floats(rotations, rotation_type, std::size_t(rotation_components));
        const int tr_in = d.floats({0, 1, 2}, "SCALAR", 1);
        const int tr = d.floats(translations, "VEC3", 3);
        d.animations.push_back(
            "{\"name\":\"wave\",\"samplers\":[{\"input\":" + std::to_string(tin) +
            ",\"output\":" + std::to_string(rot) + ",\"interpolation\":\"" + rotation_interp +
            "\"},{\"input\":" + std::to_string(tr_in) + ",\"output\":" + std::to_string(tr) +
            ",\"interpolation\":\"STEP\"}],\"channels\":[{\"sampler\":0,\"target\":{" +
            channel_target + ",\"path\":\"" + channel_path +
            "\"}},{\"sampler\":1,\"target\":{\"node\":1,\"path\":\"translation\"}}]}");
        if (!extra_animation.empty()) d.animations.push_back(extra_animation);
        return d;
    }
};

class AnimFile : public testing::Test {
protected:
    void SetUp() override {
        const testing::TestInfo *info = testing::UnitTest::GetInstance()->current_test_info();
        dir_ = fs::path(testing::TempDir()) /
               ("shadowvol_anim_" + std::to_string(getpid()) + "_" + info->name());
        fs::remove_all(dir_);
        fs::create_directories(dir_);
    }
    void TearDown() override { fs::remove_all(dir_); }

    std::string write(const std::string &json, const std::string &name = "rig.gltf") {
        const fs::path p = dir_ / name;
        std::ofstream f(p, std::ios::binary);
        f << json;
        return p.string();
    }
    std::string write(const Rig &rig, const std::string &name = "rig.gltf") {
        return write(rig.doc().json(), name);
    }

    // Loads and expects a GltfError that starts with the path and contains
    // every word given.
    void expect_error(const Rig &rig, const std::vector<std::string> &words) {
        expect_error_json(rig.doc().json(), words);
    }
    void expect_error_json(const std::string &json, const std::vector<std::string> &words) {
        const std::string path = write(json, "bad.gltf");
        try {
            sv::load_animated_gltf(path);
            ADD_FAILURE() << "loaded without error; expected: " << words[0];
        } catch (const sv::GltfError &e) {
            const std::string message = e.what();
            EXPECT_EQ(message.rfind(path + ": ", 0), 0u) << message;
            for (const std::string &w : words) {
                EXPECT_NE(message.find(w), std::string::npos)
                    << "message lacks \"" << w << "\": " << message;
            }
        } catch (const std::exception &e) {
            ADD_FAILURE() << "not a GltfError: " << e.what();
        }
    }

    fs::path dir_;
};

sv::Vec3d apply(const sv::Mat4d &m, double x, double y, double z) {
    const auto p = m.apply(x, y, z, 1);
    return {p[0], p[1], p[2]};
}

TEST_F(AnimFile, HierarchyLightsAndCameras) {
    const sv::AnimatedAsset a = sv::load_animated_gltf(write(Rig()));
    ASSERT_EQ(a.nodes.size(), 7u);
    EXPECT_EQ(a.nodes[2].parent, 1);
    EXPECT_EQ(a.nodes[1].parent, 0);
    EXPECT_EQ(a.scene_roots, std::vector<int>{0});
    ASSERT_EQ(a.animations.size(), 1u);
    EXPECT_EQ(a.animations[0].name, "wave");
    EXPECT_EQ(a.animations[0].start, 0.0);
    EXPECT_EQ(a.animations[0].end, 2.0);
    ASSERT_EQ(a.skins.size(), 1u);
    EXPECT_EQ(a.skins[0].skeleton, 1);

    // Node 2 ("arm") at (10, 1, 0) + node 1's STEP translation; its +x axis
    // turns from +x to +y over the animation.
    for (double t : {-1.0, 0.0, 0.5, 1.0, 1.5, 2.0, 3.0}) {
        const sv::Pose p = sv::pose_at(a, 0, t);
        const double tc = std::min(2.0, std::max(0.0, t));
        const double lift = tc < 1 ? 0.0 : tc < 2 ? 0.5 : 1.0;
        const double angle = tc * 45.0 * kPi / 180.0;
        const sv::Vec3d o = apply(p.world[2], 0, 0, 0), x = apply(p.world[2], 1, 0, 0);
        EXPECT_NEAR(o.x, 10, 1e-12) << t;
        EXPECT_NEAR(o.y, 1 + lift, 1e-12) << t;
        EXPECT_NEAR(x.x - o.x, std::cos(angle), 1e-7) << t;
        EXPECT_NEAR(x.y - o.y, std::sin(angle), 1e-7) << t;
    }

    // Lights in scene order (lamp, then bulb) at the file's pose.
    const sv::Pose rest = sv::pose_at(a, -1, 0);
    ASSERT_EQ(a.lights.size(), 2u);
    const sv::SceneLight spot = sv::light_at(a, 0, rest, sv::Mat4d());
    EXPECT_EQ(spot.kind, sv::LightKind::spot);
    EXPECT_NEAR(spot.position.x, 10, 1e-12);
    EXPECT_NEAR(spot.position.y, 3, 1e-12);
    EXPECT_NEAR(spot.direction.y, -1, 1e-7); // -z turned down by -90 degrees about x
    EXPECT_NEAR(spot.inner_degrees, 0.2 * 180 / kPi, 1e-12);
    EXPECT_NEAR(spot.outer_degrees, 0.5 * 180 / kPi, 1e-12);
    const sv::SceneLight bulb = sv::light_at(a, 1, rest, sv::Mat4d());
    EXPECT_EQ(bulb.kind, sv::LightKind::point);
    EXPECT_NEAR(bulb.position.x, 11, 1e-12);
    EXPECT_NEAR(bulb.position.z, 3, 1e-12);
    EXPECT_EQ(bulb.range, 5);
    EXPECT_EQ(bulb.intensity, 3);
    EXPECT_EQ(bulb.color[1], 0.5f);

    // A root placement moves them (applied last).
    sv::Mat4d root;
    root.m[13] = -7;
    EXPECT_NEAR(sv::light_at(a, 1, rest, root).position.y, 2 - 7, 1e-12);

    ASSERT_EQ(a.cameras.size(), 1u);
    double aspect = 0;
    const sv::Camera c = sv::camera_at(a, 0, rest, sv::Mat4d(), &aspect);
    EXPECT_EQ(aspect, 1.5);
    EXPECT_NEAR(c.eye.x, 10, 1e-12);
    EXPECT_NEAR(c.eye.z, 5, 1e-12);
    EXPECT_NEAR(c.target.z, 4, 1e-12);
    EXPECT_NEAR(c.up.y, 1, 1e-12);
    EXPECT_NEAR(c.fov_y_degrees, 0.8 * 180 / kPi, 1e-12);
    EXPECT_EQ(c.near_distance, 0.1);

    EXPECT_THROW(sv::pose_at(a, 1, 0), sv::GltfError);
}

TEST_F(AnimFile, SkinnedSurfaceFollowsItsJoints) {
    const std::string path = write(Rig());
    const sv::AnimatedAsset a = sv::load_animated_gltf(path);
    ASSERT_EQ(a.surfaces.size(), 1u);
    const sv::AnimatedSurface &s = a.surfaces[0];
    EXPECT_EQ(s.name, "tetra @ body");
    EXPECT_EQ(s.skin, 0);
    EXPECT_EQ(s.influences, 4);
    EXPECT_FALSE(s.mirrored);
    ASSERT_EQ(s.num_vertices(), 4); // vertex 4 welded to vertex 0
    EXPECT_EQ(s.prepared.report.triangles, 4);
    EXPECT_EQ(s.prepared.report.manifold_edges, 6);
    EXPECT_EQ(s.prepared.report.boundary_edges, 0);

    // At rest, equal to load_gltf's bind pose (the skinned node's own
    // translation of 100 ignored); the root's (10, 0, 0) applies.
    const sv::GltfModel g = sv::load_gltf(path);
    ASSERT_EQ(g.surfaces.size(), 1u);
    for (int w = 0; w < 4; w++) {
        for (int c = 0; c < 3; c++) {
            EXPECT_EQ(s.prepared.positions[3 * w + c], g.surfaces[0].positions[3 * w + c]);
        }
    }

    // At t = 2: joint 2 (node 2) turned 90 degrees about z at (10, 2, 0)
    // (node 1 lifted by 1); joint 1 moved up by 1.
    const sv::Pose p = sv::pose_at(a, 0, 2.0);
    std::vector<float> out(12);
    sv::pose_surface(a, s, p, sv::Mat4d(), out.data());
    // vertex 0 (0,0,0): joint 1 only -> (10, 1, 0)
    EXPECT_NEAR(out[0], 10, 1e-6);
    EXPECT_NEAR(out[1], 1, 1e-6);
    // vertex 2 (0,1,0): joint 2, its bind origin -> (10, 2, 0)
    EXPECT_NEAR(out[6], 10, 1e-6);
    EXPECT_NEAR(out[7], 2, 1e-6);
    // vertex 3 (0,0,1): joint 2: local (0,-1,1) turned 90 degrees about z
    // -> (1, 0, 1), + (10, 2, 0)
    EXPECT_NEAR(out[9], 11, 1e-6);
    EXPECT_NEAR(out[10], 2, 1e-6);
    EXPECT_NEAR(out[11], 1, 1e-6);
    // vertex 1 (1,0,0): half joint 1 -> (11, 1, 0), half joint 2 -> local
    // (1,-1,0) turned -> (1, 1, 0) + (10, 2, 0) = (11, 3, 0); blend (11, 2, 0)
    EXPECT_NEAR(out[3], 11, 1e-6);
    EXPECT_NEAR(out[4], 2, 1e-6);

    // prepared_at: the surface at that pose, planes re-derived.
    const sv::PreparedSurface at = sv::prepared_at(s, out.data());
    for (int t = 0; t < at.num_triangles(); t++) {
        const int *ix = &at.indices[3 * t];
        const Plane want = sv::triangle_plane(&out[3 * ix[0]], &out[3 * ix[1]], &out[3 * ix[2]]);
        EXPECT_EQ(std::memcmp(&want, &at.planes[t], sizeof want), 0);
    }
}

TEST_F(AnimFile, SecondInfluenceSet) {
    Rig rig;
    rig.second_set = true;
    rig.weights[4 * 3] = 0.75f;
    const sv::AnimatedAsset a = sv::load_animated_gltf(write(rig));
    const sv::AnimatedSurface &s = a.surfaces[0];
    ASSERT_EQ(s.influences, 8);
    EXPECT_EQ(s.weights[8 * 3 + 0], 0.75f);
    EXPECT_EQ(s.weights[8 * 3 + 7], 0.25f);
    EXPECT_EQ(s.joints[8 * 3 + 7], 0);
    // At t = 2, vertex 3 = 0.75 (11, 2, 1) + 0.25 (10, 1, 1) (joint 1: +1 up)
    const sv::Pose p = sv::pose_at(a, 0, 2.0);
    std::vector<float> out(12);
    sv::pose_surface(a, s, p, sv::Mat4d(), out.data());
    EXPECT_NEAR(out[9], 0.75 * 11 + 0.25 * 10, 1e-6);
    EXPECT_NEAR(out[10], 0.75 * 2 + 0.25 * 1, 1e-6);
    EXPECT_NEAR(out[11], 1, 1e-6);
}

TEST_F(AnimFile, WeightsThatDoNotSumToOneAreNormalizedWithANote) {
    Rig rig;
    for (int k = 0; k < 4; k++) rig.weights[4 * 2 + k] = 0.25f * (k == 0 ? 2 : 0); // sum 0.5
    const sv::AnimatedAsset a = sv::load_animated_gltf(write(rig));
    EXPECT_EQ(a.surfaces[0].weights[4 * 2], 1.0f);
    bool noted = false;
    for (const std::string &n : a.notes) noted = noted || n.find("do not sum to 1") != n.npos;
    EXPECT_TRUE(noted);
}

TEST_F(AnimFile, RigidMirroredNodeAndTheFilesPose) {
    // A rigid tetrahedron under a mirroring scale, animated in translation:
    // winding flipped once, for every frame; the file's pose is load_gltf's.
    Doc d;
    const int pos = d.floats(kTetra, "VEC3", 3);
    const int idx = d.u16(kTetraIndices, "SCALAR", 1);
    d.meshes.push_back("{\"primitives\":[{\"attributes\":{\"POSITION\":" + std::to_string(pos) +
                       "},\"indices\":" + std::to_string(idx) + "}]}");
    d.node("\"children\":[1],\"rotation\":[0.1,0.2,0.3,0.9],\"translation\":[0.1,0.2,0.3]");
    d.node("\"mesh\":0,\"scale\":[-1,1,1]");
    const int tin = d.floats({0, 1}, "SCALAR", 1);
    const int tout = d.floats({0, 0, 0, 0, 0, 3}, "VEC3", 3);
    d.animations.push_back("{\"samplers\":[{\"input\":" + std::to_string(tin) +
                           ",\"output\":" + std::to_string(tout) +
                           "}],\"channels\":[{\"sampler\":0,\"target\":{\"node\":1,\"path\":"
                           "\"translation\"}}]}");
    const std::string path = write(d.json(), "mirror.gltf");
    const sv::AnimatedAsset a = sv::load_animated_gltf(path);
    ASSERT_EQ(a.surfaces.size(), 1u);
    const sv::AnimatedSurface &s = a.surfaces[0];
    EXPECT_TRUE(s.mirrored);
    EXPECT_EQ(s.flipped_triangles, 4u);
    EXPECT_EQ(a.animations[0].name, "animation#0");
    const sv::GltfModel g = sv::load_gltf(path);
    ASSERT_EQ(g.surfaces.size(), 1u);
    const sv::PreparedSurface gp = sv::prepare_surface(g.surfaces[0].positions.data(),
                                                       g.surfaces[0].num_vertices(),
                                                       g.surfaces[0].indices.data(),
                                                       g.surfaces[0].indices.size());
    ASSERT_EQ(gp.num_vertices(), s.prepared.num_vertices());
    EXPECT_EQ(gp.positions, s.prepared.positions); // bit for bit (pose -1, rigid)
    ASSERT_EQ(gp.indices.size(), s.prepared.indices.size());
    EXPECT_TRUE(std::equal(gp.indices.begin(), gp.indices.end(), s.prepared.indices.begin()));
    // The world matrices of pose -1 are load_gltf's: the mesh node's, bit
    // for bit, reproduced here by hand would be circular; instead the
    // positions above already are. At t = 1 the mesh moved by (0, 0, 3)
    // in its parent's frame.
    const sv::Pose p0 = sv::pose_at(a, 0, 0), p1 = sv::pose_at(a, 0, 1);
    const sv::Vec3d o0 = apply(p0.world[1], 0, 0, 0), o1 = apply(p1.world[1], 0, 0, 0);
    EXPECT_NEAR(std::sqrt((o1.x - o0.x) * (o1.x - o0.x) + (o1.y - o0.y) * (o1.y - o0.y) +
                          (o1.z - o0.z) * (o1.z - o0.z)),
                3.0, 1e-12);
}

TEST_F(AnimFile, MorphTargetsAndWeightChannelsAreReported) {
    Rig rig;
    rig.mesh_extra = ",\"targets\":[{\"POSITION\":0}]";
    rig.extra_animation =
        "{\"name\":\"smile\",\"samplers\":[{\"input\":5,\"output\":5}],\"channels\":[{"
        "\"sampler\":0,\"target\":{\"node\":3,\"path\":\"weights\"}}]}";
    const sv::AnimatedAsset a = sv::load_animated_gltf(write(rig));
    ASSERT_EQ(a.animations.size(), 2u);
    EXPECT_TRUE(a.animations[1].channels.empty());
    bool targets = false, weights = false;
    for (const std::string &n : a.notes) {
        targets = targets || n.find("morph target(s) ignored") != n.npos;
        weights = weights || (n.find("'smile'") != n.npos && n.find("not supported") != n.npos);
    }
    EXPECT_TRUE(targets);
    EXPECT_TRUE(weights);
    const sv::Pose p = sv::pose_at(a, 1, 0.5); // poses the base: the file's transforms
    const sv::Pose r = sv::pose_at(a, -1, 0);
    EXPECT_EQ(std::memcmp(p.world[2].m, r.world[2].m, sizeof r.world[2].m), 0);
}

TEST_F(AnimFile, FindAnimationByNameOrIndex) {
    Rig rig;
    rig.extra_animation =
        "{\"name\":\"1\",\"samplers\":[{\"input\":7,\"output\":8}],\"channels\":[{"
        "\"sampler\":0,\"target\":{\"node\":0,\"path\":\"translation\"}}]}";
    const sv::AnimatedAsset a = sv::load_animated_gltf(write(rig));
    EXPECT_EQ(sv::find_animation(a, "wave"), 0);
    EXPECT_EQ(sv::find_animation(a, "0"), 0);
    EXPECT_EQ(sv::find_animation(a, "1"), 1); // the name "1" (also index 1)
    try {
        sv::find_animation(a, "dance");
        ADD_FAILURE() << "found 'dance'";
    } catch (const sv::GltfError &e) {
        const std::string m = e.what();
        EXPECT_NE(m.find("no animation 'dance'"), m.npos) << m;
        EXPECT_NE(m.find("0 'wave', 1 '1'"), m.npos) << m;
    }
    EXPECT_THROW(sv::find_animation(a, "2"), sv::GltfError);
    EXPECT_THROW(sv::find_animation(a, "-1"), sv::GltfError);
    EXPECT_THROW(sv::find_animation(a, ""), sv::GltfError);
}

// ------------------------------------------------------------ bad input --

TEST_F(AnimFile, SamplerInputNotIncreasing) {
    Rig rig;
    rig.times = {0, 1, 1};
    expect_error(rig, {"animation 0 'wave' sampler 0 input", "key 2 time 1 is not after key 1",
                       "increase strictly"});
    rig.times = {0, 2, 1};
    expect_error(rig, {"key 2 time 1 is not after key 1 time 2"});
}

TEST_F(AnimFile, SamplerInputNotFinite) {
    Rig rig;
    rig.times = {0, std::numeric_limits<float>::quiet_NaN(), 2};
    expect_error(rig, {"sampler 0 input", "key 1 time is not finite"});
    rig.times = {0, 1, std::numeric_limits<float>::infinity()};
    expect_error(rig, {"key 2 time is not finite"});
}

TEST_F(AnimFile, SamplerOutputWrongLength) {
    Rig rig;
    rig.rotations.resize(8); // 2 keys for 3 times
    expect_error(rig, {"sampler 0 output", "has 2 elements, expected 3 (3 keys)"});
    Rig cubic;
    cubic.rotation_interp = "CUBICSPLINE"; // needs 9
    expect_error(cubic, {"has 3 elements, expected 9", "in-tangent, value, out-tangent"});
}

TEST_F(AnimFile, SamplerOutputWrongType) {
    Rig rig;
    rig.rotation_type = "VEC3";
    rig.rotation_components = 3;
    rig.rotations.resize(9);
    expect_error(rig, {"sampler 0 output", "is FLOAT VEC3, expected FLOAT VEC4", "rotation"});
    Rig scale;
    scale.channel_path = "scale"; // a VEC4 output for a scale
    expect_error(scale, {"is FLOAT VEC4, expected FLOAT VEC3 for translation or scale"});
}

TEST_F(AnimFile, SamplerOutputNotFinite) {
    Rig rig;
    rig.rotations[5] = std::numeric_limits<float>::infinity();
    expect_error(rig, {"sampler 0 output", "key 1 is not finite"});
}

TEST_F(AnimFile, ZeroQuaternions) {
    Rig rig;
    for (int c = 0; c < 4; c++) rig.rotations[4 + c] = 0;
    expect_error(rig, {"sampler 0 output", "key 1 rotation quaternion is zero"});
    Rig node;
    node.node2_extra = ",\"rotation\":[0,0,0,0]";
    expect_error(node, {"node 2 'arm'", "rotation quaternion is zero"});
    // A CUBICSPLINE key's tangents may be zero; its value may not.
    Rig cubic;
    cubic.rotation_interp = "CUBICSPLINE";
    cubic.rotations.clear();
    for (int k = 0; k < 3; k++) {
        const std::vector<float> q = quat_z(45.0 * k);
        const std::vector<float> key = {0, 0, 0, 0, q[0], q[1], q[2], q[3], 0, 0, 0, 0};
        cubic.rotations.insert(cubic.rotations.end(), key.begin(), key.end());
    }
    EXPECT_NO_THROW(sv::load_animated_gltf(write(cubic)));
    for (int c = 4; c < 8; c++) cubic.rotations[12 * 2 + c] = 0;
    expect_error(cubic, {"key 2 rotation quaternion is zero"});
}

TEST_F(AnimFile, UnknownInterpolation) {
    Rig rig;
    rig.rotation_interp = "QUADRATIC";
    expect_error(rig,
                 {"sampler 0", "interpolation 'QUADRATIC' is not LINEAR, STEP or CUBICSPLINE"});
}

TEST_F(AnimFile, JointIndexBeyondTheSkin) {
    Rig rig;
    rig.joints[4 * 2 + 1] = 5; // weight 0 there, still out of range
    expect_error(rig, {"vertex 2", "joint index 5 is out of range", "2 joints"});
}

TEST_F(AnimFile, ChannelTargets) {
    Rig missing;
    missing.channel_target = "\"node\":99";
    expect_error(missing, {"animation 0 'wave' channel 0", "node 99 does not exist (7 nodes)"});
    // No node at all: glTF lets an extension name the target; tinygltf
    // drops such a channel, and its words become a note.
    Rig absent;
    absent.channel_target = "\"extras\":{}";
    const sv::AnimatedAsset a = sv::load_animated_gltf(write(absent));
    ASSERT_EQ(a.animations.size(), 1u);
    ASSERT_EQ(a.animations[0].channels.size(), 1u);
    EXPECT_EQ(a.animations[0].channels[0].node, 1);
    bool noted = false;
    for (const std::string &n : a.notes)
        noted = noted || n.find("`node` field is missing") != n.npos;
    EXPECT_TRUE(noted);
    Rig path;
    path.channel_path = "colour";
    expect_error(path, {"channel 0", "target path 'colour' is not translation"});
    Rig matrix;
    matrix.channel_target = "\"node\":2";
    matrix.node2_extra = ",\"matrix\":[1,0,0,0,0,1,0,0,0,0,1,0,0,0,0,1]";
    // (node 2 then has both translation and matrix; glTF forbids animating it)
    expect_error(matrix, {"channel 0", "targets node 2 'arm', which has a matrix"});
    Rig twice;
    twice.channel_target = "\"node\":1";
    twice.channel_path = "translation"; // node 1 translation is channel 1's too
    expect_error(twice, {"channel 1", "node 1 'hip' translation is animated twice"});
}

TEST_F(AnimFile, BadLights) {
    Rig range;
    range.light_point = "{\"type\":\"point\",\"range\":-1}";
    expect_error(range, {"KHR_lights_punctual light 0", "range -1 is negative"});
    Rig cone;
    cone.light_spot =
        "{\"type\":\"spot\",\"spot\":{\"innerConeAngle\":0.6,\"outerConeAngle\":0.5}}";
    expect_error(cone, {"light 1", "outerConeAngle 0.5 is smaller than innerConeAngle 0.6"});
    Rig wide;
    wide.light_spot = "{\"type\":\"spot\",\"spot\":{\"outerConeAngle\":1.6}}";
    expect_error(wide, {"light 1", "outerConeAngle 1.6 is outside (0, pi/2]"});
    Rig zero;
    zero.light_spot = "{\"type\":\"spot\",\"spot\":{\"innerConeAngle\":0,\"outerConeAngle\":0}}";
    expect_error(zero, {"outerConeAngle 0 is outside (0, pi/2]"});
    Rig negative;
    negative.light_spot = "{\"type\":\"spot\",\"spot\":{\"innerConeAngle\":-0.1}}";
    expect_error(negative, {"innerConeAngle -0.1 is negative"});
    Rig type;
    type.light_point = "{\"type\":\"area\"}";
    expect_error(type, {"light 0", "type 'area' is not point, spot or directional"});
    // JSON cannot carry an infinity: a number that overflows is refused
    // by the parser, with the file's name.
    Rig inf;
    inf.light_point = "{\"type\":\"point\",\"intensity\":1e999}";
    expect_error(inf, {"number overflow parsing '1e999'"});
    Rig dim;
    dim.light_point = "{\"type\":\"point\",\"intensity\":-2}";
    expect_error(dim, {"light 0", "intensity -2 must be finite and >= 0"});
    Rig colour;
    colour.light_point = "{\"type\":\"point\",\"color\":[1,1]}";
    expect_error(colour, {"light 0", "color must be 3 finite numbers"});
    // A node naming a light that is not there.
    Rig ref;
    ref.node2_extra = ",\"extensions\":{\"KHR_lights_punctual\":{\"light\":7}}";
    expect_error(ref, {"node 2 'arm'", "light 7 does not exist (3 lights)"});
}

TEST_F(AnimFile, BadCameras) {
    Rig yfov;
    yfov.camera = "{\"type\":\"perspective\",\"perspective\":{\"yfov\":0,\"znear\":0.1}}";
    expect_error(yfov, {"camera 0", "yfov 0 is not in (0, pi)"});
    Rig neg;
    neg.camera = "{\"type\":\"perspective\",\"perspective\":{\"yfov\":-1,\"znear\":0.1}}";
    expect_error(neg, {"yfov -1 is not in (0, pi)"});
    Rig znear;
    znear.camera = "{\"type\":\"perspective\",\"perspective\":{\"yfov\":1,\"znear\":0}}";
    expect_error(znear, {"camera 0", "znear 0 must be finite and > 0"});
    Rig zfar;
    zfar.camera = "{\"type\":\"perspective\",\"perspective\":{\"yfov\":1,\"znear\":2,\"zfar\":1}}";
    expect_error(zfar, {"zfar 1 must be > znear 2"});
    Rig inf;
    inf.camera = "{\"type\":\"perspective\",\"perspective\":{\"yfov\":1,\"znear\":1e999}}";
    expect_error(inf, {"number overflow parsing '1e999'"});
    Rig aspect;
    aspect.camera =
        "{\"type\":\"perspective\",\"perspective\":{\"yfov\":1,\"znear\":1,\"aspectRatio\":-1}}";
    expect_error(aspect, {"camera 0", "aspectRatio -1 must be finite and > 0"});
    Rig wide;
    wide.camera = "{\"type\":\"perspective\",\"perspective\":{\"yfov\":3.2,\"znear\":1}}";
    expect_error(wide, {"yfov 3.2 is not in (0, pi)"});
    Rig ortho;
    ortho.camera = "{\"type\":\"orthographic\",\"orthographic\":{\"xmag\":1,\"ymag\":1,"
                   "\"znear\":0.1,\"zfar\":10}}";
    const sv::AnimatedAsset a = sv::load_animated_gltf(write(ortho));
    EXPECT_TRUE(a.cameras.empty());
    bool noted = false;
    for (const std::string &n : a.notes) noted = noted || n.find("orthographic") != n.npos;
    EXPECT_TRUE(noted);
}

TEST_F(AnimFile, GarbageNeverCrashes) {
    // Truncations of a valid file: each loads or fails with a GltfError.
    const std::string json = Rig().doc().json();
    for (std::size_t len = 0; len < json.size(); len += 37) {
        const std::string path = write(json.substr(0, len), "cut.gltf");
        try {
            sv::load_animated_gltf(path);
        } catch (const sv::GltfError &) {
        }
    }
}

// ================================================================ skinning

std::vector<const sv::SkinningKernel *> runnable_kernels() {
    int n;
    const sv::SkinningKernel *k = sv::skinning_kernels(&n);
    std::vector<const sv::SkinningKernel *> out;
    for (int i = 0; i < n; i++) {
        if (svtest::in_this_run(k[i].isa, k[i].name)) out.push_back(&k[i]);
    }
    return out;
}

TEST(AnimSkinning, TableAndDispatch) {
    int n = 0;
    const sv::SkinningKernel *k = sv::skinning_kernels(&n);
    ASSERT_GE(n, 4);
    EXPECT_STREQ(k[0].name, "c_ref");
    EXPECT_EQ(k[0].isa, 0u);
    EXPECT_EQ(sv::skinning_kernel_by_name("avx2"), &k[2]);
    EXPECT_EQ(sv::skinning_kernel_by_name("nope"), nullptr);
    const sv::SkinningKernel *best = sv::best_skinning_kernel();
    EXPECT_EQ(best->isa & sv_cpu_isa(), best->isa);
    std::printf("[ dispatch ] best skinning kernel: %s (ISA level %s)\n", best->name,
                sv_isa_level_name());
}

SV_TIERED_TEST(AnimSkinning, KernelsMatchTheReferenceBitForBit) {
    svtest::Rng rng(svtest::seed() ^ 0x5c1);
    const std::vector<const sv::SkinningKernel *> kernels = runnable_kernels();
    const int joints = 37;
    std::vector<float> m(16 * joints);
    for (float &v : m) v = float(rng.unit() * 4 - 2);
    for (int j = 0; j < joints; j++) { // wide scales in the translations
        for (int r = 0; r < 3; r++) m[16 * j + 12 + r] = float((rng.unit() - 0.5) * 2000);
    }
    for (int influences = 1; influences <= 8; influences++) {
        for (std::size_t count : {0, 1, 2, 3, 5, 8, 17, 64, 257}) {
            std::vector<float> rest(3 * count);
            for (float &v : rest) v = float((rng.unit() - 0.5) * 10);
            std::vector<uint16_t> jt(count * influences);
            std::vector<float> wt(count * influences);
            for (std::size_t v = 0; v < count; v++) {
                double sum = 0;
                for (int k = 0; k < influences; k++) {
                    jt[v * influences + k] = uint16_t(rng.below(joints));
                    // some exact zeros, as files have them
                    wt[v * influences + k] = rng.chance(0.3) ? 0.0f : float(rng.unit());
                    sum += wt[v * influences + k];
                }
                if (sum == 0) wt[v * influences] = 1;
            }
            std::vector<float> want(3 * count + 4, 12345.0f);
            sv::skinning_kernels(nullptr)[0].fn(m.data(), rest.data(), jt.data(), wt.data(),
                                                influences, count, want.data());
            for (const sv::SkinningKernel *k : kernels) {
                std::vector<float> got(3 * count + 4, 12345.0f); // 4 guard floats after
                k->fn(m.data(), rest.data(), jt.data(), wt.data(), influences, count, got.data());
                EXPECT_EQ(std::memcmp(got.data(), want.data(), 4 * got.size()), 0)
                    << k->name << " influences " << influences << " count " << count << " "
                    << svtest::seed_trace();
                for (int g = 0; g < 4; g++) EXPECT_EQ(got[3 * count + g], 12345.0f) << k->name;
            }
        }
    }
}

// =============================================================== characters

struct Character {
    const char *file;
};
const Character kCharacters[] = {{"Fox.glb"},
                                 {"CesiumMan.glb"},
                                 {"RobotExpressive.glb"},
                                 {"RiggedFigure.glb"}};

double extent(const std::vector<float> &p) {
    float lo[3] = {1e30f, 1e30f, 1e30f}, hi[3] = {-1e30f, -1e30f, -1e30f};
    for (std::size_t i = 0; i < p.size(); i++) {
        lo[i % 3] = std::min(lo[i % 3], p[i]);
        hi[i % 3] = std::max(hi[i % 3], p[i]);
    }
    return std::max({double(hi[0]) - lo[0], double(hi[1]) - lo[1], double(hi[2]) - lo[2]});
}

SV_TIERED_TEST(AnimSharedModels, LoadPoseAndPlay) {
    const std::vector<const sv::SkinningKernel *> kernels = runnable_kernels();
    std::string missing;
    for (const Character &c : kCharacters) {
        const std::string path = svtest::shared_models_dir() + "/" + c.file;
        if (!fs::exists(path)) {
            missing += " " + path;
            continue;
        }
        SCOPED_TRACE(path);
        const sv::AnimatedAsset a = sv::load_animated_gltf(path);
        ASSERT_FALSE(a.animations.empty());
        ASSERT_FALSE(a.surfaces.empty());
        std::printf("[ anim     ] %-20s %zu nodes, %zu skins, %zu surfaces, %zu animations:",
                    c.file, a.nodes.size(), a.skins.size(), a.surfaces.size(), a.animations.size());
        for (const sv::Animation &an : a.animations) {
            std::printf(" %s (%.2f s)", an.name.c_str(), an.end - an.start);
        }
        std::printf("\n");

        // Topology and the file's pose against load_gltf + prepare_surface.
        const sv::GltfModel g = sv::load_gltf(path);
        ASSERT_EQ(g.surfaces.size(), a.surfaces.size());
        for (std::size_t i = 0; i < a.surfaces.size(); i++) {
            const sv::AnimatedSurface &s = a.surfaces[i];
            const sv::GltfSurface &gs = g.surfaces[i];
            EXPECT_EQ(s.name, gs.name);
            EXPECT_EQ(s.mirrored, gs.mirrored);
            EXPECT_EQ(s.flipped_triangles, gs.flipped_triangles);
            const sv::PreparedSurface gp = sv::prepare_surface(gs.positions.data(),
                                                               gs.num_vertices(), gs.indices.data(),
                                                               gs.indices.size());
            const sv::PrepareReport &x = s.prepared.report, &y = gp.report;
            EXPECT_EQ(x.triangles, y.triangles) << s.name;
            EXPECT_EQ(x.sil_edges, y.sil_edges) << s.name;
            EXPECT_EQ(x.dangling_sil_edges, y.dangling_sil_edges) << s.name;
            EXPECT_EQ(x.welded_vertices, y.welded_vertices) << s.name;
            EXPECT_EQ(x.boundary_edges, y.boundary_edges) << s.name;
            EXPECT_EQ(x.manifold_edges, y.manifold_edges) << s.name;
            std::printf("[ anim     ]   %-28s %6d triangles %6d SilEdges (%d dangling), "
                        "%d influences%s\n",
                        s.name.c_str(), s.prepared.num_triangles(), s.prepared.num_sil_edges(),
                        int(x.dangling_sil_edges), s.influences, s.mirrored ? ", mirrored" : "");
            // The rest pose: rigid bit for bit; skinned (float blend against
            // the loader's double blend) within 1e-5 of the size.
            if (s.num_vertices() == gp.num_vertices()) {
                const double tol = s.skin >= 0 ? 1e-5 * extent(gp.positions) : 0.0;
                double worst = 0;
                for (std::size_t e = 0; e < gp.positions.size(); e++) {
                    worst = std::max(worst,
                                     std::fabs(double(gp.positions[e]) - s.prepared.positions[e]));
                }
                EXPECT_LE(worst, tol) << s.name;
            }
        }

        // Every animation, by name and by index, at several times.
        for (std::size_t ai = 0; ai < a.animations.size(); ai++) {
            const sv::Animation &an = a.animations[ai];
            EXPECT_EQ(a.animations[sv::find_animation(a, an.name)].name, an.name);
            EXPECT_EQ(sv::find_animation(a, std::to_string(ai)), int(ai));
            std::vector<std::vector<float>> first_pose;
            bool moved = false;
            for (double f : {0.0, 0.37, 0.5, 1.0}) {
                const double t = an.start + f * (an.end - an.start);
                const sv::Pose p = sv::pose_at(a, int(ai), t);
                for (std::size_t i = 0; i < a.surfaces.size(); i++) {
                    const sv::AnimatedSurface &s = a.surfaces[i];
                    std::vector<float> want(s.rest_positions.size());
                    sv::pose_surface(a, s, p, sv::Mat4d(), want.data(),
                                     sv::skinning_kernel_by_name("c_ref"));
                    const double size = extent(a.surfaces[i].prepared.positions);
                    for (float v : want) {
                        ASSERT_TRUE(std::isfinite(v)) << s.name << " " << an.name << " t " << t;
                        ASSERT_LE(std::fabs(v), 100 * size + 1e3) << s.name;
                    }
                    for (const sv::SkinningKernel *k : kernels) {
                        std::vector<float> got(want.size());
                        sv::pose_surface(a, s, p, sv::Mat4d(), got.data(), k);
                        EXPECT_EQ(std::memcmp(got.data(), want.data(), 4 * got.size()), 0)
                            << k->name << " " << s.name << " " << an.name << " t " << t;
                    }
                    if (f == 0.0) {
                        first_pose.push_back(want);
                    } else if (want != first_pose[i]) {
                        moved = true;
                    }
                }
            }
            EXPECT_TRUE(moved) << an.name << " moves no vertex";
        }
    }
    if (!missing.empty()) GTEST_SKIP() << "not found, not tested:" << missing;
}

// rdtsc with lfence on both sides (DESIGN.md section 5; src/measure/timer.h).
inline uint64_t ticks() {
    uint32_t lo, hi;
    __asm__ __volatile__("lfence\n\trdtsc\n\tlfence" : "=a"(lo), "=d"(hi) : : "memory");
    return uint64_t(hi) << 32 | lo;
}

SV_TIERED_TEST(AnimSharedModels, SkinningTicksPerVertex) {
    const std::vector<const sv::SkinningKernel *> kernels = runnable_kernels();
    std::printf("[ ticks    ] skinning, rdtsc ticks per vertex (minimum / median of 201 "
                "runs, warm cache, joint matrices computed outside the timed region)\n");
    for (const Character &c : kCharacters) {
        const std::string path = svtest::shared_models_dir() + "/" + c.file;
        if (!fs::exists(path)) continue; // LoadPoseAndPlay names it and skips
        const sv::AnimatedAsset a = sv::load_animated_gltf(path);
        const sv::Pose p = sv::pose_at(a, 0, 0.5 * (a.animations[0].start + a.animations[0].end));
        for (const sv::AnimatedSurface &s : a.surfaces) {
            if (s.skin < 0) continue;
            sv::AlignedVector<float> jm(16 * a.skins[s.skin].joints.size());
            sv::joint_matrices(a, s.skin, p, sv::Mat4d(), jm.data());
            std::vector<float> out(s.rest_positions.size());
            std::printf("[ ticks    ] %-20s %-24s %6d vertices %d influences:", c.file,
                        s.name.c_str(), s.num_vertices(), s.influences);
            for (const sv::SkinningKernel *k : kernels) {
                std::vector<uint64_t> runs;
                for (int r = 0; r < 201; r++) {
                    const uint64_t t0 = ticks();
                    k->fn(jm.data(), s.rest_positions.data(), s.joints.data(), s.weights.data(),
                          s.influences, std::size_t(s.num_vertices()), out.data());
                    const uint64_t t1 = ticks();
                    runs.push_back(t1 - t0);
                }
                std::sort(runs.begin(), runs.end());
                std::printf("  %s %.2f / %.2f", k->name, double(runs[0]) / s.num_vertices(),
                            double(runs[runs.size() / 2]) / s.num_vertices());
            }
            std::printf("\n");
        }
    }
}

} // namespace
