// Appendices A (CalculateFacing) and B (CalculateCullBits): the paper's C.
// Hand-computed cases, the exact operation order, the surface-bounds
// early-out, bit i <-> plane i, and agreement with an independent double
// evaluation wherever the float result is not within rounding of 0.
//
// Copyright (C) 2026 the shadowvol authors. LGPL-2.1-or-later.
#include "test_support.h"

#include <cfloat>
#include <cmath>

namespace {

using svtest::Rng;

uint8_t facing1(const Plane &p, const Vec4 &light) {
    uint8_t f[3] = {0xEE, 0xEE, 0xEE};
    sv_calculate_facing_c_ref(&p, 1, &light, f);
    EXPECT_EQ(f[1], 1) << "facing[numTriangles] must be 1";
    EXPECT_EQ(f[2], 0xEE) << "wrote past facing[numTriangles]";
    return f[0];
}

TEST(CalculateFacing, HandComputed) {
    const Plane z0 = {0, 0, 1, 0};            // z = 0, normal +z
    EXPECT_EQ(facing1(z0, {0, 0, 5, 1}), 1);  // point light in front
    EXPECT_EQ(facing1(z0, {0, 0, -5, 1}), 0); // behind
    EXPECT_EQ(facing1(z0, {3, 4, 0, 1}), 0);  // on the plane: > 0.0f is strict
    const Plane z2 = {0, 0, 1, -2};           // z = 2
    EXPECT_EQ(facing1(z2, {0, 0, 2, 1}), 0);  // exactly on it: 2 - 2 = 0
    EXPECT_EQ(facing1(z2, {0, 0, 2.5f, 1}), 1);
    EXPECT_EQ(facing1(z2, {0, 0, 1.5f, 1}), 0);
    // Directional lights (w = 0): d is multiplied by 0, only the direction counts.
    EXPECT_EQ(facing1(z2, {0, 0, 1, 0}), 1);
    EXPECT_EQ(facing1(z2, {0, 0, -1, 0}), 0);
    EXPECT_EQ(facing1(z2, {1, 0, 0, 0}), 0); // grazing: 0, not facing
    // A sum of -0.0 is not > 0.
    const Plane neg = {0, 0, -1, 0};
    EXPECT_EQ(facing1(neg, {0, 0, 0, 1}), 0);
    // A zero plane (the preparation's zero-area triangle) never faces.
    EXPECT_EQ(facing1(Plane{0, 0, 0, 0}, {1, 2, 3, 1}), 0);
    // NaN never faces.
    EXPECT_EQ(facing1(z0, {0, 0, NAN, 1}), 0);
}

TEST(CalculateFacing, PaperOperationOrderLeftToRight) {
    // a*x = 1e8, b*y = 4, c*z = -1e8, d*w = -1. Exactly: 3 > 0 (facing).
    // The paper's order ((1e8 + 4) - 1e8) - 1: 1e8 + 4 rounds to 1e8 (ties
    // to even, the float spacing at 1e8 is 8), so the sum is -1: NOT facing.
    // A SIMD variant that sums in another order, or fuses into FMAs, gives
    // other bits; this pins the reference.
    const Plane p = {1e8f, 4.0f, -1e8f, -1.0f};
    EXPECT_EQ(facing1(p, {1, 1, 1, 1}), 0);
    double exact = 1e8 + 4.0 - 1e8 - 1.0;
    EXPECT_GT(exact, 0.0);
}

TEST(CalculateFacing, CountsZeroAndNegative) {
    uint8_t f[2] = {0xEE, 0xEE};
    Vec4 light = {0, 0, 0, 1};
    sv_calculate_facing_c_ref(nullptr, 0, &light, f);
    EXPECT_EQ(f[0], 1);
    EXPECT_EQ(f[1], 0xEE);
    f[0] = 0xEE;
    sv_calculate_facing_c_ref(nullptr, -5, &light, f + 1);
    EXPECT_EQ(f[0], 0xEE) << "a negative count must write nothing";
    EXPECT_EQ(f[1], 0xEE);
}

float rnd(Rng &rng, float lo, float hi) { return lo + (hi - lo) * (float)rng.unit(); }

// Double evaluation of a*x + b*y + c*z + d*w (each product exact in double)
// and a bound on the float result's rounding error: the float sum of four
// terms carries at most ~4 roundings of the partial sums plus one per
// product, each at most FLT_EPSILON/2 of the magnitudes involved.
struct Eval {
    double value;
    double bound;
};
Eval eval4(double a, double x, double b, double y, double c, double z, double d, double w) {
    double t[4] = {a * x, b * y, c * z, d * w};
    double mag = std::fabs(t[0]) + std::fabs(t[1]) + std::fabs(t[2]) + std::fabs(t[3]);
    return {t[0] + t[1] + t[2] + t[3], 8.0 * FLT_EPSILON * mag + 1e-38};
}

TEST(CalculateFacing, AgreesWithDoubleAwayFromZero) {
    SCOPED_TRACE(svtest::seed_trace());
    Rng rng = svtest::rng_for("CalculateFacing.AgreesWithDoubleAwayFromZero");
    const int n = 4099;
    std::vector<Plane> planes(n);
    std::vector<uint8_t> facing(n + 2);
    long checked = 0, close = 0;
    for (int round = 0; round < 40; round++) {
        float scale = std::ldexp(1.0f, (int)rng.below(40) - 20);
        for (auto &p : planes) {
            p = {rnd(rng, -1, 1), rnd(rng, -1, 1), rnd(rng, -1, 1), rnd(rng, -1, 1) * scale};
        }
        Vec4 light = {rnd(rng, -1, 1) * scale, rnd(rng, -1, 1) * scale, rnd(rng, -1, 1) * scale,
                      round % 4 == 3 ? 0.0f : 1.0f};
        facing[n + 1] = 0xEE;
        sv_calculate_facing_c_ref(planes.data(), n, &light, facing.data());
        ASSERT_EQ(facing[n], 1);
        ASSERT_EQ(facing[n + 1], 0xEE);
        for (int i = 0; i < n; i++) {
            const Plane &p = planes[i];
            ASSERT_TRUE(facing[i] == 0 || facing[i] == 1);
            Eval e = eval4(p.a, light.x, p.b, light.y, p.c, light.z, p.d, light.w);
            if (std::fabs(e.value) <= e.bound) {
                close++;
                continue;
            }
            checked++;
            ASSERT_EQ(facing[i], e.value > 0.0 ? 1 : 0)
                << "triangle " << i << " round " << round << " double " << e.value;
        }
    }
    EXPECT_GT(checked, 100000);
    std::printf("[          ] facing: %ld agreed with double, %ld within rounding of 0\n", checked,
                close);
}

// ---- Appendix B ------------------------------------------------------------

// The light volume of a point light's box [-1,1]^3: planes point INTO it.
// Plane i <-> bit i.
void unit_box_planes(Plane planes[6]) {
    planes[0] = {1, 0, 0, 1};  // x >= -1
    planes[1] = {-1, 0, 0, 1}; // x <= 1
    planes[2] = {0, 1, 0, 1};
    planes[3] = {0, -1, 0, 1};
    planes[4] = {0, 0, 1, 1};
    planes[5] = {0, 0, -1, 1};
}

const Bounds kHuge = {{0, 0, 0, 0}, {1e6f, 1e6f, 1e6f, 0}};

TEST(CalculateCullBits, HandComputed) {
    Plane planes[6];
    unit_box_planes(planes);
    std::vector<Vec4> v = {
        {0, 0, 0, 1},    // inside: 0
        {2, 0, 0, 1},    // x > 1: behind plane 1
        {-2, 0, 0, 1},   // plane 0
        {1, 0, 0, 1},    // on plane 1: -1 + 1 = 0 is not < 0: inside
        {2, 2, -2, 1},   // planes 1, 3, 4
        {-3, -3, -3, 1}, // planes 0, 2, 4
        {0, 0, 1.5f, 7}, // w is ignored: plane 5
    };
    std::vector<uint8_t> bits(v.size() + 1, 0xEE);
    ASSERT_EQ(sv_calculate_cull_bits_c_ref(v.data(), (int)v.size(), &kHuge, planes, bits.data()),
              0);
    EXPECT_EQ(bits[0], 0);
    EXPECT_EQ(bits[1], 1 << 1);
    EXPECT_EQ(bits[2], 1 << 0);
    EXPECT_EQ(bits[3], 0);
    EXPECT_EQ(bits[4], (1 << 1) | (1 << 3) | (1 << 4));
    EXPECT_EQ(bits[5], (1 << 0) | (1 << 2) | (1 << 4));
    EXPECT_EQ(bits[6], 1 << 5);
    EXPECT_EQ(bits[7], 0xEE) << "wrote past numVerts";
}

TEST(CalculateCullBits, BitIIsPlaneI) {
    // Six planes in general position; for each i a vertex just behind plane
    // i only (in front of the rest) gets exactly bit i.
    Plane planes[6];
    unit_box_planes(planes);
    for (int i = 0; i < 6; i++) {
        Vec4 v = {0, 0, 0, 1};
        float *c = i < 2 ? &v.x : i < 4 ? &v.y : &v.z;
        *c = (i % 2 == 0) ? -1.25f : 1.25f;
        uint8_t bit = 0xEE;
        ASSERT_EQ(sv_calculate_cull_bits_c_ref(&v, 1, &kHuge, planes, &bit), 0);
        EXPECT_EQ(bit, 1 << i) << "plane " << i;
    }
}

TEST(CalculateCullBits, SurfaceBoundsEarlyOut) {
    Plane planes[6];
    unit_box_planes(planes);
    // A surface box well inside: returns 1 and does NOT write cullBits.
    Bounds inside = {{0.1f, -0.2f, 0.3f, 0}, {0.5f, 0.5f, 0.5f, 0}};
    Vec4 v[2] = {{0, 0, 0, 1}, {0.5f, 0.2f, 0.7f, 1}};
    uint8_t bits[2] = {0xEE, 0xEE};
    EXPECT_EQ(sv_calculate_cull_bits_c_ref(v, 2, &inside, planes, bits), 1);
    EXPECT_EQ(bits[0], 0xEE);
    EXPECT_EQ(bits[1], 0xEE);
    // A box touching the volume's faces exactly (d1 - d2 == 0 for every
    // plane) counts as in front: >= CULL_EPSILON (0).
    Bounds touching = {{0, 0, 0, 0}, {1, 1, 1, 0}};
    EXPECT_EQ(sv_calculate_cull_bits_c_ref(v, 2, &touching, planes, bits), 1);
    EXPECT_EQ(bits[0], 0xEE);
    // A box poking out past x = 1 only: not inside, cullBits written, and
    // the five planes the box is in front of are NOT evaluated per vertex:
    // a vertex that (against the contract) lies outside the box behind
    // plane 0 keeps bit 0 clear. That pins the early-out per plane.
    Bounds pokes = {{0.5f, 0, 0, 0}, {0.75f, 0.5f, 0.5f, 0}};
    Vec4 w[3] = {{0, 0, 0, 1}, {1.2f, 0, 0, 1}, {-5, 0, 0, 1}};
    uint8_t b3[3] = {0xEE, 0xEE, 0xEE};
    EXPECT_EQ(sv_calculate_cull_bits_c_ref(w, 3, &pokes, planes, b3), 0);
    EXPECT_EQ(b3[0], 0);
    EXPECT_EQ(b3[1], 1 << 1);
    EXPECT_EQ(b3[2], 0) << "plane 0 was skipped by the bounds test";
    // Zero and negative counts.
    EXPECT_EQ(sv_calculate_cull_bits_c_ref(nullptr, 0, &pokes, planes, nullptr), 0);
    EXPECT_EQ(sv_calculate_cull_bits_c_ref(nullptr, -3, &pokes, planes, nullptr), 0);
}

TEST(CalculateCullBits, AgreesWithDoubleAwayFromZero) {
    SCOPED_TRACE(svtest::seed_trace());
    Rng rng = svtest::rng_for("CalculateCullBits.AgreesWithDoubleAwayFromZero");
    const int n = 2053;
    std::vector<Vec4> v(n);
    std::vector<uint8_t> bits(n);
    long checked = 0, close = 0, inside_returns = 0;
    for (int round = 0; round < 60; round++) {
        Plane planes[6];
        for (auto &p : planes) {
            p = {rnd(rng, -1, 1), rnd(rng, -1, 1), rnd(rng, -1, 1), rnd(rng, -1, 1)};
        }
        if (round % 3 == 0) {
            unit_box_planes(planes); // a real light box, often containing the surface
        }
        // The surface: random vertices in a random box, and that box as bounds.
        // Every sixth round the surface sits well inside the unit light box.
        float span = round % 6 == 0 ? 0.5f : 1.5f, ext = round % 6 == 0 ? 0.4f : 1.0f;
        float cx = rnd(rng, -span, span), cy = rnd(rng, -span, span), cz = rnd(rng, -span, span);
        float ex = rnd(rng, 0, ext), ey = rnd(rng, 0, ext), ez = rnd(rng, 0, ext);
        Bounds b = {{cx, cy, cz, 0}, {ex, ey, ez, 0}};
        for (auto &p : v) {
            p = {cx + ex * rnd(rng, -1, 1), cy + ey * rnd(rng, -1, 1), cz + ez * rnd(rng, -1, 1),
                 1};
        }
        int inside = sv_calculate_cull_bits_c_ref(v.data(), n, &b, planes, bits.data());
        inside_returns += inside;
        for (int j = 0; j < n; j++) {
            for (int i = 0; i < 6; i++) {
                const Plane &p = planes[i];
                Eval e = eval4(p.a, v[j].x, p.b, v[j].y, p.c, v[j].z, p.d, 1.0);
                if (std::fabs(e.value) <= e.bound) {
                    close++;
                    continue;
                }
                checked++;
                int expect = e.value < 0.0 ? 1 : 0;
                if (inside) {
                    ASSERT_EQ(expect, 0)
                        << "reported inside, but vertex " << j << " is behind plane " << i;
                } else if (expect) {
                    ASSERT_EQ((bits[j] >> i) & 1, 1) << "vertex " << j << " plane " << i;
                } else {
                    ASSERT_EQ((bits[j] >> i) & 1, 0) << "vertex " << j << " plane " << i;
                }
            }
            if (!inside) {
                ASSERT_EQ(bits[j] & 0xC0, 0);
            }
        }
    }
    EXPECT_GT(inside_returns, 0) << "no round exercised the early-out";
    EXPECT_LT(inside_returns, 60);
    std::printf("[          ] cull bits: %ld agreed with double, %ld within rounding of 0, "
                "%ld surfaces inside\n",
                checked, close, inside_returns);
}

} // namespace
