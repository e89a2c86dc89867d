// Per-surface preparation (include/shadowvol_mesh.h): welding, degenerate
// triangles, the SilEdge convention, the non-manifold pairing rule, planes,
// the shadow vertex buffers, bad input, and the CLOSED-VOLUME property: for
// many lights (with and without cull bits, and with random facing) every
// directed edge of the volume from every runnable variant appears exactly as
// often as its reverse.
//
// Copyright (C) 2026 the shadowvol authors. LGPL-2.1-or-later.
#include "test_support.h"

#include "shadowvol_mesh.h"
#include "shadowvol_verify.h"

#include <algorithm>
#include <cmath>
#include <map>

namespace {

using svtest::Rng;

struct Mesh {
    std::vector<float> pos;
    std::vector<uint32_t> idx;
    uint32_t v(float x, float y, float z) {
        pos.insert(pos.end(), {x, y, z});
        return (uint32_t)(pos.size() / 3 - 1);
    }
    void tri(uint32_t a, uint32_t b, uint32_t c) { idx.insert(idx.end(), {a, b, c}); }
};

sv::PreparedSurface prep(const Mesh &m) {
    return sv::prepare_surface(m.pos.data(), m.pos.size() / 3, m.idx.data(), m.idx.size());
}

// A unit cube split at its UV seams: 4 vertices per face (24), CCW from outside.
Mesh cube24() {
    Mesh m;
    const float s[6][4][3] = {
        {{0, 0, 1}, {1, 0, 1}, {1, 1, 1}, {0, 1, 1}}, // +z
        {{1, 0, 0}, {0, 0, 0}, {0, 1, 0}, {1, 1, 0}}, // -z
        {{1, 0, 1}, {1, 0, 0}, {1, 1, 0}, {1, 1, 1}}, // +x
        {{0, 0, 0}, {0, 0, 1}, {0, 1, 1}, {0, 1, 0}}, // -x
        {{0, 1, 1}, {1, 1, 1}, {1, 1, 0}, {0, 1, 0}}, // +y
        {{0, 0, 0}, {1, 0, 0}, {1, 0, 1}, {0, 0, 1}}, // -y
    };
    for (auto &f : s) {
        uint32_t a = m.v(f[0][0], f[0][1], f[0][2]), b = m.v(f[1][0], f[1][1], f[1][2]),
                 c = m.v(f[2][0], f[2][1], f[2][2]), d = m.v(f[3][0], f[3][1], f[3][2]);
        m.tri(a, b, c);
        m.tri(a, c, d);
    }
    return m;
}

Mesh tetrahedron() {
    Mesh m;
    uint32_t a = m.v(0, 0, 0), b = m.v(1, 0, 0), c = m.v(0, 1, 0), d = m.v(0, 0, 1);
    m.tri(a, c, b);
    m.tri(a, b, d);
    m.tri(a, d, c);
    m.tri(b, c, d);
    return m;
}

// A torus of nu x nv quads with a seam: (nu+1) x (nv+1) input vertices, the
// last row and column repeating the first bit for bit (positions computed
// from the index mod n), so welding leaves nu * nv.
Mesh torus(int nu, int nv) {
    Mesh m;
    const double R = 2.0, r = 0.5, tau = 6.283185307179586;
    for (int i = 0; i <= nu; i++) {
        for (int j = 0; j <= nv; j++) {
            double u = tau * (i % nu) / nu, w = tau * (j % nv) / nv;
            m.v((float)((R + r * std::cos(w)) * std::cos(u)),
                (float)((R + r * std::cos(w)) * std::sin(u)), (float)(r * std::sin(w)));
        }
    }
    auto id = [&](int i, int j) { return (uint32_t)(i * (nv + 1) + j); };
    for (int i = 0; i < nu; i++) {
        for (int j = 0; j < nv; j++) {
            m.tri(id(i, j), id(i + 1, j), id(i + 1, j + 1));
            m.tri(id(i, j), id(i + 1, j + 1), id(i, j + 1));
        }
    }
    return m;
}

struct Counts {
    int64_t welded, tris, degenerate, edges, boundary, manifold, same_dir, non_manifold, sil,
        dangling;
};

void expect_counts(const sv::PrepareReport &r, const Counts &c) {
    EXPECT_EQ(r.welded_vertices, c.welded);
    EXPECT_EQ(r.triangles, c.tris);
    EXPECT_EQ(r.degenerate_dropped, c.degenerate);
    EXPECT_EQ(r.triangles_in - r.degenerate_dropped, r.triangles);
    EXPECT_EQ(r.edges, c.edges);
    EXPECT_EQ(r.boundary_edges, c.boundary);
    EXPECT_EQ(r.manifold_edges, c.manifold);
    EXPECT_EQ(r.same_direction_edges, c.same_dir);
    EXPECT_EQ(r.non_manifold_edges, c.non_manifold);
    EXPECT_EQ(r.sil_edges, c.sil);
    EXPECT_EQ(r.dangling_sil_edges, c.dangling);
}

// The paper's convention, and "every use in exactly one SilEdge".
void check_structure(const sv::PreparedSurface &s) {
    const int nt = s.num_triangles(), nv = s.num_vertices();
    ASSERT_EQ(s.planes.size(), (size_t)nt);
    ASSERT_EQ(s.triangle_source.size(), (size_t)nt);
    ASSERT_EQ((int64_t)s.sil_edges.size(), s.report.sil_edges);
    ASSERT_EQ((uintptr_t)s.indices.data() % 64, 0u);
    ASSERT_EQ((uintptr_t)s.planes.data() % 64, 0u);
    for (int i : s.indices) {
        ASSERT_TRUE(i >= 0 && i < nv);
    }
    for (int t = 0; t < nt; t++) {
        const int *x = &s.indices[3 * t];
        ASSERT_TRUE(x[0] != x[1] && x[1] != x[2] && x[2] != x[0]) << "degenerate kept: " << t;
    }
    // Which corner of triangle t runs a -> b (-1: none).
    auto corner = [&](int t, int a, int b) {
        for (int c = 0; c < 3; c++) {
            if (s.indices[3 * t + c] == a && s.indices[3 * t + (c + 1) % 3] == b) return c;
        }
        return -1;
    };
    std::vector<int> used((size_t)nt * 3, 0);
    int64_t dangling = 0;
    for (size_t k = 0; k < s.sil_edges.size(); k++) {
        const SilEdge &e = s.sil_edges[k];
        ASSERT_TRUE(e.v1 % 2 == 0 && e.v2 % 2 == 0) << "edge " << k;
        ASSERT_TRUE(e.v1 >= 0 && e.v1 < 2 * nv && e.v2 >= 0 && e.v2 < 2 * nv) << "edge " << k;
        ASSERT_TRUE(e.p1 >= 0 && e.p1 < nt) << "edge " << k;
        ASSERT_TRUE(e.p2 >= 0 && e.p2 <= nt) << "edge " << k;
        int c1 = corner(e.p1, e.v1 / 2, e.v2 / 2);
        ASSERT_GE(c1, 0) << "edge " << k << ": v1->v2 not counter-clockwise in p1";
        used[3 * e.p1 + c1]++;
        if (e.p2 == nt) {
            dangling++;
        } else {
            int c2 = corner(e.p2, e.v2 / 2, e.v1 / 2);
            ASSERT_GE(c2, 0) << "edge " << k << ": v2->v1 not in p2 (clockwise)";
            used[3 * e.p2 + c2]++;
        }
    }
    EXPECT_EQ(dangling, s.report.dangling_sil_edges);
    for (size_t u = 0; u < used.size(); u++) {
        ASSERT_EQ(used[u], 1) << "use " << u << " (triangle " << u / 3 << ") is in " << used[u]
                              << " SilEdges";
    }
}

float rnd(Rng &rng, float lo, float hi) { return lo + (hi - lo) * (float)rng.unit(); }

// A light box as six inward planes (plane i <-> cull bit i).
void box_planes(const float c[3], const float h[3], Plane p[6]) {
    for (int a = 0; a < 3; a++) {
        float n[3] = {0, 0, 0};
        n[a] = 1;
        p[2 * a] = {n[0], n[1], n[2], -(c[a] - h[a])};     // x >= c - h
        p[2 * a + 1] = {-n[0], -n[1], -n[2], c[a] + h[a]}; // x <= c + h
    }
}

enum class Cull { none, light_box, random_bits };

// Builds the volume of S for LIGHT with every runnable variant and checks
// it closed and equal to c_ref's. facing_override: random facing bytes
// instead of the light's.
void check_closed_for(const sv::PreparedSurface &s, const Vec4 &light, Cull cull, Rng &rng,
                      bool random_facing, const std::string &what) {
    const int nt = s.num_triangles(), nv = s.num_vertices();
    sv::AlignedVector<uint8_t> facing0((size_t)nt + 1);
    sv_calculate_facing_c_ref(s.planes.data(), nt, &light, facing0.data());
    if (random_facing) {
        for (int t = 0; t < nt; t++) facing0[t] = (uint8_t)rng.below(2);
    }
    std::vector<uint8_t> cull_bits;
    const uint8_t *cb = nullptr;
    if (cull == Cull::light_box) {
        Bounds b = sv::surface_bounds(s);
        float c[3] = {b.center.x + b.extents.x * rnd(rng, -1.5f, 1.5f),
                      b.center.y + b.extents.y * rnd(rng, -1.5f, 1.5f),
                      b.center.z + b.extents.z * rnd(rng, -1.5f, 1.5f)};
        float h[3] = {b.extents.x * rnd(rng, 0.05f, 2), b.extents.y * rnd(rng, 0.05f, 2),
                      b.extents.z * rnd(rng, 0.05f, 2)};
        Plane planes[6];
        box_planes(c, h, planes);
        std::vector<Vec4> p4((size_t)nv);
        for (int v = 0; v < nv; v++) {
            p4[v] = {s.positions[3 * v], s.positions[3 * v + 1], s.positions[3 * v + 2], 1};
        }
        cull_bits.assign((size_t)nv, 0xEE);
        if (!sv_calculate_cull_bits_c_ref(p4.data(), nv, &b, planes, cull_bits.data())) {
            cb = cull_bits.data(); // else: completely inside, pass NULL
        }
    } else if (cull == Cull::random_bits) {
        cull_bits.resize((size_t)nv);
        for (auto &x : cull_bits) x = (uint8_t)(rng.below(4) == 0 ? 1u << rng.below(6) : 0);
        cb = cull_bits.data();
    }
    const size_t cap = sv_shadow_volume_capacity(s.num_indices(), s.num_sil_edges());
    std::vector<int> ref;
    bool have_ref = false;
    for (const sv_variant *v : svtest::runnable_variants()) {
        SCOPED_TRACE(what + ", variant " + v->name);
        sv::AlignedVector<uint8_t> facing(facing0);
        sv::AlignedVector<int> out(cap + 1, -7);
        int n = sv_create_shadow_volume(v, out.data(), s.indices.data(), s.num_indices(),
                                        s.sil_edges.data(), s.num_sil_edges(), facing.data(), cb);
        ASSERT_GE(n, 0);
        ASSERT_LE((size_t)n, cap);
        ASSERT_EQ(n % 3, 0);
        ASSERT_EQ(out[cap], -7) << "wrote past the capacity";
        // Indices in [0, 2 * nv) and every directed edge as often as its
        // reverse: the verifier's own closure check.
        const sv::ClosureResult closure = sv::check_closure(out.data(), n, nv);
        ASSERT_TRUE(closure.closed) << "volume not closed: " << closure.problem;
        std::vector<int> got(out.begin(), out.begin() + n);
        if (!have_ref) {
            ref = got;
            have_ref = true;
        } else {
            ASSERT_EQ(got, ref) << "differs from " << svtest::runnable_variants()[0]->name;
        }
    }
}

// Many lights: point lights around and inside the bounding box, directional
// lights; without culling, with a light box's cull bits, with random cull
// bits, and with random facing bytes.
void check_closed(const sv::PreparedSurface &s, const char *name, int lights = 24) {
    SCOPED_TRACE(svtest::seed_trace());
    Rng rng = svtest::rng_for(name);
    Bounds b = sv::surface_bounds(s);
    float ext = std::max({b.extents.x, b.extents.y, b.extents.z, 1e-3f});
    for (int l = 0; l < lights; l++) {
        Vec4 light;
        if (l % 4 == 3) {
            light = {rnd(rng, -1, 1), rnd(rng, -1, 1), rnd(rng, -1, 1), 0};
        } else {
            float k = (l % 4 == 0) ? 0.9f : 4.0f; // l % 4 == 0: inside the box
            light = {b.center.x + k * ext * rnd(rng, -1, 1), b.center.y + k * ext * rnd(rng, -1, 1),
                     b.center.z + k * ext * rnd(rng, -1, 1), 1};
        }
        for (Cull c : {Cull::none, Cull::light_box, Cull::random_bits}) {
            std::string what = std::string(name) + ": light " + std::to_string(l) + " (" +
                               std::to_string(light.x) + ", " + std::to_string(light.y) + ", " +
                               std::to_string(light.z) + ", " + std::to_string(light.w) +
                               "), cull " + std::to_string((int)c);
            check_closed_for(s, light, c, rng, false, what);
            if (::testing::Test::HasFatalFailure()) return;
        }
        check_closed_for(s, light, Cull::none, rng, true, std::string(name) + ": random facing");
        if (::testing::Test::HasFatalFailure()) return;
    }
}

// ---- The meshes --------------------------------------------------------

SV_TIERED_TEST(MeshPrep, CubeSplitAtSeamsWeldsTo8) {
    Mesh m = cube24();
    sv::PreparedSurface s = prep(m);
    expect_counts(s.report, {8, 12, 0, 18, 0, 18, 0, 0, 18, 0});
    EXPECT_EQ(s.report.vertices_in, 24);
    EXPECT_EQ(s.remap.size(), 24u);
    for (size_t i = 0; i < 24; i++) {
        int w = s.remap[i];
        ASSERT_TRUE(w >= 0 && w < 8);
        for (int c = 0; c < 3; c++) EXPECT_EQ(s.positions[3 * w + c], m.pos[3 * i + c]);
    }
    // Numbered by first input vertex: input 0 is welded vertex 0, ...
    EXPECT_EQ(s.remap[0], 0);
    EXPECT_EQ(s.remap[1], 1);
    // Outward planes, unit normals, every vertex of each triangle on it.
    for (int t = 0; t < 12; t++) {
        const Plane &p = s.planes[t];
        EXPECT_NEAR(p.a * p.a + p.b * p.b + p.c * p.c, 1.0, 1e-6);
        for (int c = 0; c < 3; c++) {
            const float *x = &s.positions[3 * s.indices[3 * t + c]];
            EXPECT_NEAR(p.a * x[0] + p.b * x[1] + p.c * x[2] + p.d, 0.0, 1e-6);
        }
        EXPECT_LT(p.a * 0.5f + p.b * 0.5f + p.c * 0.5f + p.d, 0.0f) << "normal points inward";
    }
    check_structure(s);
    check_closed(s, "MeshPrep.CubeSplitAtSeamsWeldsTo8");
}

SV_TIERED_TEST(MeshPrep, Tetrahedron) {
    sv::PreparedSurface s = prep(tetrahedron());
    expect_counts(s.report, {4, 4, 0, 6, 0, 6, 0, 0, 6, 0});
    check_structure(s);
    check_closed(s, "MeshPrep.Tetrahedron");
}

SV_TIERED_TEST(MeshPrep, OpenQuadHasDanglingEdges) {
    Mesh m;
    uint32_t a = m.v(0, 0, 0), b = m.v(1, 0, 0), c = m.v(1, 1, 0), d = m.v(0, 1, 0);
    m.tri(a, b, c);
    m.tri(a, c, d);
    sv::PreparedSurface s = prep(m);
    expect_counts(s.report, {4, 2, 0, 5, 4, 1, 0, 0, 5, 4});
    check_structure(s);
    for (const SilEdge &e : s.sil_edges) {
        bool diagonal = (e.v1 == 0 && e.v2 == 4) || (e.v1 == 4 && e.v2 == 0);
        EXPECT_EQ(e.p2 == 2, !diagonal) << "only the diagonal is shared";
    }
    check_closed(s, "MeshPrep.OpenQuadHasDanglingEdges");
}

SV_TIERED_TEST(MeshPrep, ThreeWayEdge) {
    // Three triangles fan off edge 0-1: 0->1, 1->0, 0->1. One pair, one
    // dangling use, and the six outer edges dangling.
    Mesh m;
    uint32_t v0 = m.v(0, 0, 0), v1 = m.v(1, 0, 0), v2 = m.v(0.5f, 1, 0), v3 = m.v(0.5f, -1, 0),
             v4 = m.v(0.5f, 0, 1);
    m.tri(v0, v1, v2);
    m.tri(v1, v0, v3);
    m.tri(v0, v1, v4);
    sv::PreparedSurface s = prep(m);
    expect_counts(s.report, {5, 3, 0, 7, 6, 0, 0, 1, 8, 7});
    check_structure(s);
    // The pair is the first two triangles (first with first).
    int regular = 0;
    for (const SilEdge &e : s.sil_edges) {
        if (e.p2 != 3) {
            regular++;
            EXPECT_EQ(e.p1, 0);
            EXPECT_EQ(e.p2, 1);
            EXPECT_EQ(e.v1, 0);
            EXPECT_EQ(e.v2, 2);
        }
    }
    EXPECT_EQ(regular, 1);
    check_closed(s, "MeshPrep.ThreeWayEdge");
}

SV_TIERED_TEST(MeshPrep, FourWayEdges) {
    // Balanced: 0->1, 1->0, 0->1, 1->0: two pairs.
    Mesh m;
    uint32_t v0 = m.v(0, 0, 0), v1 = m.v(1, 0, 0);
    uint32_t w[4] = {m.v(0.5f, 1, 0), m.v(0.5f, -1, 0), m.v(0.5f, 0, 1), m.v(0.5f, 0, -1)};
    m.tri(v0, v1, w[0]);
    m.tri(v1, v0, w[1]);
    m.tri(v0, v1, w[2]);
    m.tri(v1, v0, w[3]);
    sv::PreparedSurface s = prep(m);
    expect_counts(s.report, {6, 4, 0, 9, 8, 0, 0, 1, 10, 8});
    check_structure(s);
    check_closed(s, "MeshPrep.FourWayEdges.balanced");
    // All four in the same direction: four dangling uses.
    Mesh n = m;
    n.idx = {v0, v1, w[0], v0, v1, w[1], v0, v1, w[2], v0, v1, w[3]};
    sv::PreparedSurface t = prep(n);
    expect_counts(t.report, {6, 4, 0, 9, 8, 0, 0, 1, 12, 12});
    check_structure(t);
    check_closed(t, "MeshPrep.FourWayEdges.same_direction");
}

SV_TIERED_TEST(MeshPrep, TwoTrianglesSharingAnEdgeInTheSameDirection) {
    // Inconsistent winding: both use 0->1. Neither pairs: both dangling.
    Mesh m;
    uint32_t a = m.v(0, 0, 0), b = m.v(1, 0, 0), c = m.v(1, 1, 0), d = m.v(1, -1, 0);
    m.tri(a, b, c);
    m.tri(a, b, d);
    sv::PreparedSurface s = prep(m);
    expect_counts(s.report, {4, 2, 0, 5, 4, 0, 1, 0, 6, 6});
    check_structure(s);
    check_closed(s, "MeshPrep.TwoTrianglesSharingAnEdgeInTheSameDirection");
    // A closed cube with one face's two triangles flipped: still closed volumes.
    Mesh f = cube24();
    std::swap(f.idx[1], f.idx[2]);
    std::swap(f.idx[4], f.idx[5]);
    sv::PreparedSurface fs = prep(f);
    EXPECT_EQ(fs.report.same_direction_edges, 4);
    EXPECT_EQ(fs.report.manifold_edges, 14);
    check_structure(fs);
    check_closed(fs, "MeshPrep.TwoTrianglesSharingAnEdgeInTheSameDirection.flipped_face");
}

SV_TIERED_TEST(MeshPrep, DegenerateTrianglesAreDroppedAndCounted) {
    Mesh m = tetrahedron();
    uint32_t dup = m.v(1, 0, 0); // same position as vertex 1
    m.tri(0, 0, 1);              // two equal indices
    m.tri(2, 3, 2);
    m.tri(1, dup, 3); // equal after welding
    m.tri(3, 3, 3);
    sv::PreparedSurface s = prep(m);
    expect_counts(s.report, {4, 4, 4, 6, 0, 6, 0, 0, 6, 0});
    EXPECT_EQ(s.report.triangles_in, 8);
    EXPECT_EQ(s.remap[dup], 1);
    EXPECT_EQ(s.triangle_source, (std::vector<int>{0, 1, 2, 3}));
    check_structure(s);
    check_closed(s, "MeshPrep.DegenerateTrianglesAreDroppedAndCounted");
    // Interleaved: the source map skips dropped triangles.
    Mesh n;
    uint32_t a = n.v(0, 0, 0), b = n.v(1, 0, 0), c = n.v(0, 1, 0);
    n.tri(a, a, b);
    n.tri(a, b, c);
    sv::PreparedSurface t = prep(n);
    EXPECT_EQ(t.triangle_source, (std::vector<int>{1}));
}

SV_TIERED_TEST(MeshPrep, ZeroAreaSliverKeepsTheMeshClosed) {
    // Tetrahedron A B C D with edge A-B split by M on ONE side only: the
    // other side is closed by the zero-area triangle (A, M, B). It is kept
    // (dropping it would open the mesh), its plane is (0,0,0,0), it never
    // faces any light, and every volume stays closed.
    Mesh m;
    uint32_t A = m.v(0, 0, 0), B = m.v(2, 0, 0), C = m.v(0, 2, 0), D = m.v(0, 0, 2),
             M = m.v(1, 0, 0);
    m.tri(A, C, B); // its B->A pairs with the sliver's A->B
    m.tri(B, M, A); // the sliver: B->M, M->A, A->B
    m.tri(A, D, C);
    m.tri(B, C, D);
    m.tri(B, D, M);
    m.tri(M, D, A);
    sv::PreparedSurface s = prep(m);
    EXPECT_EQ(s.report.zero_normal_triangles, 1);
    EXPECT_EQ(s.report.non_manifold_edges, 0);
    EXPECT_EQ(s.report.boundary_edges + s.report.same_direction_edges, 0) << "mesh is closed";
    const Plane &p = s.planes[1];
    EXPECT_TRUE(p.a == 0 && p.b == 0 && p.c == 0 && p.d == 0);
    uint8_t f[7];
    Vec4 light = {1, -3, 0.5f, 1};
    sv_calculate_facing_c_ref(s.planes.data(), 6, &light, f);
    EXPECT_EQ(f[1], 0);
    check_structure(s);
    check_closed(s, "MeshPrep.ZeroAreaSliverKeepsTheMeshClosed");
    // A tiny but non-zero sliver still gets a unit normal (double keeps it).
    float p0[3] = {0, 0, 0}, p1[3] = {1, 0, 0}, p2[3] = {2, 1e-30f, 0};
    Plane q = sv::triangle_plane(p0, p1, p2);
    EXPECT_FLOAT_EQ(q.c, 1.0f);
    EXPECT_EQ(q.a, 0.0f);
}

SV_TIERED_TEST(MeshPrep, NegativeZeroWeldsWithPositiveZero) {
    Mesh m;
    // The -0.0 copy of b comes first, so it leads its group: stored as +0.0.
    uint32_t b2 = m.v(1, -0.0f, 0);
    uint32_t a = m.v(0, 0, 0), b = m.v(1, 0, 0), c = m.v(0, 1, 0);
    uint32_t a2 = m.v(-0.0f, 0, -0.0f), d = m.v(0, -1, 0);
    m.tri(a, b, c);
    m.tri(b2, a2, d);
    sv::PreparedSurface s = prep(m);
    EXPECT_EQ(s.remap[a2], s.remap[a]);
    EXPECT_EQ(s.remap[b2], s.remap[b]);
    expect_counts(s.report, {4, 2, 0, 5, 4, 1, 0, 0, 5, 4});
    for (float x : s.positions) EXPECT_FALSE(x == 0.0f && std::signbit(x)) << "-0.0 stored";
    check_structure(s);
    check_closed(s, "MeshPrep.NegativeZeroWeldsWithPositiveZero");
    // Different non-zero bits do not weld, however close.
    Mesh n;
    n.v(1, 0, 0);
    n.v(std::nextafter(1.0f, 2.0f), 0, 0);
    n.tri(0, 1, 1);
    sv::PreparedSurface t = prep(n);
    EXPECT_EQ(t.report.welded_vertices, 2);
}

SV_TIERED_TEST(MeshPrep, TorusBeyond16BitIndices) {
    Mesh m = torus(300, 300); // 301 * 301 = 90601 input vertices, 180000 triangles
    sv::PreparedSurface s = prep(m);
    expect_counts(s.report, {90000, 180000, 0, 270000, 0, 270000, 0, 0, 270000, 0});
    EXPECT_GT(*std::max_element(s.indices.begin(), s.indices.end()), 65535);
    check_structure(s);
    check_closed(s, "MeshPrep.TorusBeyond16BitIndices", 4);
}

SV_TIERED_TEST(MeshPrep, RandomSoupsOfInconsistentNonManifoldTriangles) {
    // Random triangles over few vertices, random winding: every edge kind at
    // once (3-, 4-, 5-way, same direction, boundary). The rule must still
    // give closed volumes.
    SCOPED_TRACE(svtest::seed_trace());
    Rng rng = svtest::rng_for("MeshPrep.RandomSoups");
    for (int round = 0; round < 30; round++) {
        Mesh m;
        int nv = 4 + (int)rng.below(8);
        for (int i = 0; i < nv; i++) m.v(rnd(rng, -1, 1), rnd(rng, -1, 1), rnd(rng, -1, 1));
        int nt = 1 + (int)rng.below(60);
        for (int t = 0; t < nt; t++) {
            m.tri(rng.below(nv), rng.below(nv), rng.below(nv));
        }
        sv::PreparedSurface s = prep(m);
        check_structure(s);
        const auto &r = s.report;
        EXPECT_EQ(r.edges, r.boundary_edges + r.manifold_edges + r.same_direction_edges +
                               r.non_manifold_edges);
        EXPECT_EQ(r.sil_edges * 2 - r.dangling_sil_edges, 3 * r.triangles)
            << "each use in exactly one SilEdge";
        check_closed(s, ("MeshPrep.RandomSoups." + std::to_string(round)).c_str(), 6);
        if (HasFatalFailure()) return;
    }
}

TEST(MeshPrep, EmptyMeshes) {
    sv::PreparedSurface s = sv::prepare_surface(nullptr, 0, nullptr, 0);
    EXPECT_EQ(s.num_triangles(), 0);
    EXPECT_EQ(s.num_sil_edges(), 0);
    Mesh m;
    m.v(0, 0, 0);
    m.tri(0, 0, 0);
    sv::PreparedSurface t = prep(m);
    EXPECT_EQ(t.report.degenerate_dropped, 1);
    EXPECT_EQ(t.num_triangles(), 0);
    EXPECT_EQ(t.num_vertices(), 1);
}

TEST(MeshPrep, BadInputThrowsWithAMessage) {
    auto msg = [](const std::vector<float> &p, const std::vector<uint32_t> &i) -> std::string {
        try {
            sv::prepare_surface(p.data(), p.size() / 3, i.data(), i.size());
        } catch (const sv::PrepareError &e) {
            return e.what();
        }
        return "";
    };
    std::vector<float> p = {0, 0, 0, 1, 0, 0, 0, 1, 0};
    EXPECT_NE(msg(p, {0, 1, 3}).find("uses vertex 3"), std::string::npos);
    EXPECT_NE(msg(p, {0, 1}).find("not a multiple of 3"), std::string::npos);
    std::vector<float> q = p;
    q[4] = NAN;
    EXPECT_NE(msg(q, {0, 1, 2}).find("vertex 1 has a NaN coordinate y"), std::string::npos);
    q[4] = -INFINITY;
    EXPECT_NE(msg(q, {0, 1, 2}).find("infinite"), std::string::npos);
    EXPECT_THROW(sv::prepare_surface(nullptr, 3, nullptr, 0), sv::PrepareError);
    EXPECT_THROW(sv::prepare_surface(p.data(), 3, nullptr, 3), sv::PrepareError);
}

TEST(MeshPrep, ShadowVertexBuffers) {
    sv::PreparedSurface s = prep(tetrahedron());
    sv::AlignedVector<Vec4> v = sv::shadow_vertices(s);
    ASSERT_EQ(v.size(), 8u);
    EXPECT_EQ((uintptr_t)v.data() % 64, 0u);
    for (int i = 0; i < 4; i++) {
        const float *p = &s.positions[3 * i];
        EXPECT_TRUE(v[2 * i].x == p[0] && v[2 * i].y == p[1] && v[2 * i].z == p[2] &&
                    v[2 * i].w == 1.0f);
        EXPECT_TRUE(v[2 * i + 1].x == p[0] && v[2 * i + 1].y == p[1] && v[2 * i + 1].z == p[2] &&
                    v[2 * i + 1].w == 0.0f);
    }
    Vec4 point = {0.25f, -2, 3, 1};
    sv::AlignedVector<Vec4> c = sv::shadow_vertices_for_light(s, point);
    Vec4 dir = {0, 0, 1, 0}; // light above: extrude downwards
    sv::AlignedVector<Vec4> d = sv::shadow_vertices_for_light(s, dir);
    for (int i = 0; i < 4; i++) {
        const float *p = &s.positions[3 * i];
        EXPECT_TRUE(c[2 * i].x == p[0] && c[2 * i].w == 1.0f);
        EXPECT_EQ(c[2 * i + 1].x, p[0] - 0.25f);
        EXPECT_EQ(c[2 * i + 1].y, p[1] + 2);
        EXPECT_EQ(c[2 * i + 1].z, p[2] - 3);
        EXPECT_EQ(c[2 * i + 1].w, 0.0f);
        EXPECT_EQ(d[2 * i + 1].x, 0.0f);
        EXPECT_EQ(d[2 * i + 1].y, 0.0f);
        EXPECT_EQ(d[2 * i + 1].z, -1.0f);
        EXPECT_EQ(d[2 * i + 1].w, 0.0f);
    }
}

TEST(MeshPrep, SurfaceBoundsContainEveryVertex) {
    SCOPED_TRACE(svtest::seed_trace());
    Rng rng = svtest::rng_for("MeshPrep.SurfaceBounds");
    for (int round = 0; round < 50; round++) {
        Mesh m;
        float scale = std::ldexp(1.0f, (int)rng.below(60) - 30);
        float off = rnd(rng, -1000, 1000);
        for (int i = 0; i < 50; i++) m.v(off + scale * rnd(rng, -1, 1), rnd(rng, -1, 1), off);
        sv::PreparedSurface s = prep(m);
        Bounds b = sv::surface_bounds(s);
        for (int v = 0; v < s.num_vertices(); v++) {
            const float *p = &s.positions[3 * v];
            ASSERT_LE(b.center.x - b.extents.x, p[0]);
            ASSERT_GE(b.center.x + b.extents.x, p[0]);
            ASSERT_LE(b.center.y - b.extents.y, p[1]);
            ASSERT_GE(b.center.y + b.extents.y, p[1]);
            ASSERT_LE(b.center.z - b.extents.z, p[2]);
            ASSERT_GE(b.center.z + b.extents.z, p[2]);
        }
    }
}

} // namespace
