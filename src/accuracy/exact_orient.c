/*
 * The exact facing predicate: the sign of
 *   det = ((p1 - p0) x (p2 - p0)) . ((x, y, z) - w p0)
 * for float points and a float light (x, y, z, w), decided exactly.
 *
 * Method (Shewchuk's adaptive orient3d, stage A then the exact stage):
 *  1. Filter. In double, with rows u = p1 - p0, v = p2 - p0, r = L - w p0
 *     each rounded once (w p0 is a product of two floats: exact in double),
 *     det is evaluated as Shewchuk's orient3dfast evaluates det[a-d; b-d;
 *     c-d], and so is the permanent (the same sum with absolute values).
 *     His bound |det_computed - det| <= (7 + 56 eps) eps permanent (eps =
 *     2^-53) holds for any three rows that are single rounded differences
 *     of doubles, without overflow or underflow, which float inputs
 *     guarantee (expansion.h). When |det_computed| exceeds it the sign is
 *     right.
 *  2. Exact stage, for the rest: the differences as two-component
 *     expansions (Two-Diff), the 2x2 minors of v and r and their products
 *     with u as expansions (at most 192 components), the sign of the sum.
 * The orientation of det: with u x v the reference's (counter-clockwise)
 * normal, det = |n| D, D the light's signed distance from the plane; det is
 * -orient3d(p0, p1, p2, L) in Shewchuk's sign convention.
 *
 * Non-finite input: the permanent of finite floats is at most 3 * 2^387; a
 * NaN or infinite coordinate makes some row component non-finite, and every
 * row component is multiplied into the permanent by a factor >= 0, which
 * gives inf or NaN (inf * 0). So "permanent is not a finite number" detects
 * exactly the non-finite inputs, at no extra cost: they give 0.
 *
 * Compiled with -ffp-contract=off: a fused a*b+c would break Two-Product
 * and the filter's error bound.
 *
 * Copyright (C) 2026 the shadowvol authors. LGPL-2.1-or-later.
 */
#include <float.h>
#include <immintrin.h>

#include "accuracy_internal.h"
#include "expansion.h"
#include "mxcsr_guard.h"
#include "shadowvol_accuracy.h"

/* Shewchuk's o3derrboundA = (7 + 56 eps) eps, eps = 2^-53. */
#define SV_O3D_ERRBOUND_A ((7.0 + 56.0 * 0x1p-53) * 0x1p-53)

/* The filter on rows (u, v, r): det[u; v; r] expanded along z as in
 * orient3dfast (a-d = u, b-d = v, c-d = r), and the permanent. */
static inline double det_filter(const double u[3], const double v[3], const double r[3],
                                double *permanent) {
    const double vxry = v[0] * r[1], rxvy = r[0] * v[1];
    const double rxuy = r[0] * u[1], uxry = u[0] * r[1];
    const double uxvy = u[0] * v[1], vxuy = v[0] * u[1];
    const double det = u[2] * (vxry - rxvy) + v[2] * (rxuy - uxry) + r[2] * (uxvy - vxuy);
    *permanent = (__builtin_fabs(vxry) + __builtin_fabs(rxvy)) * __builtin_fabs(u[2]) +
                 (__builtin_fabs(rxuy) + __builtin_fabs(uxry)) * __builtin_fabs(v[2]) +
                 (__builtin_fabs(uxvy) + __builtin_fabs(vxuy)) * __builtin_fabs(r[2]);
    return det;
}

/* a*d - b*c for two-component expansions, into h (at most 16). */
static int minor2(const double *a, int an, const double *d, int dn, const double *b, int bn,
                  const double *c, int cn, double *h) {
    double ad[8], bc[8], scratch[12];
    const int adn = sv_expansion_product(an, a, dn, d, ad, scratch);
    int bcn = sv_expansion_product(bn, b, cn, c, bc, scratch);
    for (int i = 0; i < bcn; i++) bc[i] = -bc[i];
    return sv_expansion_sum(adn, ad, bcn, bc, h);
}

int sv_exact_det_expansion(const float p0[3], const float p1[3], const float p2[3],
                           const Vec4 *light, double det[SV_EXACT_DET_MAX_COMPONENTS]) {
    const double lw = light->w;
    const double l[3] = {light->x, light->y, light->z};
    double u[3][2], v[3][2], r[3][2];
    int un[3], vn[3], rn[3];
    for (int i = 0; i < 3; i++) {
        un[i] = sv_diff_expansion(p1[i], p0[i], u[i]);
        vn[i] = sv_diff_expansion(p2[i], p0[i], v[i]);
        /* w * p0 is a product of two floats: exact in double. */
        rn[i] = sv_diff_expansion(l[i], lw * (double)p0[i], r[i]);
    }
    /* det = u . (v x r); (v x r)_i = v_j r_k - v_k r_j, (i, j, k) cyclic. */
    double m[16], t[3][64], scratch[96], s01[128];
    int tn[3];
    for (int i = 0; i < 3; i++) {
        const int j = (i + 1) % 3, k = (i + 2) % 3;
        const int mn = minor2(v[j], vn[j], r[k], rn[k], v[k], vn[k], r[j], rn[j], m);
        tn[i] = sv_expansion_product(mn, m, un[i], u[i], t[i], scratch);
    }
    const int n01 = sv_expansion_sum(tn[0], t[0], tn[1], t[1], s01);
    return sv_expansion_sum(n01, s01, tn[2], t[2], det);
}

/* The exact stage's sign. */
static int exact_stage_sign(const float p0[3], const float p1[3], const float p2[3],
                            const Vec4 *light) {
    double det[SV_EXACT_DET_MAX_COMPONENTS];
    const int n = sv_exact_det_expansion(p0, p1, p2, light, det);
    const double top = det[n - 1];
    return (top > 0.0) - (top < 0.0);
}

/* Filter, then (when it cannot decide) the exact stage. *exact_used is
 * incremented when the exact stage ran. Needs the guarded MXCSR. */
static inline int facing_sign(const float p0[3], const float p1[3], const float p2[3],
                              const Vec4 *light, int *exact_used) {
    const double lw = light->w;
    double u[3], v[3], r[3], permanent;
    u[0] = (double)p1[0] - p0[0];
    u[1] = (double)p1[1] - p0[1];
    u[2] = (double)p1[2] - p0[2];
    v[0] = (double)p2[0] - p0[0];
    v[1] = (double)p2[1] - p0[1];
    v[2] = (double)p2[2] - p0[2];
    r[0] = (double)light->x - lw * p0[0];
    r[1] = (double)light->y - lw * p0[1];
    r[2] = (double)light->z - lw * p0[2];
    const double det = det_filter(u, v, r, &permanent);
    if (!(permanent <= DBL_MAX)) return 0; /* a NaN or infinite coordinate */
    const double bound = SV_O3D_ERRBOUND_A * permanent;
    if (det > bound) return 1;
    if (-det > bound) return -1;
    ++*exact_used;
    return exact_stage_sign(p0, p1, p2, light);
}

__attribute__((noinline)) static int facing_sign_body(const float p0[3], const float p1[3],
                                                      const float p2[3], const Vec4 *light) {
    int unused = 0;
    return facing_sign(p0, p1, p2, light, &unused);
}

int sv_facing_exact_sign(const float p0[3], const float p1[3], const float p2[3],
                         const Vec4 *light) {
    const unsigned saved = sv_mxcsr_enter();
    const int s = facing_sign_body(p0, p1, p2, light);
    sv_mxcsr_leave(saved);
    return s;
}

__attribute__((noinline)) static int unfiltered_body(const float p0[3], const float p1[3],
                                                     const float p2[3], const Vec4 *light) {
    double permanent, u[3], v[3], r[3];
    for (int i = 0; i < 3; i++) {
        u[i] = (double)p1[i] - p0[i];
        v[i] = (double)p2[i] - p0[i];
    }
    r[0] = (double)light->x - (double)light->w * p0[0];
    r[1] = (double)light->y - (double)light->w * p0[1];
    r[2] = (double)light->z - (double)light->w * p0[2];
    (void)det_filter(u, v, r, &permanent); /* only to detect non-finite input */
    return permanent <= DBL_MAX ? exact_stage_sign(p0, p1, p2, light) : 0;
}

int sv_facing_exact_sign_unfiltered(const float p0[3], const float p1[3], const float p2[3],
                                    const Vec4 *light) {
    const unsigned saved = sv_mxcsr_enter();
    const int s = unfiltered_body(p0, p1, p2, light);
    sv_mxcsr_leave(saved);
    return s;
}

__attribute__((noinline)) static int filter_decides_body(const float p0[3], const float p1[3],
                                                         const float p2[3], const Vec4 *light) {
    int exact_used = 0;
    (void)facing_sign(p0, p1, p2, light, &exact_used);
    return !exact_used;
}

int sv_exact_filter_decides(const float p0[3], const float p1[3], const float p2[3],
                            const Vec4 *light) {
    const unsigned saved = sv_mxcsr_enter();
    const int decided = filter_decides_body(p0, p1, p2, light);
    sv_mxcsr_leave(saved);
    return decided;
}

/* |u x v| with u, v the exact differences: each component of the cross
 * product is an exact expansion, estimated to a few ulps, then the norm in
 * double. */
__attribute__((noinline)) static double normal_length_body(const float p0[3], const float p1[3],
                                                           const float p2[3]) {
    double u[3][2], v[3][2], m[16];
    int un[3], vn[3];
    for (int i = 0; i < 3; i++) {
        un[i] = sv_diff_expansion(p1[i], p0[i], u[i]);
        vn[i] = sv_diff_expansion(p2[i], p0[i], v[i]);
    }
    double n[3];
    for (int i = 0; i < 3; i++) {
        const int j = (i + 1) % 3, k = (i + 2) % 3;
        const int mn = minor2(u[j], un[j], v[k], vn[k], u[k], un[k], v[j], vn[j], m);
        n[i] = sv_expansion_estimate(mn, m);
    }
    return __builtin_sqrt(n[0] * n[0] + n[1] * n[1] + n[2] * n[2]);
}

double sv_exact_normal_length(const float p0[3], const float p1[3], const float p2[3]) {
    const unsigned saved = sv_mxcsr_enter();
    const double len = normal_length_body(p0, p1, p2);
    sv_mxcsr_leave(saved);
    return len;
}

/* det, relative error below 2^-45, and its exact sign. */
__attribute__((noinline)) static double det_estimate_body(const float p0[3], const float p1[3],
                                                          const float p2[3], const Vec4 *light,
                                                          int *sign) {
    double u[3], v[3], r[3], permanent;
    for (int i = 0; i < 3; i++) {
        u[i] = (double)p1[i] - p0[i];
        v[i] = (double)p2[i] - p0[i];
    }
    r[0] = (double)light->x - (double)light->w * p0[0];
    r[1] = (double)light->y - (double)light->w * p0[1];
    r[2] = (double)light->z - (double)light->w * p0[2];
    const double det = det_filter(u, v, r, &permanent);
    if (!(permanent <= DBL_MAX)) {
        *sign = 0;
        return __builtin_nan("");
    }
    const double bound = SV_O3D_ERRBOUND_A * permanent;
    /* The filter's value when its error is below 2^-46 of it (its sign is
     * then right too), else the expansion's estimate and sign. */
    if (__builtin_fabs(det) > 0x1p46 * bound) {
        *sign = det > 0.0 ? 1 : -1;
        return det;
    }
    double e[SV_EXACT_DET_MAX_COMPONENTS];
    const int n = sv_exact_det_expansion(p0, p1, p2, light, e);
    *sign = (e[n - 1] > 0.0) - (e[n - 1] < 0.0);
    return sv_expansion_estimate(n, e);
}

double sv_exact_det_estimate(const float p0[3], const float p1[3], const float p2[3],
                             const Vec4 *light, int *sign) {
    const unsigned saved = sv_mxcsr_enter();
    const double d = det_estimate_body(p0, p1, p2, light, sign);
    sv_mxcsr_leave(saved);
    return d;
}

__attribute__((noinline)) static double signed_distance_body(const float p0[3], const float p1[3],
                                                             const float p2[3], const Vec4 *light) {
    int sign;
    const double det = det_estimate_body(p0, p1, p2, light, &sign);
    if (sign == 0) return det; /* 0, or NaN for non-finite input */
    return det / normal_length_body(p0, p1, p2);
}

double sv_exact_signed_distance(const float p0[3], const float p1[3], const float p2[3],
                                const Vec4 *light) {
    const unsigned saved = sv_mxcsr_enter();
    const double d = signed_distance_body(p0, p1, p2, light);
    sv_mxcsr_leave(saved);
    return d;
}

__attribute__((noinline)) static int facing_exact_body(const float *positions, const int *indices,
                                                       int numTriangles, const Vec4 *light,
                                                       uint8_t *facing) {
    int exact_used = 0;
    for (int t = 0; t < numTriangles; t++) {
        const float *p0 = positions + 3 * (size_t)indices[3 * (size_t)t];
        const float *p1 = positions + 3 * (size_t)indices[3 * (size_t)t + 1];
        const float *p2 = positions + 3 * (size_t)indices[3 * (size_t)t + 2];
        facing[t] = facing_sign(p0, p1, p2, light, &exact_used) > 0;
    }
    facing[numTriangles] = 1;
    return exact_used;
}

int sv_calculate_facing_exact(const float *positions, const int *indices, int numTriangles,
                              const Vec4 *light, uint8_t *facing) {
    if (numTriangles < 0) return 0;
    const unsigned saved = sv_mxcsr_enter();
    const int n = facing_exact_body(positions, indices, numTriangles, light, facing);
    sv_mxcsr_leave(saved);
    return n;
}

/* ---- AVX2: the filter four triangles at a time ---------------------------
 * The same operations as facing_sign, lane by lane (mul, sub, add in the
 * same order; no FMA), so every lane's det, permanent and bound are the
 * scalar ones bit for bit and the decisions are the same; a lane the filter
 * cannot decide (or a non-finite one) goes through the scalar path. */

#define SV_TARGET_AVX2 __attribute__((target("avx2")))

SV_TARGET_AVX2 static inline __m256d abs_pd(__m256d x) {
    return _mm256_andnot_pd(_mm256_set1_pd(-0.0), x);
}

/* Coordinate c of the vertex corner k of triangles t..t+3, as doubles. */
SV_TARGET_AVX2 static inline __m256d gather_coord(const float *positions, const int *indices,
                                                  size_t t, int corner, int c) {
    const int *ix = indices + 3 * t + corner;
    return _mm256_setr_pd(positions[3 * (size_t)ix[0] + c], positions[3 * (size_t)ix[3] + c],
                          positions[3 * (size_t)ix[6] + c], positions[3 * (size_t)ix[9] + c]);
}

SV_TARGET_AVX2 __attribute__((noinline)) static int
facing_exact_avx2_body(const float *positions, const int *indices, int numTriangles,
                       const Vec4 *light, uint8_t *facing) {
    int exact_used = 0;
    const __m256d lx = _mm256_set1_pd(light->x), ly = _mm256_set1_pd(light->y);
    const __m256d lz = _mm256_set1_pd(light->z), lw = _mm256_set1_pd(light->w);
    const __m256d errA = _mm256_set1_pd(SV_O3D_ERRBOUND_A);
    const __m256d dmax = _mm256_set1_pd(DBL_MAX);
    int t = 0;
    for (; t <= numTriangles - 4; t += 4) {
        const __m256d p0x = gather_coord(positions, indices, (size_t)t, 0, 0);
        const __m256d p0y = gather_coord(positions, indices, (size_t)t, 0, 1);
        const __m256d p0z = gather_coord(positions, indices, (size_t)t, 0, 2);
        const __m256d ux = _mm256_sub_pd(gather_coord(positions, indices, (size_t)t, 1, 0), p0x);
        const __m256d uy = _mm256_sub_pd(gather_coord(positions, indices, (size_t)t, 1, 1), p0y);
        const __m256d uz = _mm256_sub_pd(gather_coord(positions, indices, (size_t)t, 1, 2), p0z);
        const __m256d vx = _mm256_sub_pd(gather_coord(positions, indices, (size_t)t, 2, 0), p0x);
        const __m256d vy = _mm256_sub_pd(gather_coord(positions, indices, (size_t)t, 2, 1), p0y);
        const __m256d vz = _mm256_sub_pd(gather_coord(positions, indices, (size_t)t, 2, 2), p0z);
        const __m256d rx = _mm256_sub_pd(lx, _mm256_mul_pd(lw, p0x));
        const __m256d ry = _mm256_sub_pd(ly, _mm256_mul_pd(lw, p0y));
        const __m256d rz = _mm256_sub_pd(lz, _mm256_mul_pd(lw, p0z));
        const __m256d vxry = _mm256_mul_pd(vx, ry), rxvy = _mm256_mul_pd(rx, vy);
        const __m256d rxuy = _mm256_mul_pd(rx, uy), uxry = _mm256_mul_pd(ux, ry);
        const __m256d uxvy = _mm256_mul_pd(ux, vy), vxuy = _mm256_mul_pd(vx, uy);
        __m256d det = _mm256_mul_pd(uz, _mm256_sub_pd(vxry, rxvy));
        det = _mm256_add_pd(det, _mm256_mul_pd(vz, _mm256_sub_pd(rxuy, uxry)));
        det = _mm256_add_pd(det, _mm256_mul_pd(rz, _mm256_sub_pd(uxvy, vxuy)));
        __m256d perm = _mm256_mul_pd(_mm256_add_pd(abs_pd(vxry), abs_pd(rxvy)), abs_pd(uz));
        perm = _mm256_add_pd(perm,
                             _mm256_mul_pd(_mm256_add_pd(abs_pd(rxuy), abs_pd(uxry)), abs_pd(vz)));
        perm = _mm256_add_pd(perm,
                             _mm256_mul_pd(_mm256_add_pd(abs_pd(uxvy), abs_pd(vxuy)), abs_pd(rz)));
        const __m256d bound = _mm256_mul_pd(errA, perm);
        const int pos = _mm256_movemask_pd(_mm256_cmp_pd(det, bound, _CMP_GT_OQ));
        const int neg = _mm256_movemask_pd(
            _mm256_cmp_pd(_mm256_sub_pd(_mm256_setzero_pd(), det), bound, _CMP_GT_OQ));
        const int finite = _mm256_movemask_pd(_mm256_cmp_pd(perm, dmax, _CMP_LE_OQ));
        /* pos and neg exclude each other; a finite lane in neither is undecided. */
        const int undecided = finite & ~(pos | neg);
        for (int k = 0; k < 4; k++) facing[t + k] = (uint8_t)((pos >> k) & 1);
        if (undecided) {
            for (int k = 0; k < 4; k++) {
                if (!((undecided >> k) & 1)) continue;
                const size_t tk = (size_t)t + (size_t)k;
                facing[tk] = exact_stage_sign(positions + 3 * (size_t)indices[3 * tk],
                                              positions + 3 * (size_t)indices[3 * tk + 1],
                                              positions + 3 * (size_t)indices[3 * tk + 2],
                                              light) > 0;
                exact_used++;
            }
        }
    }
    for (; t < numTriangles; t++) {
        const float *p0 = positions + 3 * (size_t)indices[3 * (size_t)t];
        const float *p1 = positions + 3 * (size_t)indices[3 * (size_t)t + 1];
        const float *p2 = positions + 3 * (size_t)indices[3 * (size_t)t + 2];
        facing[t] = facing_sign(p0, p1, p2, light, &exact_used) > 0;
    }
    facing[numTriangles] = 1;
    return exact_used;
}

int sv_calculate_facing_exact_avx2(const float *positions, const int *indices, int numTriangles,
                                   const Vec4 *light, uint8_t *facing) {
    if (numTriangles < 0) return 0;
    const unsigned saved = sv_mxcsr_enter();
    const int n = facing_exact_avx2_body(positions, indices, numTriangles, light, facing);
    sv_mxcsr_leave(saved);
    return n;
}
