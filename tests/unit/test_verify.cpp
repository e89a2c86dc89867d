// The verifier (shadowvol_verify.h) checked on its own: winding numbers of
// known solids, closure on broken lists, and -- the part that matters -- that
// verify_light FAILS for volumes that are wrong in the ways a broken kernel
// would make them wrong (a missing quad, the whole volume reversed, the
// volume of the wrong triangles, culling ignored), while it passes
// every real variant on the generated character and on meshes with open and
// non-manifold edges.
//
// Copyright (C) 2026 the shadowvol authors. LGPL-2.1-or-later.
#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <string>
#include <vector>

#include "model_gen.h"
#include "open_cases.h"
#include "shadowvol_casters.h"
#include "shadowvol_mesh.h"
#include "shadowvol_verify.h"

namespace {

using sv::Point3;

uint64_t test_seed() {
    const char *s = std::getenv("SV_TEST_SEED");
    if (s && std::strcmp(s, "random") != 0) return std::strtoull(s, nullptr, 0);
    return 20050408;
}

sv::PreparedSurface prepare(const std::vector<float> &pos, const std::vector<uint32_t> &idx) {
    return sv::prepare_surface(pos.data(), pos.size() / 3, idx.data(), idx.size());
}

// An axis-aligned cube [-1, 1]^3, outward counter-clockwise triangles.
sv::PreparedSurface cube() {
    std::vector<float> p;
    for (int i = 0; i < 8; i++) {
        p.push_back(i & 1 ? 1.f : -1.f);
        p.push_back(i & 2 ? 1.f : -1.f);
        p.push_back(i & 4 ? 1.f : -1.f);
    }
    const std::vector<uint32_t> idx = {0, 2, 3, 0, 3, 1, 4, 5, 7, 4, 7, 6, 0, 1, 5, 0, 5, 4,
                                       2, 6, 7, 2, 7, 3, 0, 4, 6, 0, 6, 2, 1, 3, 7, 1, 7, 5};
    return prepare(p, idx);
}

TEST(WindingVolume, TetrahedronIsOneInsideZeroOutside) {
    const std::vector<Point3> v = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0, 0, 1}};
    const int outward[] = {0, 2, 1, 0, 1, 3, 0, 3, 2, 1, 2, 3};
    sv::WindingVolume vol(v, outward, 12);
    uint64_t rng = 1;
    int w = 99;
    ASSERT_EQ(vol.winding({0.1, 0.1, 0.1}, rng, &w, nullptr), sv::WindingVolume::Status::ok);
    EXPECT_EQ(w, 1);
    ASSERT_EQ(vol.winding({2, 2, 2}, rng, &w, nullptr), sv::WindingVolume::Status::ok);
    EXPECT_EQ(w, 0);
    // Reversed, the inside counts -1: the sign is checked, not just != 0.
    const int inward[] = {0, 1, 2, 0, 3, 1, 0, 2, 3, 1, 3, 2};
    sv::WindingVolume rev(v, inward, 12);
    ASSERT_EQ(rev.winding({0.1, 0.1, 0.1}, rng, &w, nullptr), sv::WindingVolume::Status::ok);
    EXPECT_EQ(w, -1);
    // On a face: reported, not guessed.
    EXPECT_EQ(vol.winding({0.2, 0.2, 0}, rng, &w, nullptr), sv::WindingVolume::Status::on_boundary);
}

TEST(Closure, FindsTheOpenEdgeAndBadIndices) {
    const int tet[] = {0, 4, 2, 0, 2, 6, 0, 6, 4, 2, 4, 6};
    EXPECT_TRUE(sv::check_closure(tet, 12, 4).closed);
    sv::ClosureResult r = sv::check_closure(tet, 9, 4);
    EXPECT_FALSE(r.closed);
    EXPECT_NE(r.problem.find("open"), std::string::npos) << r.problem;
    EXPECT_FALSE(sv::check_closure(tet, 12, 3).closed); // index 6 >= 2 * 3
    EXPECT_FALSE(sv::check_closure(tet, 11, 4).closed); // not whole triangles
    // Two copies of one triangle, opposite windings: closed (degenerate).
    const int pair[] = {0, 2, 4, 4, 2, 0};
    EXPECT_TRUE(sv::check_closure(pair, 6, 3).closed);
}

// ---- Broken "variants": each wraps c_ref and breaks one thing -----------

int sil_drop_last_quad(int *out, const uint8_t *facing, const SilEdge *e, int n) {
    int k = sv_create_sil_triangles_c_ref(out, facing, e, n);
    return k >= 6 ? k - 6 : k;
}
int sil_reversed(int *out, const uint8_t *facing, const SilEdge *e, int n) {
    int k = sv_create_sil_triangles_c_ref(out, facing, e, n);
    for (int i = 0; i < k; i += 3) std::swap(out[i + 1], out[i + 2]);
    return k;
}
int cap_reversed(int *out, const uint8_t *facing, const int *idx, int n) {
    int k = sv_create_cap_triangles_c_ref(out, facing, idx, n);
    for (int i = 0; i < k; i += 3) std::swap(out[i + 1], out[i + 2]);
    return k;
}
// Culling ignored: triangles outside the light volume still cast (closed,
// but wrong in space for a culled light).
int count_cull_ignored(uint8_t *facing, int n, const int *, const uint8_t *) {
    return sv_count_facing_c_ref(facing, n);
}
// The volume of the lit triangles instead of the unlit ones.
int count_inverted(const uint8_t *facing, int n) { return n - sv_count_facing_c_ref(facing, n); }
int g_num_triangles = 0; // of the surface under test (the sil routine is not told)
int sil_inverted(int *out, const uint8_t *facing, const SilEdge *e, int n) {
    // Facing flipped for every triangle (the dangling byte stays 1).
    const int nt = g_num_triangles;
    std::vector<uint8_t> f(facing, facing + nt + 1);
    for (int i = 0; i < nt; i++) f[i] ^= 1;
    return sv_create_sil_triangles_c_ref(out, f.data(), e, n);
}
int cap_inverted(int *out, const uint8_t *facing, const int *idx, int n) {
    std::vector<uint8_t> f(facing, facing + n / 3 + 1);
    for (int i = 0; i < n / 3; i++) f[i] ^= 1;
    return sv_create_cap_triangles_c_ref(out, f.data(), idx, n);
}

sv_variant broken(const char *name) {
    sv_variant v = *sv_variant_by_name("c_ref");
    v.name = name;
    return v;
}

std::vector<sv::VerifyLight> lights_for(const sv::PreparedSurface &s, int n) {
    return sv::make_verify_lights(s, n, test_seed());
}

// Runs every light; returns the first failure ("" when all pass).
std::string run_all(const sv::PreparedSurface &s, const std::vector<const sv_variant *> &vars,
                    int lights, int points, sv::InSpaceCounts *total = nullptr) {
    sv::VerifyOptions o;
    o.points_per_light = points;
    int i = 0;
    int64_t culled_total = 0;
    for (const sv::VerifyLight &l : lights_for(s, lights)) {
        sv::LightResult r = sv::verify_light(s, l, vars, o, test_seed() + (uint64_t)i++);
        if (!r.ok) return r.failure;
        if (total) total->add(r.counts);
        if (l.culled) culled_total += r.culled_triangles;
    }
    // The culled lights must really cull something, or culling is untested.
    if (lights >= 2 && culled_total == 0) return "no light culled any triangle";
    return "";
}

sv::PreparedSurface character() {
    const svgen::TriMesh m = svgen::build_character(1);
    return prepare(m.positions, m.indices);
}

TEST(VerifyLight, EveryRealVariantPassesOnTheCharacter) {
    const sv::PreparedSurface s = character();
    ASSERT_EQ(s.num_triangles(), 1344);
    sv::InSpaceCounts total;
    const std::string failure = run_all(s, sv::supported_variants(), 12, 300, &total);
    EXPECT_EQ(failure, "");
    // The check has teeth only if both outcomes occur often.
    EXPECT_GT(total.in_shadow, 300);
    EXPECT_GT(total.lit, 300);
    EXPECT_GT(total.crossing_checked, 300);
    EXPECT_LT(total.skipped, total.points / 50 + 1);
}

TEST(VerifyLight, CubeShadowsExactlyBehindIt) {
    const sv::PreparedSurface s = cube();
    sv::VerifyLight l;
    l.light = {0, 0, 10, 1};
    sv::VerifyOptions o;
    o.points_per_light = 2000;
    sv::LightResult r = sv::verify_light(s, l, sv::supported_variants(), o, test_seed());
    EXPECT_TRUE(r.ok) << r.failure;
    EXPECT_EQ(r.distinct_volumes, 1) << "variants disagree with c_ref";
    EXPECT_GT(r.counts.in_shadow, 100);
}

// A broken variant, what breaks it, and a word its failure must hold.
template <class Variant> struct BrokenCase {
    const char *what;
    Variant v;
    const char *expect;
};

// RUN(variant) gives each case's first failure: it must name the variant
// and hold the expected word.
template <class Variant, class Run>
void expect_each_caught(const std::vector<BrokenCase<Variant>> &cases, Run run) {
    for (const BrokenCase<Variant> &c : cases) {
        SCOPED_TRACE(c.what);
        const std::string failure = run(c.v);
        EXPECT_NE(failure.find(c.expect), std::string::npos) << "failure: '" << failure << "'";
        EXPECT_NE(failure.find(c.v.name), std::string::npos) << failure;
        std::printf("  caught %s: %s\n", c.what, failure.c_str());
    }
}

TEST(VerifyLight, CatchesEveryBrokenVolume) {
    const sv::PreparedSurface s = character();
    g_num_triangles = s.num_triangles();
    using Case = BrokenCase<sv_variant>;
    std::vector<Case> cases;
    {
        sv_variant v = broken("drops_a_quad");
        v.create_sil_triangles = sil_drop_last_quad;
        cases.push_back({"a missing silhouette quad", v, "not closed"});
    }
    {
        sv_variant v = broken("reversed");
        v.create_sil_triangles = sil_reversed;
        v.create_cap_triangles = cap_reversed;
        cases.push_back({"every triangle reversed", v, "winding number"});
    }
    {
        sv_variant v = broken("ignores_culling");
        v.count_facing_cull = count_cull_ignored;
        cases.push_back({"culled triangles still cast", v, "winding number"});
    }
    {
        sv_variant v = broken("lit_triangles");
        v.count_facing = count_inverted;
        v.create_sil_triangles = sil_inverted;
        v.create_cap_triangles = cap_inverted;
        cases.push_back({"the volume of the lit triangles", v, "winding number"});
    }
    expect_each_caught(cases, [&](const sv_variant &v) { return run_all(s, {&v}, 4, 300); });
}

// An open box (cube without its top) plus a fin: three triangles on one
// edge, and one triangle sharing an edge in the same direction.
sv::PreparedSurface open_box_with_fin() {
    sv::PreparedSurface c = cube();
    std::vector<float> p(c.positions);
    std::vector<uint32_t> idx(c.indices.begin(), c.indices.end() - 6);
    const uint32_t n = (uint32_t)p.size() / 3;
    for (float f : {0.f, 3.f, 0.f, 0.f, 2.5f, 2.5f}) p.push_back(f);
    idx.insert(idx.end(), {2, 3, n, 3, 2, n + 1, 0, 2, n});
    return prepare(p, idx);
}

// Open and non-manifold meshes: the identity holds for any mesh (the
// "iff the segment crosses" check is for closed meshes only).
TEST(VerifyLight, OpenAndNonManifoldMeshes) {
    const sv::PreparedSurface s = open_box_with_fin();
    ASSERT_GT(s.report.boundary_edges, 0);
    ASSERT_GT(s.report.non_manifold_edges + s.report.same_direction_edges, 0);
    EXPECT_EQ(run_all(s, sv::supported_variants(), 16, 400), "");
}

// ---- The general rule's direct kernels (issue 27) ----------------------------

// Broken general kernels, each from the reference: a quad dropped; every
// triangle reversed; the paper's rule (a lit triangle's reverse casts
// nothing: byte 2 read as 1).
int gsil_drop_last_quad(int *out, const uint8_t *facing, const sv_general_edges *e) {
    const int n = sv_create_general_sil_triangles_c_ref(out, facing, e);
    return n >= 6 ? n - 6 : n;
}
void reverse_triangles(int *out, int n) {
    for (int i = 0; i + 2 < n; i += 3) std::swap(out[i], out[i + 1]);
}
int gsil_reversed(int *out, const uint8_t *facing, const sv_general_edges *e) {
    const int n = sv_create_general_sil_triangles_c_ref(out, facing, e);
    reverse_triangles(out, n);
    return n;
}
int gcap_reversed(int *out, const uint8_t *facing, const int *idx, int n) {
    const int m = sv_create_general_cap_triangles_c_ref(out, facing, idx, n);
    reverse_triangles(out, m);
    return m;
}
int g_general_triangles = 0; // of the surface under test (the sil kernel is not told)
std::vector<uint8_t> papers_bytes(const uint8_t *facing, int nt) {
    std::vector<uint8_t> f(facing, facing + nt + 1);
    for (uint8_t &b : f) b = b == SV_GENERAL_LIT ? (uint8_t)SV_GENERAL_NONE : b;
    return f;
}
int gsil_papers(int *out, const uint8_t *facing, const sv_general_edges *e) {
    return sv_create_general_sil_triangles_c_ref(out,
                                                 papers_bytes(facing, g_general_triangles).data(),
                                                 e);
}
int gcap_papers(int *out, const uint8_t *facing, const int *idx, int n) {
    return sv_create_general_cap_triangles_c_ref(out, papers_bytes(facing, n / 3).data(), idx, n);
}

// Every light on S, its general edge table under RULE; the first failure
// ("" when all pass).
std::string run_general(const sv::PreparedSurface &s, sv::CasterRule rule,
                        const std::vector<const sv_general_variant *> &vars, int lights, int points,
                        sv::InSpaceCounts *total = nullptr) {
    const sv::GeneralEdgeTable table = sv::general_edge_table(s, sv::find_shells(s), rule);
    sv::VerifyOptions o;
    o.points_per_light = points;
    int i = 0;
    for (const sv::VerifyLight &l : lights_for(s, lights)) {
        const sv::LightResult r = sv::verify_general_light(s, table, l, vars, o,
                                                           test_seed() + (uint64_t)i++);
        if (!r.ok) return r.failure;
        if (total) total->add(r.counts);
    }
    return "";
}

TEST(VerifyGeneralLight, EveryGeneralKernelPassesOnOpenMeshes) {
    // Every generated open case of issue 27 and the box with its fin, under
    // the general rule: closed with the multiplicities, right in space, and
    // in shadow exactly where the segment to the light crosses the mesh.
    std::vector<std::pair<std::string, sv::PreparedSurface>> meshes;
    for (const svgen::Soup &c : svgen::open_cases())
        meshes.emplace_back(c.name, prepare(c.pos, c.idx));
    meshes.emplace_back("open box with a fin", open_box_with_fin());
    sv::InSpaceCounts total;
    for (const auto &m : meshes) {
        SCOPED_TRACE(m.first);
        EXPECT_EQ(run_general(m.second, sv::CasterRule::general, sv::supported_general_variants(),
                              8, 200, &total),
                  "");
    }
    EXPECT_GT(total.in_shadow, 300);
    EXPECT_GT(total.lit, 300);
    EXPECT_GT(total.crossing_checked, 300);
    // Under auto the closed shells keep the paper's class in the same
    // table: the character (one closed shell) and the fin's mesh.
    EXPECT_EQ(run_general(character(), sv::CasterRule::automatic, sv::supported_general_variants(),
                          4, 200),
              "");
}

TEST(VerifyGeneralLight, CatchesEveryBrokenGeneralKernel) {
    const sv::PreparedSurface s = open_box_with_fin();
    g_general_triangles = s.num_triangles();
    using Case = BrokenCase<sv_general_variant>;
    const sv_general_variant ref = *sv_general_variant_by_name("c_ref");
    std::vector<Case> cases;
    {
        sv_general_variant v = ref;
        v.name = "drops_a_quad";
        v.create_general_sil_triangles = gsil_drop_last_quad;
        cases.push_back({"a missing silhouette quad", v, "not closed"});
    }
    {
        sv_general_variant v = ref;
        v.name = "reversed";
        v.create_general_sil_triangles = gsil_reversed;
        v.create_general_cap_triangles = gcap_reversed;
        cases.push_back({"every triangle reversed", v, "winding number"});
    }
    {
        sv_general_variant v = ref;
        v.name = "papers_rule";
        v.create_general_sil_triangles = gsil_papers;
        v.create_general_cap_triangles = gcap_papers;
        cases.push_back({"the paper's rule on an open mesh", v, "winding number"});
    }
    expect_each_caught(cases, [&](const sv_general_variant &v) {
        return run_general(s, sv::CasterRule::general, {&v}, 8, 300);
    });
}

} // namespace

// The hierarchy only prunes: every triangle a ray really crosses must be
// among the candidates it hands out (checked against a plain plane-and-
// barycentric test of every triangle, for rays and segments).
#include "ray_triangles.h"

namespace {

bool crosses(const Point3 &p, const Point3 &r, double s_max, const Point3 &a, const Point3 &e1,
             const Point3 &e2) {
    const Point3 n{e1.y * e2.z - e1.z * e2.y, e1.z * e2.x - e1.x * e2.z, e1.x * e2.y - e1.y * e2.x};
    const double rn = r.x * n.x + r.y * n.y + r.z * n.z;
    if (rn == 0) return false;
    const double s = ((a.x - p.x) * n.x + (a.y - p.y) * n.y + (a.z - p.z) * n.z) / rn;
    if (s < 0 || s > s_max) return false;
    const Point3 q{p.x + s * r.x - a.x, p.y + s * r.y - a.y, p.z + s * r.z - a.z};
    // Barycentrics by least squares on the two edges.
    const double d11 = e1.x * e1.x + e1.y * e1.y + e1.z * e1.z;
    const double d12 = e1.x * e2.x + e1.y * e2.y + e1.z * e2.z;
    const double d22 = e2.x * e2.x + e2.y * e2.y + e2.z * e2.z;
    const double q1 = q.x * e1.x + q.y * e1.y + q.z * e1.z;
    const double q2 = q.x * e2.x + q.y * e2.y + q.z * e2.z;
    const double den = d11 * d22 - d12 * d12;
    const double u = (q1 * d22 - q2 * d12) / den, v = (q2 * d11 - q1 * d12) / den;
    return u >= 0 && v >= 0 && u + v <= 1;
}

TEST(RayTriangles, CandidatesContainEveryCrossing) {
    const sv::PreparedSurface s = character();
    sv::RayTriangles tr;
    for (int t = 0; t < s.num_triangles(); t++) {
        const int *i = &s.indices[3 * (size_t)t];
        auto v = [&](int k) {
            return Point3{s.positions[3 * (size_t)k], s.positions[3 * (size_t)k + 1],
                          s.positions[3 * (size_t)k + 2]};
        };
        tr.add(v(i[0]), v(i[1]), v(i[2]));
    }
    tr.build(1e-7);
    uint64_t state = test_seed();
    auto rnd = [&]() {
        state = state * 6364136223846793005ull + 1442695040888963407ull;
        return (double)(state >> 11) * 0x1.0p-53 * 4 - 2;
    };
    int64_t crossings = 0, candidates = 0;
    for (int ray = 0; ray < 2000; ray++) {
        // From a random point towards a random corner of the mesh (nudged),
        // so that most rays do cross it.
        const Point3 p{rnd(), rnd(), rnd()};
        const size_t k = (size_t)(state >> 20) % tr.size();
        Point3 r{tr.a[k].x + 0.01 * rnd() - p.x, tr.a[k].y + 0.01 * rnd() - p.y,
                 tr.a[k].z + 0.01 * rnd() - p.z};
        const double len = std::sqrt(r.x * r.x + r.y * r.y + r.z * r.z);
        r = {r.x / len, r.y / len, r.z / len}; // odd rays: to infinity; even: segments
        const double s_max = ray % 2 ? HUGE_VAL : len;
        std::vector<char> seen(tr.size(), 0);
        tr.for_each_candidate(p, r, s_max, [&](uint32_t t) {
            seen[t] = 1;
            candidates++;
            return true;
        });
        for (size_t t = 0; t < tr.size(); t++) {
            if (crosses(p, r, s_max, tr.a[t], tr.e1[t], tr.e2[t])) {
                crossings++;
                ASSERT_TRUE(seen[t]) << "ray " << ray << " crosses triangle " << t
                                     << " but the hierarchy skipped it";
            }
        }
    }
    EXPECT_GT(crossings, 1000);                            // the rays do cross the mesh
    EXPECT_LT(candidates, 2000 * (int64_t)tr.size() / 10); // and it prunes
}

} // namespace

// Issue 17: verify's range of scales, and "cannot decide" as a result of its
// own. A tetrahedron scaled 1e-45 used to FAIL with a winding-number
// "mismatch" while its volume was closed and right: the verifier clamped the
// surface's radius at 1e-30, so its lights and sample points sat 10^15 mesh
// sizes away, beyond double's precision near the mesh. Without the clamp,
// tetrahedra across the documented range decide and pass; below FLT_MIN the
// answer is "cannot decide", with the reason, never a failure.
namespace {
sv::LightResult verify_tetrahedron(double scale, int lights, bool *all_decided) {
    const float s = (float)scale;
    const std::vector<float> pos = {0, 0, 0, s, 0, 0, 0, s, 0, 0, 0, s};
    const std::vector<uint32_t> idx = {0, 2, 1, 0, 1, 3, 0, 3, 2, 1, 2, 3};
    const sv::PreparedSurface t = prepare(pos, idx);
    sv::VerifyOptions o;
    o.points_per_light = 400;
    sv::LightResult last;
    *all_decided = true;
    for (const sv::VerifyLight &l : sv::make_verify_lights(t, lights, 11)) {
        last = sv::verify_light(t, l, sv::supported_variants(), o, 5);
        if (!last.ok) return last;
        if (last.undecided) *all_decided = false;
    }
    return last;
}
} // namespace

TEST(VerifyScale, TetrahedraAcrossTheRangeDecideAndPass) {
    for (double scale : {2e-38, 1e-33, 1e-20, 1.0, 1e20, 1e30, 5e35}) {
        bool decided = false;
        const sv::LightResult r = verify_tetrahedron(scale, 8, &decided);
        EXPECT_TRUE(r.ok) << scale << ": " << r.failure;
        EXPECT_TRUE(decided) << scale << ": " << r.undecided_reason;
    }
}

TEST(VerifyScale, OutsideTheRangeIsUndecidedNeverFailed) {
    for (double scale : {1e-45, 1e-40, 2e36}) {
        bool decided = true;
        const sv::LightResult r = verify_tetrahedron(scale, 8, &decided);
        EXPECT_TRUE(r.ok) << scale << ": " << r.failure;
        EXPECT_FALSE(decided) << scale;
    }
    bool decided = true;
    const sv::LightResult r = verify_tetrahedron(1e-45, 1, &decided);
    EXPECT_NE(r.undecided_reason.find("outside the range verify decides"), std::string::npos)
        << r.undecided_reason;
    EXPECT_LT(sv::kVerifyMinRadius, 2e-38 * 0.87);
    EXPECT_GT(sv::kVerifyMaxRadius, 5e35 * 0.87);
}

// Three vertices at one position and collinear triangles: many points
// cannot be decided; that is "cannot decide" with its reason, not FAILED.
TEST(VerifyScale, DegenerateMeshIsUndecidedNotFailed) {
    // A flat fan of collinear triangles plus a triangle with coincident
    // corners, in a line: nothing but boundaries.
    const std::vector<float> pos = {0, 0, 0, 1, 0, 0, 2, 0, 0, 3, 0, 0, 1, 1e-7f, 0};
    const std::vector<uint32_t> idx = {0, 1, 4, 1, 2, 4, 2, 3, 4, 0, 4, 3};
    const sv::PreparedSurface t = prepare(pos, idx);
    sv::VerifyOptions o;
    o.points_per_light = 400;
    int undecided = 0;
    for (const sv::VerifyLight &l : sv::make_verify_lights(t, 8, 3)) {
        const sv::LightResult r = sv::verify_light(t, l, sv::supported_variants(), o, 9);
        EXPECT_TRUE(r.ok) << r.failure;
        if (r.undecided) {
            undecided++;
            EXPECT_NE(r.undecided_reason.find("too close to a boundary"), std::string::npos)
                << r.undecided_reason;
        }
    }
    EXPECT_GT(undecided, 0);
}
