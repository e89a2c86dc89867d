/*
 * The fuzz targets' seed corpus, generated (issue 17: no third-party file is
 * committed). Writes into DIR/glb and DIR/gltf small documents that reach
 * every part of the loader: indexed and plain triangles, strips and fans,
 * u8/u16/u32 indices, a node hierarchy with a mirror, TRS and matrix nodes,
 * a skin with two joints, a sparse accessor, two primitives in one mesh,
 * and the project's own character (models/character_1344.glb) in both
 * containers. tools/run.sh fuzz adds ../shared/models and Debian's
 * assimp-testmodels at run time when they are there.
 *
 * usage: sv_fuzz_corpus DIR [models/character_1344.glb]
 *
 * Copyright (C) 2026 the shadowvol authors. LGPL-2.1-or-later.
 */
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <utility>
#include <string>
#include <vector>

namespace fs = std::filesystem;

namespace {

std::string base64(const std::string &in) {
    static const char t[] = "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
    std::string out;
    size_t i = 0;
    for (; i + 2 < in.size(); i += 3) {
        const uint32_t v = uint32_t(uint8_t(in[i])) << 16 | uint32_t(uint8_t(in[i + 1])) << 8 |
                           uint8_t(in[i + 2]);
        for (int s = 18; s >= 0; s -= 6) out += t[(v >> s) & 63];
    }
    const size_t rest = in.size() - i;
    if (rest) {
        uint32_t v = uint32_t(uint8_t(in[i])) << 16;
        if (rest == 2) v |= uint32_t(uint8_t(in[i + 1])) << 8;
        out += t[v >> 18];
        out += t[(v >> 12) & 63];
        out += rest == 2 ? t[(v >> 6) & 63] : '=';
        out += '=';
    }
    return out;
}

/* A document: binary data, bufferViews and accessors over it, and the
 * JSON members the caller writes. */
struct Doc {
    std::string bin;
    std::vector<std::string> views, accessors;
    template <class T>
    int data(const std::vector<T> &v, int component, const char *type, size_t count,
             const std::string &extra = "") {
        while (bin.size() % 4) bin += '\0';
        const size_t off = bin.size();
        bin.append(reinterpret_cast<const char *>(v.data()), v.size() * sizeof(T));
        views.push_back("{\"buffer\":0,\"byteOffset\":" + std::to_string(off) +
                        ",\"byteLength\":" + std::to_string(v.size() * sizeof(T)) + "}");
        accessors.push_back("{\"bufferView\":" + std::to_string(views.size() - 1) +
                            ",\"componentType\":" + std::to_string(component) + ",\"count\":" +
                            std::to_string(count) + ",\"type\":\"" + type + "\"" + extra + "}");
        return int(accessors.size()) - 1;
    }
    int vec3(const std::vector<float> &p) {
        float lo[3] = {1e30f, 1e30f, 1e30f}, hi[3] = {-1e30f, -1e30f, -1e30f};
        for (size_t i = 0; i < p.size(); i++) {
            lo[i % 3] = std::min(lo[i % 3], p[i]);
            hi[i % 3] = std::max(hi[i % 3], p[i]);
        }
        char mm[160];
        std::snprintf(mm, sizeof mm, ",\"min\":[%g,%g,%g],\"max\":[%g,%g,%g]", lo[0], lo[1], lo[2],
                      hi[0], hi[1], hi[2]);
        return data(p, 5126, "VEC3", p.size() / 3, mm);
    }
    std::string json(const std::string &members, bool glb) const {
        std::string j = "{\"asset\":{\"version\":\"2.0\",\"generator\":\"sv_fuzz_corpus\"}," +
                        members + ",\"accessors\":[";
        for (size_t i = 0; i < accessors.size(); i++) j += (i ? "," : "") + accessors[i];
        j += "],\"bufferViews\":[";
        for (size_t i = 0; i < views.size(); i++) j += (i ? "," : "") + views[i];
        j += "],\"buffers\":[{\"byteLength\":" + std::to_string(bin.size());
        if (!glb) j += ",\"uri\":\"data:application/octet-stream;base64," + base64(bin) + "\"";
        return j + "}]}";
    }
};

void put_u32(std::string &s, uint32_t v) { s.append(reinterpret_cast<const char *>(&v), 4); }

std::string glb(std::string json, std::string bin) {
    while (json.size() % 4) json += ' ';
    while (bin.size() % 4) bin += '\0';
    std::string out = "glTF";
    put_u32(out, 2);
    put_u32(out, uint32_t(12 + 8 + json.size() + (bin.empty() ? 0 : 8 + bin.size())));
    put_u32(out, uint32_t(json.size()));
    out += "JSON" + json;
    if (!bin.empty()) {
        put_u32(out, uint32_t(bin.size()));
        out += std::string("BIN\0", 4) + bin;
    }
    return out;
}

void write(const fs::path &p, const std::string &bytes) {
    std::ofstream f(p, std::ios::binary);
    f.write(bytes.data(), std::streamsize(bytes.size()));
}

void emit(const fs::path &dir, const std::string &name, const Doc &d, const std::string &members) {
    write(dir / "gltf" / (name + ".gltf"), d.json(members, false));
    write(dir / "glb" / (name + ".glb"), glb(d.json(members, true), d.bin));
}

const std::vector<float> kCube = {-1, -1, -1, 1, -1, -1, -1, 1, -1, 1, 1, -1,
                                  -1, -1, 1,  1, -1, 1,  -1, 1, 1,  1, 1, 1};
const std::vector<uint32_t> kCubeIdx = {0, 4, 6, 0, 6, 2, 1, 3, 7, 1, 7, 5, 0, 1, 5, 0, 5, 4,
                                        2, 6, 7, 2, 7, 3, 0, 2, 3, 0, 3, 1, 4, 5, 7, 4, 7, 6};

} // namespace

int main(int argc, char **argv) {
    if (argc < 2) {
        std::fprintf(stderr, "usage: sv_fuzz_corpus DIR [character.glb]\n");
        return 2;
    }
    const fs::path dir = argv[1];
    fs::create_directories(dir / "glb");
    fs::create_directories(dir / "gltf");
    const std::string one_mesh = "\"scenes\":[{\"nodes\":[0]}],\"nodes\":[{\"mesh\":0}]";
    { // the cube, u32 / u16 / u8 indices
        for (int ct : {5125, 5123, 5121}) {
            Doc d;
            const int p = d.vec3(kCube);
            int i;
            if (ct == 5125)
                i = d.data(kCubeIdx, ct, "SCALAR", kCubeIdx.size());
            else if (ct == 5123)
                i = d.data(std::vector<uint16_t>(kCubeIdx.begin(), kCubeIdx.end()), ct, "SCALAR",
                           kCubeIdx.size());
            else
                i = d.data(std::vector<uint8_t>(kCubeIdx.begin(), kCubeIdx.end()), ct, "SCALAR",
                           kCubeIdx.size());
            emit(dir, "cube_" + std::to_string(ct), d,
                 one_mesh +
                     ",\"meshes\":[{\"name\":\"cube\",\"primitives\":[{\"attributes\":"
                     "{\"POSITION\":" +
                     std::to_string(p) + "},\"indices\":" + std::to_string(i) + "}]}]");
        }
    }
    { // strip and fan, not indexed, in one mesh; and points
        Doc d;
        const int s = d.vec3({0, 0, 0, 1, 0, 0, 0, 1, 0, 1, 1, 0, 0, 2, 0});
        const int f = d.vec3({0, 0, 1, 1, 0, 1, 1, 1, 1, 0, 1, 1});
        emit(dir, "strip_fan", d,
             one_mesh + ",\"meshes\":[{\"primitives\":[{\"attributes\":{\"POSITION\":" +
                 std::to_string(s) +
                 "},\"mode\":5},{\"attributes\":{\"POSITION\":" + std::to_string(f) +
                 "},\"mode\":6},{\"attributes\":{\"POSITION\":" + std::to_string(f) +
                 "},\"mode\":0}]}]");
    }
    { // a hierarchy: TRS, a matrix, a mirror, two instances
        Doc d;
        const int p = d.vec3(kCube);
        const int i = d.data(kCubeIdx, 5125, "SCALAR", kCubeIdx.size());
        emit(dir, "hierarchy", d,
             "\"scene\":0,\"scenes\":[{\"nodes\":[0]}],\"nodes\":[{\"children\":[1,2],"
             "\"translation\":[1,2,3],\"rotation\":[0,0.7071068,0,0.7071068],\"scale\":[2,2,2]},"
             "{\"mesh\":0,\"name\":\"mirror\",\"scale\":[-1,1,1]},"
             "{\"mesh\":0,\"matrix\":[1,0,0,0,0,1,0,0,0,0,1,0,5,0,0,1]}],"
             "\"meshes\":[{\"primitives\":[{\"attributes\":{\"POSITION\":" +
                 std::to_string(p) + "},\"indices\":" + std::to_string(i) + "}]}]");
    }
    { // a skin: two joints, u8 joints, float weights, inverse bind matrices
        Doc d;
        const int p = d.vec3(kCube);
        const int i = d.data(kCubeIdx, 5125, "SCALAR", kCubeIdx.size());
        std::vector<uint8_t> j;
        std::vector<float> w;
        for (int v = 0; v < 8; v++) {
            j.insert(j.end(), {0, 1, 0, 0});
            const float a = (v & 4) ? 0.75f : 0.25f;
            w.insert(w.end(), {a, 1 - a, 0, 0});
        }
        const int ja = d.data(j, 5121, "VEC4", 8);
        const int wa = d.data(w, 5126, "VEC4", 8);
        std::vector<float> ibm;
        for (int k = 0; k < 2; k++) {
            ibm.insert(ibm.end(), {1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, -float(k), 0, 1});
        }
        const int ia = d.data(ibm, 5126, "MAT4", 2);
        emit(dir, "skin", d,
             "\"scenes\":[{\"nodes\":[0,1]}],\"nodes\":[{\"mesh\":0,\"skin\":0},{\"children\":"
             "[2],\"name\":\"root\"},{\"translation\":[0,1,0],\"rotation\":[0.2,0,0,0.98]}],"
             "\"skins\":[{\"joints\":[1,2],\"inverseBindMatrices\":" +
                 std::to_string(ia) +
                 "}],\"meshes\":[{\"primitives\":[{\"attributes\":{\"POSITION\":" +
                 std::to_string(p) + ",\"JOINTS_0\":" + std::to_string(ja) + ",\"WEIGHTS_0\":" +
                 std::to_string(wa) + "},\"indices\":" + std::to_string(i) + "}]}]");
    }
    { // a sparse accessor over the cube's positions
        Doc d;
        d.vec3(kCube);
        const int i = d.data(kCubeIdx, 5125, "SCALAR", kCubeIdx.size());
        d.data(std::vector<uint32_t>{7}, 5125, "SCALAR", 1);
        d.data(std::vector<float>{1.5f, 1.5f, 1.5f}, 5126, "VEC3", 1);
        d.accessors[0].pop_back();
        d.accessors[0] += ",\"sparse\":{\"count\":1,\"indices\":{\"bufferView\":2,"
                          "\"componentType\":5125},\"values\":{\"bufferView\":3}}}";
        emit(dir, "sparse", d,
             one_mesh +
                 ",\"meshes\":[{\"primitives\":[{\"attributes\":{\"POSITION\":0},"
                 "\"indices\":" +
                 std::to_string(i) + "}]}]");
    }
    { // command lines for fuzz_options: the selector byte, then NUL-separated arguments
        fs::create_directories(dir / "options");
        const std::vector<std::pair<char, std::vector<std::string>>> lines = {
            {0,
             {"--add", "models/character_1344.glb@1,0,-2,30,1.5", "--ground", "--light",
              "point:2,4,3,20", "--light", "spot:0,5,0,0,-1,0,10,30", "--camera",
              "eye=3,2,5,target=0,1,0,fov=50,near=0.1", "--size", "640x480", "--mode=zfail",
              "--threads", "2", "--no-gl", "--stencil", "bf"}},
            {1,
             {"scene.glb@0,0,0", "--frames", "12", "--light", "dir:0.2,-1,0.1", "--size=320x200",
              "--animation", "0", "--fps", "24", "--full", "--json", "-"}},
            {1,
             {"scene.glb", "--time", "0.5:2.25", "--light", "point:auto", "--no-truth",
              "--stencil=bf"}},
            {2, {"spot:1,2,3,0,0,-1,5,40"}},
            {3, {"eye=0,1.5,4,target=0,1,0,up=0,1,0,fov=45"}},
            {4, {"a.glb@1e3,-2.5e-3,7,-90,0.25"}},
            {5, {"8192x8192"}},
            {6,
             {"scene.glb:walk", "--add", "b.glb@1,0,0:0", "--script", "s.txt", "--no-hud",
              "--stencil", "hier", "--fps", "12", "--size=320x240"}},
            {7,
             {"# a script\n0 key Space\n1 drag left 10 20 30 5\n2 wheel -3\n3 key .\n"
              "3 snap a.png\n3 print\n4 quit\n"}}};
        int k = 0;
        for (const auto &line : lines) {
            std::string bytes(1, line.first);
            for (std::size_t i = 0; i < line.second.size(); i++) {
                bytes += (i ? std::string(1, '\0') : std::string()) + line.second[i];
            }
            write(dir / "options" / ("line_" + std::to_string(k++)), bytes);
        }
    }
    if (argc > 2) { // the project's character, in both containers
        std::ifstream in(argv[2], std::ios::binary);
        const std::string g((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
        if (g.size() > 28) {
            write(dir / "glb" / "character_1344.glb", g);
            uint32_t jl, bl;
            std::memcpy(&jl, g.data() + 12, 4);
            std::memcpy(&bl, g.data() + 20 + jl, 4);
            std::string json = g.substr(20, jl), bin = g.substr(28 + jl, bl);
            while (!json.empty() && json.back() == ' ') json.pop_back();
            /* the first buffer gets the data: URI */
            const std::string key = "\"buffers\":[{";
            const size_t at = json.find(key);
            if (at != std::string::npos) {
                json.insert(at + key.size(), "\"uri\":\"data:application/octet-stream;base64," +
                                                 base64(bin) + "\",");
                write(dir / "gltf" / "character_1344.gltf", json);
            }
        }
    }
    return 0;
}
