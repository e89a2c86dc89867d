// Seed 003's silhouette finders against the paper's SilEdges: on the bundled
// character, on every real character in ../shared/models (each surface),
// lit from many lights, and on random triangle soups with boundary,
// non-manifold and same-direction edges under random facing bytes (so every
// loop tail and the dangling rule are exercised). The hash table's overflow
// is provoked and must be reported; bad set-up input throws.
//
// Copyright (C) 2026 the shadowvol authors. LGPL-2.1-or-later.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <string>
#include <vector>

#include "shadowvol.h"
#include "shadowvol_mesh.h"
#include "shadowvol_silhouette.h"
#include "model_surfaces.h"
#include "test_support.h"

using sv::DirectedEdge;
using svtest::Rng;

namespace {

// Every finder configuration, run against one facing array.
struct Finders {
    const sv::PreparedSurface *s;
    sv::SilhouetteMesh mesh;
    sv::ConnectivityTable conn;
    sv::ClassicFinder classic;
    std::vector<std::unique_ptr<sv::HashFinderBase>> hash;
    std::vector<std::string> hash_names;
    std::vector<int> hash_columns;
    bool run_classic;

    Finders(const sv::PreparedSurface &surface, bool withClassic)
        : s(&surface), mesh(sv::silhouette_mesh(surface)),
          conn(sv::connectivity_linear(surface.indices.data(), surface.num_triangles(),
                                       surface.num_vertices())),
          classic(mesh), run_classic(withClassic) {
        for (int bits : {16, 32}) {
            if (bits == 16 && mesh.num_vertices > 65535) continue;
            for (int cols : {8, 16, 32, 64}) {
                for (bool simd : {false, true}) {
                    hash.push_back(sv::make_hash_finder(mesh, bits, cols, simd));
                    hash_names.push_back("hash" + std::to_string(cols) + "_u" +
                                         std::to_string(bits) + (simd ? "_sse2" : ""));
                    hash_columns.push_back(cols);
                }
            }
        }
    }

    // Checks every finder on FACING (numTriangles + 4 bytes, the last
    // numTriangles .. +3 set as the header asks). Returns how many hash
    // runs overflowed.
    int check(const std::vector<uint8_t> &facing, const std::string &what) {
        SCOPED_TRACE(what);
        std::vector<DirectedEdge> buf(sv::silhouette_capacity(mesh) + 1);
        const std::size_t nref = sv::silhouette_from_sil_edges(s->sil_edges.data(),
                                                               s->num_sil_edges(), facing.data(),
                                                               buf.data());
        const std::vector<DirectedEdge> exact = sv::canonical_silhouette(buf.data(), nref);
        const std::vector<DirectedEdge> net = sv::net_silhouette(buf.data(), nref);
        const int need = sv::hash_columns_needed(mesh);
        for (const sv::ConnectivityVariant &v : sv::connectivity_variants()) {
            if (!svtest::in_this_run(v.isa, v.name)) continue;
            const std::size_t n = v.fn(conn, s->indices.data(), s->num_triangles(), facing.data(),
                                       buf.data());
            EXPECT_EQ(sv::canonical_silhouette(buf.data(), n), exact) << v.name;
        }
        if (run_classic) {
            const std::size_t n = classic.find(facing.data(), buf.data());
            EXPECT_EQ(sv::canonical_silhouette(buf.data(), n), net) << "classic";
        }
        int overflows = 0;
        for (std::size_t k = 0; k < hash.size(); k++) {
            std::size_t n = 99;
            const sv::HashStatus st = hash[k]->find(facing.data(), buf.data(), &n);
            if (st == sv::HashStatus::overflow) {
                overflows++;
                // Only a table too narrow for this surface may overflow,
                // and then it names a vertex and returns no edges.
                EXPECT_LT(hash_columns[k], need) << hash_names[k];
                EXPECT_GE(hash[k]->overflow_vertex(), 0) << hash_names[k];
                EXPECT_LT(hash[k]->overflow_vertex(), mesh.num_vertices) << hash_names[k];
                EXPECT_EQ(n, 0u) << hash_names[k];
                continue;
            }
            EXPECT_EQ(hash[k]->overflow_vertex(), -1) << hash_names[k];
            EXPECT_EQ(sv::canonical_silhouette(buf.data(), n), net) << hash_names[k];
        }
        return overflows;
    }
};

std::vector<uint8_t> light_facing(const sv::PreparedSurface &s, const Vec4 &light) {
    std::vector<uint8_t> f((std::size_t)s.num_triangles() + 4, 1);
    sv_calculate_facing_c_ref(s.planes.data(), s.num_triangles(), &light, f.data());
    return f;
}

// Lights around (and some inside) the surface's bounds: points at 0.3 to 4
// radii in random directions, directional lights, and the two placements of
// the benchmark (above, beside).
std::vector<Vec4> lights_for(const sv::PreparedSurface &s, Rng &rng, int count) {
    const Bounds b = sv::surface_bounds(s);
    const float r = std::max({b.extents.x, b.extents.y, b.extents.z, 1e-3f});
    std::vector<Vec4> l;
    l.push_back({b.center.x, b.center.y + 3 * r, b.center.z, 1});
    l.push_back({b.center.x + 3 * r, b.center.y, b.center.z, 1});
    while ((int)l.size() < count) {
        double d[3], len = 0;
        for (double &c : d) {
            c = 2 * rng.unit() - 1;
            len += c * c;
        }
        len = std::sqrt(len) + 1e-9;
        const bool directional = rng.chance(0.25);
        const float dist = directional ? 1.0f : r * (0.3f + 3.7f * (float)rng.unit());
        l.push_back({(directional ? 0 : b.center.x) + dist * (float)(d[0] / len),
                     (directional ? 0 : b.center.y) + dist * (float)(d[1] / len),
                     (directional ? 0 : b.center.z) + dist * (float)(d[2] / len),
                     directional ? 0.0f : 1.0f});
    }
    return l;
}

#ifndef SV_SILHOUETTE_LIGHTS
#define SV_SILHOUETTE_LIGHTS 40 /* per surface (tests/CMakeLists.txt sets it) */
#endif

// Above this many triangles the classic finder (quadratic) is run for the
// first benchmark light only, and the quadratic table is not built: the
// sanitizer build would take minutes. The benchmark checks classic on
// every mesh it times.
constexpr int kBigSurface = 12000;

// Once per model set (bundled, SharedModels: tests/support/model_surfaces.h).
class SilhouetteModels : public ::testing::TestWithParam<std::string> {};
INSTANTIATE_TEST_SUITE_P(ModelSets, SilhouetteModels, ::testing::ValuesIn(svtest::model_sets()),
                         svtest::param_name);

SV_TIERED_TEST_P(SilhouetteModels, EveryModelAndLightMatchesTheSilEdges) {
    Rng rng = svtest::rng_for("SilhouetteFinders.Models");
    SCOPED_TRACE(svtest::seed_trace());
    int surfaces = 0, lights = 0;
    for (const std::string &path : svtest::seed_model_paths(GetParam())) {
        std::vector<sv::PreparedSurface> ss = svtest::prepared_surfaces(path);
        for (std::size_t k = 0; k < ss.size(); k++) {
            const sv::PreparedSurface &s = ss[k];
            const bool big = s.num_triangles() > kBigSurface;
            Finders f(s, true);
            const std::vector<Vec4> ls = lights_for(s, rng, big ? 6 : SV_SILHOUETTE_LIGHTS);
            for (std::size_t i = 0; i < ls.size(); i++) {
                f.run_classic = !big || i == 0;
                f.check(light_facing(s, ls[i]),
                        path + " surface " + std::to_string(k) + " light " + std::to_string(i));
                lights++;
            }
            surfaces++;
        }
    }
    EXPECT_GE(surfaces, 1);
    std::printf("[  NOTE    ] %d surfaces, %d (surface, light) pairs\n", surfaces, lights);
}

SV_TIERED_TEST_P(SilhouetteModels, QuadraticAndLinearTablesAgreeWithTheSilEdges) {
    for (const std::string &path : svtest::seed_model_paths(GetParam())) {
        for (const sv::PreparedSurface &s : svtest::prepared_surfaces(path)) {
            SCOPED_TRACE(path);
            const int nt = s.num_triangles();
            const sv::ConnectivityTable lin = sv::connectivity_linear(s.indices.data(), nt,
                                                                      s.num_vertices());
            if (nt <= kBigSurface) {
                const sv::ConnectivityTable quad = sv::connectivity_quadratic(s.indices.data(), nt);
                EXPECT_TRUE(quad.neighbour == lin.neighbour);
                EXPECT_EQ(quad.dangling_uses, lin.dangling_uses);
            }
            // Every regular SilEdge is a pair of uses whose neighbours are
            // each other's triangles; dangling SilEdges are the dangling uses.
            std::size_t dangling = 0;
            for (const SilEdge &e : s.sil_edges) {
                if (e.p2 == nt) {
                    dangling++;
                    continue;
                }
                bool found = false;
                for (int u = 3 * e.p1; u < 3 * e.p1 + 3; u++) {
                    const int next = u % 3 == 2 ? u - 2 : u + 1;
                    if (2 * s.indices[u] == e.v1 && 2 * s.indices[next] == e.v2) {
                        found = lin.neighbour[u] == e.p2;
                    }
                }
                EXPECT_TRUE(found) << "SilEdge p1 " << e.p1 << " p2 " << e.p2;
            }
            EXPECT_EQ(lin.dangling_uses.size(), dangling);
            EXPECT_EQ(lin.permanent_bytes(), (3 * (std::size_t)nt + dangling) * sizeof(int));
        }
    }
}

// A soup over few vertices: boundary edges, edges of three and more uses,
// edges used twice in one direction; every count from 0 (loop tails of the
// 8- and 16-triangle SIMD steps).
SV_TIERED_TEST(SilhouetteFinders, RandomSoupsWithNonManifoldEdges) {
    Rng rng = svtest::rng_for("SilhouetteFinders.Soups");
    SCOPED_TRACE(svtest::seed_trace());
    int differ = 0, overflowed = 0;
    for (int n = 0; n <= 120; n++) {
        const int nv = 3 + (int)rng.below(std::max(1, n / 2) + 3);
        std::vector<float> pos;
        for (int v = 0; v < nv; v++) {
            for (int c = 0; c < 3; c++) pos.push_back((float)rng.unit());
        }
        std::vector<uint32_t> idx;
        for (int t = 0; t < n; t++) {
            for (int c = 0; c < 3; c++) idx.push_back(rng.below((uint32_t)nv));
        }
        const sv::PreparedSurface s = sv::prepare_surface(pos.data(), (std::size_t)nv, idx.data(),
                                                          idx.size());
        const sv::ConnectivityTable quad = sv::connectivity_quadratic(s.indices.data(),
                                                                      s.num_triangles());
        Finders f(s, true);
        EXPECT_TRUE(quad.neighbour == f.conn.neighbour) << "n " << n;
        for (int rep = 0; rep < 6; rep++) {
            std::vector<uint8_t> facing((std::size_t)s.num_triangles() + 4, 1);
            const double p = rep == 0 ? 0.0 : rep == 1 ? 1.0 : rng.unit();
            for (int t = 0; t < s.num_triangles(); t++) facing[(std::size_t)t] = rng.chance(p);
            overflowed += f.check(facing,
                                  "soup n " + std::to_string(n) + " rep " + std::to_string(rep));
            std::vector<DirectedEdge> buf(s.num_sil_edges() + 1);
            const std::size_t m = sv::silhouette_from_sil_edges(s.sil_edges.data(),
                                                                s.num_sil_edges(), facing.data(),
                                                                buf.data());
            differ += sv::net_silhouette(buf.data(), m) != sv::canonical_silhouette(buf.data(), m);
        }
    }
    // The soups must reach the case that tells the two oracles apart (an
    // undirected edge left with both directions by the SilEdge rule), and
    // overflow the narrow tables at times.
    EXPECT_GT(differ, 0);
    EXPECT_GT(overflowed, 0);
}

// An open fan of 80 triangles around one vertex (a cone without its base),
// every other triangle lit: the apex row must hold the 40 spokes of the lit
// triangles at once. hash8..hash32 overflow there, report the apex and
// return nothing; hash64 is right. By the project's rule the open rim's
// edges are dangling (a virtual lit triangle beyond them): a lit triangle's
// rim edge is not on the silhouette, an unlit one's is, reversed.
TEST(SilhouetteFinders, HashOverflowIsReportedNeverWrong) {
    const int k = 80;
    std::vector<float> pos{0, 0, 1};
    for (int i = 0; i < k; i++) {
        const double a = 2 * M_PI * i / k;
        pos.insert(pos.end(), {(float)std::cos(a), (float)std::sin(a), 0});
    }
    std::vector<uint32_t> idx;
    for (int i = 0; i < k; i++) idx.insert(idx.end(), {0u, 1u + i, 1u + (i + 1) % k});
    const sv::PreparedSurface s = sv::prepare_surface(pos.data(), pos.size() / 3, idx.data(),
                                                      idx.size());
    const sv::SilhouetteMesh m = sv::silhouette_mesh(s);
    EXPECT_EQ(sv::hash_columns_needed(m), k);
    std::vector<uint8_t> alternate((std::size_t)k + 4, 1), single((std::size_t)k + 4, 0);
    for (int i = 0; i < k; i++) alternate[(std::size_t)i] = i % 2 == 0;
    std::fill(single.begin() + k, single.end(), 1);
    single[3] = 1;
    // By hand: lit triangle i (0 -> i+1 -> i+2) casts its spokes 0 -> i+1
    // and i+2 -> 0, unlit triangle i its rim reversed, i+2 -> i+1.
    std::vector<DirectedEdge> want;
    for (int i = 0; i < k; i++) {
        const uint32_t b = 1u + i, c = 1u + (i + 1) % k;
        if (i % 2 == 0) {
            want.push_back({0, b});
            want.push_back({c, 0});
        } else {
            want.push_back({c, b});
        }
    }
    std::sort(want.begin(), want.end());
    std::vector<DirectedEdge> buf(sv::silhouette_capacity(m));
    std::size_t n = sv::silhouette_from_sil_edges(s.sil_edges.data(), s.num_sil_edges(),
                                                  alternate.data(), buf.data());
    ASSERT_EQ(sv::net_silhouette(buf.data(), n), want);
    sv::ClassicFinder classic(m);
    n = classic.find(alternate.data(), buf.data());
    EXPECT_EQ(sv::canonical_silhouette(buf.data(), n), want);
    for (int bits : {16, 32}) {
        for (int cols : {8, 16, 32, 64}) {
            for (bool simd : {false, true}) {
                SCOPED_TRACE("bits " + std::to_string(bits) + " cols " + std::to_string(cols) +
                             (simd ? " sse2" : ""));
                auto h = sv::make_hash_finder(m, bits, cols, simd);
                n = 7;
                const sv::HashStatus st = h->find(alternate.data(), buf.data(), &n);
                if (cols < k / 2) {
                    EXPECT_EQ(st, sv::HashStatus::overflow);
                    EXPECT_EQ(h->overflow_vertex(), 0); /* the apex */
                    EXPECT_EQ(n, 0u);
                } else {
                    ASSERT_EQ(st, sv::HashStatus::ok);
                    EXPECT_EQ(sv::canonical_silhouette(buf.data(), n), want);
                }
                // The same table is reusable after an overflow: one lit
                // triangle casts its two spokes, the 79 unlit ones their rims.
                ASSERT_EQ(h->find(single.data(), buf.data(), &n), sv::HashStatus::ok);
                EXPECT_EQ(n, 2u + (k - 1));
                EXPECT_EQ(h->overflow_vertex(), -1);
            }
        }
    }
}

SV_TIERED_TEST(SilhouetteFinders, BadSetUpThrows) {
    sv::SilhouetteMesh m;
    m.num_vertices = 65536;
    EXPECT_THROW(sv::make_hash_finder(m, 16, 8, false), sv::SilhouetteError);
    m.num_vertices = 65535; /* the largest a 16-bit table takes */
    EXPECT_NO_THROW(sv::make_hash_finder(m, 16, 8, false));
    m.num_vertices = 10;
    EXPECT_THROW(sv::make_hash_finder(m, 16, 12, false), sv::SilhouetteError);
    EXPECT_THROW(sv::make_hash_finder(m, 24, 8, true), sv::SilhouetteError);
    m.num_triangles = 2; /* indices missing */
    EXPECT_THROW(sv::make_hash_finder(m, 32, 8, false), sv::SilhouetteError);
    const int bad[3] = {0, 1, 5};
    EXPECT_THROW(sv::connectivity_linear(bad, 1, 3), sv::SilhouetteError);
    EXPECT_THROW(sv::connectivity_quadratic(nullptr, 1), sv::SilhouetteError);
    EXPECT_THROW(sv::connectivity_linear(bad, -1, 3), sv::SilhouetteError);
    // An empty surface: every finder returns nothing.
    const sv::ConnectivityTable c = sv::connectivity_linear(nullptr, 0, 0);
    const uint8_t facing[4] = {1, 1, 1, 1};
    DirectedEdge out[1];
    for (const sv::ConnectivityVariant &v : sv::connectivity_variants()) {
        if (!svtest::in_this_run(v.isa, v.name)) continue;
        EXPECT_EQ(v.fn(c, nullptr, 0, facing, out), 0u) << v.name;
    }
}

} // namespace
