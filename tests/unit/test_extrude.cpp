// Seed 002's extrusion (include/shadowvol_extrude.h, src/extrude/): every
// SIMD variant of the vertex program bit-identical to the C reference at
// every length 0..80 and a few thousand, under point lights with and
// without a range and directional lights, through the ABI checker, with
// guard bytes around every output; the reference's documented cases (the
// light on a vertex, no range, a directional light, vertices at and beyond
// the range, the seed's finite length). The preprocessing's counts
// (GenShadowMesh's: 3F vertices, 4F triangles for a closed mesh) on the
// bundled closed character, the generated open cases (the seed's flag
// under the paper's rule, every edge paired under the caster rule), the
// open asset pack character when present; every quad degenerate before
// extrusion.
//
// Copyright (C) 2026 the shadowvol authors. LGPL-2.1-or-later.
#include "test_support.h"

#include <unistd.h>

#include <cfloat>
#include <cmath>
#include <cstring>
#include <limits>
#include <string>
#include <vector>

#include "open_cases.h"
#include "shadowvol_casters.h"
#include "shadowvol_extrude.h"
#include "shadowvol_gltf.h"
#include "shadowvol_mesh.h"

namespace {

using svtest::GuardedBuffer;
using svtest::Rng;

std::vector<const sv_extrude_variant *> runnable() {
    int n = 0;
    const sv_extrude_variant *all = sv_extrude_variants(&n);
    std::vector<const sv_extrude_variant *> out;
    for (int i = 0; i < n; i++)
        if (svtest::in_this_run(all[i].isa, all[i].name)) out.push_back(&all[i]);
    return out;
}

// Equal bits, or both NaN (a NaN's sign and payload follow the operand
// order of a commutative operation, which the compiler may swap).
bool same_float(float a, float b) {
    if (std::isnan(a) && std::isnan(b)) return true;
    uint32_t x, y;
    std::memcpy(&x, &a, 4), std::memcpy(&y, &b, 4);
    return x == y;
}

bool same_vec4(const Vec4 &a, const Vec4 &b) {
    return same_float(a.x, b.x) && same_float(a.y, b.y) && same_float(a.z, b.z) &&
           same_float(a.w, b.w);
}

float coordinate(Rng &rng, bool nasty) {
    static const float special[] = {0.0f,
                                    -0.0f,
                                    1.0f,
                                    -1.0f,
                                    FLT_MIN,
                                    FLT_TRUE_MIN,
                                    FLT_MAX,
                                    -FLT_MAX,
                                    1e-30f,
                                    1e30f,
                                    std::numeric_limits<float>::infinity(),
                                    std::numeric_limits<float>::quiet_NaN()};
    if (nasty && rng.chance(0.3)) return special[rng.below(sizeof special / sizeof special[0])];
    return (float)((rng.unit() * 2 - 1) * 10);
}

// A random stream: positions in a 20-unit cube, unit face normals (some
// zero, some shared with the light's position so the light sits on them).
std::vector<float> random_stream(Rng &rng, int n, bool nasty, const Vec4 &light) {
    std::vector<float> s((size_t)n * SV_EXTRUDE_STREAM_FLOATS);
    for (int i = 0; i < n; i++) {
        float *v = s.data() + (size_t)i * SV_EXTRUDE_STREAM_FLOATS;
        for (int c = 0; c < 3; c++) v[c] = coordinate(rng, nasty);
        if (rng.chance(0.05)) v[0] = light.x, v[1] = light.y, v[2] = light.z;
        float nx = (float)(rng.unit() * 2 - 1), ny = (float)(rng.unit() * 2 - 1),
              nz = (float)(rng.unit() * 2 - 1);
        const float len = std::sqrt(nx * nx + ny * ny + nz * nz);
        if (len > 0) nx /= len, ny /= len, nz /= len;
        if (rng.chance(0.05)) nx = ny = nz = 0;
        v[3] = nx, v[4] = ny, v[5] = nz;
        if (nasty && rng.chance(0.1)) v[3 + rng.below(3)] = coordinate(rng, true);
    }
    return s;
}

struct LightCase {
    const char *name;
    Vec4 light;
    float range;
};

const LightCase kLights[] = {
    {"point with range", {1.5f, 4.0f, -2.0f, 1.0f}, 12.0f},
    {"point, short range", {0.0f, 0.0f, 0.0f, 1.0f}, 3.0f},
    {"point, no range", {1.5f, 4.0f, -2.0f, 1.0f}, 0.0f},
    {"point, infinite range", {-3.0f, 2.0f, 5.0f, 1.0f}, std::numeric_limits<float>::infinity()},
    {"directional", {0.3f, 0.9f, -0.2f, 0.0f}, 10.0f},
};

// Every variant against the reference on one stream: outputs at every
// offset from a 64-byte boundary in steps of 4 bytes, guard bytes around,
// through the ABI checker.
void check_stream(const std::vector<float> &stream, int n, const LightCase &lc,
                  const std::vector<const sv_extrude_variant *> &variants, Rng &rng,
                  const std::string &what) {
    std::vector<Vec4> ref((size_t)n + 1);
    const sv_extrude_light el{lc.light, lc.range};
    sv_extrude_c_ref(stream.data(), n, &el, ref.data());
    for (const sv_extrude_variant *v : variants) {
        const size_t offset = 4 * rng.below(16);
        GuardedBuffer out((size_t)n * sizeof(Vec4), offset);
        out.fill(0x5A);
        svtest::checked_call(rng, v->extrude, stream.data(), n, &el, out.as<Vec4>());
        EXPECT_TRUE(out.guards_intact()) << v->name << ", " << what << ", " << n << " vertices";
        for (int i = 0; i < n; i++) {
            Vec4 got;
            std::memcpy(&got, out.data() + (size_t)i * sizeof(Vec4), sizeof got);
            if (!same_vec4(got, ref[(size_t)i])) {
                ADD_FAILURE() << v->name << ", " << what << " (" << lc.name << "), vertex " << i
                              << " of " << n << ": (" << got.x << ", " << got.y << ", " << got.z
                              << ", " << got.w << ") against the reference's (" << ref[(size_t)i].x
                              << ", " << ref[(size_t)i].y << ", " << ref[(size_t)i].z << ", "
                              << ref[(size_t)i].w << ")";
                if (svtest::stop_after_failures()) return;
                break;
            }
        }
    }
}

SV_TIERED_TEST(Extrude, EveryTailEveryLight) {
    SCOPED_TRACE(svtest::seed_trace());
    Rng rng = svtest::rng_for("EveryTailEveryLight");
    const auto variants = runnable();
    for (const LightCase &lc : kLights) {
        for (int nasty = 0; nasty < 2; nasty++) {
            for (int n = 0; n <= 80; n++) {
                const auto s = random_stream(rng, n, nasty != 0, lc.light);
                check_stream(s, n, lc, variants, rng, nasty ? "nasty values" : "ordinary");
                if (HasFailure()) return;
            }
            for (int n : {1000, 4099}) {
                const auto s = random_stream(rng, n, nasty != 0, lc.light);
                check_stream(s, n, lc, variants, rng, nasty ? "nasty values" : "ordinary");
                if (HasFailure()) return;
            }
        }
    }
}

SV_TIERED_TEST(Extrude, NegativeCountsWriteNothing) {
    const float stream[6] = {0, 0, 0, 0, 0, 1};
    const sv_extrude_light l{{0, 0, 1, 1}, 5.0f};
    for (const sv_extrude_variant *v : runnable()) {
        for (int n : {-1, -8, -17, std::numeric_limits<int>::min()}) {
            GuardedBuffer out(64, 0);
            out.fill(0x5A);
            v->extrude(stream, n, &l, out.as<Vec4>());
            for (size_t i = 0; i < out.size(); i++) ASSERT_EQ(out.data()[i], 0x5A) << v->name;
            EXPECT_TRUE(out.guards_intact()) << v->name;
        }
    }
}

Vec4 extrude_one(const float p[3], const float n[3], const Vec4 &light, float range) {
    const float s[6] = {p[0], p[1], p[2], n[0], n[1], n[2]};
    const sv_extrude_light l{light, range};
    Vec4 o;
    sv_extrude_c_ref(s, 1, &l, &o);
    return o;
}

// The rsqrt variant (not bit-identical): against the reference, the
// infinite outputs equal and the finite ones within 1e-6 * (range + |vLP|)
// wherever both decide the same facing; a facing that differs only where
// the exact dot is within 1e-5 of 0 (a face edge-on to the light).
SV_TIERED_TEST(Extrude, RsqrtVariantWithinItsBound) {
    if (!svtest::in_this_run(SV_ISA_SSE2 | SV_ISA_AVX2, "avx2_rsqrt")) return;
    SCOPED_TRACE(svtest::seed_trace());
    Rng rng = svtest::rng_for("RsqrtVariantWithinItsBound");
    int64_t flips = 0, compared = 0;
    for (const LightCase &lc : kLights) {
        for (int n : {0, 1, 7, 8, 9, 31, 4099}) {
            const auto s = random_stream(rng, n, false, lc.light);
            const sv_extrude_light el{lc.light, lc.range};
            std::vector<Vec4> ref((size_t)n + 1);
            sv_extrude_c_ref(s.data(), n, &el, ref.data());
            GuardedBuffer out((size_t)n * sizeof(Vec4), 4 * rng.below(16));
            svtest::checked_call(rng, sv_extrude_avx2_rsqrt, s.data(), n, &el, out.as<Vec4>());
            EXPECT_TRUE(out.guards_intact()) << lc.name << ", " << n;
            for (int i = 0; i < n; i++) {
                Vec4 got;
                std::memcpy(&got, out.data() + (size_t)i * sizeof(Vec4), sizeof got);
                const Vec4 &r = ref[(size_t)i];
                const float *v = s.data() + (size_t)i * SV_EXTRUDE_STREAM_FLOATS;
                const double dx = (double)v[0] * lc.light.w - lc.light.x,
                             dy = (double)v[1] * lc.light.w - lc.light.y,
                             dz = (double)v[2] * lc.light.w - lc.light.z;
                const double len = std::sqrt(dx * dx + dy * dy + dz * dz);
                const bool keptRef = r.w == 1.0f && r.x == v[0] && r.y == v[1] && r.z == v[2];
                const bool keptGot = got.w == 1.0f && got.x == v[0] && got.y == v[1] &&
                                     got.z == v[2];
                compared++;
                if (keptRef != keptGot && (r.w == 0.0f || got.w == 0.0f || len > 0)) {
                    const double dot = (v[3] * dx + v[4] * dy + v[5] * dz) / std::max(len, 1e-30);
                    // A finite extrusion that does not move (at or beyond the
                    // range) is no flip.
                    if (std::fabs(dot) > 1e-5 && !(lc.range > 0 && len >= lc.range * (1 - 1e-5))) {
                        ADD_FAILURE()
                            << lc.name << ", vertex " << i << ": facing differs at dot " << dot;
                    }
                    flips++;
                    continue;
                }
                if (r.w == 0.0f) {
                    EXPECT_TRUE(same_vec4(got, r)) << lc.name << ", vertex " << i;
                } else {
                    const double e = std::sqrt(((double)got.x - r.x) * ((double)got.x - r.x) +
                                               ((double)got.y - r.y) * ((double)got.y - r.y) +
                                               ((double)got.z - r.z) * ((double)got.z - r.z));
                    EXPECT_LE(e, 1e-6 * (lc.range + len)) << lc.name << ", vertex " << i;
                }
                if (svtest::stop_after_failures()) return;
            }
        }
    }
    EXPECT_LE(flips, compared / 1000) << "facing flips";
}

// The reference's documented results, case by case.
TEST(Extrude, SpecialCases) {
    const float p[3] = {1.0f, 2.0f, 3.0f};
    const float away[3] = {0.0f, 0.0f, 1.0f}; // faces +z
    const float towards[3] = {0.0f, 0.0f, -1.0f};
    const float zero[3] = {0.0f, 0.0f, 0.0f};
    const Vec4 below{1.0f, 2.0f, -1.0f, 1.0f}; // 4 units below p in z
    // A face towards the light stays, w = 1.
    Vec4 o = extrude_one(p, towards, below, 10.0f);
    EXPECT_TRUE(same_vec4(o, {1.0f, 2.0f, 3.0f, 1.0f}));
    // Away: the seed's finite length, clamp0(range - |vLP|) = 6 more along +z.
    o = extrude_one(p, away, below, 10.0f);
    EXPECT_TRUE(same_vec4(o, {1.0f, 2.0f, 9.0f, 1.0f})) << o.z;
    // At the range, and beyond it: no extrusion (the vertex, bit for bit).
    o = extrude_one(p, away, below, 4.0f);
    EXPECT_TRUE(same_vec4(o, {1.0f, 2.0f, 3.0f, 1.0f})) << o.z;
    o = extrude_one(p, away, below, 2.5f);
    EXPECT_TRUE(same_vec4(o, {1.0f, 2.0f, 3.0f, 1.0f})) << o.z;
    // No range (0 = unlimited), a negative or infinite one: to infinity,
    // (p - light, 0) as the paper's shadow vertices.
    for (float r : {0.0f, -1.0f, std::numeric_limits<float>::infinity(),
                    std::numeric_limits<float>::quiet_NaN()}) {
        o = extrude_one(p, away, below, r);
        EXPECT_TRUE(same_vec4(o, {0.0f, 0.0f, 4.0f, 0.0f})) << r;
    }
    // Directional (towards the light -y... here +z down: light.xyz points
    // to the light): to infinity along -light.xyz whatever the range.
    const Vec4 sun{0.0f, 0.0f, -1.0f, 0.0f};
    o = extrude_one(p, away, sun, 10.0f);
    EXPECT_TRUE(same_vec4(o, {0.0f, 0.0f, 1.0f, 0.0f}));
    o = extrude_one(p, towards, sun, 10.0f);
    EXPECT_TRUE(same_vec4(o, {1.0f, 2.0f, 3.0f, 1.0f}));
    // The light on the vertex: it stays (not NaN), whatever its normal.
    const Vec4 on{1.0f, 2.0f, 3.0f, 1.0f};
    for (const float *n : {away, towards, zero}) {
        for (float r : {0.0f, 5.0f}) {
            o = extrude_one(p, n, on, r);
            EXPECT_TRUE(same_vec4(o, {1.0f, 2.0f, 3.0f, 1.0f})) << r;
        }
    }
    // A zero normal (a zero-area face) or a face edge-on to the light: dot
    // = 0 is not < 0, so it is extruded, as the paper's zero plane is dark.
    o = extrude_one(p, zero, below, 0.0f);
    EXPECT_EQ(o.w, 0.0f);
    const float sideways[3] = {1.0f, 0.0f, 0.0f};
    o = extrude_one(p, sideways, below, 0.0f);
    EXPECT_EQ(o.w, 0.0f);
}

// The finite length on random vertices: each extruded vertex lands at the
// range from the light (to float accuracy), on the ray from the light
// through it; the kept ones are the vertex.
TEST(Extrude, FiniteLengthReachesTheRange) {
    Rng rng = svtest::rng_for("FiniteLengthReachesTheRange");
    const Vec4 light{0.5f, -1.0f, 2.0f, 1.0f};
    const float range = 25.0f;
    const int n = 2000;
    const auto s = random_stream(rng, n, false, {100, 100, 100, 1});
    std::vector<Vec4> out((size_t)n);
    const sv_extrude_light el{light, range};
    sv_extrude_c_ref(s.data(), n, &el, out.data());
    int extruded = 0;
    for (int i = 0; i < n; i++) {
        const float *v = s.data() + (size_t)i * SV_EXTRUDE_STREAM_FLOATS;
        const double dx = v[0] - light.x, dy = v[1] - light.y, dz = v[2] - light.z;
        const double dot = v[3] * dx + v[4] * dy + v[5] * dz;
        const Vec4 &o = out[(size_t)i];
        ASSERT_EQ(o.w, 1.0f);
        const double len = std::sqrt(dx * dx + dy * dy + dz * dz);
        if (dot < -1e-4 || len > range * (1 + 1e-6)) { // towards the light, or beyond its range
            EXPECT_TRUE(o.x == v[0] && o.y == v[1] && o.z == v[2]) << i;
        } else if (dot > 1e-4 && len < range * (1 - 1e-6)) {
            extruded++;
            const double ox = o.x - light.x, oy = o.y - light.y, oz = o.z - light.z;
            EXPECT_NEAR(std::sqrt(ox * ox + oy * oy + oz * oz), range, 1e-4 * range) << i;
            const double olen = std::sqrt(ox * ox + oy * oy + oz * oz);
            EXPECT_NEAR((ox * dx + oy * dy + oz * dz) / (len * olen), 1.0, 1e-6) << i;
        }
    }
    EXPECT_GT(extruded, n / 4);
}

sv::PreparedSurface prepare(const std::vector<float> &pos, const std::vector<uint32_t> &idx) {
    return sv::prepare_surface(pos.data(), pos.size() / 3, idx.data(), idx.size());
}

// Every count and invariant of a shadow mesh of caster C: 3 vertices per
// face carrying the face's plane normal and its corners, the faces in order
// in the draw list with their quads after them, every quad degenerate
// (a1 = a2, b1 = b2 in position).
void check_mesh_shape(const sv::ShadowMesh &m, const sv::PreparedSurface &c,
                      const std::string &what) {
    SCOPED_TRACE(what);
    ASSERT_EQ(m.faces, c.num_triangles());
    ASSERT_EQ(m.num_vertices(), 3 * c.num_triangles());
    ASSERT_EQ(m.quads + m.open_edges, c.num_sil_edges());
    EXPECT_EQ(m.open_edges, c.report.dangling_sil_edges);
    EXPECT_EQ(m.closed_volume, m.open_edges == 0);
    ASSERT_EQ(m.num_indices(), 3 * m.faces + 6 * m.quads);
    const float *st = m.stream.data();
    for (int t = 0; t < c.num_triangles(); t++) {
        for (int k = 0; k < 3; k++) {
            const float *v = st + (3 * (size_t)t + (size_t)k) * SV_EXTRUDE_STREAM_FLOATS;
            const float *p = c.positions.data() + 3 * (size_t)c.indices[3 * (size_t)t + (size_t)k];
            ASSERT_TRUE(v[0] == p[0] && v[1] == p[1] && v[2] == p[2]) << t;
            const Plane &pl = c.planes[(size_t)t];
            ASSERT_TRUE(v[3] == pl.a && v[4] == pl.b && v[5] == pl.c) << t;
        }
    }
    auto same_position = [&](int a, int b) {
        return std::memcmp(st + (size_t)a * SV_EXTRUDE_STREAM_FLOATS,
                           st + (size_t)b * SV_EXTRUDE_STREAM_FLOATS, 3 * sizeof(float)) == 0;
    };
    int next_face = 0;
    int64_t quads = 0;
    for (size_t i = 0; i < m.indices.size();) {
        const int *x = m.indices.data() + i;
        // A face is (3t, 3t+1, 3t+2); a quad's first triangle never is (its
        // second vertex is on the other face).
        if (x[0] == 3 * next_face && x[1] == 3 * next_face + 1 && x[2] == 3 * next_face + 2) {
            next_face++;
            i += 3;
            continue;
        }
        // A quad (a1, b2, b1), (a1, a2, b2): a1, b1 on the earlier face, a2,
        // b2 on the later one, the face just emitted.
        ASSERT_LE(i + 6, m.indices.size());
        const int a1 = x[0], b2 = x[1], b1 = x[2], a2 = x[4];
        ASSERT_TRUE(x[3] == a1 && x[5] == b2) << "quad at " << i;
        EXPECT_EQ(a1 / 3, b1 / 3);
        EXPECT_EQ(a2 / 3, b2 / 3);
        EXPECT_EQ(b2 / 3, next_face - 1) << "a quad follows the later of its faces";
        EXPECT_LT(a1 / 3, b2 / 3);
        EXPECT_TRUE(same_position(a1, a2) && same_position(b1, b2)) << "quad at " << i;
        quads++;
        i += 6;
    }
    EXPECT_EQ(next_face, m.faces);
    EXPECT_EQ(quads, m.quads);
}

TEST(ShadowMesh, ClosedCharacterHasGenShadowMeshCounts) {
    const sv::GltfModel model = sv::load_gltf(std::string(SV_MODELS_DIR) + "/character_1344.glb");
    for (const sv::GltfSurface &gs : model.surfaces) {
        const sv::PreparedSurface s = prepare(gs.positions, gs.indices);
        const sv::ShadowMesh m = sv::build_shadow_mesh(s, sv::CasterRule::automatic);
        check_mesh_shape(m, s, gs.name);
        EXPECT_TRUE(m.closed_volume);
        EXPECT_EQ(m.open_edges, 0);
        EXPECT_EQ(2 * m.quads, 3 * m.faces);
        EXPECT_EQ(m.num_triangles(), 4 * m.faces); // GenShadowMesh: about 4F
        // The general rule everywhere: every face and its reverse.
        const sv::ShadowMesh g = sv::build_shadow_mesh(s, sv::CasterRule::general);
        EXPECT_EQ(g.faces, 2 * m.faces);
        EXPECT_TRUE(g.closed_volume);
    }
}

void check_open(const sv::PreparedSurface &s, const std::string &what) {
    const sv::ShadowMesh seed = sv::build_shadow_mesh(s, sv::CasterRule::closed);
    check_mesh_shape(seed, s, what + ", the seed's (closed rule)");
    EXPECT_EQ(seed.closed_volume, s.report.dangling_sil_edges == 0) << what;
    const sv::ShellMap shells = sv::find_shells(s);
    const auto caster = sv::two_sided_caster(s, shells, sv::CasterRule::automatic);
    const sv::ShadowMesh m = sv::build_shadow_mesh(s, sv::CasterRule::automatic);
    check_mesh_shape(m, caster ? *caster : s, what + ", the caster rule");
    EXPECT_TRUE(m.closed_volume) << what << ": the caster rule pairs every edge";
    EXPECT_EQ(2 * m.quads, 3 * m.faces) << what;
}

TEST(ShadowMesh, OpenCasesFlaggedAndClosedByTheCasterRule) {
    int flagged = 0;
    for (const svgen::Soup &soup : svgen::open_cases()) {
        const sv::PreparedSurface s = prepare(soup.pos, soup.idx);
        check_open(s, soup.name);
        flagged += sv::build_shadow_mesh(s, sv::CasterRule::closed).closed_volume ? 0 : 1;
    }
    EXPECT_GE(flagged, 5);
}

TEST(ShadowMesh, OpenCharacterSharedModels) {
    const std::string path = svtest::shared_models_dir() + "/open/Zombie_Basic.glb";
    if (access(path.c_str(), R_OK) != 0) GTEST_SKIP() << "not found, not tested: " << path;
    const sv::GltfModel model = sv::load_gltf(path);
    int64_t open = 0;
    for (const sv::GltfSurface &gs : model.surfaces) {
        const sv::PreparedSurface s = prepare(gs.positions, gs.indices);
        check_open(s, gs.name);
        open += sv::build_shadow_mesh(s, sv::CasterRule::closed).open_edges;
    }
    EXPECT_GT(open, 0);
}

TEST(ShadowMesh, EmptySurface) {
    const sv::PreparedSurface s = prepare({}, {});
    const sv::ShadowMesh m = sv::build_shadow_mesh(s, sv::CasterRule::automatic);
    EXPECT_EQ(m.num_vertices(), 0);
    EXPECT_EQ(m.num_indices(), 0);
    EXPECT_TRUE(m.closed_volume);
}

} // namespace
