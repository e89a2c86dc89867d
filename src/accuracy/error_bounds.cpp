/*
 * A priori error bounds of the inexact facing variants, in the units of D
 * (the light's signed distance from the triangle's plane; see
 * shadowvol_accuracy.h): |D| > B implies the variant's facing byte is the
 * exact one.
 *
 * Notation: eta = 2^-53 and eps = 2^-24 (unit roundoffs of double and
 * float), gamma_k(u) = k u / (1 - k u) (Higham: k operations in a chain
 * multiply the error by at most gamma_k), n^ = n / |n| the exact unit
 * normal, L = (x, y, z) and w the light, p0 the plane's anchor.
 *
 * 1. The double normal. sv::triangle_plane rounds the edges u = p1 - p0,
 *    v = p2 - p0 (rel. eta each), forms n_c = u x v (each component two
 *    rounded products and a rounded difference), then n_d = n_c / |n_c|.
 *    With P_x = |u_y v_z| + |u_z v_y| (and cyclic), |n_c - n| <= e :=
 *    gamma_4 (1 + gamma_4) |P|, so the direction is off by at most
 *    2 e / (|n_c| - e) (|a/|a| - b/|b|| <= 2 |a - b| / |b|), and the
 *    normalisation (sqrt of a rounded sum, a division) adds 3.5 eta:
 *      alpha = 2 e / (|n_c| - e) + 3.5 eta        (+inf when |n_c| <= e:
 *    the triangle is too thin for the computed normal to have a direction;
 *    this covers every zero-area triangle).
 *    d_d = -(n_d . p0) in double is within gamma_3(eta) P0 of -(n_d . p0),
 *    P0 = sum |n_d,i p0_i|.
 * 2. A plane in any precision, evaluated exactly, differs from D by
 *      (n_plane - n_d) . L + (n_d - n^) . (L - w p0) + (d_plane - d_d) w
 *      + (d_d + n_d . p0) w,
 *    so the plane's own error is at most
 *      [rounding of n_d, d_d to the plane's type] + alpha R + gamma_3(eta) P0 |w|,
 *    R = |L - w p0|, the lever arm of the direction error.
 * 3. float_planes (c_ref and its SIMD twins, eps_bias): rounding to float
 *    costs eps M_d (M_d = sum |n_d,i L_i| + |d_d w|) plus 2^-150 per
 *    component that lands among the subnormals; the float dot product, a
 *    chain of 4 products and 3 sums, gamma_4(eps) M_f (M_f the same sum
 *    with the float plane) plus 2^-150 per operation for gradual underflow.
 *    With the caller's FTZ/DAZ (the reference runs in the caller's MXCSR),
 *    a flushed input or result costs up to 2^-126 times the other factor
 *    instead: 2^-126 (|L|_1 + |w| + |plane|_1 + 8).
 *    float_planes_fma: the same plane, a*x and three fused steps: gamma_4
 *    bounds it too, with 4 underflow terms.
 * 4. double_planes: no rounding of the plane; the dot product in double
 *    gamma_4(eta) M_d; nothing underflows (float-derived values stay above
 *    2^-760).
 * 5. fixed16: N = q / 32767 is lambda n^ + Delta with lambda = 1 / m_d (m_d
 *    the largest |n_d,i|) and |Delta| <= sqrt(3) (0.5 + 2^-37) / 32767 +
 *    sqrt(3) alpha (1 + 4 eta) (quantisation, plus the double normal's
 *    direction, scaled by 1 / m_d <= sqrt(3)). tn is anchored at the
 *    computed centroid c_d, within gamma_3(eta) |S| of the true one (S_i =
 *    |p0_i| + |p1_i| + |p2_i|), which lies on the plane. So
 *      s / lambda - D <= m_d [|Delta| R_c + eps sum |N_i L_i|
 *                         + 2^-150 sum |q_i|          (light / 32767 rounded)
 *                         + |w| (gamma_4(eta) sum |N_i c_d,i| + eps |tn| + 2^-150)
 *                         + gamma_4(eps) M_16 + 7 2^-150] + |w| gamma_3(eta) |S|
 *    with R_c = |L - w c_d|, M_16 = sum |q_i l_i| + |tn w|, m_d <= 1 + 3.5 eta.
 * Overflow: where a float operation of the variant could overflow (M_f or
 * M_16 near FLT_MAX, an infinite d or tn) the bound is +inf, as it is for a
 * non-finite light or position.
 *
 * Every bound is the first-order sum above times 1.01: the products of two
 * roundoffs dropped on the way are below 1e-6 of it, and the bounds' own
 * evaluation in double is good to a few eta.
 *
 * Compiled with -ffp-contract=off.
 *
 * Copyright (C) 2026 the shadowvol authors. LGPL-2.1-or-later.
 */
#include <algorithm>
#include <cfloat>
#include <cmath>
#include <limits>

#include "accuracy_internal.h"
#include "mxcsr_guard.h"
#include "shadowvol_accuracy.h"

namespace sv {

namespace {

constexpr double kEta = 0x1p-53;
constexpr double kEps = 0x1p-24;
constexpr double kSub = 0x1p-150; /* half the float subnormal spacing */
constexpr double kFtz = 0x1p-126; /* what a flush to zero can lose */
constexpr double kMargin = 1.01;
constexpr double kInf = std::numeric_limits<double>::infinity();

constexpr double gamma(int k, double u) { return k * u / (1.0 - k * u); }

double norm3(double x, double y, double z) { return std::sqrt(x * x + y * y + z * z); }

bool light_finite(const Vec4 &l) {
    return std::isfinite(l.x) && std::isfinite(l.y) && std::isfinite(l.z) && std::isfinite(l.w);
}

} // namespace

const char *facing_arithmetic_name(FacingArithmetic a) {
    switch (a) {
    case FacingArithmetic::float_planes: return "float_planes";
    case FacingArithmetic::float_planes_fma: return "float_planes_fma";
    case FacingArithmetic::double_planes: return "double_planes";
    case FacingArithmetic::fixed16: return "fixed16";
    }
    return "?";
}

namespace {

__attribute__((noinline)) TriangleErrorModel error_model_impl(const float p0[3], const float p1[3],
                                                              const float p2[3]) {
    TriangleErrorModel m;
    for (int i = 0; i < 3; i++) {
        m.finite = m.finite && std::isfinite(p0[i]) && std::isfinite(p1[i]) && std::isfinite(p2[i]);
    }
    m.plane = triangle_plane(p0, p1, p2);
    m.plane_d = triangle_plane_double(p0, p1, p2);
    triangle_plane16(p0, p1, p2, m.q, &m.tn);
    if (!m.finite) {
        m.alpha = kInf;
        return m;
    }
    for (int i = 0; i < 3; i++) {
        m.p0[i] = p0[i];
        /* The centroid exactly as triangle_plane16 computes it. */
        m.c[i] = ((double)p0[i] + p1[i] + p2[i]) / 3.0;
        m.abs_sum[i] = std::fabs((double)p0[i]) + std::fabs((double)p1[i]) +
                       std::fabs((double)p2[i]);
    }
    const double u[3] = {(double)p1[0] - p0[0], (double)p1[1] - p0[1], (double)p1[2] - p0[2]};
    const double v[3] = {(double)p2[0] - p0[0], (double)p2[1] - p0[1], (double)p2[2] - p0[2]};
    const double nc = norm3(u[1] * v[2] - u[2] * v[1], u[2] * v[0] - u[0] * v[2],
                            u[0] * v[1] - u[1] * v[0]);
    const double P = norm3(std::fabs(u[1] * v[2]) + std::fabs(u[2] * v[1]),
                           std::fabs(u[2] * v[0]) + std::fabs(u[0] * v[2]),
                           std::fabs(u[0] * v[1]) + std::fabs(u[1] * v[0]));
    const double e = gamma(4, kEta) * (1.0 + gamma(4, kEta)) * P * (1.0 + 4 * kEta);
    const double nc_low = nc * (1.0 - 4 * kEta);
    m.alpha = nc_low > e ? 2.0 * e / (nc_low - e) + 3.5 * kEta : kInf;
    return m;
}

__attribute__((noinline)) double bound_impl(FacingArithmetic a, const TriangleErrorModel &m,
                                            const Vec4 &light, bool caller_ftz_daz) {
    if (!m.finite || !std::isfinite(m.alpha) || !light_finite(light)) return kInf;
    const double L[3] = {light.x, light.y, light.z};
    const double w = light.w, aw = std::fabs(w);
    const double L1 = std::fabs(L[0]) + std::fabs(L[1]) + std::fabs(L[2]);
    const double nd[3] = {m.plane_d.a, m.plane_d.b, m.plane_d.c};

    if (a == FacingArithmetic::fixed16) {
        if (!std::isfinite(m.tn)) return kInf;
        const float l[3] = {light.x / 32767.0f, light.y / 32767.0f, light.z / 32767.0f};
        double NL = 0, Nc = 0, q1 = 0, M16 = std::fabs((double)m.tn * w);
        for (int i = 0; i < 3; i++) {
            const double N = m.q[i] / 32767.0;
            NL += std::fabs(N * L[i]);
            Nc += std::fabs(N * m.c[i]);
            q1 += std::fabs((double)m.q[i]);
            M16 += std::fabs((double)m.q[i] * l[i]);
        }
        if (!(M16 * (1.0 + gamma(4, kEps)) < (double)FLT_MAX)) return kInf;
        const double Rc = norm3(L[0] - w * m.c[0], L[1] - w * m.c[1], L[2] - w * m.c[2]);
        const double delta = std::sqrt(3.0) * (0.5 + 0x1p-37) / 32767.0 +
                             std::sqrt(3.0) * m.alpha * (1.0 + 4 * kEta);
        const double s_err = delta * Rc + kEps * NL + kSub * q1 +
                             aw * (gamma(4, kEta) * Nc + kEps * std::fabs((double)m.tn) + kSub) +
                             gamma(4, kEps) * M16 + 7 * kSub;
        const double S = norm3(m.abs_sum[0], m.abs_sum[1], m.abs_sum[2]);
        return kMargin * ((1.0 + 3.5 * kEta) * s_err + aw * gamma(3, kEta) * S);
    }

    /* Planes anchored at p0 (sections 2-4). */
    double Md = std::fabs(m.plane_d.d * w), P0 = 0;
    for (int i = 0; i < 3; i++) {
        Md += std::fabs(nd[i] * L[i]);
        P0 += std::fabs(nd[i] * m.p0[i]);
    }
    const double R = norm3(L[0] - w * m.p0[0], L[1] - w * m.p0[1], L[2] - w * m.p0[2]);
    const double direction = m.alpha * R + gamma(3, kEta) * P0 * aw;
    if (a == FacingArithmetic::double_planes) {
        return kMargin * (direction + gamma(4, kEta) * Md);
    }
    const double pf[4] = {m.plane.a, m.plane.b, m.plane.c, m.plane.d};
    const double Mf = std::fabs(pf[0] * L[0]) + std::fabs(pf[1] * L[1]) + std::fabs(pf[2] * L[2]) +
                      std::fabs(pf[3] * w);
    if (!(Mf * (1.0 + gamma(4, kEps)) < (double)FLT_MAX)) return kInf;
    const double rounding = kEps * Md + kSub * (L1 + aw);
    const int ops = a == FacingArithmetic::float_planes ? 7 : 4;
    double eval = gamma(4, kEps) * Mf + ops * kSub;
    if (caller_ftz_daz) {
        eval += kFtz * (L1 + aw + std::fabs(pf[0]) + std::fabs(pf[1]) + std::fabs(pf[2]) +
                        std::fabs(pf[3]) + 8.0);
    }
    return kMargin * (rounding + direction + eval);
}

} // namespace

/* Both under the default MXCSR, like the preparation they describe (the
 * planes of sv::prepare_surface are assumed built without DAZ). */
TriangleErrorModel triangle_error_model(const float p0[3], const float p1[3], const float p2[3]) {
    const unsigned saved = sv_mxcsr_enter();
    TriangleErrorModel m = error_model_impl(p0, p1, p2);
    sv_mxcsr_leave(saved);
    return m;
}

double facing_error_bound(FacingArithmetic a, const TriangleErrorModel &m, const Vec4 &light,
                          bool caller_ftz_daz) {
    const unsigned saved = sv_mxcsr_enter();
    const double b = bound_impl(a, m, light, caller_ftz_daz);
    sv_mxcsr_leave(saved);
    return b;
}

double exact_signed_distance(const float p0[3], const float p1[3], const float p2[3],
                             const Vec4 &light) {
    return sv_exact_signed_distance(p0, p1, p2, &light);
}

} // namespace sv
