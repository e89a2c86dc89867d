// The numerical extremes (issue 7), every test named Extreme.*: coordinates
// near FLT_MAX, near FLT_MIN and among the subnormals; a light exactly on a
// triangle's plane, at a vertex, at infinity along an axis and along a face
// normal; zero-area triangles; NaN and infinite positions and light
// components; counts at the limits of int.
//
// For each mesh and light, in the default MXCSR and with FTZ and DAZ set:
//  - every implementation of appendix A in sv_facing_variants() gives the
//    reference's bytes;
//  - every variant of the accuracy study (accuracy_variants.h) keeps its
//    contract: SIMD twins equal their definitions, exact equals the
//    big-integer reference, the inexact ones equal exact wherever |D|
//    exceeds their error bound; and gives the same bytes in both MXCSR
//    modes (the reference may not: its bound then covers FTZ/DAZ);
//  - nothing is written past numTriangles + 1 facing bytes (guard bytes);
//  - for every distinct facing array, every kernel set of sv_variants()
//    builds, through sv_create_shadow_volume (with and without cull bits),
//    the same index list as the reference kernels, writes nothing past
//    sv_shadow_volume_capacity, and the volume is closed (sv::check_closure).
//
// Copyright (C) 2026 the shadowvol authors. LGPL-2.1-or-later.
#include "test_support.h"

#include <xmmintrin.h>

#include <algorithm>
#include <cfloat>
#include <climits>
#include <cmath>
#include <cstring>
#include <limits>
#include <set>

#include "accuracy_reference.h"
#include "accuracy_variants.h"
#include "shadowvol_accuracy.h"
#include "shadowvol_gltf.h"
#include "shadowvol_verify.h"

namespace {

using svtest::GuardedBuffer;
namespace acc = sv::acc;

constexpr float kNaN = std::numeric_limits<float>::quiet_NaN();
constexpr float kInf = std::numeric_limits<float>::infinity();
constexpr unsigned kDefaultCsr = 0x1F80u, kFtzDazCsr = 0x1F80u | 0x8040u;

struct Mesh {
    std::vector<float> positions;
    std::vector<uint32_t> indices;
};

// A closed octahedron: vertices +-S on the axes around CENTER, outward
// (counter-clockwise from outside) faces.
Mesh octahedron(float s, const float center[3] = nullptr) {
    const float c[3] = {center ? center[0] : 0, center ? center[1] : 0, center ? center[2] : 0};
    Mesh m;
    const float v[6][3] = {{s, 0, 0}, {-s, 0, 0}, {0, s, 0}, {0, -s, 0}, {0, 0, s}, {0, 0, -s}};
    for (const auto &p : v) {
        for (int i = 0; i < 3; i++) m.positions.push_back(p[i] == 0 ? c[i] : c[i] + p[i]);
    }
    // +x=0 -x=1 +y=2 -y=3 +z=4 -z=5
    m.indices = {0, 2, 4, 2, 1, 4, 1, 3, 4, 3, 0, 4, 2, 0, 5, 1, 2, 5, 3, 1, 5, 0, 3, 5};
    return m;
}

// A closed cube [0, k]^3 * unit, 12 triangles, outward.
Mesh cube(float k, float unit) {
    Mesh m;
    for (int i = 0; i < 8; i++) {
        m.positions.push_back((float)(i & 1) * k * unit);
        m.positions.push_back((float)((i >> 1) & 1) * k * unit);
        m.positions.push_back((float)((i >> 2) & 1) * k * unit);
    }
    m.indices = {0, 2, 1, 1, 2, 3, 4, 5, 6, 5, 7, 6, 0, 1, 4, 1, 5, 4,
                 2, 6, 3, 3, 6, 7, 0, 4, 2, 2, 4, 6, 1, 3, 5, 3, 7, 5};
    return m;
}

Mesh character() {
    const sv::GltfModel g = sv::load_gltf(std::string(SV_MODELS_DIR) + "/character_1344.glb");
    return Mesh{g.surfaces[0].positions, g.surfaces[0].indices};
}

sv::PreparedSurface prepare(const Mesh &m) {
    return sv::prepare_surface(m.positions.data(), m.positions.size() / 3, m.indices.data(),
                               m.indices.size());
}

const float *corner(const sv::PreparedSurface &s, int t, int k) {
    return &s.positions[3 * (std::size_t)s.indices[3 * (std::size_t)t + (std::size_t)k]];
}

template <class F> void with_mxcsr(unsigned csr, F &&f) {
    const unsigned saved = _mm_getcsr();
    _mm_setcsr(csr);
    f();
    _mm_setcsr(saved);
}

bool light_finite(const Vec4 &l) {
    return std::isfinite(l.x) && std::isfinite(l.y) && std::isfinite(l.z) && std::isfinite(l.w);
}

std::string light_text(const Vec4 &l) {
    char buf[160];
    std::snprintf(buf, sizeof buf, "light (%a, %a, %a, %g)", l.x, l.y, l.z, l.w);
    return buf;
}

// The light box of a point light (appendix B's planes, inward), for the
// culled volumes: a cube of half size H around it.
void light_box(const Vec4 &l, float h, Plane planes[SV_NUM_LIGHT_PLANES]) {
    const float c[3] = {l.x, l.y, l.z};
    for (int i = 0; i < 3; i++) {
        Plane lo{0, 0, 0, 0}, hi{0, 0, 0, 0};
        (&lo.a)[i] = 1;
        lo.d = -(c[i] - h);
        (&hi.a)[i] = -1;
        hi.d = c[i] + h;
        planes[2 * i] = lo;
        planes[2 * i + 1] = hi;
    }
}

// Builds the volume of FACING with every kernel set; compares with the
// reference kernels, checks guards and closure.
void check_volumes(const sv::PreparedSurface &s, const std::vector<uint8_t> &facing,
                   const uint8_t *cull, const std::string &what) {
    const int ni = s.num_indices(), ne = s.num_sil_edges(), nt = s.num_triangles();
    const std::size_t cap = sv_shadow_volume_capacity(ni, ne);
    ASSERT_LE(cap, (std::size_t)INT_MAX);
    std::vector<int> want;
    int want_n = -1;
    for (const sv_variant *v : svtest::runnable_variants()) {
        GuardedBuffer f((std::size_t)nt + 1, 0);
        std::memcpy(f.data(), facing.data(), (std::size_t)nt + 1);
        GuardedBuffer out(cap * sizeof(int), 0);
        const int n = sv_create_shadow_volume(v, out.as<int>(), s.indices.data(), ni,
                                              s.sil_edges.data(), ne, f.data(), cull);
        ASSERT_TRUE(out.guards_intact()) << v->name << ": wrote past the capacity, " << what;
        ASSERT_TRUE(f.guards_intact()) << v->name << ": wrote past facing, " << what;
        ASSERT_GE(n, 0);
        ASSERT_LE((std::size_t)n, cap);
        const sv::ClosureResult c = sv::check_closure(out.as<int>(), n, s.num_vertices());
        ASSERT_TRUE(c.closed) << v->name << ": " << c.problem << ", " << what;
        if (want_n < 0) {
            want_n = n;
            want.assign(out.as<int>(), out.as<int>() + n);
        } else {
            ASSERT_EQ(n, want_n) << v->name << ", " << what;
            ASSERT_TRUE(std::equal(want.begin(), want.end(), out.as<int>()))
                << v->name << ", " << what;
        }
    }
}

enum class Reference { bigint, none };

// The whole check of the file's header comment, for one surface and its
// lights.
void check_everything(const sv::PreparedSurface &s, const std::vector<Vec4> &lights, Reference ref,
                      const char *scene) {
    svtest::IsaLimitLifted lifted;
    const int nt = s.num_triangles();
    const float center[3] = {0, 0, 0};
    const acc::SurfaceData data = acc::make_surface_data(s, center, 1.0f);
    std::vector<sv::TriangleErrorModel> em((std::size_t)nt);
    for (int t = 0; t < nt; t++) {
        em[(std::size_t)t] = sv::triangle_error_model(corner(s, t, 0), corner(s, t, 1),
                                                      corner(s, t, 2));
    }
    int nfv = 0;
    const sv_facing_variant *fv = sv_facing_variants(&nfv);
    for (const Vec4 &l : lights) {
        const std::string what = std::string(scene) + ", " + light_text(l);
        SCOPED_TRACE(what);
        // Ground truth, once (the predicate is MXCSR-independent; tested).
        std::vector<uint8_t> exact((std::size_t)nt + 1, 1);
        std::vector<double> D((std::size_t)nt);
        for (int t = 0; t < nt; t++) {
            const int sg = sv_facing_exact_sign(corner(s, t, 0), corner(s, t, 1), corner(s, t, 2),
                                                &l);
            exact[(std::size_t)t] = sg > 0;
            D[(std::size_t)t] = sv::exact_signed_distance(corner(s, t, 0), corner(s, t, 1),
                                                          corner(s, t, 2), l);
            if (ref == Reference::bigint && light_finite(l)) {
                ASSERT_EQ(sg, svtest::reference_facing_sign(corner(s, t, 0), corner(s, t, 1),
                                                            corner(s, t, 2), l))
                    << "triangle " << t;
            }
            if (!light_finite(l)) {
                ASSERT_EQ(sg, 0);
            }
        }
        std::vector<std::vector<uint8_t>> facings = {exact};
        std::vector<std::vector<uint8_t>> mine_default;
        for (unsigned csr : {kDefaultCsr, kFtzDazCsr}) {
            const bool ftz = csr != kDefaultCsr;
            // Appendix A: every implementation gives the reference's bytes.
            std::vector<uint8_t> ref_bytes;
            for (int i = 0; i < nfv; i++) {
                if (!svtest::in_this_run(fv[i].isa, fv[i].name)) continue;
                GuardedBuffer f((std::size_t)nt + 1, 0);
                with_mxcsr(csr, [&] { fv[i].calculate_facing(s.planes.data(), nt, &l, f.data()); });
                ASSERT_TRUE(f.guards_intact()) << fv[i].name;
                std::vector<uint8_t> bytes(f.data(), f.data() + nt + 1);
                ASSERT_EQ(bytes[(std::size_t)nt], 1);
                if (ref_bytes.empty()) {
                    ref_bytes = bytes;
                } else {
                    ASSERT_EQ(bytes, ref_bytes) << fv[i].name << (ftz ? " (FTZ/DAZ)" : "");
                }
            }
            facings.push_back(ref_bytes);
            // The accuracy variants, each within its contract.
            std::size_t mine = 0;
            for (const acc::Variant &v : acc::variants()) {
                if (!svtest::in_this_run(v.isa, v.name)) continue;
                GuardedBuffer f((std::size_t)nt + 1, 0);
                with_mxcsr(csr, [&] { v.run(data, l, nullptr, f.data()); });
                ASSERT_TRUE(f.guards_intact()) << v.name;
                std::vector<uint8_t> bytes(f.data(), f.data() + nt + 1);
                ASSERT_EQ(bytes[(std::size_t)nt], 1) << v.name;
                const bool caller_env = std::strncmp(v.name, "c_ref", 5) == 0;
                const acc::Contract c = v.contract == acc::Contract::same_as
                                            ? acc::variant_by_name(v.same_as)->contract
                                            : v.contract;
                const float tau = sv_eps_bias_threshold(data.eps_distance, data.eps_angle,
                                                        data.center, &l);
                for (int t = 0; t < nt; t++) {
                    const uint8_t got = bytes[(std::size_t)t];
                    ASSERT_LE(got, 1) << v.name;
                    if (c == acc::Contract::exact) {
                        ASSERT_EQ(got, exact[(std::size_t)t]) << v.name << " triangle " << t;
                        continue;
                    }
                    const double B = sv::facing_error_bound(v.arithmetic, em[(std::size_t)t], l,
                                                            ftz && caller_env);
                    const double target = c == acc::Contract::biased ? (double)tau : 0.0;
                    const double dist = D[(std::size_t)t] - target;
                    if (std::fabs(dist) > B) {
                        const bool want = c == acc::Contract::biased ? dist > 0
                                                                     : exact[(std::size_t)t] != 0;
                        ASSERT_EQ(got, want)
                            << v.name << " triangle " << t << " D " << D[(std::size_t)t]
                            << " bound " << B << (ftz ? " (FTZ/DAZ)" : "");
                    }
                }
                if (!caller_env) {
                    // The accuracy routines set their own MXCSR: the same
                    // bytes in both modes.
                    if (!ftz) {
                        mine_default.push_back(bytes);
                    } else {
                        ASSERT_EQ(bytes, mine_default[mine]) << v.name << ": depends on FTZ/DAZ";
                    }
                    mine++;
                }
                facings.push_back(bytes);
            }
        }
        // The volumes of every distinct facing array (the kernels are
        // integer code: one of them under FTZ/DAZ as well is enough).
        std::set<std::vector<uint8_t>> distinct(facings.begin(), facings.end());
        with_mxcsr(kFtzDazCsr, [&] { check_volumes(s, exact, nullptr, what + ", FTZ/DAZ"); });
        if (::testing::Test::HasFatalFailure()) return;
        for (const std::vector<uint8_t> &f : distinct) {
            check_volumes(s, f, nullptr, what);
            if (::testing::Test::HasFatalFailure()) return;
            if (light_finite(l) && l.w != 0.0f && s.num_vertices() > 0) {
                // Culled: a light box of half the surface's size around it.
                Plane box[SV_NUM_LIGHT_PLANES];
                const Bounds b = sv::surface_bounds(s);
                const float h = std::max({b.extents.x, b.extents.y, b.extents.z});
                light_box(l, h, box);
                std::vector<Vec4> pos((std::size_t)s.num_vertices());
                for (int v = 0; v < s.num_vertices(); v++) {
                    pos[(std::size_t)v] = Vec4{s.positions[3 * (std::size_t)v],
                                               s.positions[3 * (std::size_t)v + 1],
                                               s.positions[3 * (std::size_t)v + 2], 1.0f};
                }
                std::vector<uint8_t> cull((std::size_t)s.num_vertices());
                if (!sv_calculate_cull_bits_c_ref(pos.data(), s.num_vertices(), &b, box,
                                                  cull.data())) {
                    check_volumes(s, f, cull.data(), what + ", culled");
                    if (::testing::Test::HasFatalFailure()) return;
                }
            }
        }
    }
}

// Point lights at, around and far from a surface, and directional lights
// along the axes and diagonals.
std::vector<Vec4> lights_around(float s) {
    std::vector<Vec4> l = {{0, 0, 0, 1},          {s * 0.5f, s * 0.25f, s * 0.125f, 1},
                           {-s, s, s, 1},         {s * 3, 0, 0, 1},
                           {1, 0, 0, 0},          {0, -1, 0, 0},
                           {0, 0, 1, 0},          {1, 1, 1, 0},
                           {-0.3f, 0.5f, 0.8f, 0}};
    return l;
}

// ---- Coordinates at the ends of the float range --------------------------------

SV_TIERED_TEST(Extreme, CoordinatesNearFltMax) {
    for (float s : {FLT_MAX, FLT_MAX / 2, 0x1p126f}) {
        const sv::PreparedSurface o = prepare(octahedron(s));
        std::vector<Vec4> l = lights_around(s);
        l.push_back({FLT_MAX, FLT_MAX, FLT_MAX, 1}); // beyond every face
        l.push_back({-FLT_MAX, 0, 0, 1});
        l.push_back({s, 0, 0, 1});                    // at a vertex
        l.push_back({FLT_MAX, -FLT_MAX, FLT_MAX, 0}); // directional, huge components
        l.push_back({1, 1, 1, FLT_MAX});              // homogeneous, w huge
        check_everything(o, l, Reference::bigint, "octahedron near FLT_MAX");
        if (HasFatalFailure()) return;
    }
    // A small closed mesh far out, where d = -(n . p0) exceeds FLT_MAX:
    // the reference's float plane has d = -inf; its bound says so (+inf),
    // the exact predicate and the double and fixed16 variants do not care.
    const float far[3] = {0x1.8p127f, 0x1.8p127f, 0x1.8p127f};
    const sv::PreparedSurface t = prepare(octahedron(0x1p110f, far));
    bool overflowed = false;
    for (const Plane &p : t.planes) overflowed = overflowed || std::isinf(p.d);
    EXPECT_TRUE(overflowed) << "the test wants a float plane whose d overflows";
    std::vector<Vec4> l = {{0, 0, 0, 1},
                           {far[0], far[1], far[2], 1},
                           {1, 1, 1, 0},
                           {-1, 0, 0, 0},
                           {FLT_MAX, FLT_MAX, FLT_MAX, 1}};
    check_everything(t, l, Reference::bigint, "octahedron at 1.5 * 2^127");
}

SV_TIERED_TEST(Extreme, CoordinatesNearTheSmallestNormalFloat) {
    // Integer meshes scaled by 2^-126 (FLT_MIN): every coordinate normal.
    const sv::PreparedSurface c = prepare(cube(5, FLT_MIN));
    std::vector<Vec4> l;
    for (const Vec4 &p : lights_around(5 * FLT_MIN)) l.push_back(p);
    l.push_back({2 * FLT_MIN, 3 * FLT_MIN, 5 * FLT_MIN, 1}); // on the top face's plane
    l.push_back({FLT_MIN, 0, 0, 1});
    check_everything(c, l, Reference::bigint, "cube of 5 * FLT_MIN");
    if (HasFatalFailure()) return;
    const sv::PreparedSurface o = prepare(octahedron(3 * FLT_MIN));
    check_everything(o, lights_around(3 * FLT_MIN), Reference::bigint, "octahedron of FLT_MIN");
}

// Subnormal coordinates: the predicate, the accuracy variants and their
// preparation give the same answer with and without FTZ/DAZ; the
// reference's bytes under FTZ/DAZ stay within its FTZ/DAZ bound.
SV_TIERED_TEST(Extreme, SubnormalCoordinatesWithAndWithoutFtzDaz) {
    const float d = 0x1p-149f;
    const sv::PreparedSurface c = prepare(cube(7, d));
    std::vector<Vec4> l = {{3 * d, 2 * d, 20 * d, 1},
                           {-5 * d, 3 * d, 3 * d, 1},
                           {3 * d, 3 * d, 7 * d, 1},
                           {0, 0, 0, 1},
                           {d, d, d, 1},
                           {0, 0, 1, 0},
                           {d, 0, 0, 0},
                           {1, 2, 3, 1}};
    check_everything(c, l, Reference::bigint, "cube of 7 subnormal granules");
    if (HasFatalFailure()) return;
    const sv::PreparedSurface o = prepare(octahedron(100 * d));
    check_everything(o, l, Reference::bigint, "octahedron of 100 subnormal granules");
    if (HasFatalFailure()) return;
    // A plane with a subnormal component: (0, -1e-40, 1) rounds to a float
    // normal whose b is subnormal, and a light far along -y sees the plane
    // only through b. Without DAZ the reference is right (s = 1e-10); DAZ
    // reads b as 0 and its answer changes to "on the plane". That stays
    // within its FTZ/DAZ bound; the exact predicate and the accuracy
    // variants answer the same in both modes (checked above and here).
    {
        Mesh m;
        m.positions = {0, 0, 0, 1, 0, 0, 0, 1, 1e-40f};
        m.indices = {0, 1, 2};
        const sv::PreparedSurface s = prepare(m);
        ASSERT_NE(std::fpclassify(s.planes[0].b), FP_NORMAL);
        const Vec4 far{0, -1e30f, 0, 1};
        const float *p = s.positions.data();
        uint8_t f[2], g[2];
        sv_calculate_facing_c_ref(s.planes.data(), 1, &far, f);
        with_mxcsr(kFtzDazCsr, [&] { sv_calculate_facing_c_ref(s.planes.data(), 1, &far, g); });
        int exact_daz = 9;
        with_mxcsr(kFtzDazCsr, [&] { exact_daz = sv_facing_exact_sign(p, p + 3, p + 6, &far); });
        EXPECT_EQ(sv_facing_exact_sign(p, p + 3, p + 6, &far), 1);
        EXPECT_EQ(exact_daz, 1);
        EXPECT_EQ(f[0], 1);
        const double D = sv::exact_signed_distance(p, p + 3, p + 6, far);
        EXPECT_LE(D, sv::facing_error_bound(sv::FacingArithmetic::float_planes,
                                            sv::triangle_error_model(p, p + 3, p + 6), far, true));
        std::printf("[   NOTE   ] sv_calculate_facing_c_ref, plane b = %g (subnormal), light "
                    "(0, -1e30, 0, 1), D = %g: facing %d without DAZ, %d with FTZ/DAZ; exact "
                    "%d in both\n",
                    (double)s.planes[0].b, D, f[0], g[0], exact_daz);
        check_everything(s, {far}, Reference::bigint, "subnormal plane component");
        if (HasFatalFailure()) return;
    }
    // Preparing under FTZ/DAZ (the library's own sv::prepare_surface is the
    // caller's business): the accuracy variants' data does not change.
    const float center[3] = {0, 0, 0};
    const acc::SurfaceData ref = acc::make_surface_data(o, center, 1.0f);
    with_mxcsr(kFtzDazCsr, [&] {
        const sv::AlignedVector<PlaneD> pd = sv::double_planes(o);
        const sv::AlignedVector<sv_plane16_block> p16 = sv::fixed16_planes(o);
        EXPECT_EQ(std::memcmp(pd.data(), ref.planes_d.data(), pd.size() * sizeof pd[0]), 0);
        EXPECT_EQ(std::memcmp(p16.data(), ref.planes16.data(), p16.size() * sizeof p16[0]), 0);
    });
}

// ---- Lights where the decision is balanced on an edge ------------------------------

SV_TIERED_TEST(Extreme, LightExactlyOnATrianglesPlane) {
    // The cube's face planes (axis-aligned: the reference is exact there)...
    const sv::PreparedSurface c = prepare(cube(4, 1));
    std::vector<Vec4> l = {{1, 1, 4, 1}, {9, -3, 4, 1}, {4, 2, 2, 1}, {0, 2, -7, 1}, {2, 0, 2, 1}};
    check_everything(c, l, Reference::bigint, "cube, lights on face planes");
    if (HasFatalFailure()) return;
    for (const Vec4 &p : l) {
        // ...where the exact facing of every triangle in that plane is 0.
        for (int t = 0; t < c.num_triangles(); t++) {
            if (svtest::reference_facing_sign(corner(c, t, 0), corner(c, t, 1), corner(c, t, 2),
                                              p) == 0) {
                EXPECT_EQ(sv_facing_exact_sign(corner(c, t, 0), corner(c, t, 1), corner(c, t, 2),
                                               &p),
                          0);
            }
        }
    }
    // ...and a tilted plane x + 2y + 3z = 12, where float arithmetic is not
    // exact: an octahedron-like fan of integer points on that plane, lights
    // on it (integer points satisfying the equation).
    Mesh tilt;
    const float pts[5][3] = {{12, 0, 0}, {0, 6, 0}, {0, 0, 4}, {2, 2, 2}, {6, 3, 0}};
    for (const auto &p : pts) {
        for (float x : p) tilt.positions.push_back(x);
    }
    tilt.indices = {0, 1, 2, 0, 3, 1, 3, 2, 1, 4, 1, 0};
    const sv::PreparedSurface tp = prepare(tilt);
    std::vector<Vec4> on = {
        {4, 1, 2, 1}, {-12, 6, 4, 1}, {100, -50, 4, 1}, {2, 2, 2, 1}, {1e6f, -5e5f, 4, 1}};
    check_everything(tp, on, Reference::bigint, "tilted plane, lights on it");
    for (const Vec4 &p : on) {
        for (int t = 0; t < tp.num_triangles(); t++) {
            EXPECT_EQ(sv_facing_exact_sign(corner(tp, t, 0), corner(tp, t, 1), corner(tp, t, 2),
                                           &p),
                      0);
        }
    }
}

SV_TIERED_TEST(Extreme, LightAtAVertex) {
    const sv::PreparedSurface ch = prepare(character());
    std::vector<Vec4> l;
    for (int v = 0; v < ch.num_vertices(); v += 193) {
        l.push_back({ch.positions[3 * (std::size_t)v], ch.positions[3 * (std::size_t)v + 1],
                     ch.positions[3 * (std::size_t)v + 2], 1});
    }
    check_everything(ch, l, Reference::none, "character, light at a vertex");
    if (HasFatalFailure()) return;
    // Every triangle at that vertex has the light on its plane: exact 0.
    for (const Vec4 &p : l) {
        for (int t = 0; t < ch.num_triangles(); t++) {
            for (int k = 0; k < 3; k++) {
                const float *q = corner(ch, t, k);
                if (q[0] == p.x && q[1] == p.y && q[2] == p.z) {
                    EXPECT_EQ(sv_facing_exact_sign(corner(ch, t, 0), corner(ch, t, 1),
                                                   corner(ch, t, 2), &p),
                              0);
                }
            }
        }
    }
    const sv::PreparedSurface c = prepare(cube(3, 1));
    check_everything(c, {{0, 0, 0, 1}, {3, 3, 3, 1}, {3, 0, 3, 1}}, Reference::bigint,
                     "cube, light at a corner");
}

SV_TIERED_TEST(Extreme, LightAtInfinityAlongAnAxis) {
    std::vector<Vec4> axes;
    for (int i = 0; i < 6; i++) {
        Vec4 l{0, 0, 0, 0};
        (&l.x)[i / 2] = i % 2 ? -1.0f : 1.0f;
        axes.push_back(l);
    }
    // The cube's side faces are parallel to each axis: exact facing 0.
    const sv::PreparedSurface c = prepare(cube(2, 1));
    check_everything(c, axes, Reference::bigint, "cube, directional along the axes");
    if (HasFatalFailure()) return;
    const sv::PreparedSurface ch = prepare(character());
    check_everything(ch, axes, Reference::bigint, "character, directional along the axes");
}

SV_TIERED_TEST(Extreme, LightAtInfinityAlongAFaceNormal) {
    const sv::PreparedSurface ch = prepare(character());
    std::vector<Vec4> l;
    for (int t = 0; t < ch.num_triangles(); t += 331) {
        const Plane &p = ch.planes[(std::size_t)t];
        l.push_back({p.a, p.b, p.c, 0});
        l.push_back({-p.a, -p.b, -p.c, 0});
    }
    check_everything(ch, l, Reference::bigint, "character, directional along face normals");
    if (HasFatalFailure()) return;
    // The face itself: facing for +n, not for -n.
    for (int t = 0; t < ch.num_triangles(); t += 331) {
        const Plane &p = ch.planes[(std::size_t)t];
        const Vec4 up{p.a, p.b, p.c, 0}, down{-p.a, -p.b, -p.c, 0};
        EXPECT_EQ(sv_facing_exact_sign(corner(ch, t, 0), corner(ch, t, 1), corner(ch, t, 2), &up),
                  1);
        EXPECT_EQ(sv_facing_exact_sign(corner(ch, t, 0), corner(ch, t, 1), corner(ch, t, 2), &down),
                  -1);
    }
}

// ---- Degenerate and non-finite input ------------------------------------------------

SV_TIERED_TEST(Extreme, ZeroAreaTriangles) {
    // A closed tetrahedron whose bottom face is split at the midpoint m of
    // the edge a-b into two triangles, plus the zero-area triangle (a, m, b)
    // and its reverse (together they keep the mesh closed), plus triangles
    // with a repeated corner, which preparation drops.
    Mesh m;
    const float pts[6][3] = {{0, 0, 0}, {4, 0, 0}, {0, 4, 0}, {1, 1, 4}, {2, 0, 0}, {2, 0, 0}};
    for (const auto &p : pts) {
        for (float x : p) m.positions.push_back(x);
    }
    // a=0 b=1 c=2 apex=3 m=4 (5 is a copy of m: welded)
    m.indices = {0, 2, 4, 4, 2, 1, 0, 4, 3, 4, 1, 3,
                 1, 2, 3, 2, 0, 3, 0, 4, 1, 1, 5, 0, // zero area: collinear a, m, b (both windings)
                 0, 0, 3, 3, 5, 4};                  // repeated corners (5 welds to 4)
    const sv::PreparedSurface s = prepare(m);
    EXPECT_EQ(s.report.degenerate_dropped, 2);
    EXPECT_EQ(s.report.zero_normal_triangles, 2);
    std::vector<Vec4> l = {{1, 1, 1, 1}, {1, -5, 0, 1}, {2, 0, 0, 1},
                           {0, 0, 1, 0}, {0, -1, 0, 0}, {1, 0, 0, 0}};
    check_everything(s, l, Reference::bigint, "tetrahedron with zero-area triangles");
    if (HasFatalFailure()) return;
    // The zero-area triangles face no light, in every variant.
    for (const Vec4 &p : l) {
        for (int t = 0; t < s.num_triangles(); t++) {
            const Plane &pl = s.planes[(std::size_t)t];
            if (pl.a != 0 || pl.b != 0 || pl.c != 0 || pl.d != 0) continue;
            EXPECT_EQ(sv_facing_exact_sign(corner(s, t, 0), corner(s, t, 1), corner(s, t, 2), &p),
                      0);
        }
    }
}

SV_TIERED_TEST(Extreme, NanAndInfinitePositions) {
    // Preparation refuses them, naming the vertex.
    for (float bad : {kNaN, kInf, -kInf}) {
        Mesh m = cube(1, 1);
        m.positions[3 * 5 + 1] = bad;
        try {
            (void)prepare(m);
            ADD_FAILURE() << "prepare_surface accepted " << bad;
        } catch (const sv::PrepareError &e) {
            EXPECT_NE(std::string(e.what()).find("vertex 5"), std::string::npos) << e.what();
            EXPECT_NE(std::string(e.what()).find(std::isnan(bad) ? "NaN" : "infinite"),
                      std::string::npos)
                << e.what();
        }
    }
    // Below preparation: planes and positions with NaN and inf given to the
    // routines directly. The reference's implementations agree byte for
    // byte; the accuracy variants write 0 or 1 within bounds, and give the
    // triangles with a non-finite corner facing 0.
    svtest::IsaLimitLifted lifted;
    const Mesh c = cube(1, 1);
    sv::PreparedSurface s = prepare(c);
    const int nt = s.num_triangles();
    s.positions[3 * 5 + 1] = kNaN;
    s.positions[3 * 6 + 2] = kInf;
    s.positions[3 * 3 + 0] = -kInf;
    for (int t = 0; t < nt; t++) {
        s.planes[(std::size_t)t] = sv::triangle_plane(corner(s, t, 0), corner(s, t, 1),
                                                      corner(s, t, 2));
    }
    s.planes[0] = {kNaN, 0, 1, 0};
    s.planes[1] = {kInf, 0, 0, 0};
    s.planes[2] = {0, 0, 1, -kInf};
    const float center[3] = {0, 0, 0};
    const acc::SurfaceData data = acc::make_surface_data(s, center, 1.0f);
    int nfv = 0;
    const sv_facing_variant *fv = sv_facing_variants(&nfv);
    for (const Vec4 &l : lights_around(2)) {
        SCOPED_TRACE(light_text(l));
        std::vector<uint8_t> ref;
        for (int i = 0; i < nfv; i++) {
            if (!svtest::in_this_run(fv[i].isa, fv[i].name)) continue;
            GuardedBuffer f((std::size_t)nt + 1, 0);
            fv[i].calculate_facing(s.planes.data(), nt, &l, f.data());
            ASSERT_TRUE(f.guards_intact());
            std::vector<uint8_t> b(f.data(), f.data() + nt + 1);
            if (ref.empty()) ref = b;
            ASSERT_EQ(b, ref) << fv[i].name;
        }
        for (const acc::Variant &v : acc::variants()) {
            if (!svtest::in_this_run(v.isa, v.name)) continue;
            GuardedBuffer f((std::size_t)nt + 1, 0);
            v.run(data, l, nullptr, f.data());
            ASSERT_TRUE(f.guards_intact()) << v.name;
            for (int t = 0; t < nt; t++) {
                ASSERT_LE(f.data()[t], 1) << v.name;
                bool finite = true;
                for (int k = 0; k < 3; k++) {
                    for (int i = 0; i < 3; i++)
                        finite = finite && std::isfinite(corner(s, t, k)[i]);
                }
                // Planes 0..2 were replaced by hand: only position-derived
                // data is defined by the corners.
                const bool from_positions = std::strncmp(v.name, "c_ref", 5) != 0 &&
                                            std::strncmp(v.name, "fma", 3) != 0 &&
                                            std::strncmp(v.name, "eps", 3) != 0;
                if (!finite && from_positions) {
                    ASSERT_EQ(f.data()[t], 0) << v.name << " t " << t;
                }
            }
            ASSERT_EQ(f.data()[nt], 1);
        }
        // The volumes stay closed whatever those bytes are.
        std::vector<uint8_t> f0(ref);
        check_volumes(s, f0, nullptr, "NaN/inf planes");
        if (HasFatalFailure()) return;
    }
}

SV_TIERED_TEST(Extreme, NanAndInfiniteLightComponents) {
    const sv::PreparedSurface ch = prepare(character());
    std::vector<Vec4> l;
    for (float bad : {kNaN, kInf, -kInf}) {
        for (int c = 0; c < 4; c++) {
            // A point light for NaN, a directional one for the infinities.
            Vec4 p = std::isnan(bad) ? Vec4{0.3f, 1.2f, 0.4f, 1.0f} : Vec4{0.3f, 0.5f, -0.2f, 0.0f};
            (&p.x)[c] = bad;
            l.push_back(p);
        }
    }
    l.push_back({kInf, kInf, kInf, kInf});
    l.push_back({kNaN, kNaN, kNaN, kNaN});
    // The exact predicate gives 0 for all (checked inside); bounds are +inf,
    // so the variants owe only well-formed bytes and closed volumes.
    check_everything(ch, l, Reference::none, "character, NaN/inf light");
}

// ---- Counts at the limits of int -------------------------------------------------

SV_TIERED_TEST(Extreme, CountsThatWouldOverflowIntAreRejected) {
    svtest::IsaLimitLifted lifted;
    // Tiny real arrays and huge counts: the checks come before any read, so
    // AddressSanitizer would catch a routine that looked past them.
    alignas(64) int out[64] = {0};
    alignas(64) int indices[64] = {0};
    alignas(64) uint8_t facing[64] = {1};
    const SilEdge edge{0, 0, 0, 2};
    for (const sv_variant *v : svtest::runnable_variants()) {
        SCOPED_TRACE(v->name);
        // 6 * numSilEdges > INT_MAX.
        EXPECT_EQ(sv_create_sil_triangles_checked(v, out, SIZE_MAX, facing, 0, &edge,
                                                  INT_MAX / 6 + 1),
                  SV_E_OVERFLOW);
        // 2 * numIndices > INT_MAX (6 outputs per triangle).
        EXPECT_EQ(sv_create_cap_triangles_checked(v, out, SIZE_MAX, facing, indices,
                                                  3 * (INT_MAX / 2 / 3 + 1), 3),
                  SV_E_OVERFLOW);
        // The whole volume: 6 * edges + 2 * indices > INT_MAX, each alone
        // below.
        EXPECT_EQ(sv_create_shadow_volume_checked(v, out, SIZE_MAX, indices, 3 * 200000000, 3,
                                                  &edge, 200000000, facing, nullptr),
                  SV_E_OVERFLOW);
        EXPECT_EQ(sv_create_shadow_volume_checked(v, out, SIZE_MAX, indices, INT_MAX - 1, 3, &edge,
                                                  0, facing, nullptr),
                  SV_E_OVERFLOW);
        // numIndices = 3 * numTriangles > INT_MAX for the culling count.
        EXPECT_EQ(sv_count_facing_cull_checked(v, facing, INT_MAX / 3 + 1, indices, facing, 3),
                  SV_E_OVERFLOW);
        // Room below the bound is refused before anything is written.
        EXPECT_EQ(sv_create_sil_triangles_checked(v, out, 64, facing, 0, &edge, 11), SV_E_CAPACITY);
    }
    // The messages say what is wrong.
    EXPECT_NE(std::string(sv_status_string(SV_E_OVERFLOW)).find("INT_MAX"), std::string::npos);
    // The capacity itself is computed without overflow.
    EXPECT_EQ(sv_shadow_volume_capacity(INT_MAX - 1, INT_MAX),
              6ull * INT_MAX + 2ull * (INT_MAX - 1));
    EXPECT_EQ(sv_shadow_volume_capacity(-3, 5), 0u);
    // Preparation refuses counts beyond int before reading the arrays.
    const float p[9] = {0, 0, 0, 1, 0, 0, 0, 1, 0};
    const uint32_t idx[3] = {0, 1, 2};
    try {
        (void)sv::prepare_surface(p, 3, idx, (std::size_t)INT_MAX + 2);
        ADD_FAILURE() << "2^31 + 1 indices accepted";
    } catch (const sv::PrepareError &e) {
        EXPECT_NE(std::string(e.what()).find("too many indices"), std::string::npos) << e.what();
    }
    try {
        (void)sv::prepare_surface(p, (std::size_t)INT_MAX + 1, idx, 3);
        ADD_FAILURE() << "2^31 vertices accepted";
    } catch (const sv::PrepareError &e) {
        EXPECT_NE(std::string(e.what()).find("too many vertices"), std::string::npos) << e.what();
    }
    // The accuracy routines: a negative count writes nothing at all.
    GuardedBuffer g(0, 0);
    const Vec4 l{0, 0, 1, 1};
    EXPECT_EQ(sv_calculate_facing_exact(nullptr, nullptr, INT_MIN, &l, g.data()), 0);
    sv_calculate_facing_fixed16(nullptr, INT_MIN, &l, g.data());
    sv_calculate_facing_double(nullptr, -1, &l, g.data());
    EXPECT_TRUE(g.guards_intact());
}

} // namespace
