// The facing decision's accuracy (issue 7): the exact predicate against a
// big-integer reference and by hand; the inexact variants' contracts
// (SIMD twins bit-identical to their definitions; bounded difference from
// exact wherever |D| exceeds the stated error bound; eps_bias's threshold
// and hysteresis); independence from the caller's MXCSR; the study and its
// plot on the bundled character.
//
// Copyright (C) 2026 the shadowvol authors. LGPL-2.1-or-later.
#include "test_support.h"

#include <xmmintrin.h>

#include <algorithm>
#include <cfloat>
#include <cmath>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <limits>

#include <unistd.h>

#include <nlohmann/json.hpp>

#include "accuracy_internal.h"
#include "expansion.h"
#include "svg_scatter.h"
#include "accuracy_reference.h"
#include "accuracy_study.h"
#include "accuracy_variants.h"
#include "shadowvol_accuracy.h"

namespace {

using svtest::GuardedBuffer;
using svtest::Rng;
namespace acc = sv::acc;

constexpr float kNaN = std::numeric_limits<float>::quiet_NaN();
constexpr float kInf = std::numeric_limits<float>::infinity();

// MXCSR settings a caller may have: default, FTZ+DAZ, and the three other
// rounding modes (with FTZ+DAZ for good measure on one of them).
const unsigned kCallerMxcsr[] = {0x1F80u, 0x1F80u | 0x8040u, 0x1F80u | 0x2000u, 0x1F80u | 0x4000u,
                                 0x1F80u | 0x6000u | 0x8040u};

template <class F> void with_mxcsr(unsigned csr, F &&f) {
    const unsigned saved = _mm_getcsr();
    _mm_setcsr(csr);
    f();
    _mm_setcsr(saved);
}

// A float of any exponent from the subnormals to near FLT_MAX, any sign.
float wide_float(Rng &rng) {
    const int e = (int)rng.below(277) - 149; // 2^e in [2^-149, 2^127]
    const double m = 1.0 + rng.unit();
    float f = (float)std::ldexp(m, e);
    if (!std::isfinite(f)) f = FLT_MAX;
    return rng.chance(0.5) ? -f : f;
}

float ordinary(Rng &rng, double scale = 1.0) { return (float)((2.0 * rng.unit() - 1.0) * scale); }

struct Tri {
    float p[3][3];
};

int naive_double_sign(const Tri &t, const Vec4 &l) {
    // det[u; v; r] in plain double, the filter's expression without its bound.
    double u[3], v[3], r[3];
    const float lc[3] = {l.x, l.y, l.z};
    for (int i = 0; i < 3; i++) {
        u[i] = (double)t.p[1][i] - t.p[0][i];
        v[i] = (double)t.p[2][i] - t.p[0][i];
        r[i] = (double)lc[i] - (double)l.w * t.p[0][i];
    }
    const double det = u[2] * (v[0] * r[1] - r[0] * v[1]) + v[2] * (r[0] * u[1] - u[0] * r[1]) +
                       r[2] * (u[0] * v[1] - v[0] * u[1]);
    return (det > 0) - (det < 0);
}

int exact_sign(const Tri &t, const Vec4 &l) {
    return sv_facing_exact_sign(t.p[0], t.p[1], t.p[2], &l);
}

int ref_sign(const Tri &t, const Vec4 &l) {
    return svtest::reference_facing_sign(t.p[0], t.p[1], t.p[2], l);
}

// Near-degenerate configurations: a light (nearly) on the triangle's
// plane, a (nearly) collinear triangle, a light at a vertex, a direction
// in the plane; over wide scales and offsets from the origin.
void near_degenerate(Rng &rng, Tri &t, Vec4 &l) {
    const double scale = std::ldexp(1.0, (int)rng.below(80) - 40);
    const double off = rng.chance(0.5) ? 0.0 : std::ldexp(1.0, (int)rng.below(100) - 30);
    double base[3], e1[3], e2[3];
    for (int i = 0; i < 3; i++) {
        base[i] = off * (2 * rng.unit() - 1);
        e1[i] = scale * (2 * rng.unit() - 1);
        e2[i] = scale * (2 * rng.unit() - 1);
    }
    const int kind = (int)rng.below(5);
    if (kind == 1) { // collinear up to rounding
        const double s = 2 * rng.unit() - 1;
        for (int i = 0; i < 3; i++) e2[i] = s * e1[i];
    }
    for (int i = 0; i < 3; i++) {
        t.p[0][i] = (float)base[i];
        t.p[1][i] = (float)(base[i] + e1[i]);
        t.p[2][i] = (float)(base[i] + e2[i]);
    }
    const double s = 4 * rng.unit() - 2, u = 4 * rng.unit() - 2;
    double q[3];
    for (int i = 0; i < 3; i++) q[i] = base[i] + s * e1[i] + u * e2[i];
    switch (kind) {
    case 2: // a vertex, maybe an ulp off
        for (int i = 0; i < 3; i++) {
            q[i] = t.p[rng.below(3)][i];
            if (rng.chance(0.3)) q[i] = std::nextafter((float)q[i], rng.chance(0.5) ? kInf : -kInf);
        }
        break;
    case 3: // a direction in the plane (w = 0)
        l = Vec4{(float)(s * e1[0] + u * e2[0]), (float)(s * e1[1] + u * e2[1]),
                 (float)(s * e1[2] + u * e2[2]), 0.0f};
        return;
    default: break;
    }
    // Homogeneous: the same point with w in {1, 2, -1, 0.5} now and then.
    static const float ws[] = {1.0f, 1.0f, 1.0f, 2.0f, -1.0f, 0.5f};
    const float w = ws[rng.below(6)];
    l = Vec4{(float)(q[0] * w), (float)(q[1] * w), (float)(q[2] * w), w};
}

// ---- Expansion arithmetic --------------------------------------------------------

// A double with a full random 53-bit significand and an exponent in
// [-150, 150]: every such value, and every product of two, is an integer
// multiple of 2^-400.
double full_double(Rng &rng) {
    const uint64_t m = (rng.next() >> 11) | (1ull << 52);
    const double d = std::ldexp((double)m, (int)rng.below(301) - 150 - 52);
    return rng.chance(0.5) ? -d : d;
}

constexpr int kScale = 500; // doubles above times 2^kScale are integers

svtest::BigInt big(double d) { return svtest::BigInt::from_double_scaled(d, kScale); }

svtest::BigInt big_sum(const double *e, int n, int scale = kScale) {
    svtest::BigInt s;
    for (int i = 0; i < n; i++) s = s + svtest::BigInt::from_double_scaled(e[i], scale);
    return s;
}

// Components nonzero (unless the only one), increasing in magnitude, and
// nonoverlapping in the weak sense the merge needs: each below the next.
void expect_well_formed(const double *e, int n) {
    ASSERT_GE(n, 1);
    if (n == 1) return;
    for (int i = 0; i < n; i++) ASSERT_NE(e[i], 0.0) << i;
    for (int i = 0; i + 1 < n; i++) ASSERT_LT(std::fabs(e[i]), std::fabs(e[i + 1])) << i;
}

TEST(Expansion, PrimitivesAreExact) {
    Rng rng = svtest::rng_for("Expansion.Primitives");
    SCOPED_TRACE(svtest::seed_trace());
    for (int k = 0; k < 20000; k++) {
        const double a = full_double(rng), b = full_double(rng);
        double x, y;
        sv_two_sum(a, b, &x, &y);
        ASSERT_TRUE(big(x) + big(y) == big(a) + big(b)) << a << " + " << b;
        ASSERT_EQ(x, a + b);
        sv_two_diff(a, b, &x, &y);
        ASSERT_TRUE(big(x) + big(y) == big(a) - big(b)) << a << " - " << b;
        ASSERT_EQ(x, a - b);
        // Products at a larger scale: 2^-300 * 2^-300 needs 2^600 to be whole.
        const double pa = std::ldexp(a, -std::ilogb(a) + (int)rng.below(60) - 30);
        const double pb = std::ldexp(b, -std::ilogb(b) + (int)rng.below(60) - 30);
        sv_two_product(pa, pb, &x, &y);
        const svtest::BigInt want = svtest::BigInt::from_double_scaled(pa, 200) *
                                    svtest::BigInt::from_double_scaled(pb, 200);
        ASSERT_TRUE(svtest::BigInt::from_double_scaled(x, 400) +
                        svtest::BigInt::from_double_scaled(y, 400) ==
                    want)
            << pa << " * " << pb;
        ASSERT_EQ(x, pa * pb);
    }
}

TEST(Expansion, SumsAndProductsAreExact) {
    Rng rng = svtest::rng_for("Expansion.SumsAndProducts");
    SCOPED_TRACE(svtest::seed_trace());
    // Random expansions, built exactly by summing doubles of nearby
    // magnitudes (so products stay within the scale of the reference).
    auto random_expansion = [&](double *e, int terms) {
        int n = 1;
        e[0] = std::ldexp(full_double(rng), -(int)rng.below(40));
        for (int t = 1; t < terms; t++) {
            const double d = std::ldexp(full_double(rng), -(int)rng.below(40));
            double tmp[64];
            const double one[1] = {d};
            n = sv_expansion_sum(n, e, 1, one, tmp);
            std::memcpy(e, tmp, sizeof(double) * (std::size_t)n);
        }
        return n;
    };
    for (int k = 0; k < 3000; k++) {
        double e[64], f[64], h[128], scratch[192], p[512];
        const int en = random_expansion(e, 1 + (int)rng.below(6));
        const int fn = random_expansion(f, 1 + (int)rng.below(6));
        expect_well_formed(e, en);
        const int hn = sv_expansion_sum(en, e, fn, f, h);
        expect_well_formed(h, hn);
        ASSERT_TRUE(big_sum(h, hn) == big_sum(e, en) + big_sum(f, fn));
        const double b = std::ldexp(full_double(rng), -std::ilogb(full_double(rng)) % 20);
        const int sn = sv_scale_expansion(en, e, b, h);
        expect_well_formed(h, sn);
        ASSERT_TRUE(big_sum(h, sn, 1000) ==
                    big_sum(e, en, 500) * svtest::BigInt::from_double_scaled(b, 500));
        const int pn = sv_expansion_product(en, e, fn, f, p, scratch);
        expect_well_formed(p, pn);
        ASSERT_TRUE(big_sum(p, pn, 1000) == big_sum(e, en, 500) * big_sum(f, fn, 500));
        // Opposite values cancel to the single component 0.
        for (int i = 0; i < en; i++) f[i] = -e[i];
        ASSERT_EQ(sv_expansion_sum(en, e, en, f, h), 1);
        ASSERT_EQ(h[0], 0.0);
    }
}

// ---- The exact predicate ----------------------------------------------------

TEST(ExactPredicate, HandCases) {
    // Counter-clockwise seen from +z: normal +z.
    const float a[3] = {0, 0, 0}, b[3] = {1, 0, 0}, c[3] = {0, 1, 0};
    struct Case {
        Vec4 l;
        int sign;
    } cases[] = {
        {{0, 0, 1, 1}, 1},        {{0, 0, -1, 1}, -1},        {{0.25f, 0.25f, 0, 1}, 0},
        {{5, -3, 0, 1}, 0},       {{0, 0, 1, 0}, 1},          {{0, 0, -1, 0}, -1},
        {{1, 0, 0, 0}, 0},        {{0, 0, 2, 2}, 1},          {{0, 0, 1e-30f, 1}, 1},
        {{0, 0, -1e-45f, 1}, -1}, {{1e30f, -1e30f, 0, 1}, 0},
    };
    for (const Case &k : cases) {
        EXPECT_EQ(sv_facing_exact_sign(a, b, c, &k.l), k.sign)
            << "light " << k.l.x << " " << k.l.y << " " << k.l.z << " " << k.l.w;
    }
    // Clockwise (b and c swapped): every sign turns.
    const Vec4 up{0, 0, 1, 1};
    EXPECT_EQ(sv_facing_exact_sign(a, c, b, &up), -1);
    // Homogeneous w: p0 = (1, 1, 1); (2, 2, 3, 2) is the point (1, 1, 1.5),
    // above; w = -1 names the same point but turns plane . light, as it does
    // for the reference.
    const float a1[3] = {1, 1, 1}, b1[3] = {2, 1, 1}, c1[3] = {1, 2, 1};
    const Vec4 w2{2, 2, 3, 2}, wm{-1, -1, -1.5f, -1};
    EXPECT_EQ(sv_facing_exact_sign(a1, b1, c1, &w2), 1);
    EXPECT_EQ(sv_facing_exact_sign(a1, b1, c1, &wm), -1);
    // Zero area: collinear, and a repeated corner.
    const float d[3] = {2, 0, 0};
    EXPECT_EQ(sv_facing_exact_sign(a, b, d, &up), 0);
    EXPECT_EQ(sv_facing_exact_sign(a, b, b, &up), 0);
}

// The sign convention is the reference's: on well-conditioned input (light
// far from every plane) the exact facing equals sv_calculate_facing_c_ref.
TEST(ExactPredicate, ConventionMatchesTheReference) {
    Rng rng = svtest::rng_for("ExactPredicate.Convention");
    SCOPED_TRACE(svtest::seed_trace());
    int compared = 0;
    for (int k = 0; k < 20000; k++) {
        Tri t;
        for (auto &p : t.p) {
            for (float &x : p) x = ordinary(rng);
        }
        const float w = rng.chance(0.3) ? 0.0f : 1.0f;
        const Vec4 l{ordinary(rng, 10), ordinary(rng, 10), ordinary(rng, 10), w};
        const double D = sv::exact_signed_distance(t.p[0], t.p[1], t.p[2], l);
        const Plane pl = sv::triangle_plane(t.p[0], t.p[1], t.p[2]);
        if (std::fabs(D) < 1e-3 || (pl.a == 0 && pl.b == 0 && pl.c == 0)) continue;
        uint8_t f[2];
        sv_calculate_facing_c_ref(&pl, 1, &l, f);
        ASSERT_EQ(exact_sign(t, l) > 0, f[0] == 1) << "D " << D;
        ASSERT_EQ(exact_sign(t, l), D > 0 ? 1 : -1);
        compared++;
    }
    EXPECT_GT(compared, 15000);
}

TEST(ExactPredicate, AgreesWithBigIntegers) {
    Rng rng = svtest::rng_for("ExactPredicate.BigIntegers");
    SCOPED_TRACE(svtest::seed_trace());
    int exact_stage = 0, zero = 0;
    for (int k = 0; k < 12000; k++) {
        Tri t;
        Vec4 l;
        if (k % 3 == 0) { // any floats at all
            for (auto &p : t.p) {
                for (float &x : p) x = wide_float(rng);
            }
            l = Vec4{wide_float(rng), wide_float(rng), wide_float(rng),
                     rng.chance(0.3)   ? 0.0f
                     : rng.chance(0.7) ? 1.0f
                                       : wide_float(rng)};
        } else {
            near_degenerate(rng, t, l);
        }
        const int want = ref_sign(t, l);
        ASSERT_EQ(exact_sign(t, l), want)
            << "p0 " << t.p[0][0] << " " << t.p[0][1] << " " << t.p[0][2] << " light " << l.x << " "
            << l.y << " " << l.z << " " << l.w;
        ASSERT_EQ(sv_facing_exact_sign_unfiltered(t.p[0], t.p[1], t.p[2], &l), want);
        int sign = 9;
        (void)sv_exact_det_estimate(t.p[0], t.p[1], t.p[2], &l, &sign);
        ASSERT_EQ(sign, want);
        exact_stage += !sv_exact_filter_decides(t.p[0], t.p[1], t.p[2], &l);
        zero += want == 0;
    }
    // The exact stage and the zero answer were both exercised.
    EXPECT_GT(exact_stage, 500);
    EXPECT_GT(zero, 100);
}

TEST(ExactPredicate, AgreesWithInt128OnSmallIntegers) {
    Rng rng = svtest::rng_for("ExactPredicate.Int128");
    SCOPED_TRACE(svtest::seed_trace());
    int zero = 0;
    for (int k = 0; k < 50000; k++) {
        const int range = k % 2 ? 16 : (1 << 20);
        auto coord = [&] { return (float)((int)rng.below(2u * (uint32_t)range + 1) - range); };
        Tri t;
        for (auto &p : t.p) {
            for (float &x : p) x = coord();
        }
        Vec4 l{coord(), coord(), coord(), (float)((int)rng.below(5) - 2)};
        if (k % 5 == 0) { // on the plane: p0 + i (p1 - p0) + j (p2 - p0), w = 1
            const int i = (int)rng.below(5) - 2, j = (int)rng.below(5) - 2;
            const float *p = t.p[0], *q = t.p[1], *r = t.p[2];
            l = Vec4{p[0] + i * (q[0] - p[0]) + j * (r[0] - p[0]),
                     p[1] + i * (q[1] - p[1]) + j * (r[1] - p[1]),
                     p[2] + i * (q[2] - p[2]) + j * (r[2] - p[2]), 1.0f};
            if (std::fabs(l.x) >= (1 << 20) || std::fabs(l.y) >= (1 << 20) ||
                std::fabs(l.z) >= (1 << 20)) {
                continue;
            }
        }
        const int want = svtest::reference_facing_sign_int128(t.p[0], t.p[1], t.p[2], l);
        ASSERT_EQ(exact_sign(t, l), want);
        if (k % 16 == 0) {
            ASSERT_EQ(ref_sign(t, l), want); // the two references agree
        }
        zero += want == 0;
    }
    EXPECT_GT(zero, 5000);
}

// Where plain double arithmetic decides wrongly, and the predicate does not.
TEST(ExactPredicate, PlainDoubleGetsTheSignWrong) {
    // A triangle of the bundled character (models/character_1344.glb): two
    // x coordinates near 1e-17 next to one near -0.068, where p1 - p0 and
    // p2 - p0 need 58 bits. Both differences round to the same double, so
    // the double normal's y component is exactly 0 (the reference's float
    // plane too): a light along +y sees the plane edge-on, while exactly it
    // is 2.5e-18 in front.
    const Tri t{{{-0x1.17c5d4p-4f, 0x1.ae147ap+0f, 0x1.53e006p-4f},
                 {0x1.124924p-58f, 0x1.ae147ap+0f, 0x1.d70a3ep-4f},
                 {0x1.283a84p-58f, 0x1.bae148p+0f, 0x1.d70a3ep-4f}}};
    const Vec4 up{0, 1, 0, 0};
    EXPECT_EQ(ref_sign(t, up), 1);
    EXPECT_EQ(exact_sign(t, up), 1);
    EXPECT_EQ(naive_double_sign(t, up), 0);
    const PlaneD pd = sv::triangle_plane_double(t.p[0], t.p[1], t.p[2]);
    EXPECT_EQ(pd.b, 0.0);
    // The double variant is wrong there, and its bound says it may be.
    uint8_t f[2];
    sv_calculate_facing_double(&pd, 1, &up, f);
    EXPECT_EQ(f[0], 0);
    const double D = sv::exact_signed_distance(t.p[0], t.p[1], t.p[2], up);
    EXPECT_GT(D, 0.0);
    EXPECT_LE(D, sv::facing_error_bound(sv::FacingArithmetic::double_planes,
                                        sv::triangle_error_model(t.p[0], t.p[1], t.p[2]), up));

    // And an outright wrong sign (+1 for -1 or the reverse), found among
    // near-degenerate inputs from a fixed generator: plain double must fail
    // on some, the predicate on none.
    Rng rng(7);
    int wrong_sign = 0, tried = 0;
    Tri first{};
    Vec4 first_l{};
    for (; tried < 200000 && wrong_sign < 3; tried++) {
        Tri c;
        Vec4 l;
        near_degenerate(rng, c, l);
        const int naive = naive_double_sign(c, l);
        if (naive == 0) continue;
        const int want = ref_sign(c, l);
        if (naive == -want) {
            if (!wrong_sign) {
                first = c;
                first_l = l;
            }
            wrong_sign++;
            ASSERT_EQ(exact_sign(c, l), want);
        }
    }
    ASSERT_GT(wrong_sign, 0) << "no input in " << tried << " made plain double flip the sign";
    std::printf("[          ] plain double flipped the sign %d time(s) in %d near-degenerate "
                "inputs; first: p0 (%a %a %a) p1 (%a %a %a) p2 (%a %a %a) light (%a %a %a %g)\n",
                wrong_sign, tried, first.p[0][0], first.p[0][1], first.p[0][2], first.p[1][0],
                first.p[1][1], first.p[1][2], first.p[2][0], first.p[2][1], first.p[2][2],
                first_l.x, first_l.y, first_l.z, first_l.w);
}

TEST(ExactPredicate, NonFiniteInputGivesZero) {
    const float good[3][3] = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}};
    const float bad[] = {kNaN, kInf, -kInf};
    for (float b : bad) {
        for (int corner = 0; corner < 4; corner++) {
            for (int c = 0; c < (corner < 3 ? 3 : 4); c++) {
                Tri t;
                std::memcpy(t.p, good, sizeof t.p);
                Vec4 l{0.2f, 0.2f, 1, 1};
                if (corner < 3) {
                    t.p[corner][c] = b;
                } else {
                    (&l.x)[c] = b;
                }
                EXPECT_EQ(exact_sign(t, l), 0) << "corner " << corner << " coord " << c;
                EXPECT_EQ(sv_facing_exact_sign_unfiltered(t.p[0], t.p[1], t.p[2], &l), 0);
                EXPECT_TRUE(std::isnan(sv::exact_signed_distance(t.p[0], t.p[1], t.p[2], l)));
            }
        }
    }
}

TEST(ExactPredicate, IndependentOfTheCallersMxcsr) {
    Rng rng = svtest::rng_for("ExactPredicate.Mxcsr");
    SCOPED_TRACE(svtest::seed_trace());
    for (int k = 0; k < 3000; k++) {
        Tri t;
        Vec4 l;
        if (k % 2) {
            // Subnormal scale: every coordinate a small multiple of 2^-149.
            for (auto &p : t.p) {
                for (float &x : p) x = (float)((int)rng.below(64) - 32) * 0x1p-149f;
            }
            l = Vec4{(float)((int)rng.below(64) - 32) * 0x1p-149f,
                     (float)((int)rng.below(64) - 32) * 0x1p-149f,
                     (float)((int)rng.below(64) - 32) * 0x1p-149f, 1.0f};
        } else {
            near_degenerate(rng, t, l);
        }
        const int want = ref_sign(t, l);
        for (unsigned csr : kCallerMxcsr) {
            int got = 9, got_u = 9;
            with_mxcsr(csr, [&] {
                got = exact_sign(t, l);
                got_u = sv_facing_exact_sign_unfiltered(t.p[0], t.p[1], t.p[2], &l);
                ASSERT_EQ(_mm_getcsr() & ~0x3Fu, csr & ~0x3Fu) << "MXCSR not restored";
            });
            ASSERT_EQ(got, want) << "MXCSR " << std::hex << csr;
            ASSERT_EQ(got_u, want) << "MXCSR " << std::hex << csr;
        }
    }
}

// A random mesh for the array routines: shared vertices, some degenerate
// and near-degenerate triangles, and (with NONFINITE) NaN and inf.
struct RawMesh {
    std::vector<float> positions;
    std::vector<int> indices;
};
RawMesh random_mesh(Rng &rng, int triangles, bool nonfinite) {
    RawMesh m;
    const int nv = std::max(3, triangles);
    for (int v = 0; v < nv; v++) {
        for (int c = 0; c < 3; c++) {
            float x = ordinary(rng);
            if (rng.chance(0.05)) x = wide_float(rng);
            if (nonfinite && rng.chance(0.02)) x = rng.chance(0.5) ? kNaN : kInf;
            m.positions.push_back(x);
        }
    }
    for (int t = 0; t < triangles; t++) {
        for (int c = 0; c < 3; c++) m.indices.push_back((int)rng.below((uint32_t)nv));
    }
    return m;
}

SV_TIERED_TEST(ExactPredicate, ArrayRoutinesMatchThePredicate) {
    Rng rng = svtest::rng_for("ExactPredicate.Arrays");
    SCOPED_TRACE(svtest::seed_trace());
    svtest::IsaLimitLifted lifted;
    const bool avx2 = svtest::in_this_run(SV_ISA_SSE2 | SV_ISA_AVX2, "exact_avx2");
    for (int n = 0; n <= 130; n++) {
        for (bool nonfinite : {false, true}) {
            const RawMesh m = random_mesh(rng, n, nonfinite);
            const Vec4 l{ordinary(rng, 3), ordinary(rng, 3), ordinary(rng, 3),
                         rng.chance(0.3) ? 0.0f : 1.0f};
            std::vector<uint8_t> want((std::size_t)n + 1, 1);
            int want_stage = 0;
            for (int t = 0; t < n; t++) {
                const float *p0 = &m.positions[3 * (std::size_t)m.indices[3 * (std::size_t)t]];
                const float *p1 = &m.positions[3 * (std::size_t)m.indices[3 * (std::size_t)t + 1]];
                const float *p2 = &m.positions[3 * (std::size_t)m.indices[3 * (std::size_t)t + 2]];
                want[(std::size_t)t] = sv_facing_exact_sign(p0, p1, p2, &l) > 0;
                want_stage += !sv_exact_filter_decides(p0, p1, p2, &l);
            }
            GuardedBuffer f((std::size_t)n + 1, rng.below(64));
            const int stage = sv_calculate_facing_exact(m.positions.data(), m.indices.data(), n, &l,
                                                        f.data());
            ASSERT_EQ(std::memcmp(f.data(), want.data(), want.size()), 0) << "n " << n;
            ASSERT_EQ(stage, want_stage);
            ASSERT_TRUE(f.guards_intact());
            if (avx2) {
                GuardedBuffer g((std::size_t)n + 1, rng.below(64));
                const int stage2 = sv_calculate_facing_exact_avx2(m.positions.data(),
                                                                  m.indices.data(), n, &l,
                                                                  g.data());
                ASSERT_EQ(std::memcmp(g.data(), want.data(), want.size()), 0) << "avx2 n " << n;
                ASSERT_EQ(stage2, want_stage);
                ASSERT_TRUE(g.guards_intact());
            }
        }
    }
    // A negative count writes nothing.
    GuardedBuffer f(0, 0);
    const Vec4 l{0, 0, 1, 1};
    EXPECT_EQ(sv_calculate_facing_exact(nullptr, nullptr, -1, &l, f.data()), 0);
    if (avx2) {
        EXPECT_EQ(sv_calculate_facing_exact_avx2(nullptr, nullptr, -5, &l, f.data()), 0);
    }
    EXPECT_TRUE(f.guards_intact());
}

// ---- The inexact variants: SIMD twins ---------------------------------------

float plane_value(Rng &rng, bool extremes) {
    if (extremes && rng.chance(0.15)) {
        static const float special[] = {0.0f,       -0.0f,    kNaN,    kInf,     -kInf,
                                        FLT_MAX,    -FLT_MAX, FLT_MIN, -FLT_MIN, 0x1p-149f,
                                        -0x1p-149f, 1e-40f,   3e38f};
        return special[rng.below(sizeof special / sizeof special[0])];
    }
    return ordinary(rng, 2.0);
}

// The AVX2 twins only: one instance named by its tier, so that it runs in
// the avx2 ctest entry alone (tests/support/test_conditions.h) and skips there
// where the CPU lacks AVX2.
class SimdTwins : public ::testing::TestWithParam<std::string> {};
INSTANTIATE_TEST_SUITE_P(Tier, SimdTwins, ::testing::Values("avx2"), svtest::param_name);

TEST_P(SimdTwins, BitIdenticalToTheirDefinitions) {
    Rng rng = svtest::rng_for("Variants.SimdTwins");
    SCOPED_TRACE(svtest::seed_trace());
    svtest::IsaLimitLifted lifted;
    if (!svtest::in_this_run(SV_ISA_SSE2 | SV_ISA_AVX2, "the AVX2 twins")) {
        GTEST_SKIP() << "the AVX2 twins: this CPU lacks AVX2";
    }
    for (bool extremes : {false, true}) {
        for (unsigned csr : {kCallerMxcsr[0], kCallerMxcsr[1], kCallerMxcsr[2]}) {
            for (int n = 0; n <= 200; n++) {
                std::vector<Plane> planes((std::size_t)n);
                std::vector<PlaneD> pd((std::size_t)n);
                std::vector<sv_plane16_block> blocks(((std::size_t)n + 7) / 8);
                for (int i = 0; i < n; i++) {
                    planes[(std::size_t)i] = {plane_value(rng, extremes),
                                              plane_value(rng, extremes),
                                              plane_value(rng, extremes),
                                              plane_value(rng, extremes)};
                    const Plane &p = planes[(std::size_t)i];
                    pd[(std::size_t)i] = {p.a * (1.0 + 1e-12), p.b, p.c, p.d * (1.0 - 1e-12)};
                    sv_plane16_block &b = blocks[(std::size_t)i / 8];
                    b.tn[i % 8] = plane_value(rng, extremes);
                    b.nx[i % 8] = (int16_t)((int)rng.below(65535) - 32767);
                    b.ny[i % 8] = (int16_t)((int)rng.below(65535) - 32767);
                    b.nz[i % 8] = (int16_t)((int)rng.below(65535) - 32767);
                }
                const Vec4 l{plane_value(rng, extremes), plane_value(rng, extremes),
                             plane_value(rng, extremes),
                             extremes          ? plane_value(rng, true)
                             : rng.chance(0.3) ? 0.0f
                                               : 1.0f};
                auto check = [&](const char *name, auto scalar, auto simd) {
                    GuardedBuffer a((std::size_t)n + 1, rng.below(64));
                    GuardedBuffer b((std::size_t)n + 1, rng.below(64));
                    with_mxcsr(csr, [&] {
                        scalar(a.data());
                        simd(b.data());
                    });
                    ASSERT_EQ(std::memcmp(a.data(), b.data(), (std::size_t)n + 1), 0)
                        << name << " n " << n << " extremes " << extremes;
                    ASSERT_EQ(a.data()[n], 1);
                    for (int i = 0; i < n; i++) ASSERT_LE(a.data()[i], 1);
                    ASSERT_TRUE(a.guards_intact() && b.guards_intact()) << name;
                };
                check(
                    "fma", [&](uint8_t *f) { sv_calculate_facing_fma(planes.data(), n, &l, f); },
                    [&](uint8_t *f) { sv_calculate_facing_fma_avx2(planes.data(), n, &l, f); });
                check(
                    "double", [&](uint8_t *f) { sv_calculate_facing_double(pd.data(), n, &l, f); },
                    [&](uint8_t *f) { sv_calculate_facing_double_avx2(pd.data(), n, &l, f); });
                check(
                    "fixed16",
                    [&](uint8_t *f) { sv_calculate_facing_fixed16(blocks.data(), n, &l, f); },
                    [&](uint8_t *f) { sv_calculate_facing_fixed16_avx2(blocks.data(), n, &l, f); });
                check(
                    "fixed16_prefetch",
                    [&](uint8_t *f) { sv_calculate_facing_fixed16(blocks.data(), n, &l, f); },
                    [&](uint8_t *f) {
                        sv_calculate_facing_fixed16_avx2_prefetch(blocks.data(), n, &l, f);
                    });
            }
        }
    }
}

SV_TIERED_TEST(Variants, NegativeCountsWriteNothing) {
    GuardedBuffer f(0, 0);
    const Vec4 l{0, 0, 1, 1};
    sv_calculate_facing_fma(nullptr, -1, &l, f.data());
    sv_calculate_facing_double(nullptr, -2, &l, f.data());
    sv_calculate_facing_fixed16(nullptr, -3, &l, f.data());
    sv_calculate_facing_eps_bias(nullptr, -4, &l, 0.0f, nullptr, f.data());
    if (svtest::in_this_run(SV_ISA_SSE2 | SV_ISA_AVX2, "the AVX2 twins")) {
        sv_calculate_facing_fma_avx2(nullptr, -1, &l, f.data());
        sv_calculate_facing_double_avx2(nullptr, -1, &l, f.data());
        sv_calculate_facing_fixed16_avx2(nullptr, -1, &l, f.data());
        sv_calculate_facing_fixed16_avx2_prefetch(nullptr, -1, &l, f.data());
    }
    EXPECT_TRUE(f.guards_intact());
}

// ---- Preparation --------------------------------------------------------------

TEST(Variants, DoublePlanesRoundToTheReferencePlanes) {
    Rng rng = svtest::rng_for("Variants.DoublePlanes");
    SCOPED_TRACE(svtest::seed_trace());
    for (int k = 0; k < 20000; k++) {
        Tri t;
        Vec4 l;
        if (k % 2) {
            near_degenerate(rng, t, l);
        } else {
            for (auto &p : t.p) {
                for (float &x : p) x = rng.chance(0.9) ? ordinary(rng, 100) : wide_float(rng);
            }
        }
        const Plane f = sv::triangle_plane(t.p[0], t.p[1], t.p[2]);
        const PlaneD d = sv::triangle_plane_double(t.p[0], t.p[1], t.p[2]);
        if (!std::isfinite(f.d)) continue; /* |d| beyond FLT_MAX: rounds to inf */
        const float r[4] = {(float)d.a, (float)d.b, (float)d.c, (float)d.d};
        ASSERT_EQ(std::memcmp(r, &f, sizeof r), 0)
            << f.a << " " << f.b << " " << f.c << " " << f.d << " vs " << d.a << " " << d.b << " "
            << d.c << " " << d.d;
    }
}

TEST(Variants, Fixed16Preparation) {
    Rng rng = svtest::rng_for("Variants.Fixed16Preparation");
    SCOPED_TRACE(svtest::seed_trace());
    for (int k = 0; k < 5000; k++) {
        Tri t;
        for (auto &p : t.p) {
            for (float &x : p) x = ordinary(rng, 10);
        }
        int16_t q[3];
        float tn;
        sv::triangle_plane16(t.p[0], t.p[1], t.p[2], q, &tn);
        const PlaneD d = sv::triangle_plane_double(t.p[0], t.p[1], t.p[2]);
        const int top = std::max({std::abs(q[0]), std::abs(q[1]), std::abs(q[2])});
        ASSERT_EQ(top, 32767); // the largest component uses all 16 bits
        const double m = std::max({std::fabs(d.a), std::fabs(d.b), std::fabs(d.c)});
        const double n[3] = {d.a, d.b, d.c};
        for (int i = 0; i < 3; i++) ASSERT_LE(std::fabs(q[i] - 32767.0 * n[i] / m), 0.5 + 1e-9);
        // tn: the quantised normal's plane through the centroid.
        double c[3];
        for (int i = 0; i < 3; i++) c[i] = ((double)t.p[0][i] + t.p[1][i] + t.p[2][i]) / 3.0;
        const double want = (q[0] * c[0] + q[1] * c[1] + q[2] * c[2]) / 32767.0;
        ASSERT_LE(std::fabs(tn - want), 1e-6 * (std::fabs(want) + 1e-30) + 1e-38);
    }
    // Zero area and non-finite corners: the zero plane, never facing.
    const float a[3] = {0, 0, 0}, b[3] = {1, 1, 1}, c[3] = {2, 2, 2}, nan3[3] = {kNaN, 0, 0};
    int16_t q[3];
    float tn;
    sv::triangle_plane16(a, b, c, q, &tn);
    EXPECT_TRUE(q[0] == 0 && q[1] == 0 && q[2] == 0 && tn == 0.0f);
    sv::triangle_plane16(a, b, nan3, q, &tn);
    EXPECT_TRUE(q[0] == 0 && q[1] == 0 && q[2] == 0 && tn == 0.0f);
    const PlaneD z = sv::triangle_plane_double(a, nan3, c);
    EXPECT_TRUE(z.a == 0 && z.b == 0 && z.c == 0 && z.d == 0);
}

// ---- Bounded difference -------------------------------------------------------

// One surface of N disjoint triangles, planes by sv::triangle_plane, as
// sv::prepare_surface would build it (without welding, which would merge
// nothing here anyway), for running the registry's variants.
sv::PreparedSurface surface_of(const std::vector<Tri> &tris) {
    sv::PreparedSurface s;
    for (std::size_t t = 0; t < tris.size(); t++) {
        for (int c = 0; c < 3; c++) {
            for (int i = 0; i < 3; i++) s.positions.push_back(tris[t].p[c][i]);
            s.indices.push_back((int)(3 * t + (std::size_t)c));
        }
        s.planes.push_back(sv::triangle_plane(tris[t].p[0], tris[t].p[1], tris[t].p[2]));
    }
    return s;
}

// Triangles whose planes pass at distances from 1e-13 to 1 of their size
// from the light, on both sides, at lever arms from 0.1 to 1e6 sizes; every
// shape from equilateral to slivers; anywhere from the origin to 1e6 away.
std::vector<Tri> adversarial_triangles(Rng &rng, const Vec4 &l, int count) {
    std::vector<Tri> out;
    const double L[3] = {l.x, l.y, l.z};
    for (int k = 0; k < count; k++) {
        double n[3], a[3], b[3];
        for (;;) { // a random unit normal n, and a, b spanning its plane
            for (double &x : n) x = 2 * rng.unit() - 1;
            const double r = std::sqrt(n[0] * n[0] + n[1] * n[1] + n[2] * n[2]);
            if (r < 0.1 || r > 1) continue;
            for (double &x : n) x /= r;
            break;
        }
        const double h0[3] = {std::fabs(n[0]) < 0.6 ? 1.0 : 0.0, std::fabs(n[0]) < 0.6 ? 0.0 : 1.0,
                              0.0};
        a[0] = n[1] * h0[2] - n[2] * h0[1];
        a[1] = n[2] * h0[0] - n[0] * h0[2];
        a[2] = n[0] * h0[1] - n[1] * h0[0];
        const double ar = std::sqrt(a[0] * a[0] + a[1] * a[1] + a[2] * a[2]);
        for (double &x : a) x /= ar;
        b[0] = n[1] * a[2] - n[2] * a[1];
        b[1] = n[2] * a[0] - n[0] * a[2];
        b[2] = n[0] * a[1] - n[1] * a[0];
        const double size = std::ldexp(1.0, (int)rng.below(20) - 10);
        const double sliver = rng.chance(0.3) ? std::ldexp(1.0, -(int)rng.below(40)) : 1.0;
        const double lever = size * std::pow(10.0, 6 * rng.unit() - 1);
        const double height = (rng.chance(0.5) ? 1 : -1) * size * std::pow(10.0, -13 * rng.unit());
        // For a directional light the plane contains the direction up to
        // height (radians, relative).
        double c[3];
        if (l.w == 0.0f) {
            const double dl = std::sqrt(L[0] * L[0] + L[1] * L[1] + L[2] * L[2]);
            // Rotate n to be perpendicular to the direction, up to height/size.
            double proj = (n[0] * L[0] + n[1] * L[1] + n[2] * L[2]) / dl;
            for (int i = 0; i < 3; i++) n[i] -= proj * L[i] / dl;
            const double r = std::sqrt(n[0] * n[0] + n[1] * n[1] + n[2] * n[2]);
            if (r < 1e-6) continue;
            for (int i = 0; i < 3; i++) n[i] = n[i] / r + height / size * L[i] / dl;
            // Recompute the in-plane axes for the tilted normal.
            a[0] = n[1] * h0[2] - n[2] * h0[1];
            a[1] = n[2] * h0[0] - n[0] * h0[2];
            a[2] = n[0] * h0[1] - n[1] * h0[0];
            const double ar2 = std::sqrt(a[0] * a[0] + a[1] * a[1] + a[2] * a[2]);
            for (double &x : a) x /= ar2;
            b[0] = n[1] * a[2] - n[2] * a[1];
            b[1] = n[2] * a[0] - n[0] * a[2];
            b[2] = n[0] * a[1] - n[1] * a[0];
            const double off = std::ldexp(1.0, (int)rng.below(40) - 20);
            for (int i = 0; i < 3; i++) c[i] = off * (2 * rng.unit() - 1);
        } else {
            // Centroid at the lever arm from the light, in the plane that
            // passes HEIGHT from the light.
            const double ang = 6.283185307179586 * rng.unit();
            for (int i = 0; i < 3; i++) {
                c[i] = L[i] / l.w - height * n[i] +
                       lever * (std::cos(ang) * a[i] + std::sin(ang) * b[i]);
            }
        }
        const double ang0 = 6.283185307179586 * rng.unit();
        Tri t;
        for (int v = 0; v < 3; v++) {
            const double ang = ang0 + v * 2.0943951023931953;
            const double x = size * std::cos(ang), y = size * sliver * std::sin(ang);
            for (int i = 0; i < 3; i++) t.p[v][i] = (float)(c[i] + x * a[i] + y * b[i]);
        }
        out.push_back(t);
    }
    return out;
}

SV_TIERED_TEST(Variants, BoundedDifferenceContracts) {
    Rng rng = svtest::rng_for("Variants.BoundedDifference");
    SCOPED_TRACE(svtest::seed_trace());
    svtest::IsaLimitLifted lifted;
    std::vector<const acc::Variant *> vars;
    for (const acc::Variant &v : acc::variants()) {
        if (svtest::in_this_run(v.isa, v.name)) vars.push_back(&v);
    }
    struct Stats {
        int64_t tests = 0, in_band = 0, wrong_in_band = 0;
        double worst = 0; /* largest |D| / bound among the differing bytes */
    };
    std::vector<Stats> stats(vars.size());
    for (int batch = 0; batch < 120; batch++) {
        const double off = rng.chance(0.5) ? 0.0 : std::pow(10.0, 6 * rng.unit());
        Vec4 l;
        if (batch % 4 == 3) {
            double d[3];
            for (double &x : d) x = 2 * rng.unit() - 1;
            l = Vec4{(float)d[0], (float)d[1], (float)d[2], 0.0f};
        } else {
            static const float ws[] = {1.0f, 1.0f, 2.0f, -1.0f, 0.5f};
            const float w = ws[rng.below(5)];
            l = Vec4{(float)(off * (2 * rng.unit() - 1) * w),
                     (float)(off * (2 * rng.unit() - 1) * w),
                     (float)(off * (2 * rng.unit() - 1) * w), w};
        }
        const std::vector<Tri> tris = adversarial_triangles(rng, l, 200);
        const sv::PreparedSurface s = surface_of(tris);
        const float center[3] = {0, 0, 0};
        const acc::SurfaceData data = acc::make_surface_data(s, center, 1.0f);
        const int nt = s.num_triangles();
        std::vector<double> D((std::size_t)nt);
        std::vector<uint8_t> exact((std::size_t)nt);
        std::vector<sv::TriangleErrorModel> em((std::size_t)nt);
        for (int t = 0; t < nt; t++) {
            const Tri &tr = tris[(std::size_t)t];
            D[(std::size_t)t] = sv::exact_signed_distance(tr.p[0], tr.p[1], tr.p[2], l);
            exact[(std::size_t)t] = exact_sign(tr, l) > 0;
            em[(std::size_t)t] = sv::triangle_error_model(tr.p[0], tr.p[1], tr.p[2]);
        }
        const float tau = sv_eps_bias_threshold(data.eps_distance, data.eps_angle, data.center, &l);
        for (std::size_t vi = 0; vi < vars.size(); vi++) {
            const acc::Variant &v = *vars[vi];
            GuardedBuffer f((std::size_t)nt + 1, 0);
            v.run(data, l, nullptr, f.data());
            ASSERT_TRUE(f.guards_intact()) << v.name;
            const acc::Contract c = v.contract == acc::Contract::same_as
                                        ? acc::variant_by_name(v.same_as)->contract
                                        : v.contract;
            for (int t = 0; t < nt; t++) {
                const uint8_t got = f.data()[t];
                stats[vi].tests++;
                if (c == acc::Contract::exact) {
                    ASSERT_EQ(got, exact[(std::size_t)t]) << v.name;
                    continue;
                }
                const double B = sv::facing_error_bound(v.arithmetic, em[(std::size_t)t], l);
                // biased: the threshold moves the decision; compare with D > tau.
                const double target = c == acc::Contract::biased ? (double)tau : 0.0;
                const double dist = D[(std::size_t)t] - target;
                const bool want = c == acc::Contract::biased ? dist > 0 : exact[(std::size_t)t];
                if (std::fabs(dist) <= B) {
                    stats[vi].in_band++;
                    stats[vi].wrong_in_band += got != want;
                    if (got != want)
                        stats[vi].worst = std::max(stats[vi].worst, std::fabs(dist) / B);
                } else {
                    const Tri &tr = tris[(std::size_t)t];
                    ASSERT_EQ(got, want)
                        << v.name << ": D " << D[(std::size_t)t] << " bound " << B << " light "
                        << l.x << " " << l.y << " " << l.z << " " << l.w << " p0 " << tr.p[0][0]
                        << " " << tr.p[0][1] << " " << tr.p[0][2];
                }
            }
        }
    }
    for (std::size_t vi = 0; vi < vars.size(); vi++) {
        const acc::Variant &v = *vars[vi];
        std::printf("[          ] %-22s %7lld tests, %6lld within the bound, %5lld of them "
                    "differ (the farthest at %.3f of the bound)\n",
                    v.name, (long long)stats[vi].tests, (long long)stats[vi].in_band,
                    (long long)stats[vi].wrong_in_band, stats[vi].worst);
        // The band is not empty, and the inexact arithmetic really errs in
        // it: the test has teeth, the bounds are not vacuous claims. (The
        // double variant errs only where |D| is near 1e-16 of the scale,
        // which random geometry rounded to float almost never produces:
        // PlainDoubleGetsTheSignWrong shows it on a real triangle.)
        if (v.contract == acc::Contract::bounded &&
            v.arithmetic != sv::FacingArithmetic::double_planes) {
            EXPECT_GT(stats[vi].in_band, 0) << v.name;
            EXPECT_GT(stats[vi].wrong_in_band, 0) << v.name;
        }
    }
}

// The bounds promise something useful: on well-shaped triangles they are
// a small multiple of the arithmetic's unit roundoff times the scale.
TEST(Variants, BoundsAreTight) {
    Rng rng = svtest::rng_for("Variants.BoundsAreTight");
    SCOPED_TRACE(svtest::seed_trace());
    for (int k = 0; k < 5000; k++) {
        Tri t;
        for (int v = 0; v < 3; v++) {
            const double ang = v * 2.0943951023931953 + 0.3 * rng.unit();
            t.p[v][0] = (float)std::cos(ang);
            t.p[v][1] = (float)std::sin(ang);
            t.p[v][2] = ordinary(rng, 0.2);
        }
        const Vec4 l{ordinary(rng, 10), ordinary(rng, 10), ordinary(rng, 10),
                     rng.chance(0.3) ? 0.0f : 1.0f};
        const sv::TriangleErrorModel m = sv::triangle_error_model(t.p[0], t.p[1], t.p[2]);
        // The scale: the light's distance from the triangle plus 1.
        const double scale = 1.0 +
                             std::sqrt((double)l.x * l.x + (double)l.y * l.y + (double)l.z * l.z);
        using A = sv::FacingArithmetic;
        EXPECT_LT(sv::facing_error_bound(A::float_planes, m, l) / scale, 2e-6);
        EXPECT_LT(sv::facing_error_bound(A::float_planes_fma, m, l) / scale, 2e-6);
        EXPECT_LT(sv::facing_error_bound(A::double_planes, m, l) / scale, 1e-14);
        EXPECT_LT(sv::facing_error_bound(A::fixed16, m, l) / scale, 1e-4);
        EXPECT_GT(sv::facing_error_bound(A::fixed16, m, l) / scale, 1e-7);
    }
    // No promise where none can be made: zero area, non-finite.
    const float a[3] = {0, 0, 0}, b[3] = {1, 0, 0}, c[3] = {3, 0, 0};
    const Vec4 up{0, 0, 1, 1}, bad{kNaN, 0, 1, 1};
    EXPECT_TRUE(std::isinf(sv::facing_error_bound(sv::FacingArithmetic::double_planes,
                                                  sv::triangle_error_model(a, b, c), up)));
    const float d[3] = {0, 1, 0};
    EXPECT_TRUE(std::isinf(sv::facing_error_bound(sv::FacingArithmetic::float_planes,
                                                  sv::triangle_error_model(a, b, d), bad)));
}

// ---- eps_bias ------------------------------------------------------------------

TEST(EpsBias, Threshold) {
    const float center[3] = {1, 2, 3};
    const Vec4 p{1, 2, 13, 1}, dir{0, 0, 2, 0};
    // 0.5 * |w| + 0.01 * |L - w c|, rounded up.
    EXPECT_FLOAT_EQ(sv_eps_bias_threshold(0.5f, 0.01f, center, &p), 0.5f + 0.1f);
    EXPECT_GE((double)sv_eps_bias_threshold(0.5f, 0.01f, center, &p), 0.5 + 0.01 * 10);
    EXPECT_FLOAT_EQ(sv_eps_bias_threshold(0.5f, 0.01f, center, &dir), 0.02f);
    const Vec4 w2{2, 4, 26, 2}; // the same point as p
    EXPECT_GE((double)sv_eps_bias_threshold(0.5f, 0.01f, center, &w2), 2 * (0.5 + 0.1));
    EXPECT_TRUE(std::isnan(sv_eps_bias_threshold(-1.0f, 0.0f, center, &p)));
    EXPECT_TRUE(std::isnan(sv_eps_bias_threshold(0.0f, kNaN, center, &p)));
    const Vec4 inf{kInf, 0, 0, 1};
    EXPECT_TRUE(std::isnan(sv_eps_bias_threshold(0.0f, 0.0f, center, &inf)));
    // A NaN threshold: nothing faces.
    const Plane pl{0, 0, 1, 0};
    uint8_t f[2] = {7, 7};
    sv_calculate_facing_eps_bias(&pl, 1, &p, kNaN, nullptr, f);
    EXPECT_EQ(f[0], 0);
    EXPECT_EQ(f[1], 1);
}

// With hysteresis, a light jittering within a region smaller than the band
// makes each triangle change side at most once (the first time its plane
// is more than the threshold away on the other side), never back: no
// flicker. The stateless test on the same frames flickers.
TEST(EpsBias, HysteresisDoesNotFlicker) {
    Rng rng = svtest::rng_for("EpsBias.Hysteresis");
    SCOPED_TRACE(svtest::seed_trace());
    const int n = 4000;
    std::vector<Plane> planes((std::size_t)n);
    const Vec4 l0{0.1f, 0.2f, 0.3f, 1.0f};
    for (Plane &p : planes) { // planes passing within 1e-3 of l0
        double nn[3];
        for (double &x : nn) x = 2 * rng.unit() - 1;
        const double r = std::sqrt(nn[0] * nn[0] + nn[1] * nn[1] + nn[2] * nn[2]);
        const double off = (2 * rng.unit() - 1) * 1e-3;
        p = {(float)(nn[0] / r), (float)(nn[1] / r), (float)(nn[2] / r), 0};
        p.d = -(p.a * l0.x + p.b * l0.y + p.c * l0.z) + (float)off;
    }
    // Every light lies in a cube of half size 1e-3 around l0, so a plane's
    // distance varies by at most 2 sqrt(3) 1e-3 = 3.5e-3 over all frames:
    // less than the band's width 2 tau = 4e-3.
    const float tau = 2e-3f;
    std::vector<uint8_t> hyst((std::size_t)n + 1), stateless((std::size_t)n + 1),
        before_h((std::size_t)n + 1), before_s((std::size_t)n + 1);
    std::vector<int> changes_h((std::size_t)n, 0), changes_s((std::size_t)n, 0);
    for (int frame = 0; frame < 60; frame++) {
        const double j = 1e-3;
        const Vec4 l{(float)(l0.x + j * (2 * rng.unit() - 1)),
                     (float)(l0.y + j * (2 * rng.unit() - 1)),
                     (float)(l0.z + j * (2 * rng.unit() - 1)), 1.0f};
        before_h = hyst;
        before_s = stateless;
        // In place: previous == facing.
        sv_calculate_facing_eps_bias(planes.data(), n, &l, tau, frame ? hyst.data() : nullptr,
                                     hyst.data());
        sv_calculate_facing_eps_bias(planes.data(), n, &l, tau, nullptr, stateless.data());
        ASSERT_EQ(hyst[(std::size_t)n], 1);
        if (frame == 0) continue;
        for (int t = 0; t < n; t++) {
            changes_h[(std::size_t)t] += before_h[(std::size_t)t] != hyst[(std::size_t)t];
            changes_s[(std::size_t)t] += before_s[(std::size_t)t] != stateless[(std::size_t)t];
        }
    }
    int flicker_h = 0, flicker_s = 0;
    for (int t = 0; t < n; t++) {
        flicker_h += changes_h[(std::size_t)t] > 1;
        flicker_s += changes_s[(std::size_t)t] > 1;
    }
    EXPECT_EQ(flicker_h, 0);
    EXPECT_GT(flicker_s, 100);
}

// ---- The caller's MXCSR --------------------------------------------------------

SV_TIERED_TEST(Variants, IndependentOfTheCallersMxcsr) {
    Rng rng = svtest::rng_for("Variants.Mxcsr");
    SCOPED_TRACE(svtest::seed_trace());
    svtest::IsaLimitLifted lifted;
    std::vector<Tri> tris;
    for (int k = 0; k < 300; k++) {
        Tri t;
        for (auto &p : t.p) {
            for (float &x : p) {
                // Subnormal, tiny-normal and ordinary scales mixed.
                const int kind = (int)rng.below(3);
                x = kind == 0   ? (float)((int)rng.below(200) - 100) * 0x1p-149f
                    : kind == 1 ? ordinary(rng) * 0x1p-120f
                                : ordinary(rng);
            }
        }
        tris.push_back(t);
    }
    const sv::PreparedSurface s = surface_of(tris);
    const float center[3] = {0, 0, 0};
    const acc::SurfaceData data = acc::make_surface_data(s, center, 1.0f);
    const int nt = s.num_triangles();
    for (int li = 0; li < 40; li++) {
        const float sc = li % 2 ? 0x1p-140f : 1.0f;
        const Vec4 l{ordinary(rng) * sc, ordinary(rng) * sc, ordinary(rng) * sc,
                     li % 5 == 0 ? 0.0f : 1.0f};
        for (const acc::Variant &v : acc::variants()) {
            if (!svtest::in_this_run(v.isa, v.name) || std::strncmp(v.name, "c_ref", 5) == 0)
                continue;
            std::vector<uint8_t> want((std::size_t)nt + 1);
            v.run(data, l, nullptr, want.data());
            for (unsigned csr : kCallerMxcsr) {
                std::vector<uint8_t> got((std::size_t)nt + 1);
                with_mxcsr(csr, [&] {
                    v.run(data, l, nullptr, got.data());
                    ASSERT_EQ(_mm_getcsr() & ~0x3Fu, csr & ~0x3Fu) << v.name;
                });
                ASSERT_EQ(got, want) << v.name << " MXCSR " << std::hex << csr;
            }
        }
    }
    // The preparation too: double and fixed16 planes of subnormal triangles.
    for (unsigned csr : kCallerMxcsr) {
        with_mxcsr(csr, [&] {
            const sv::AlignedVector<PlaneD> pd = sv::double_planes(s);
            const sv::AlignedVector<sv_plane16_block> p16 = sv::fixed16_planes(s);
            ASSERT_EQ(std::memcmp(pd.data(), data.planes_d.data(), pd.size() * sizeof pd[0]), 0);
            ASSERT_EQ(std::memcmp(p16.data(), data.planes16.data(), p16.size() * sizeof p16[0]), 0);
        });
    }
}

// ---- The study and its plot ----------------------------------------------------

TEST(Study, CharacterWithoutTiming) {
    std::unique_ptr<acc::StudyModel> m = acc::load_study_model(std::string(SV_MODELS_DIR) +
                                                               "/character_1344.glb");
    ASSERT_EQ(m->triangles, 1344);
    acc::StudyOptions o;
    o.lights = 4;
    o.timing = false;
    const acc::StudyResult r = acc::run_study({m.get()}, o);
    for (const std::string &f : r.failures) ADD_FAILURE() << f;
    EXPECT_EQ(r.failure_count, 0);
    int rows = 0;
    for (const acc::StudyRow &row : r.rows) {
        rows++;
        EXPECT_EQ(row.tests, row.triangles * row.lights);
        EXPECT_EQ(row.violations, 0);
        EXPECT_FALSE(row.timed);
        if (std::string(row.variant->name).rfind("exact", 0) == 0) {
            EXPECT_EQ(row.misclassified, 0);
            EXPECT_EQ(row.silhouette_changed, 0);
        }
        if (row.variant->contract == acc::Contract::same_as) {
            // The same bytes as the definition's row.
            for (const acc::StudyRow &d : r.rows) {
                if (d.placement == row.placement &&
                    std::string(d.variant->name) == row.variant->same_as) {
                    EXPECT_EQ(d.misclassified, row.misclassified) << row.variant->name;
                    EXPECT_EQ(d.flicker, row.flicker) << row.variant->name;
                }
            }
        }
    }
    int runnable = 0;
    for (const acc::Variant &v : acc::variants()) runnable += acc::runnable(v);
    EXPECT_EQ(rows, runnable * (int)acc::placements().size());
    // The light placements put the lights where they say.
    for (const acc::Placement &p : acc::placements()) {
        const acc::LightSet ls = acc::make_lights(*m, p, 8, 3);
        for (const Vec4 &l : ls.lights) EXPECT_EQ(l.w, p.directional ? 0.0f : 1.0f) << p.name;
        if (p.radii > 0) {
            EXPECT_NEAR(ls.mean_distance_radii, p.radii, 1e-3 * p.radii) << p.name;
        }
    }
}

namespace {
std::string test_base64(const std::string &in) {
    static const char kTable[] = "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
    std::string out;
    std::size_t i = 0;
    for (; i + 2 < in.size(); i += 3) {
        const uint32_t v = uint32_t(uint8_t(in[i])) << 16 | uint32_t(uint8_t(in[i + 1])) << 8 |
                           uint8_t(in[i + 2]);
        for (int sh = 18; sh >= 0; sh -= 6) out += kTable[(v >> sh) & 63];
    }
    const std::size_t rest = in.size() - i;
    if (rest) {
        uint32_t v = uint32_t(uint8_t(in[i])) << 16;
        if (rest == 2) v |= uint32_t(uint8_t(in[i + 1])) << 8;
        out += kTable[v >> 18];
        out += kTable[(v >> 12) & 63];
        out += rest == 2 ? kTable[(v >> 6) & 63] : '=';
        out += '=';
    }
    return out;
}
} // namespace

// Issue 17: the lights were seeded from the model's FILE NAME, so the
// .gltf and the .glb of one geometry (or one file under two names) gave
// different tables at the same --seed. They come from the content now.
TEST(Study, LightsAreSeededByContentNotFileName) {
    namespace fs = std::filesystem;
    const std::string glb_path = std::string(SV_MODELS_DIR) + "/character_1344.glb";
    std::ifstream in(glb_path, std::ios::binary);
    ASSERT_TRUE(in.good()) << glb_path;
    const std::string glb((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    uint32_t json_len = 0, bin_len = 0;
    std::memcpy(&json_len, glb.data() + 12, 4);
    const std::string json_text = glb.substr(20, json_len);
    std::memcpy(&bin_len, glb.data() + 20 + json_len, 4);
    const std::string bin = glb.substr(28 + json_len, bin_len);
    nlohmann::json doc = nlohmann::json::parse(json_text);
    doc["buffers"][0]["uri"] = "data:application/octet-stream;base64," + test_base64(bin);
    const fs::path dir = fs::path(testing::TempDir()) / ("sv_acc_seed_" + std::to_string(getpid()));
    fs::create_directories(dir);
    std::ofstream(dir / "same_geometry.gltf") << doc.dump();
    fs::copy_file(glb_path, dir / "another_name.glb", fs::copy_options::overwrite_existing);

    const auto a = acc::load_study_model(glb_path);
    const auto b = acc::load_study_model((dir / "same_geometry.gltf").string());
    const auto c = acc::load_study_model((dir / "another_name.glb").string());
    EXPECT_NE(a->name, b->name);
    EXPECT_EQ(a->content_hash, b->content_hash);
    EXPECT_EQ(a->content_hash, c->content_hash);
    acc::StudyOptions o;
    o.timing = false;
    o.lights = 4;
    o.seed = 7;
    const acc::StudyResult ra = acc::run_study({a.get()}, o);
    const acc::StudyResult rb = acc::run_study({b.get()}, o);
    const acc::StudyResult rc = acc::run_study({c.get()}, o);
    ASSERT_EQ(ra.rows.size(), rb.rows.size());
    ASSERT_EQ(ra.rows.size(), rc.rows.size());
    for (std::size_t i = 0; i < ra.rows.size(); i++) {
        for (const acc::StudyResult *r : {&rb, &rc}) {
            const acc::StudyRow &x = ra.rows[i], &y = r->rows[i];
            EXPECT_EQ(x.misclassified, y.misclassified) << x.variant->name;
            EXPECT_EQ(x.flicker, y.flicker) << x.variant->name;
            EXPECT_EQ(x.uncertain, y.uncertain) << x.variant->name;
            EXPECT_EQ(x.silhouette_changed, y.silhouette_changed) << x.variant->name;
            EXPECT_EQ(x.mean_distance_radii, y.mean_distance_radii) << x.variant->name;
            EXPECT_EQ(x.height_radii, y.height_radii) << x.variant->name;
        }
    }
    for (const acc::Placement &p : acc::placements()) {
        const acc::LightSet la = acc::make_lights(*a, p, 8, 3), lb = acc::make_lights(*b, p, 8, 3);
        ASSERT_EQ(la.lights.size(), lb.lights.size());
        for (std::size_t i = 0; i < la.lights.size(); i++) {
            EXPECT_EQ(0, std::memcmp(&la.lights[i], &lb.lights[i], sizeof(Vec4))) << p.name;
        }
    }
    fs::remove_all(dir);
}

TEST(Study, BadModelIsAnError) {
    EXPECT_THROW(acc::load_study_model("/nonexistent/model.glb"), acc::StudyError);
}

TEST(Plot, SvgIsWellFormed) {
    std::vector<svplot::ScatterPoint> pts = {{"c_ref", "c_ref", 1.2, 1e-6},
                                             {"c_ref_avx2", "c_ref", 0.5, 1e-6},
                                             {"exact", "exact", 20, 0},
                                             {"a<b>&\"", "odd", 3, 0.5},
                                             {"no speed", "odd", 0, 0.5}};
    svplot::ScatterText text{"T", "S", "X", "Y", "0", "F"};
    const std::string svg = svplot::render_loglog_scatter(pts, text);
    EXPECT_EQ(svg.rfind("<?xml", 0), 0u);
    EXPECT_NE(svg.find("</svg>"), std::string::npos);
    EXPECT_NE(svg.find(">c_ref_avx2<"), std::string::npos);
    EXPECT_NE(svg.find("a&lt;b&gt;&amp;&quot;"), std::string::npos);
    EXPECT_EQ(svg.find("a<b>"), std::string::npos);
    EXPECT_NE(svg.find("1 point(s) without a positive speed left out"), std::string::npos);
    // Every opened element is closed or self-closed: count tags.
    std::size_t open = 0, close = 0, self = 0;
    for (std::size_t i = 0; (i = svg.find('<', i)) != std::string::npos; i++) {
        if (svg.compare(i, 2, "</") == 0) {
            close++;
        } else if (svg.compare(i, 2, "<?") != 0) {
            const std::size_t e = svg.find('>', i);
            if (svg[e - 1] == '/') {
                self++;
            } else {
                open++;
            }
        }
    }
    EXPECT_EQ(open, close);
    EXPECT_GT(self, 5u);
}

} // namespace
