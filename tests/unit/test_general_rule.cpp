/*
 * The general rule built directly (issue 27, second stop): the general
 * edge table (sv::general_edge_table) and the C reference of the general
 * kernels (src/core/ref/reference_general.c).
 *
 *  - a surface of closed shells keeps the paper's SilEdges in the table,
 *    in their order, and the general kernels give the paper's index list
 *    for any facing and cull bits (every model; under the general rule its
 *    pairs are the same SilEdges);
 *  - every use of every edge is in the table once; the quads an edge gets
 *    add up to its multiplicity m, k-way edges and inconsistent winding
 *    included, within 6 k indices; the checked entry points refuse what
 *    breaks the contract;
 *  - the stencil of `--general-build direct` is the two-sided caster's byte
 *    for byte on every generated open case and on the open character's
 *    animation frames, both modes, every light kind;
 *  - the 8-bit wrap-around docs/CASTERS.md states: 256 open layers count
 *    0, and so do 128 closed shells under the general rule (2 each),
 *    where the paper's rule counts them 128.
 *
 * Copyright (C) 2026 the shadowvol authors. LGPL-2.1-or-later.
 */
#include <gtest/gtest.h>

#include <algorithm>
#include <cstdint>
#include <map>
#include <random>
#include <string>
#include <vector>

#include "frame.h"
#include "model_surfaces.h"
#include "open_case_scenes.h"
#include "sequence.h"
#include "shadowvol.h"
#include "shadowvol_casters.h"
#include "shadowvol_scene.h"
#include "test_conditions.h"
#include "truth.h"

namespace {

using namespace sv;
using namespace sv::render;

#ifdef SV_TEST_SMALL_FRAMES
constexpr int kW = 128, kH = 104;
#else
constexpr int kW = 320, kH = 256;
#endif

bool same(const SilEdge &a, const SilEdge &b) {
    return a.p1 == b.p1 && a.p2 == b.p2 && a.v1 == b.v1 && a.v2 == b.v2;
}

bool same_edges(const std::vector<SilEdge> &a, const std::vector<SilEdge> &b) {
    return a.size() == b.size() && std::equal(a.begin(), a.end(), b.begin(), same);
}

/* The paper's facing bytes for a random light (with the sentinel), and
 * random cull bits (some triangles culled). */
struct RandomLight {
    std::vector<uint8_t> facing;
    std::vector<uint8_t> cull;
};
RandomLight random_light(const PreparedSurface &s, std::mt19937 &rng) {
    std::uniform_real_distribution<float> u(-3, 3);
    const Vec4 light{u(rng), u(rng), u(rng), (rng() & 1) ? 1.0f : 0.0f};
    RandomLight r;
    r.facing.assign((std::size_t)s.num_triangles() + 1, 1);
    sv_calculate_facing_c_ref(s.planes.data(), s.num_triangles(), &light, r.facing.data());
    r.cull.resize((std::size_t)s.num_vertices());
    for (uint8_t &c : r.cull) c = (rng() % 4 == 0) ? (uint8_t)(1u << (rng() % 6)) : 0;
    return r;
}

/* A surface of closed shells: the table under auto holds its SilEdges as
 * they are, and the general kernels give the paper's list, quads and caps,
 * for random lights with and without cull bits. Under the general rule
 * its pairs are the same SilEdges. */
void expect_closed_surface_is_the_papers(const PreparedSurface &s, const std::string &what) {
    const ShellMap shells = find_shells(s);
    const GeneralEdgeTable automatic = general_edge_table(s, shells, CasterRule::automatic);
    if (shells.closed_shells() != (int64_t)shells.shells.size()) {
        /* Not every shell is closed: the table keeps the closed shells'
         * SilEdges only. */
        std::vector<SilEdge> closed;
        for (const SilEdge &e : s.sil_edges)
            if (shells.shells[(std::size_t)shells.triangle_shell[(std::size_t)e.p1]].closed())
                closed.push_back(e);
        EXPECT_TRUE(same_edges(automatic.paper, closed)) << what;
        return;
    }
    EXPECT_EQ(automatic.general_triangles, 0) << what;
    EXPECT_TRUE(same_edges(automatic.paper, s.sil_edges)) << what;
    EXPECT_TRUE(automatic.pairs.empty() && automatic.opens.empty() && automatic.shared.empty())
        << what;
    const GeneralEdgeTable general = general_edge_table(s, shells, CasterRule::general);
    EXPECT_TRUE(general.paper.empty()) << what;
    EXPECT_TRUE(same_edges(general.pairs, s.sil_edges)) << what << ": today's SilEdges as pairs";

    std::mt19937 rng(7);
    const int n = s.num_triangles();
    const sv_general_edges edges = automatic.view();
    for (int trial = 0; trial < 4; trial++) {
        const RandomLight l = random_light(s, rng);
        for (bool cull : {false, true}) {
            std::vector<uint8_t> paper = l.facing, gen((std::size_t)n + 1, 1);
            sv_general_facing_from_calculated(gen.data(), l.facing.data(),
                                              automatic.lit_byte.data(), n);
            if (cull) {
                sv_count_facing_cull_c_ref(paper.data(), n, s.indices.data(), l.cull.data());
                sv_general_cull_c_ref(gen.data(), n, s.indices.data(), l.cull.data());
            }
            std::vector<int> want(6 * s.sil_edges.size() + 2 * (std::size_t)s.num_indices());
            int w = sv_create_sil_triangles_c_ref(want.data(), paper.data(), s.sil_edges.data(),
                                                  s.num_sil_edges());
            w += sv_create_cap_triangles_c_ref(want.data() + w, paper.data(), s.indices.data(),
                                               s.num_indices());
            want.resize((std::size_t)w);
            int count = 0;
            const sv_general_variant *gv = sv_general_variants(&count);
            for (int vi = 0; vi < count; vi++) {
                if (!svtest::in_this_run(gv[vi].isa, gv[vi].name)) continue;
                std::vector<int> got(want.size() + automatic.sil_capacity() + 16);
                int g = sv_create_general_sil_triangles_checked(&gv[vi], got.data(), got.size(),
                                                                gen.data(), n, s.num_vertices(),
                                                                &edges);
                ASSERT_GE(g, 0) << sv_status_string(g);
                const int c = sv_create_general_cap_triangles_checked(&gv[vi], got.data() + g,
                                                                      got.size() - (std::size_t)g,
                                                                      gen.data(), s.indices.data(),
                                                                      s.num_indices(),
                                                                      s.num_vertices());
                ASSERT_GE(c, 0) << sv_status_string(c);
                got.resize((std::size_t)(g + c));
                EXPECT_EQ(got, want) << what << ", " << gv[vi].name << ", light " << trial
                                     << (cull ? ", culled" : "");
            }
        }
    }
}

SV_TIERED_TEST(GeneralEdges, ClosedSurfacesGiveThePapersSilEdgesAndIndexList) {
    for (const std::string &path : svtest::seed_model_paths("bundled"))
        for (const PreparedSurface &s : svtest::prepared_surfaces(path))
            expect_closed_surface_is_the_papers(s, path);
    /* The generated closed box and the box of the closed-and-open case. */
    svtest::Soup box{"box"};
    svtest::add_box(box, 0, 0, 0, 1, 2, 3, true);
    expect_closed_surface_is_the_papers(svtest::surface_of(box).prepared, "box");
}

SV_TIERED_TEST(GeneralEdgesSharedModels, ClosedSurfacesGiveThePapersSilEdgesAndIndexList) {
    /* ../shared/models and its open/ folder. */
    const std::vector<std::string> paths = svtest::seed_model_paths("SharedModels");
    int closed_surfaces = 0;
    for (const std::string &path : paths) {
        for (const PreparedSurface &s : svtest::prepared_surfaces(path)) {
            const ShellMap shells = find_shells(s);
            closed_surfaces += shells.closed_shells() == (int64_t)shells.shells.size();
            expect_closed_surface_is_the_papers(s, path);
        }
    }
    EXPECT_GT(closed_surfaces, 0);
}

/* Every directed use of every edge of the general shells is in the table
 * exactly once, with its direction. */
void expect_every_use_once(const PreparedSurface &s, const GeneralEdgeTable &g) {
    std::map<std::pair<int, int>, int> uses; /* (from, to) doubled -> count */
    const int nt = s.num_triangles();
    for (int u = 0; u < 3 * nt; u++) {
        if (g.lit_byte[(std::size_t)(u / 3)] != SV_GENERAL_LIT) continue;
        const int a = s.indices[(std::size_t)u],
                  b = s.indices[(std::size_t)(u % 3 == 2 ? u - 2 : u + 1)];
        uses[{2 * a, 2 * b}]++;
    }
    auto take = [&](int from, int to) { return --uses[{from, to}] >= 0; };
    for (const SilEdge &e : g.pairs) EXPECT_TRUE(take(e.v1, e.v2) && take(e.v2, e.v1));
    for (const SilEdge &e : g.opens) {
        EXPECT_EQ(e.p1, e.p2);
        EXPECT_TRUE(take(e.v1, e.v2));
    }
    for (const sv_shared_edge &e : g.shared) {
        EXPECT_TRUE(e.numUses >= 3 || e.numUses == 2);
        for (int k = 0; k < e.numUses; k++) {
            const int u = g.shared_uses[(std::size_t)(e.firstUse + k)];
            EXPECT_TRUE((u & 1) ? take(e.v2, e.v1) : take(e.v1, e.v2));
        }
    }
    for (const auto &kv : uses) EXPECT_EQ(kv.second, 0);
}

TEST(GeneralEdges, EveryUseOnceOnTheGeneratedOpenCases) {
    for (const svtest::Soup &soup : svtest::open_cases()) {
        const PreparedSurface s = svtest::surface_of(soup).prepared;
        const GeneralEdgeTable g = general_edge_table(s, find_shells(s), CasterRule::automatic);
        EXPECT_EQ(g.general_triangles, s.num_triangles()) << soup.name;
        expect_every_use_once(s, g);
    }
}

/* The signed sum of Q(v1 -> v2) in a list of quads: +1 for the paper's
 * dark form of (a, b), -1 for its lit form, per edge {a, b} oriented
 * a < b. */
std::map<std::pair<int, int>, int> quad_chain(const int *si, int n) {
    std::map<std::pair<int, int>, int> m;
    for (int i = 0; i < n; i += 6) {
        /* dark form of a -> b: (a, b, b+1, a+1, a, b+1);
         * lit form: (a, b+1, b, a, a+1, b+1). */
        const int a = si[i];
        const bool dark = si[i + 2] == si[i + 1] + 1;
        const int b = dark ? si[i + 1] : si[i + 2];
        const int sign = dark ? 1 : -1;
        if (a < b)
            m[{a, b}] += sign;
        else
            m[{b, a}] -= sign;
    }
    return m;
}

TEST(GeneralKernels, QuadsAddUpToTheMultiplicityOfKWayEdges) {
    /* K triangles (1 .. 6) on the edge (0, 1), each running it either way,
     * each byte 0, 1 or 2: the quads sum to m, within 6 K indices. */
    std::mt19937 rng(27);
    for (int trial = 0; trial < 400; trial++) {
        const int k = 1 + trial % 6;
        svtest::Soup soup{"fan"};
        const uint32_t a = soup.vertex(0, 0, 0), b = soup.vertex(1, 0, 0);
        for (int i = 0; i < k; i++) {
            const uint32_t c = soup.vertex(0.5, std::cos(i), std::sin(i) + 0.01 * trial);
            if (rng() & 1)
                soup.tri(a, b, c);
            else
                soup.tri(b, a, c);
        }
        const PreparedSurface s = prepare_surface(soup.pos.data(), soup.pos.size() / 3,
                                                  soup.idx.data(), soup.idx.size());
        const GeneralEdgeTable g = general_edge_table(s, find_shells(s), CasterRule::general);
        expect_every_use_once(s, g);
        std::vector<uint8_t> facing((std::size_t)k + 1, 1);
        int m = 0;
        for (int t = 0; t < k; t++) {
            facing[(std::size_t)t] = (uint8_t)(rng() % 3);
            const int sigma = 1 - facing[(std::size_t)t];
            /* t runs 0 -> 1 when 1 follows 0 in its corners. */
            int dir = 0;
            for (int c = 0; c < 3; c++)
                if (s.indices[3 * (std::size_t)t + c] == 0 &&
                    s.indices[3 * (std::size_t)t + (c + 1) % 3] == 1)
                    dir = 1;
            m += dir ? sigma : -sigma;
        }
        const sv_general_edges edges = g.view();
        const std::size_t bound = g.sil_capacity();
        std::vector<int> out(bound + 8, -7);
        const int n = sv_create_general_sil_triangles_c_ref(out.data(), facing.data(), &edges);
        ASSERT_LE((std::size_t)n, bound);
        const std::map<std::pair<int, int>, int> chain = quad_chain(out.data(), n);
        const auto it = chain.find({0, 2});
        EXPECT_EQ(it == chain.end() ? 0 : it->second, m) << "k " << k << ", trial " << trial;
        if (k >= 3) {
            /* A shared edge: exactly |m| quads on it. */
            int on_edge = 0;
            for (int i = 0; i < n; i += 6)
                on_edge += std::min(out[(std::size_t)i], out[(std::size_t)i + 1] & ~1) == 0 &&
                           std::max(out[(std::size_t)i], out[(std::size_t)i + 1] & ~1) == 2;
            EXPECT_EQ(on_edge, std::abs(m));
        }
    }
}

TEST(GeneralKernels, TheBoundIsReachedAndEnforced) {
    /* Four triangles on one edge, all running it the same way and all
     * dark: m = 4, 24 indices, the whole 6 k bound. */
    svtest::Soup soup{"fan"};
    const uint32_t a = soup.vertex(0, 0, 0), b = soup.vertex(1, 0, 0);
    for (int i = 0; i < 4; i++) soup.tri(a, b, soup.vertex(0.5, std::cos(i), std::sin(i)));
    const PreparedSurface s = prepare_surface(soup.pos.data(), soup.pos.size() / 3, soup.idx.data(),
                                              soup.idx.size());
    const GeneralEdgeTable g = general_edge_table(s, find_shells(s), CasterRule::general);
    ASSERT_EQ(g.shared.size(), 1u);
    const sv_general_edges e = g.view();
    const std::vector<uint8_t> facing(5, 0);
    const sv_general_variant *v = sv_general_variant_by_name("c_ref");
    ASSERT_NE(v, nullptr);
    const std::size_t bound = sv_general_sil_capacity(&e);
    std::vector<int> out(bound + 8, -7);
    int nv = s.num_vertices();
    /* The shared edge alone gives 24; the open edges 6 each. */
    EXPECT_EQ(bound, 6u * 4 + 6u * g.opens.size());
    EXPECT_EQ(sv_create_general_sil_triangles_checked(v, out.data(), bound, facing.data(), 4, nv,
                                                      &e),
              (int)bound);
    EXPECT_EQ(out[bound], -7) << "wrote past the bound";
    EXPECT_EQ(sv_create_general_sil_triangles_checked(v, out.data(), bound - 1, facing.data(), 4,
                                                      nv, &e),
              SV_E_CAPACITY);
    /* Bad bytes, bad tables. */
    std::vector<uint8_t> bad = facing;
    bad[2] = 3;
    EXPECT_EQ(sv_create_general_sil_triangles_checked(v, out.data(), bound, bad.data(), 4, nv, &e),
              SV_E_GENERAL_FACING);
    EXPECT_EQ(sv_create_general_sil_triangles_checked(v, out.data(), bound, facing.data(), 4, 1,
                                                      &e),
              SV_E_INDEX_RANGE);
    EXPECT_EQ(sv_create_general_sil_triangles_checked(v, out.data(), bound, facing.data(), 3, nv,
                                                      &e),
              SV_E_INDEX_RANGE);
    std::vector<int> uses = g.shared_uses;
    sv_general_edges e2 = e;
    e2.sharedUses = uses.data();
    uses[1] = 2 * 9;
    EXPECT_EQ(sv_create_general_sil_triangles_checked(v, out.data(), bound, facing.data(), 4, nv,
                                                      &e2),
              SV_E_INDEX_RANGE);
    std::vector<sv_shared_edge> shared = g.shared;
    shared[0].numUses = 5;
    e2 = e;
    e2.shared = shared.data();
    EXPECT_EQ(sv_create_general_sil_triangles_checked(v, out.data(), bound, facing.data(), 4, nv,
                                                      &e2),
              SV_E_INDEX_RANGE);
    std::vector<SilEdge> opens = g.opens;
    opens[0].v1 += 1;
    e2 = e;
    e2.opens = opens.data();
    EXPECT_EQ(sv_create_general_sil_triangles_checked(v, out.data(), bound, facing.data(), 4, nv,
                                                      &e2),
              SV_E_ODD_VERTEX);
    EXPECT_EQ(sv_create_general_sil_triangles_checked(v, out.data(), bound, facing.data(), 4, nv,
                                                      nullptr),
              SV_E_NULL);
    /* The caps: 6 per casting triangle, 2 * numIndices at most. */
    std::vector<int> caps(2 * (std::size_t)s.num_indices());
    EXPECT_EQ(sv_create_general_cap_triangles_checked(v, caps.data(), caps.size(), facing.data(),
                                                      s.indices.data(), s.num_indices(), nv),
              24);
    EXPECT_EQ(sv_create_general_cap_triangles_checked(v, caps.data(), caps.size() - 1,
                                                      facing.data(), s.indices.data(),
                                                      s.num_indices(), nv),
              SV_E_CAPACITY);
    EXPECT_EQ(sv_create_general_cap_triangles_checked(v, caps.data(), caps.size(), bad.data(),
                                                      s.indices.data(), s.num_indices(), nv),
              SV_E_GENERAL_FACING);
}

Frame render(const Scene &scene, ModeChoice mode, CasterRule rule, GeneralBuild build, int w,
             int h) {
    RenderOptions o;
    o.width = w, o.height = h, o.mode = mode, o.caster_rule = rule, o.general_build = build;
    return render_frame(scene, o);
}

/* The stencils of direct and two-sided, byte for byte; the pictures. */
void expect_direct_is_two_sided(const Scene &scene, ModeChoice mode, CasterRule rule, int w, int h,
                                const std::string &what) {
    const Frame d = render(scene, mode, rule, GeneralBuild::direct, w, h);
    const Frame t = render(scene, mode, rule, GeneralBuild::two_sided, w, h);
    ASSERT_EQ(d.lights.size(), t.lights.size());
    for (std::size_t li = 0; li < d.lights.size(); li++)
        EXPECT_EQ(d.lights[li].stencil, t.lights[li].stencil)
            << what << ", " << mode_name(mode) << ", " << caster_rule_name(rule) << ", light "
            << li;
    EXPECT_EQ(d.rgb, t.rgb) << what << ", " << mode_name(mode);
}

class DirectOpenCase : public ::testing::TestWithParam<int> {};

TEST_P(DirectOpenCase, DirectDrawsTheTwoSidedStencil) {
    const svtest::Soup soup = svtest::open_cases()[(std::size_t)GetParam()];
    const Scene scene = svtest::scene_of(soup, kW, kH);
    for (ModeChoice mode : {ModeChoice::zpass, ModeChoice::zfail})
        for (CasterRule rule : {CasterRule::automatic, CasterRule::general})
            expect_direct_is_two_sided(scene, mode, rule, kW, kH, soup.name);
    /* And the truth, off the boundary, as two-sided has it. */
    const TruthCaster caster(scene);
    for (ModeChoice mode : {ModeChoice::zpass, ModeChoice::zfail}) {
        const Frame f = render(scene, mode, CasterRule::automatic, GeneralBuild::direct, kW, kH);
        for (std::size_t li = 0; li < f.lights.size(); li++)
            EXPECT_EQ(
                caster.compare(f, (int)li, caster.cast(f, (int)li, 2)).off_boundary_mismatches, 0u)
                << soup.name << ", " << mode_name(mode) << ", light " << li;
    }
}

INSTANTIATE_TEST_SUITE_P(Generated, DirectOpenCase,
                         ::testing::Range(0, (int)svtest::open_cases().size()),
                         [](const ::testing::TestParamInfo<int> &i) {
                             std::string n = svtest::open_cases()[(std::size_t)i.param].name;
                             for (char &ch : n)
                                 if (!std::isalnum((unsigned char)ch)) ch = '_';
                             return n;
                         });

TEST(GeneralRuleSharedModels, DirectDrawsTheTwoSidedStencilOnTheOpenCharactersAnimations) {
    /* Two frames of every animation (its start and middle), a point, a
     * spot and a directional light, both modes, at 320x256. */
    SequenceOptions o;
    o.file = svtest::shared_models_dir() + "/open/Zombie_Basic.glb";
    o.ground = true;
    constexpr int w = 320, h = 256;
    o.aspect = (double)w / h;
    int animations = 0;
    for (int a = 0;; a++) {
        o.animation = std::to_string(a);
        std::unique_ptr<SceneSequence> seq;
        try {
            seq = std::make_unique<SceneSequence>(o);
        } catch (const std::exception &e) {
            if (a == 0) GTEST_SKIP() << o.file << ": " << e.what();
            break; /* no animation A */
        }
        animations++;
        for (double t : {seq->start(), 0.5 * (seq->start() + seq->end())}) {
            seq->set_time(t);
            for (ModeChoice mode : {ModeChoice::zpass, ModeChoice::zfail})
                expect_direct_is_two_sided(seq->scene(), mode, CasterRule::automatic, w, h,
                                           "animation " + std::to_string(a) + " at " +
                                               std::to_string(t));
        }
    }
    EXPECT_GT(animations, 1);
}

/* N stacked horizontal layers over a ground, a light above: the stencil
 * at a ground point under them all, in z-pass, with the camera outside
 * every volume. Each layer is a closed flat box (CLOSED) or one open
 * quad. */
uint8_t stencil_under_layers(int n, bool closed, CasterRule rule) {
    svtest::Soup layers{"layers"};
    for (int i = 0; i < n; i++) {
        const double y = 1.0 + 0.004 * i;
        if (closed) {
            svtest::add_box(layers, -1, y, -1, 1, y + 0.002, 1, true);
        } else {
            layers.quad(layers.vertex(-1, y, 1), layers.vertex(1, y, 1), layers.vertex(1, y, -1),
                        layers.vertex(-1, y, -1));
        }
    }
    Scene scene = svtest::scene_of(layers, 64, 64);
    svtest::view_under_point_light(scene, {0, 0.5, 6}, {0, 0, 0}, {0.3, 6, 0.2});
    const Frame f = render(scene, ModeChoice::zpass, rule, GeneralBuild::direct, 64, 64);
    /* The picture's centre: the ground near the origin, under every layer
     * (the light is off the layers' diagonals there). */
    const std::size_t i = (std::size_t)32 * 64 + 32;
    EXPECT_GE(f.target.ids[i], scene.surfaces[0].prepared.num_triangles()) << "not the ground";
    return f.lights[0].stencil[i];
}

TEST(GeneralRule, EightBitWrapAroundOfTheCount) {
    /* Open layers count 1 each under the general rule: 255 still shadow,
     * 256 wrap to 0, the point wrongly lit (docs/CASTERS.md). */
    EXPECT_EQ(stencil_under_layers(255, false, CasterRule::automatic), 255);
    EXPECT_EQ(stencil_under_layers(256, false, CasterRule::automatic), 0);
    EXPECT_EQ(stencil_under_layers(257, false, CasterRule::automatic), 1);
    /* Closed layers: 1 each under the paper's rule (auto keeps it), 2
     * under the general rule: 128 of them wrap there. */
    EXPECT_EQ(stencil_under_layers(128, true, CasterRule::automatic), 128);
    EXPECT_EQ(stencil_under_layers(127, true, CasterRule::general), 254);
    EXPECT_EQ(stencil_under_layers(128, true, CasterRule::general), 0);
}

} // namespace
