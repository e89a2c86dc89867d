// The demo scene (src/modelgen/scene_gen.cpp, written at build time
// to build/models/demo_scene.glb by target shadowvol_demo_scene): the file
// is what the generator writes (deterministic: twice the same bytes), loads
// with the project's loader, has a terrain of more than 100k triangles and
// a closed, skinned character; its JSON (read here with nlohmann::json, not
// the generator's code) has the three kinds of light, the camera and the
// walk, with valid accessors by glTF's rules: sampler inputs strictly
// increasing, quaternion outputs of unit length, output counts matching
// the interpolation, joint indices below the skin's joint count, weights
// summing to 1.
//
// Copyright (C) 2026 the shadowvol authors. LGPL-2.1-or-later.
#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <fstream>
#include <iterator>
#include <map>
#include <set>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "model_gen.h"
#include "shadowvol_gltf.h"
#include "shadowvol_mesh.h"

#ifndef SV_DEMO_SCENE_GLB
#error "SV_DEMO_SCENE_GLB must name build/models/demo_scene.glb"
#endif

namespace {

using nlohmann::json;

std::vector<std::uint8_t> read_file(const std::string &path) {
    std::ifstream f(path, std::ios::binary);
    return std::vector<std::uint8_t>(std::istreambuf_iterator<char>(f), {});
}

uint32_t u32(const std::vector<std::uint8_t> &b, size_t at) {
    uint32_t v;
    std::memcpy(&v, &b[at], 4);
    return v;
}

struct Glb {
    json doc;
    std::vector<std::uint8_t> bin;
};

Glb parse(const std::vector<std::uint8_t> &file) {
    Glb g;
    EXPECT_GE(file.size(), 28u);
    EXPECT_EQ(u32(file, 0), 0x46546C67u);
    EXPECT_EQ(u32(file, 4), 2u);
    EXPECT_EQ(u32(file, 8), file.size());
    const uint32_t jlen = u32(file, 12);
    EXPECT_EQ(u32(file, 16), 0x4E4F534Au);
    g.doc = json::parse(std::string(file.begin() + 20, file.begin() + 20 + jlen));
    const size_t b = 20 + jlen;
    const uint32_t blen = u32(file, b);
    EXPECT_EQ(u32(file, b + 4), 0x004E4942u);
    g.bin.assign(file.begin() + (long)b + 8, file.begin() + (long)b + 8 + blen);
    return g;
}

// Accessor A as doubles (float, u8, u16, u32 components), checked against
// its bufferView and the buffer.
std::vector<double> values(const Glb &g, int a, size_t *components = nullptr) {
    const json &acc = g.doc["accessors"][a];
    static const std::map<std::string, size_t> comps = {
        {"SCALAR", 1}, {"VEC2", 2}, {"VEC3", 3}, {"VEC4", 4}, {"MAT4", 16}};
    const size_t nc = comps.at(acc["type"].get<std::string>());
    if (components) *components = nc;
    const int ct = acc["componentType"];
    const size_t cs = ct == 5126 || ct == 5125 ? 4 : ct == 5123 ? 2 : 1;
    const json &bv = g.doc["bufferViews"][acc["bufferView"].get<int>()];
    const size_t off = bv["byteOffset"].get<size_t>() + acc.value("byteOffset", (size_t)0);
    const size_t count = acc["count"];
    EXPECT_LE(count * nc * cs, bv["byteLength"].get<size_t>()) << "accessor " << a;
    EXPECT_LE(off + count * nc * cs, g.bin.size()) << "accessor " << a;
    EXPECT_EQ(off % cs, 0u) << "accessor " << a << " misaligned";
    std::vector<double> out;
    for (size_t i = 0; i < count * nc; i++) {
        const uint8_t *p = &g.bin[off + i * cs];
        if (ct == 5126) {
            float f;
            std::memcpy(&f, p, 4);
            out.push_back(f);
        } else if (ct == 5125) {
            uint32_t v;
            std::memcpy(&v, p, 4);
            out.push_back(v);
        } else if (ct == 5123) {
            uint16_t v;
            std::memcpy(&v, p, 2);
            out.push_back(v);
        } else {
            out.push_back(*p);
        }
    }
    return out;
}

const std::vector<std::uint8_t> &scene_file() {
    static const std::vector<std::uint8_t> f = read_file(SV_DEMO_SCENE_GLB);
    return f;
}

TEST(DemoScene, FileIsWhatTheGeneratorWrites) {
    ASSERT_FALSE(scene_file().empty())
        << SV_DEMO_SCENE_GLB << " is missing: build shadowvol_demo_scene";
    const std::vector<std::uint8_t> a = svgen::write_demo_scene_glb();
    const std::vector<std::uint8_t> b = svgen::write_demo_scene_glb();
    EXPECT_TRUE(a == b) << "the generator is not deterministic";
    EXPECT_TRUE(a == scene_file()) << SV_DEMO_SCENE_GLB << " differs from the generator's output";
}

TEST(DemoScene, LoadsTerrainAndClosedSkinnedCharacter) {
    const sv::GltfModel m = sv::load_gltf(SV_DEMO_SCENE_GLB);
    std::map<std::string, const sv::GltfSurface *> by;
    for (const auto &s : m.surfaces) by[s.name] = &s;
    ASSERT_TRUE(by.count("terrain @ terrain"));
    ASSERT_TRUE(by.count("character @ character"));
    EXPECT_GT(by["terrain @ terrain"]->num_triangles(), 100000u);
    EXPECT_EQ(by["terrain @ terrain"]->num_triangles(),
              (size_t)svgen::demo_scene_info().terrain_triangles);
    const sv::GltfSurface &c = *by["character @ character"];
    EXPECT_TRUE(c.skinned);
    EXPECT_FALSE(c.mirrored);
    EXPECT_EQ(c.num_triangles(), 1344u);
    const sv::PreparedSurface p = sv::prepare_surface(c.positions.data(), c.num_vertices(),
                                                      c.indices.data(), c.indices.size());
    const sv::PrepareReport &r = p.report;
    EXPECT_EQ(r.boundary_edges, 0u);
    EXPECT_EQ(p.num_triangles(), 1344);
    // Bind pose: the character stands at its root (0, 0, -2), soles near 0.
    float lo[3] = {1e9f, 1e9f, 1e9f}, hi[3] = {-1e9f, -1e9f, -1e9f};
    for (size_t v = 0; v < c.num_vertices(); v++)
        for (int k = 0; k < 3; k++) {
            lo[k] = std::min(lo[k], c.positions[3 * v + k]);
            hi[k] = std::max(hi[k], c.positions[3 * v + k]);
        }
    EXPECT_NEAR(lo[1], 0.0, 0.02);
    EXPECT_NEAR(hi[1], 1.865, 0.02);
    EXPECT_NEAR(0.5 * (lo[2] + hi[2]), -2.0, 0.1);
    // The terrain, open, is declared ground in its mesh's extras
    // (docs/CASTERS.md, "The ground hint"); nothing else is.
    for (const auto &s : m.surfaces)
        EXPECT_EQ(s.declared_ground, s.name == "terrain @ terrain") << s.name;
    for (const auto &s : m.surfaces) {
        if (s.name.rfind("pillar", 0) == 0 || s.name.rfind("wall", 0) == 0 ||
            s.name.rfind("ground", 0) == 0) {
            const sv::PreparedSurface q = sv::prepare_surface(s.positions.data(), s.num_vertices(),
                                                              s.indices.data(), s.indices.size());
            EXPECT_EQ(q.report.boundary_edges, 0u) << s.name;
        }
    }
}

TEST(DemoScene, LightsCameraAnimationValid) {
    const Glb g = parse(scene_file());
    const json &d = g.doc;
    EXPECT_EQ(d["asset"]["version"], "2.0");
    ASSERT_TRUE(d.contains("extensionsUsed"));
    EXPECT_NE(std::find(d["extensionsUsed"].begin(), d["extensionsUsed"].end(),
                        "KHR_lights_punctual"),
              d["extensionsUsed"].end());
    const json &lights = d["extensions"]["KHR_lights_punctual"]["lights"];
    std::map<std::string, int> kinds;
    for (const json &l : lights) {
        kinds[l["type"]]++;
        if (l["type"] == "point") {
            EXPECT_GT(l["range"].get<double>(), 0);
        }
        if (l["type"] == "spot") {
            const double in = l["spot"]["innerConeAngle"], out = l["spot"]["outerConeAngle"];
            EXPECT_GE(in, 0);
            EXPECT_LT(in, out);
            EXPECT_LE(out, M_PI / 2);
        }
        if (l["type"] == "directional") {
            EXPECT_FALSE(l.contains("range"));
        }
    }
    EXPECT_EQ(kinds["point"], 1);
    EXPECT_EQ(kinds["spot"], 2);
    EXPECT_EQ(kinds["directional"], 1);
    // Every light is on a node; node rotations are unit quaternions.
    std::set<int> lit;
    int cameraNodes = 0;
    for (const json &n : d["nodes"]) {
        if (n.contains("extensions"))
            lit.insert(n["extensions"]["KHR_lights_punctual"]["light"].get<int>());
        if (n.contains("camera")) {
            cameraNodes++;
            EXPECT_EQ(n["camera"], 0);
        }
        if (n.contains("rotation")) {
            double s = 0;
            for (const json &c : n["rotation"]) s += c.get<double>() * c.get<double>();
            EXPECT_NEAR(s, 1.0, 1e-6) << n["name"];
        }
    }
    EXPECT_EQ(lit.size(), lights.size());
    EXPECT_EQ(cameraNodes, 1);
    ASSERT_EQ(d["cameras"].size(), 1u);
    EXPECT_EQ(d["cameras"][0]["type"], "perspective");
    EXPECT_GT(d["cameras"][0]["perspective"]["yfov"].get<double>(), 0);

    // The skin: joints are nodes; JOINTS_0 below the joint count; weights sum to 1.
    ASSERT_EQ(d["skins"].size(), 1u);
    const json &skin = d["skins"][0];
    const size_t nj = skin["joints"].size();
    EXPECT_EQ(nj, (size_t)svgen::demo_scene_info().joints);
    EXPECT_EQ(values(g, skin["inverseBindMatrices"]).size(), 16 * nj);
    int skinnedPrims = 0;
    for (const json &mesh : d["meshes"]) {
        for (const json &prim : mesh["primitives"]) {
            if (!prim["attributes"].contains("JOINTS_0")) continue;
            skinnedPrims++;
            const std::vector<double> j = values(g, prim["attributes"]["JOINTS_0"]);
            const std::vector<double> w = values(g, prim["attributes"]["WEIGHTS_0"]);
            ASSERT_EQ(j.size(), w.size());
            for (double x : j) ASSERT_LT(x, (double)nj);
            for (size_t v = 0; v < w.size(); v += 4) {
                const float s = (float)w[v] + (float)w[v + 1] + (float)w[v + 2] + (float)w[v + 3];
                ASSERT_EQ(s, 1.0f) << "vertex " << v / 4;
                for (int k = 0; k < 4; k++) ASSERT_GE(w[v + k], 0.0);
            }
        }
    }
    EXPECT_EQ(skinnedPrims, 1);

    // The walk: ~1 s, every interpolation, valid samplers.
    ASSERT_EQ(d["animations"].size(), 1u);
    const json &walk = d["animations"][0];
    EXPECT_EQ(walk["name"], "walk");
    std::set<std::string> interps, paths;
    double duration = 0;
    for (const json &ch : walk["channels"]) {
        const json &s = walk["samplers"][ch["sampler"].get<int>()];
        const std::string interp = s.value("interpolation", "LINEAR");
        const std::string path = ch["target"]["path"];
        interps.insert(interp);
        paths.insert(path);
        EXPECT_LT(ch["target"]["node"].get<size_t>(), d["nodes"].size());
        const std::vector<double> in = values(g, s["input"]);
        ASSERT_FALSE(in.empty());
        for (size_t i = 1; i < in.size(); i++)
            ASSERT_LT(in[i - 1], in[i]) << "input not increasing";
        const json &inAcc = d["accessors"][s["input"].get<int>()];
        ASSERT_TRUE(inAcc.contains("min") && inAcc.contains("max"));
        EXPECT_EQ(inAcc["min"][0].get<double>(), in.front());
        EXPECT_EQ(inAcc["max"][0].get<double>(), in.back());
        duration = std::max(duration, in.back());
        size_t nc = 0;
        const std::vector<double> out = values(g, s["output"], &nc);
        const size_t per = interp == "CUBICSPLINE" ? 3 : 1;
        EXPECT_EQ(out.size(), in.size() * per * nc) << path;
        EXPECT_EQ(nc, path == "rotation" ? 4u : 3u);
        if (path == "rotation") {
            for (size_t k = 0; k < out.size(); k += 4) {
                const double l = out[k] * out[k] + out[k + 1] * out[k + 1] +
                                 out[k + 2] * out[k + 2] + out[k + 3] * out[k + 3];
                EXPECT_NEAR(std::sqrt(l), 1.0, 1e-6);
            }
        }
    }
    EXPECT_EQ(interps, (std::set<std::string>{"LINEAR", "STEP", "CUBICSPLINE"}));
    EXPECT_TRUE(paths.count("rotation") && paths.count("translation"));
    EXPECT_NEAR(duration, 1.0, 1e-6);
}

} // namespace
