// The generated models (tools/generate_models): the 1344-triangle character
// is closed, 2-manifold, consistently and outward wound, has the paper's
// counts (1344 triangles, 2016 edges), does not cut through itself, and the
// committed models/character_1344.glb is exactly what the generator writes
// now. The committed file is read with a tiny GLB reader written here (not
// the generator's code, not tinygltf).

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <fstream>
#include <iterator>
#include <map>
#include <memory>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

#include "model_gen.h"

#ifndef SV_MODELS_DIR
#error "SV_MODELS_DIR must name the repository's models/ folder"
#endif

namespace {

// ------------------------------------------------------ a tiny JSON parser --

struct Json {
    enum Kind { Null, Bool, Number, String, Array, Object } kind = Null;
    double num = 0;
    bool b = false;
    std::string str;
    std::vector<Json> arr;
    std::vector<std::pair<std::string, Json>> obj;

    const Json &operator[](const std::string &key) const {
        for (auto &kv : obj)
            if (kv.first == key) return kv.second;
        throw std::runtime_error("json: no key " + key);
    }
    const Json &operator[](std::size_t i) const {
        if (kind != Array || i >= arr.size()) throw std::runtime_error("json: bad index");
        return arr[i];
    }
    bool has(const std::string &key) const {
        for (auto &kv : obj)
            if (kv.first == key) return true;
        return false;
    }
    std::size_t as_size() const {
        if (kind != Number || num < 0 || num != std::floor(num))
            throw std::runtime_error("json: not a count");
        return static_cast<std::size_t>(num);
    }
};

struct JsonParser {
    const std::string &s;
    std::size_t i = 0;
    void ws() {
        while (i < s.size() && (s[i] == ' ' || s[i] == '\n' || s[i] == '\r' || s[i] == '\t')) ++i;
    }
    void expect(char c) {
        ws();
        if (i >= s.size() || s[i] != c)
            throw std::runtime_error(std::string("json: expected ") + c);
        ++i;
    }
    std::string string() {
        expect('"');
        std::string out;
        while (i < s.size() && s[i] != '"') {
            if (s[i] == '\\')
                throw std::runtime_error("json: escapes not supported by this test reader");
            out += s[i++];
        }
        expect('"');
        return out;
    }
    Json value() {
        ws();
        if (i >= s.size()) throw std::runtime_error("json: unexpected end");
        Json j;
        const char c = s[i];
        if (c == '{') {
            j.kind = Json::Object;
            ++i;
            ws();
            if (s[i] == '}') return ++i, j;
            for (;;) {
                std::string k = string();
                expect(':');
                j.obj.emplace_back(k, value());
                ws();
                if (s[i] == ',') {
                    ++i;
                    continue;
                }
                expect('}');
                return j;
            }
        }
        if (c == '[') {
            j.kind = Json::Array;
            ++i;
            ws();
            if (s[i] == ']') return ++i, j;
            for (;;) {
                j.arr.push_back(value());
                ws();
                if (s[i] == ',') {
                    ++i;
                    continue;
                }
                expect(']');
                return j;
            }
        }
        if (c == '"') {
            j.kind = Json::String;
            j.str = string();
            return j;
        }
        if (s.compare(i, 4, "true") == 0) {
            i += 4;
            j.kind = Json::Bool;
            j.b = true;
            return j;
        }
        if (s.compare(i, 5, "false") == 0) {
            i += 5;
            j.kind = Json::Bool;
            return j;
        }
        if (s.compare(i, 4, "null") == 0) {
            i += 4;
            return j;
        }
        std::size_t end = i;
        while (end < s.size() && std::strchr("+-0123456789.eE", s[end])) ++end;
        if (end == i) throw std::runtime_error("json: bad value");
        j.kind = Json::Number;
        j.num = std::stod(s.substr(i, end - i));
        i = end;
        return j;
    }
};

// ------------------------------------------------------- a tiny GLB reader --

std::uint32_t u32(const std::vector<std::uint8_t> &d, std::size_t at) {
    if (at + 4 > d.size()) throw std::runtime_error("glb: truncated");
    return std::uint32_t(d[at]) | std::uint32_t(d[at + 1]) << 8 | std::uint32_t(d[at + 2]) << 16 |
           std::uint32_t(d[at + 3]) << 24;
}

struct Glb {
    Json json;
    std::string json_text;
    svgen::TriMesh mesh;
};

// Reads the first primitive of the first mesh: POSITION (float VEC3) and
// indices (u8/u16/u32 SCALAR), checking the structure on the way.
Glb read_glb(const std::vector<std::uint8_t> &d) {
    Glb g;
    if (u32(d, 0) != 0x46546C67u) throw std::runtime_error("glb: magic");
    if (u32(d, 4) != 2) throw std::runtime_error("glb: version");
    if (u32(d, 8) != d.size()) throw std::runtime_error("glb: length");
    const std::uint32_t jlen = u32(d, 12);
    if (u32(d, 16) != 0x4E4F534Au || jlen % 4 || 20 + std::size_t(jlen) > d.size())
        throw std::runtime_error("glb: JSON chunk");
    g.json_text.assign(d.begin() + 20, d.begin() + 20 + jlen);
    JsonParser p{g.json_text};
    g.json = p.value();
    p.ws();
    if (p.i != g.json_text.size())
        throw std::runtime_error("glb: JSON chunk not padded with spaces");
    const std::size_t bhead = 20 + jlen;
    const std::uint32_t blen = u32(d, bhead);
    if (u32(d, bhead + 4) != 0x004E4942u || blen % 4 || bhead + 8 + blen != d.size())
        throw std::runtime_error("glb: BIN chunk");
    const std::uint8_t *bin = d.data() + bhead + 8;
    if (g.json["buffers"][0]["byteLength"].as_size() > blen)
        throw std::runtime_error("glb: buffer length");

    const Json &prim = g.json["meshes"][0]["primitives"][0];
    if (prim.has("mode") && prim["mode"].num != 4) throw std::runtime_error("glb: not TRIANGLES");
    auto view = [&](const Json &acc, std::size_t elem, std::size_t &count) {
        count = acc["count"].as_size();
        const Json &bv = g.json["bufferViews"][acc["bufferView"].as_size()];
        const std::size_t off = bv["byteOffset"].as_size() +
                                (acc.has("byteOffset") ? acc["byteOffset"].as_size() : 0);
        if (bv.has("byteStride") && bv["byteStride"].as_size() != elem)
            throw std::runtime_error("glb: stride");
        if (off + count * elem > bv["byteOffset"].as_size() + bv["byteLength"].as_size() ||
            off + count * elem > blen)
            throw std::runtime_error("glb: accessor out of its buffer view");
        return bin + off;
    };
    const Json &pacc = g.json["accessors"][prim["attributes"]["POSITION"].as_size()];
    if (pacc["componentType"].num != 5126 || pacc["type"].str != "VEC3")
        throw std::runtime_error("glb: POSITION type");
    std::size_t nv = 0;
    const std::uint8_t *pp = view(pacc, 12, nv);
    g.mesh.positions.resize(nv * 3);
    std::memcpy(g.mesh.positions.data(), pp, nv * 12);
    const Json &iacc = g.json["accessors"][prim["indices"].as_size()];
    const double ct = iacc["componentType"].num;
    const std::size_t isz = ct == 5121 ? 1 : ct == 5123 ? 2 : ct == 5125 ? 4 : 0;
    if (!isz || iacc["type"].str != "SCALAR") throw std::runtime_error("glb: indices type");
    std::size_t ni = 0;
    const std::uint8_t *ip = view(iacc, isz, ni);
    for (std::size_t k = 0; k < ni; ++k) {
        std::uint32_t v = 0;
        for (std::size_t b = 0; b < isz; ++b) v |= std::uint32_t(ip[k * isz + b]) << (8 * b);
        g.mesh.indices.push_back(v);
    }
    return g;
}

std::vector<std::uint8_t> read_file(const std::string &path) {
    std::ifstream f(path, std::ios::binary);
    if (!f) throw std::runtime_error("cannot open " + path);
    return std::vector<std::uint8_t>(std::istreambuf_iterator<char>(f),
                                     std::istreambuf_iterator<char>());
}

// ------------------------------------------------------------- properties --

struct Topology {
    std::size_t vertices = 0, triangles = 0, edges = 0;
    std::size_t bad_edges = 0;      // undirected edges not used by exactly 2 triangles
    std::size_t same_direction = 0; // pairs that share an edge in the same direction
    std::size_t degenerate = 0;     // repeated index or zero area
    std::size_t unused_vertices = 0;
    double volume = 0; // sum of det(p0, p1, p2) / 6
};

Topology topology(const svgen::TriMesh &m) {
    Topology t;
    t.vertices = m.num_vertices();
    t.triangles = m.num_triangles();
    std::vector<bool> used(t.vertices, false);
    std::map<std::pair<std::uint32_t, std::uint32_t>, int> directed;
    auto p = [&](std::uint32_t v) {
        return std::array<double, 3>{m.positions[3 * v], m.positions[3 * v + 1],
                                     m.positions[3 * v + 2]};
    };
    for (std::size_t f = 0; f < t.triangles; ++f) {
        const std::uint32_t v[3] = {m.indices[3 * f], m.indices[3 * f + 1], m.indices[3 * f + 2]};
        for (int k = 0; k < 3; ++k) {
            EXPECT_LT(v[k], t.vertices);
            used[v[k]] = true;
            ++directed[{v[k], v[(k + 1) % 3]}];
        }
        const auto a = p(v[0]), b = p(v[1]), c = p(v[2]);
        const double u[3] = {b[0] - a[0], b[1] - a[1], b[2] - a[2]};
        const double w[3] = {c[0] - a[0], c[1] - a[1], c[2] - a[2]};
        const double n[3] = {u[1] * w[2] - u[2] * w[1], u[2] * w[0] - u[0] * w[2],
                             u[0] * w[1] - u[1] * w[0]};
        const double area2 = std::sqrt(n[0] * n[0] + n[1] * n[1] + n[2] * n[2]);
        if (v[0] == v[1] || v[1] == v[2] || v[0] == v[2] || !(area2 > 1e-10)) ++t.degenerate;
        t.volume += (a[0] * (b[1] * c[2] - b[2] * c[1]) - a[1] * (b[0] * c[2] - b[2] * c[0]) +
                     a[2] * (b[0] * c[1] - b[1] * c[0])) /
                    6.0;
    }
    for (bool u : used) t.unused_vertices += !u;
    for (const auto &e : directed) {
        if (e.second > 1) ++t.same_direction;
        const auto rev = directed.find({e.first.second, e.first.first});
        const int back = rev == directed.end() ? 0 : rev->second;
        if (e.first.first < e.first.second || back == 0) {
            ++t.edges;
            if (e.second != 1 || back != 1) ++t.bad_edges;
        }
    }
    return t;
}

void expect_closed_manifold(const svgen::TriMesh &m, const char *what) {
    SCOPED_TRACE(what);
    const Topology t = topology(m);
    EXPECT_EQ(t.edges * 2, t.triangles * 3) << "a closed triangle mesh has 3F/2 edges";
    EXPECT_EQ(t.bad_edges, 0u) << "edges not used by exactly two triangles in opposite directions";
    EXPECT_EQ(t.same_direction, 0u);
    EXPECT_EQ(t.degenerate, 0u);
    EXPECT_EQ(t.unused_vertices, 0u);
    EXPECT_EQ(long(t.vertices) - long(t.edges) + long(t.triangles), 2L)
        << "Euler characteristic (genus 0)";
    EXPECT_GT(t.volume, 0.0) << "outward (counter-clockwise) winding encloses a positive volume";
}

// Do two triangles that share no vertex intersect? (An edge of one crossing
// the other, which covers every non-coplanar case.)
bool segment_hits_triangle(const double *p, const double *q, const double *a, const double *b,
                           const double *c) {
    auto orient = [](const double *o, const double *x, const double *y, const double *z) {
        const double u[3] = {x[0] - o[0], x[1] - o[1], x[2] - o[2]};
        const double v[3] = {y[0] - o[0], y[1] - o[1], y[2] - o[2]};
        const double w[3] = {z[0] - o[0], z[1] - o[1], z[2] - o[2]};
        return u[0] * (v[1] * w[2] - v[2] * w[1]) - u[1] * (v[0] * w[2] - v[2] * w[0]) +
               u[2] * (v[0] * w[1] - v[1] * w[0]);
    };
    const double sp = orient(a, b, c, p), sq = orient(a, b, c, q);
    if ((sp > 0 && sq > 0) || (sp < 0 && sq < 0)) return false;
    if (sp == 0 && sq == 0) return false; // coplanar: not expected here
    const double s1 = orient(p, q, a, b), s2 = orient(p, q, b, c), s3 = orient(p, q, c, a);
    return (s1 >= 0 && s2 >= 0 && s3 >= 0) || (s1 <= 0 && s2 <= 0 && s3 <= 0);
}

std::size_t self_intersections(const svgen::TriMesh &m) {
    const std::size_t nt = m.num_triangles();
    std::vector<std::array<double, 9>> tri(nt);
    std::vector<std::array<double, 6>> box(nt);
    for (std::size_t f = 0; f < nt; ++f) {
        for (int k = 0; k < 3; ++k)
            for (int c = 0; c < 3; ++c)
                tri[f][3 * k + c] = m.positions[3 * m.indices[3 * f + k] + c];
        for (int c = 0; c < 3; ++c) {
            box[f][c] = std::min({tri[f][c], tri[f][3 + c], tri[f][6 + c]});
            box[f][3 + c] = std::max({tri[f][c], tri[f][3 + c], tri[f][6 + c]});
        }
    }
    std::size_t hits = 0;
    for (std::size_t f = 0; f < nt; ++f)
        for (std::size_t g = f + 1; g < nt; ++g) {
            bool apart = false;
            for (int c = 0; c < 3; ++c)
                apart |= box[f][3 + c] < box[g][c] || box[g][3 + c] < box[f][c];
            if (apart) continue;
            bool shared = false;
            for (int i = 0; i < 3; ++i)
                for (int j = 0; j < 3; ++j) shared |= m.indices[3 * f + i] == m.indices[3 * g + j];
            if (shared) continue;
            const double *A = tri[f].data();
            const double *B = tri[g].data();
            bool hit = false;
            for (int k = 0; k < 3 && !hit; ++k) {
                hit |= segment_hits_triangle(A + 3 * k, A + 3 * ((k + 1) % 3), B, B + 3, B + 6);
                hit |= segment_hits_triangle(B + 3 * k, B + 3 * ((k + 1) % 3), A, A + 3, A + 6);
            }
            hits += hit;
        }
    return hits;
}

// ------------------------------------------------------------------ tests --

TEST(GeneratedModels, CharacterHasThePapersCounts) {
    const svgen::QuadMesh q = svgen::build_character_quads();
    EXPECT_EQ(q.quads.size(), 672u);
    EXPECT_EQ(q.vertices.size(), 674u);
    const svgen::TriMesh m = svgen::build_character();
    const Topology t = topology(m);
    EXPECT_EQ(t.triangles, 1344u);
    EXPECT_EQ(t.edges, 2016u);
    EXPECT_EQ(t.vertices, 674u);
}

TEST(GeneratedModels, CharacterIsClosedManifoldAndOutwardWound) {
    expect_closed_manifold(svgen::build_character(), "character_1344");
}

TEST(GeneratedModels, CharacterDoesNotCutThroughItself) {
    EXPECT_EQ(self_intersections(svgen::build_character()), 0u);
}

TEST(GeneratedModels, CharacterIsFigureShaped) {
    // Standing on y = 0, taller than wide in depth, arms spread (T-pose): a
    // sphere or a torus would fail these proportions.
    const svgen::TriMesh m = svgen::build_character();
    float lo[3] = {1e9f, 1e9f, 1e9f}, hi[3] = {-1e9f, -1e9f, -1e9f};
    for (std::size_t v = 0; v < m.num_vertices(); ++v)
        for (int c = 0; c < 3; ++c) {
            lo[c] = std::min(lo[c], m.positions[3 * v + c]);
            hi[c] = std::max(hi[c], m.positions[3 * v + c]);
        }
    EXPECT_NEAR(lo[1], 0.0f, 0.01f);
    EXPECT_GT(hi[1] - lo[1], 1.7f); // height
    EXPECT_GT(hi[0] - lo[0], 1.5f); // arm span
    EXPECT_LT(hi[2] - lo[2], 0.4f); // depth
}

TEST(GeneratedModels, CommittedGlbIsWhatTheGeneratorWrites) {
    const std::string path = std::string(SV_MODELS_DIR) + "/character_1344.glb";
    const std::vector<std::uint8_t> file = read_file(path);
    const svgen::TriMesh m = svgen::build_character();
    const std::vector<std::uint8_t> now = svgen::write_glb(m, "character_1344");
    EXPECT_TRUE(file == now) << path << " differs from the generator's output: regenerate it with "
                             << "shadowvol_generate_models --out models (and commit it)";
}

TEST(GeneratedModels, CommittedGlbReadsBackAsTheClosedCharacter) {
    const std::string path = std::string(SV_MODELS_DIR) + "/character_1344.glb";
    const Glb g = read_glb(read_file(path));
    EXPECT_EQ(g.json["asset"]["version"].str, "2.0");
    EXPECT_NE(g.json["asset"]["generator"].str.find("shadowvol"), std::string::npos);
    EXPECT_EQ(g.json["scenes"][g.json["scene"].as_size()]["nodes"][0].as_size(), 0u);
    EXPECT_EQ(g.json["nodes"][0]["mesh"].as_size(), 0u);
    const Topology t = topology(g.mesh);
    EXPECT_EQ(t.triangles, 1344u);
    EXPECT_EQ(t.edges, 2016u);
    EXPECT_EQ(t.vertices, 674u);
    expect_closed_manifold(g.mesh, "committed character_1344.glb");
    // POSITION min/max (required by glTF) are the exact bounds.
    const Json &acc =
        g.json["accessors"]
              [g.json["meshes"][0]["primitives"][0]["attributes"]["POSITION"].as_size()];
    for (int c = 0; c < 3; ++c) {
        float lo = g.mesh.positions[c], hi = lo;
        for (std::size_t v = 0; v < t.vertices; ++v) {
            lo = std::min(lo, g.mesh.positions[3 * v + c]);
            hi = std::max(hi, g.mesh.positions[3 * v + c]);
        }
        EXPECT_EQ(static_cast<float>(acc["min"][std::size_t(c)].num), lo);
        EXPECT_EQ(static_cast<float>(acc["max"][std::size_t(c)].num), hi);
    }
}

TEST(GeneratedModels, ScalingMeshesAreClosedManifold) {
    // The scaling mode's ~10k and ~100k meshes (each quad 3x3 and 9x9; the 1M
    // one, 27x27, is the same code and is left out for time), and their glb
    // round trip.
    const svgen::TriMesh m = svgen::build_character(3);
    EXPECT_EQ(m.num_triangles(), 12096u);
    expect_closed_manifold(m, "character_12096");
    const Glb g = read_glb(svgen::write_glb(m, "character_12096"));
    EXPECT_TRUE(g.mesh.positions == m.positions);
    EXPECT_TRUE(g.mesh.indices == m.indices);

    const svgen::TriMesh big = svgen::build_character(9);
    EXPECT_EQ(big.num_triangles(), 108864u);
    expect_closed_manifold(big, "character_108864");
}

TEST(GeneratedModels, GlbUsesUnsignedIntIndicesFrom65536Vertices) {
    const svgen::TriMesh small = svgen::build_character(9); // 54434 vertices
    ASSERT_LE(small.num_vertices(), 65535u);
    EXPECT_EQ(read_glb(svgen::write_glb(small, "s")).json["accessors"][1]["componentType"].num,
              5123);
    const svgen::TriMesh big = svgen::build_character(12); // 96770 vertices
    ASSERT_GT(big.num_vertices(), 65535u);
    const Glb g = read_glb(svgen::write_glb(big, "b"));
    EXPECT_EQ(g.json["accessors"][1]["componentType"].num, 5125);
    EXPECT_TRUE(g.mesh.indices == big.indices);
    EXPECT_TRUE(g.mesh.positions == big.positions);
}

TEST(GeneratedModels, SelfIntersectionCheckFindsACrossing) {
    // The checker itself: a thin triangle piercing another is found; moved
    // aside, it is not.
    svgen::TriMesh m;
    m.positions = {-1, 0,  -1, 1,    0, -1, 0,     0, 1,  // in the plane y = 0
                   0,  -1, 0,  0.1f, 1, 0,  -0.1f, 1, 0}; // through it
    m.indices = {0, 1, 2, 3, 4, 5};
    EXPECT_EQ(self_intersections(m), 1u);
    for (int v = 3; v < 6; ++v) m.positions[3 * v] += 5;
    EXPECT_EQ(self_intersections(m), 0u);
}

} // namespace
