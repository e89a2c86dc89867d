// Per-frame plane derivation and facing from positions
// (include/shadowvol_planes.h, src/planes/): every SIMD variant BIT-
// IDENTICAL to the C reference, on random meshes of every length 0..40 and
// large ones (every tail of every vector width), random index orders,
// degenerate triangles (coincident, collinear, zero area), huge, tiny and
// subnormal coordinates, NaN and infinities; negative counts write nothing;
// nothing is written past planes[numTriangles-1] (facing[numTriangles]),
// and nothing is read outside the positions array (it is placed against
// inaccessible pages). The reference's documented results (the zero plane,
// no NaN) and its agreement with sv::triangle_plane on ordinary triangles.
// Vertex 0 at a page start after an inaccessible page; degenerate
// triangles in every lane position over several blocks.
// The project's character and the real characters, when present.
// Planes by clusters: the clusters' contract (every triangle once, at most
// 32 vertices, corners that name the triangle's vertices in order, the
// padding), their density on real meshes, and every clustered kernel
// bit-identical to sv_derive_planes_c_ref through the ABI checker.
//
// Copyright (C) 2026 the shadowvol authors. LGPL-2.1-or-later.
#include "test_support.h"

#include <sys/mman.h>
#include <xmmintrin.h>
#include <unistd.h>

#include <algorithm>
#include <cfloat>
#include <cmath>
#include <cstring>
#include <initializer_list>
#include <limits>
#include <string>
#include <vector>

#include "shadowvol_gltf.h"
#include "shadowvol_mesh.h"
#include "shadowvol_planes.h"

namespace {

using svtest::GuardedBuffer;
using svtest::Rng;

std::vector<const sv_planes_variant *> runnable() {
    int n = 0;
    const sv_planes_variant *all = sv_planes_variants(&n);
    std::vector<const sv_planes_variant *> out;
    for (int i = 0; i < n; i++) {
        if (svtest::in_this_run(all[i].isa, all[i].name)) out.push_back(&all[i]);
    }
    return out;
}

// Positions at the very end of an accessible region, with an inaccessible
// page right after the last float and right before the first: a SIMD load
// that reads one byte outside the array faults.
class FencedPositions {
public:
    // AT_START: the array begins right after the guard page before it
    // (vertex 0's shifted masked load starts on that inaccessible page);
    // otherwise it ends right before the guard page after it.
    explicit FencedPositions(size_t floats, bool atStart = false) : floats_(floats) {
        const size_t page = (size_t)sysconf(_SC_PAGESIZE);
        const size_t bytes = floats * sizeof(float);
        const size_t body = (bytes + page - 1) / page * page;
        total_ = body + 2 * page;
        void *p = mmap(nullptr, total_, PROT_NONE, MAP_PRIVATE | MAP_ANONYMOUS, -1, 0);
        if (p == MAP_FAILED) return;
        base_ = static_cast<uint8_t *>(p);
        if (mprotect(base_ + page, body, PROT_READ | PROT_WRITE) != 0) return;
        // The array ends at the guard page after it; when it fills the body
        // exactly it also starts at the guard page before it.
        data_ = reinterpret_cast<float *>(atStart ? base_ + page : base_ + page + body - bytes);
    }
    ~FencedPositions() {
        if (base_) munmap(base_, total_);
    }
    FencedPositions(const FencedPositions &) = delete;
    FencedPositions &operator=(const FencedPositions &) = delete;
    float *data() { return data_; }
    bool ok() const { return data_ != nullptr; }

private:
    size_t floats_, total_ = 0;
    uint8_t *base_ = nullptr;
    float *data_ = nullptr;
};

enum class Scale { ordinary, tiny, huge, subnormal, mixed, nasty };

float coordinate(Rng &rng, Scale s) {
    const double u = rng.unit() * 2 - 1;
    switch (s) {
    case Scale::ordinary: return (float)(u * 10);
    case Scale::tiny: return (float)(u * 1e-30);
    case Scale::huge: return (float)(u * 1e30);
    case Scale::subnormal: return (float)(u * 1e-39);
    case Scale::mixed: {
        static const double scales[] = {1e-38, 1e-30, 1e-20, 1e-10, 1,
                                        1e10,  1e19,  1e20,  1e30,  3e38};
        return (float)(u * scales[rng.below(10)]);
    }
    case Scale::nasty: {
        static const float special[] = {0.0f,
                                        -0.0f,
                                        1.0f,
                                        -1.0f,
                                        FLT_MIN,
                                        -FLT_MIN,
                                        FLT_TRUE_MIN,
                                        -FLT_TRUE_MIN,
                                        FLT_MAX,
                                        -FLT_MAX,
                                        std::numeric_limits<float>::infinity(),
                                        -std::numeric_limits<float>::infinity(),
                                        std::numeric_limits<float>::quiet_NaN(),
                                        1e-30f,
                                        1e30f};
        if (rng.chance(0.4)) return special[rng.below(sizeof special / sizeof special[0])];
        return (float)(u * 100);
    }
    }
    return 0;
}

struct Mesh {
    std::vector<float> positions;
    std::vector<int> indices;
    int triangles() const { return (int)(indices.size() / 3); }
    int vertices() const { return (int)(positions.size() / 3); }
};

// A random mesh: random corners, some triangles degenerate on purpose
// (repeated corner, collinear corners, a copy of another vertex).
Mesh random_mesh(Rng &rng, int numVerts, int numTris, Scale s) {
    Mesh m;
    m.positions.resize(3 * (size_t)numVerts);
    for (auto &f : m.positions) f = coordinate(rng, s);
    // A few collinear and coincident vertices.
    for (int v = 2; v < numVerts; v++) {
        if (rng.chance(0.05)) { // v on the line through v-2 and v-1
            const float k = (float)rng.below(5);
            for (int c = 0; c < 3; c++) {
                const float a = m.positions[3 * (v - 2) + c], b = m.positions[3 * (v - 1) + c];
                m.positions[3 * v + c] = a + (b - a) * k;
            }
        } else if (rng.chance(0.05)) {
            for (int c = 0; c < 3; c++) m.positions[3 * v + c] = m.positions[3 * (v - 1) + c];
        }
    }
    m.indices.resize(3 * (size_t)numTris);
    for (int t = 0; t < numTris; t++) {
        for (int k = 0; k < 3; k++) m.indices[3 * t + k] = (int)rng.below((uint32_t)numVerts);
        if (rng.chance(0.05)) m.indices[3 * t + 1] = m.indices[3 * t]; // zero area
        if (rng.chance(0.02)) m.indices[3 * t + 2] = m.indices[3 * t + 1];
    }
    // Vertex 0 and the last vertex are used: the loads nearest the fences.
    if (numTris > 0) {
        m.indices[0] = 0;
        m.indices[3 * (size_t)numTris - 1] = numVerts - 1;
    }
    return m;
}

bool same_bits(const Plane &a, const Plane &b) { return std::memcmp(&a, &b, sizeof a) == 0; }

std::string plane_str(const Plane &p) {
    char buf[160];
    std::snprintf(buf, sizeof buf, "(%a, %a, %a, %a)", p.a, p.b, p.c, p.d);
    return buf;
}

// Runs every variant on M (its positions copied against fenced pages) and
// compares with the reference bit for bit; guard bytes after the planes
// and the facing bytes must survive.
void check_mesh(const Mesh &m, const std::vector<const sv_planes_variant *> &variants, Rng &rng,
                const std::string &what) {
    const int n = m.triangles();
    FencedPositions fenced(m.positions.size());
    ASSERT_TRUE(fenced.ok());
    std::memcpy(fenced.data(), m.positions.data(), m.positions.size() * sizeof(float));
    const float *pos = fenced.data();

    std::vector<Plane> ref((size_t)n);
    sv_derive_planes_c_ref(pos, m.indices.data(), n, ref.data());
    for (int t = 0; t < n; t++) {
        ASSERT_FALSE(std::isnan(ref[t].a) || std::isnan(ref[t].b) || std::isnan(ref[t].c) ||
                     std::isnan(ref[t].d))
            << what << ": reference plane " << t << " has a NaN";
    }
    Vec4 lights[3] = {{coordinate(rng, Scale::ordinary), coordinate(rng, Scale::ordinary),
                       coordinate(rng, Scale::ordinary), 1.0f},
                      {coordinate(rng, Scale::ordinary), 5.0f, -2.0f, 0.0f},
                      {0.0f, 0.0f, 0.0f, 1.0f}};
    if (n > 0) { // a light exactly on a vertex: the facing sum is 0
        const int v = m.indices[0];
        lights[2] = Vec4{m.positions[3 * v], m.positions[3 * v + 1], m.positions[3 * v + 2], 1.0f};
    }
    std::vector<uint8_t> refFacing[3];
    for (int l = 0; l < 3; l++) {
        refFacing[l].assign((size_t)n + 1, 0xEE);
        sv_facing_from_positions_c_ref(pos, m.indices.data(), n, &lights[l], refFacing[l].data());
        ASSERT_EQ(refFacing[l][n], 1);
    }

    for (const sv_planes_variant *v : variants) {
        SCOPED_TRACE(what + ", variant " + v->name + ", " + std::to_string(n) + " triangles");
        const size_t offset = rng.below(16) * 4; // any float alignment
        GuardedBuffer out((size_t)n * sizeof(Plane), offset);
        out.fill(0xCD);
        v->derive_planes(pos, m.indices.data(), n, reinterpret_cast<Plane *>(out.data()));
        ASSERT_TRUE(out.guards_intact()) << "wrote outside planes[0.." << n << ")";
        for (int t = 0; t < n; t++) {
            Plane got;
            std::memcpy(&got, out.data() + (size_t)t * sizeof(Plane), sizeof got);
            ASSERT_TRUE(same_bits(got, ref[t]))
                << "plane " << t << ": " << plane_str(got) << ", reference " << plane_str(ref[t]);
        }
        for (int l = 0; l < 3; l++) {
            GuardedBuffer f((size_t)n + 1, rng.below(64));
            f.fill(0xEE);
            v->facing_from_positions(pos, m.indices.data(), n, &lights[l], f.data());
            ASSERT_TRUE(f.guards_intact()) << "facing: wrote outside facing[0.." << n << "]";
            for (int t = 0; t <= n; t++)
                ASSERT_EQ(f.data()[t], refFacing[l][t]) << "facing byte " << t << ", light " << l;
        }
    }
}

TEST(Planes, TableAndDispatch) {
    int n = 0;
    const sv_planes_variant *all = sv_planes_variants(&n);
    ASSERT_EQ(n, 5);
    EXPECT_STREQ(all[0].name, "c_ref");
    EXPECT_EQ(all[0].isa, (unsigned)SV_ISA_NONE);
    for (int i = 0; i < n; i++) {
        EXPECT_EQ(sv_planes_variant_by_name(all[i].name), &all[i]);
        EXPECT_NE(all[i].derive_planes, nullptr);
        EXPECT_NE(all[i].facing_from_positions, nullptr);
    }
    EXPECT_EQ(sv_planes_variant_by_name("nope"), nullptr);
    EXPECT_EQ(sv_planes_variant_by_name(nullptr), nullptr);
    const sv_planes_variant *best = sv_best_planes_variant();
    ASSERT_NE(best, nullptr);
    EXPECT_EQ(best->isa & sv_cpu_isa(), best->isa);
    // Under an ISA limit the best one obeys it.
    const char *saved = sv_isa_limit_name();
    ASSERT_EQ(sv_set_isa_limit("sse2"), 0);
    EXPECT_STREQ(sv_best_planes_variant()->name, "sse2");
    ASSERT_EQ(sv_set_isa_limit("c"), 0);
    EXPECT_STREQ(sv_best_planes_variant()->name, "c_ref");
    sv_set_isa_limit(saved);
}

TEST(Planes, ReferenceDocumentedResults) {
    const float pos[] = {0,
                         0,
                         0,
                         1,
                         0,
                         0,
                         0,
                         1,
                         0,
                         2,
                         0,
                         0,
                         1e-30f,
                         0,
                         0,
                         0,
                         1e-30f,
                         0,
                         std::numeric_limits<float>::quiet_NaN(),
                         0,
                         0,
                         1e30f,
                         0,
                         0,
                         0,
                         1e30f,
                         0};
    // Ordinary: z = 0 plane facing +z; degenerate ones give (0,0,0,0).
    const int idx[] = {0, 1, 2,  // unit right triangle: (0, 0, 1, 0)
                       0, 1, 3,  // collinear
                       0, 0, 2,  // repeated corner
                       0, 4, 5,  // cross product 1e-60 underflows: zero plane
                       6, 1, 2,  // NaN corner
                       0, 7, 8}; // 1e60 overflows: zero plane
    Plane p[6];
    sv_derive_planes_c_ref(pos, idx, 6, p);
    const Plane z{0, 0, 0, 0};
    EXPECT_TRUE(same_bits(p[0], (Plane{0, 0, 1, -0.0f}))) << plane_str(p[0]);
    for (int t = 1; t < 6; t++) EXPECT_TRUE(same_bits(p[t], z)) << t << ": " << plane_str(p[t]);
    // sv::triangle_plane (double) still finds the tiny and huge triangles'
    // normal: the documented difference.
    const Plane dtiny = sv::triangle_plane(&pos[0], &pos[12], &pos[15]);
    EXPECT_EQ(dtiny.c, 1.0f);
    // Negative counts write nothing.
    Plane guard{1, 2, 3, 4};
    sv_derive_planes_c_ref(pos, idx, -1, &guard);
    EXPECT_TRUE(same_bits(guard, (Plane{1, 2, 3, 4})));
    uint8_t f[2] = {7, 7};
    const Vec4 l{0, 0, 5, 1};
    sv_facing_from_positions_c_ref(pos, idx, -3, &l, f);
    EXPECT_EQ(f[0], 7);
    sv_facing_from_positions_c_ref(pos, idx, 1, &l, f);
    EXPECT_EQ(f[0], 1);
    EXPECT_EQ(f[1], 1);
}

TEST(Planes, ReferenceAgreesWithTrianglePlane) {
    SCOPED_TRACE(svtest::seed_trace());
    Rng rng = svtest::rng_for("ReferenceAgreesWithTrianglePlane");
    const Mesh m = random_mesh(rng, 300, 2000, Scale::ordinary);
    std::vector<Plane> p(2000);
    sv_derive_planes_c_ref(m.positions.data(), m.indices.data(), 2000, p.data());
    int compared = 0;
    for (int t = 0; t < 2000; t++) {
        const int *i = &m.indices[3 * t];
        const Plane q = sv::triangle_plane(&m.positions[3 * i[0]], &m.positions[3 * i[1]],
                                           &m.positions[3 * i[2]]);
        const double nn = (double)q.a * q.a + (double)q.b * q.b + (double)q.c * q.c;
        if (nn == 0) {
            EXPECT_TRUE(same_bits(p[t], (Plane{0, 0, 0, 0})));
            continue;
        }
        // Slivers: the float cross product cancels; compare well-shaped ones.
        const float *a = &m.positions[3 * i[0]], *b = &m.positions[3 * i[1]],
                    *c = &m.positions[3 * i[2]];
        double e[3][3];
        for (int k = 0; k < 3; k++) {
            e[0][k] = (double)b[k] - a[k];
            e[1][k] = (double)c[k] - a[k];
            e[2][k] = (double)c[k] - b[k];
        }
        const double nx = e[0][1] * e[1][2] - e[0][2] * e[1][1];
        const double ny = e[0][2] * e[1][0] - e[0][0] * e[1][2];
        const double nz = e[0][0] * e[1][1] - e[0][1] * e[1][0];
        const double area2 = std::sqrt(nx * nx + ny * ny + nz * nz);
        double longest = 0;
        for (auto &ed : e)
            longest = std::max(longest, std::sqrt(ed[0] * ed[0] + ed[1] * ed[1] + ed[2] * ed[2]));
        if (area2 < 1e-2 * longest * longest) continue;
        compared++;
        EXPECT_NEAR(p[t].a, q.a, 1e-5);
        EXPECT_NEAR(p[t].b, q.b, 1e-5);
        EXPECT_NEAR(p[t].c, q.c, 1e-5);
        EXPECT_NEAR(p[t].d, q.d, 1e-4);
    }
    EXPECT_GT(compared, 1000);
}

SV_TIERED_TEST(Planes, EveryTailEveryScale) {
    SCOPED_TRACE(svtest::seed_trace());
    Rng rng = svtest::rng_for("EveryTailEveryScale");
    const auto variants = runnable();
    const Scale scales[] = {Scale::ordinary,  Scale::tiny,  Scale::huge,
                            Scale::subnormal, Scale::mixed, Scale::nasty};
    const char *names[] = {"ordinary", "tiny", "huge", "subnormal", "mixed", "nasty"};
    for (int s = 0; s < 6; s++) {
        for (int n = 0; n <= 40; n++) {
            const int verts = 1 + (int)rng.below(3 * (uint32_t)n + 3);
            const Mesh m = random_mesh(rng, verts, n, scales[s]);
            check_mesh(m, variants, rng, std::string(names[s]) + " mesh");
            if (HasFatalFailure()) return;
        }
        for (int n : {255, 256, 257, 1000, 4099}) {
            const Mesh m = random_mesh(rng, 1 + (int)rng.below(2 * (uint32_t)n), n, scales[s]);
            check_mesh(m, variants, rng, std::string(names[s]) + " mesh");
            if (HasFatalFailure()) return;
        }
    }
}

SV_TIERED_TEST(Planes, FlushToZeroToo) {
    // FTZ/DAZ change the results of subnormal inputs; both sides alike.
    SCOPED_TRACE(svtest::seed_trace());
    Rng rng = svtest::rng_for("FlushToZeroToo");
    const auto variants = runnable();
    const unsigned saved = _mm_getcsr();
    _mm_setcsr(saved | 0x8040);
    for (int n : {7, 33, 500}) {
        const Mesh m = random_mesh(rng, n, n, Scale::subnormal);
        check_mesh(m, variants, rng, "subnormal, FTZ/DAZ");
        const Mesh m2 = random_mesh(rng, n, n, Scale::mixed);
        check_mesh(m2, variants, rng, "mixed, FTZ/DAZ");
    }
    _mm_setcsr(saved);
}

SV_TIERED_TEST(Planes, NegativeCountsWriteNothing) {
    const float pos[9] = {0, 0, 0, 1, 0, 0, 0, 1, 0};
    const int idx[3] = {0, 1, 2};
    const Vec4 l{0, 0, 1, 1};
    for (const sv_planes_variant *v : runnable()) {
        for (int n : {-1, -8, -17, std::numeric_limits<int>::min()}) {
            GuardedBuffer out(64, 0);
            out.fill(0x5A);
            v->derive_planes(pos, idx, n, out.as<Plane>());
            for (size_t i = 0; i < out.size(); i++) ASSERT_EQ(out.data()[i], 0x5A) << v->name;
            EXPECT_TRUE(out.guards_intact()) << v->name;
            v->facing_from_positions(pos, idx, n, &l, out.data());
            for (size_t i = 0; i < out.size(); i++) ASSERT_EQ(out.data()[i], 0x5A) << v->name;
            EXPECT_TRUE(out.guards_intact()) << v->name;
        }
    }
}

// Vertex 0 at the very start of a page after an inaccessible one, used
// by every corner of every lane of several blocks (the avx2 derive kernel
// loads each corner from one float before the vertex, masked): nothing
// faults, every plane bit-identical. And meshes whose triangles are all
// degenerate, or degenerate in one lane position only, over several
// blocks of 256 triangles (every lane of the SIMD step rewritten by the
// scalar reference).
SV_TIERED_TEST(Planes, VertexZeroAtPageStartAndDegenerateLanes) {
    SCOPED_TRACE(svtest::seed_trace());
    Rng rng = svtest::rng_for("VertexZeroAtPageStart");
    const auto variants = runnable();
    for (int n : {8, 64, 263, 600}) {
        Mesh m = random_mesh(rng, 40, n, Scale::ordinary);
        for (int t = 0; t < n; t++) m.indices[3 * t + (t % 3)] = 0;
        FencedPositions fenced(m.positions.size(), true);
        ASSERT_TRUE(fenced.ok());
        std::memcpy(fenced.data(), m.positions.data(), m.positions.size() * sizeof(float));
        std::vector<Plane> ref((size_t)n);
        sv_derive_planes_c_ref(fenced.data(), m.indices.data(), n, ref.data());
        for (const sv_planes_variant *v : variants) {
            std::vector<Plane> got((size_t)n);
            v->derive_planes(fenced.data(), m.indices.data(), n, got.data());
            for (int t = 0; t < n; t++)
                ASSERT_TRUE(same_bits(got[t], ref[t])) << v->name << ", plane " << t;
        }
    }
    for (int lane = -1; lane < 8; lane++) {
        Mesh m = random_mesh(rng, 50, 777, Scale::ordinary);
        for (int t = 0; t < 777; t++) {
            if (lane < 0 || t % 8 == lane) m.indices[3 * t + 1] = m.indices[3 * t];
        }
        check_mesh(m, variants, rng, "degenerate lane " + std::to_string(lane));
        if (HasFatalFailure()) return;
    }
}

// The files of model set SET (svtest::model_sets()): the bundled
// character, or NAMES in the shared folder, those not readable listed in
// MISSING.
std::vector<std::string> model_files(const std::string &set,
                                     std::initializer_list<const char *> names,
                                     std::string *missing) {
    std::vector<std::string> files;
    if (set == "bundled") files.push_back(std::string(SV_MODELS_DIR) + "/character_1344.glb");
    if (set != "SharedModels") return files;
    for (const char *name : names) {
        const std::string p = svtest::shared_models_dir() + "/" + name;
        if (access(p.c_str(), R_OK) == 0)
            files.push_back(p);
        else
            *missing += " " + p;
    }
    return files;
}

// The project's character and the real characters (when their folder is
// there): every variant bit-identical on real index orders.
// Once per model set: the bundled character, and the real characters of
// ../shared/models (the SharedModels instance runs in the shared-models
// ctest entry, tests/support/test_conditions.h; a character missing there skips).
class PlanesModels : public ::testing::TestWithParam<std::string> {};
INSTANTIATE_TEST_SUITE_P(ModelSets, PlanesModels, ::testing::ValuesIn(svtest::model_sets()),
                         svtest::param_name);

SV_TIERED_TEST_P(PlanesModels, RealMeshes) {
    SCOPED_TRACE(svtest::seed_trace());
    Rng rng = svtest::rng_for("RealMeshes");
    const auto variants = runnable();
    std::string missing;
    const std::vector<std::string> files = model_files(GetParam(),
                                                       {"Fox.glb", "CesiumMan.glb",
                                                        "RobotExpressive.glb", "RiggedFigure.glb"},
                                                       &missing);
    for (const std::string &f : files) {
        const sv::GltfModel model = sv::load_gltf(f);
        for (const sv::GltfSurface &s : model.surfaces) {
            Mesh m;
            m.positions = s.positions;
            m.indices.assign(s.indices.begin(), s.indices.end());
            check_mesh(m, variants, rng, f + " " + s.name);
            if (HasFatalFailure()) return;
        }
    }
    if (!missing.empty()) GTEST_SKIP() << "not found, not tested:" << missing;
}

// ---- Planes by clusters ----------------------------------------------------

std::vector<const sv_planes_clustered_variant *> runnable_clustered() {
    int n = 0;
    const sv_planes_clustered_variant *all = sv_planes_clustered_variants(&n);
    std::vector<const sv_planes_clustered_variant *> out;
    for (int i = 0; i < n; i++) {
        if (svtest::in_this_run(all[i].isa, all[i].name)) out.push_back(&all[i]);
    }
    return out;
}

// The contract of include/shadowvol_planes.h ("Planes by clusters") for
// the clusters of M.
void check_clusters(const Mesh &m, const sv::PlaneClusters &c, const std::string &what) {
    SCOPED_TRACE(what);
    const int n = m.triangles();
    ASSERT_EQ(c.vertex_begin.size(), c.group_begin.size());
    ASSERT_EQ(c.vertex_begin.front(), 0);
    ASSERT_EQ(c.group_begin.front(), 0);
    ASSERT_EQ((std::size_t)c.vertex_begin.back(), c.vertex_offsets.size());
    ASSERT_EQ(16 * (std::size_t)c.group_begin.back(), c.plane_offsets.size());
    ASSERT_EQ(48 * (std::size_t)c.group_begin.back(), c.corners.size());
    std::vector<int> seen((std::size_t)n, 0);
    for (int k = 0; k < c.num_clusters(); k++) {
        std::vector<int> list;
        for (int i = c.vertex_begin[(std::size_t)k]; i < c.vertex_begin[(std::size_t)k + 1]; i++) {
            ASSERT_EQ(c.vertex_offsets[(std::size_t)i] % 12, 0u);
            list.push_back((int)(c.vertex_offsets[(std::size_t)i] / 12));
        }
        const int size = c.vertex_begin[(std::size_t)k + 1] - c.vertex_begin[(std::size_t)k];
        ASSERT_TRUE(size == 16 || size == 32) << "cluster " << k << ": list of " << size;
        // The real vertices first, distinct; then copies of the first.
        int real = 1;
        while (real < size && list[real] != list[0]) real++;
        for (int i = real; i < size; i++) ASSERT_EQ(list[i], list[0]) << "cluster " << k;
        std::vector<int> sorted(list.begin(), list.begin() + real);
        std::sort(sorted.begin(), sorted.end());
        ASSERT_EQ(std::adjacent_find(sorted.begin(), sorted.end()), sorted.end())
            << "cluster " << k << ": a vertex twice";
        const int g0 = c.group_begin[(std::size_t)k], g1 = c.group_begin[(std::size_t)k + 1];
        ASSERT_LT(g0, g1) << "cluster " << k << ": no triangles";
        int last = -1;
        for (int g = g0; g < g1; g++) {
            for (int i = 0; i < 16; i++) {
                ASSERT_EQ(c.plane_offsets[16 * (std::size_t)g + (std::size_t)i] % 16, 0u);
                const int t = (int)(c.plane_offsets[16 * (std::size_t)g + (std::size_t)i] / 16);
                ASSERT_TRUE(t >= 0 && t < n) << "cluster " << k << ": triangle " << t;
                for (int corner = 0; corner < 3; corner++) {
                    const int place =
                        c.corners[48 * (std::size_t)g + 16 * (std::size_t)corner + (std::size_t)i];
                    ASSERT_LT(place, real) << "cluster " << k << ", triangle " << t;
                    ASSERT_EQ(list[place], m.indices[3 * (std::size_t)t + (std::size_t)corner])
                        << "cluster " << k << ", triangle " << t << ", corner " << corner;
                }
                if (t == last) { // filling: only at the end of the last group
                    ASSERT_EQ(g, g1 - 1) << "cluster " << k << ": a triangle repeated";
                    for (int j = i; j < 16; j++)
                        ASSERT_EQ(c.plane_offsets[16 * (std::size_t)g + (std::size_t)j],
                                  16u * (uint32_t)t);
                    break;
                }
                seen[(std::size_t)t]++;
                last = t;
            }
        }
    }
    for (int t = 0; t < n; t++) ASSERT_EQ(seen[(std::size_t)t], 1) << "triangle " << t;
}

// Every clustered kernel against sv_derive_planes_c_ref on M: positions
// against fenced pages, planes between guard bytes, through the ABI
// checker.
void check_clustered_mesh(const Mesh &m, Rng &rng, const std::string &what) {
    const int n = m.triangles();
    const sv::PlaneClusters c = sv::plane_clusters(m.indices.data(), n, m.vertices());
    check_clusters(m, c, what);
    if (::testing::Test::HasFatalFailure()) return;
    const sv_plane_clusters view = c.view();
    FencedPositions fenced(m.positions.size(), rng.chance(0.5));
    ASSERT_TRUE(fenced.ok());
    std::memcpy(fenced.data(), m.positions.data(), m.positions.size() * sizeof(float));
    std::vector<Plane> ref((size_t)n);
    sv_derive_planes_c_ref(fenced.data(), m.indices.data(), n, ref.data());
    for (const sv_planes_clustered_variant *v : runnable_clustered()) {
        SCOPED_TRACE(what + ", " + v->name + ", " + std::to_string(n) + " triangles");
        GuardedBuffer out((size_t)n * sizeof(Plane), rng.below(16) * 4);
        out.fill(0xCD);
        svtest::checked_call(rng, v->derive_planes, (const float *)fenced.data(), &view,
                             out.as<Plane>());
        ASSERT_TRUE(out.guards_intact()) << "wrote outside planes[0.." << n << ")";
        for (int t = 0; t < n; t++) {
            Plane got;
            std::memcpy(&got, out.data() + (size_t)t * sizeof(Plane), sizeof got);
            ASSERT_TRUE(same_bits(got, ref[(size_t)t]))
                << "plane " << t << ": " << plane_str(got) << ", reference "
                << plane_str(ref[(size_t)t]);
        }
    }
}

SV_TIERED_TEST(PlaneClusters, RefusesBadInputAndBuildsNothingForNothing) {
    const int idx[6] = {0, 1, 2, 2, 1, 3};
    EXPECT_THROW(sv::plane_clusters(idx, -1, 4), sv::PrepareError);
    EXPECT_THROW(sv::plane_clusters(idx, 2, 3), sv::PrepareError); // index 3 of 3 vertices
    const int neg[3] = {0, -1, 2};
    EXPECT_THROW(sv::plane_clusters(neg, 1, 3), sv::PrepareError);
    EXPECT_THROW(sv::plane_clusters(nullptr, 1, 3), sv::PrepareError);
    const sv::PlaneClusters none = sv::plane_clusters(nullptr, 0, 0);
    EXPECT_EQ(none.num_clusters(), 0);
    const sv_plane_clusters view = none.view();
    Plane guard{1, 2, 3, 4};
    for (const sv_planes_clustered_variant *v : runnable_clustered()) {
        v->derive_planes(nullptr, &view, &guard);
        EXPECT_TRUE(same_bits(guard, (Plane{1, 2, 3, 4}))) << v->name;
    }
    EXPECT_NE(sv_planes_clustered_variant_by_name("c_ref"), nullptr);
    EXPECT_EQ(sv_planes_clustered_variant_by_name("avx2"), nullptr);
    EXPECT_EQ(sv_planes_clustered_variant_by_name(nullptr), nullptr);
}

// Random meshes of every size 0..40 and larger ones (a cluster's last
// group at every fill), every scale and degenerate triangles; random
// meshes are the clusters' worst case: few shared corners.
SV_TIERED_TEST(PlaneClusters, EveryKernelBitIdenticalOnRandomMeshes) {
    SCOPED_TRACE(svtest::seed_trace());
    Rng rng = svtest::rng_for("PlaneClustersRandom");
    const Scale scales[] = {Scale::ordinary,  Scale::tiny,  Scale::huge,
                            Scale::subnormal, Scale::mixed, Scale::nasty};
    for (Scale s : scales) {
        for (int n = 0; n <= 40; n++) {
            const Mesh m = random_mesh(rng, 1 + (int)rng.below(3 * (uint32_t)n + 3), n, s);
            check_clustered_mesh(m, rng, "random mesh, scale " + std::to_string((int)s));
            if (HasFatalFailure()) return;
        }
        for (int n : {257, 1000}) {
            // Few vertices: many triangles share them (dense clusters).
            const Mesh m = random_mesh(rng, 1 + (int)rng.below(40), n, s);
            check_clustered_mesh(m, rng, "dense random mesh");
            if (HasFatalFailure()) return;
        }
    }
}

// The real characters: the clusters hold many triangles (the point of
// them: measured 30 to 42 per cluster of at most 32 vertices over a whole
// character; a surface of many small shells, as RobotExpressive's head,
// about 22) and every kernel is bit-identical.
class PlaneClustersModels : public ::testing::TestWithParam<std::string> {};
INSTANTIATE_TEST_SUITE_P(ModelSets, PlaneClustersModels, ::testing::ValuesIn(svtest::model_sets()),
                         svtest::param_name);

SV_TIERED_TEST_P(PlaneClustersModels, RealMeshesDenseAndBitIdentical) {
    SCOPED_TRACE(svtest::seed_trace());
    Rng rng = svtest::rng_for("PlaneClustersModels");
    std::string missing;
    const std::vector<std::string> files = model_files(GetParam(),
                                                       {"Fox.glb", "CesiumMan.glb",
                                                        "RobotExpressive.glb", "RiggedFigure.glb",
                                                        "open/Zombie_Basic.glb"},
                                                       &missing);
    for (const std::string &f : files) {
        const sv::GltfModel model = sv::load_gltf(f);
        int triangles = 0, clusters = 0;
        for (const sv::GltfSurface &gs : model.surfaces) {
            const sv::PreparedSurface p = sv::prepare_surface(gs.positions.data(),
                                                              gs.num_vertices(), gs.indices.data(),
                                                              gs.indices.size());
            Mesh m;
            m.positions = p.positions;
            m.indices.assign(p.indices.begin(), p.indices.end());
            const sv::PlaneClusters c = sv::plane_clusters(m.indices.data(), m.triangles(),
                                                           m.vertices());
            triangles += m.triangles();
            clusters += c.num_clusters();
            check_clustered_mesh(m, rng, f + " " + gs.name);
            if (HasFatalFailure()) return;
        }
        EXPECT_GE((double)triangles / clusters, 28.0)
            << f << ": " << clusters << " clusters for " << triangles << " triangles";
    }
    if (!missing.empty()) GTEST_SKIP() << "not found, not tested:" << missing;
}

} // namespace
