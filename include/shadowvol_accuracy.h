/*
 * shadowvol: speed against accuracy in the facing decision (issue 7).
 *
 * Appendix A decides, per triangle, whether a light is in front of the
 * triangle's plane: facing = plane . light > 0. Every SIMD variant of
 * sv_facing_variants() makes that decision bit for bit like the paper's C
 * (float planes, float dot product). This header adds the other ways of
 * making it, each a named routine with its own contract, and the ground
 * truth they are measured against:
 *
 *   exact     the sign of an exact orientation determinant of the welded
 *             float positions and the light (never wrong)
 *   fma       the reference's float planes, the dot product with FMA
 *   double    planes and dot product in double
 *   fixed16   seed 001's compact planes: 16-bit fixed-point normals and a
 *             precomputed dot product, 10 bytes per triangle instead of 16
 *   eps_bias  the reference's planes and dot product against a threshold
 *             (and optional hysteresis) for frame-to-frame stability
 *
 * THE CONVENTION. For a triangle (p0, p1, p2), counter-clockwise seen from
 * its front, and a light (x, y, z, w) (w = 1 point light, w = 0 directional
 * light with (x, y, z) pointing towards the light, any other w homogeneous):
 *   n      = (p1 - p0) x (p2 - p0)                 (the reference's normal)
 *   det    = n . ((x, y, z) - w p0)                 (exactly, over the reals)
 *   D      = det / |n|                              (signed distance)
 *   facing = det > 0                                (strictly in front)
 * which is what sv_calculate_facing_c_ref computes with a float plane
 * (a, b, c) = n / |n|, d = -(n / |n|) . p0: plane . light = D up to
 * rounding. For w = 1, D is the distance of the light from the triangle's
 * plane in model units, positive in front. (In Shewchuk's notation, det =
 * -orient3d(p0, p1, p2, light): facing is "orient3d < 0".) A light on the
 * plane (det = 0), a zero-area triangle (n = 0) and any NaN or infinite
 * coordinate give facing 0, as the reference's strict "> 0" does for a
 * zero or NaN sum.
 *
 * BOUNDED DIFFERENCE. Each inexact variant V has an a priori error bound
 * B_V(triangle, light) in the units of D (sv::facing_error_bound): whenever
 * |D| > B_V its facing byte equals the exact one. Where the variant's
 * arithmetic could overflow, or the triangle is too thin for its normal to
 * have a direction, B_V is +infinity and nothing is promised beyond "a byte
 * of 0 or 1". The bounds are derived in src/accuracy/error_bounds.cpp.
 *
 * FLOATING-POINT ENVIRONMENT. The routines declared here set MXCSR to
 * round-to-nearest with FTZ and DAZ off for their duration and restore the
 * caller's MXCSR: their results do not depend on the caller's FTZ/DAZ or
 * rounding mode. (sv_calculate_facing_c_ref and its SIMD twins use the
 * caller's MXCSR: under DAZ a subnormal plane or light component reads as
 * zero, which can change their answer. Their bound covers that.)
 *
 * Every routine writes facing[0 .. numTriangles - 1] (each 0 or 1) and
 * facing[numTriangles] = 1 (the byte dangling SilEdges point at), exactly
 * numTriangles + 1 bytes, like sv_calculate_facing_c_ref; a negative count
 * writes nothing. No alignment is needed. The *_avx2 routines need
 * SV_ISA_AVX2 in sv_cpu_isa() (x86-64-v3, which includes FMA).
 *
 * Copyright (C) 2026 the shadowvol authors. LGPL-2.1-or-later.
 */
#ifndef SHADOWVOL_ACCURACY_H
#define SHADOWVOL_ACCURACY_H

#include <stddef.h>
#include <stdint.h>

#include "shadowvol.h"

#ifdef __cplusplus
extern "C" {
#endif

/* ---- exact: the ground truth ---------------------------------------------
 * sign(det) for one triangle: +1 the light is strictly in front (facing),
 * 0 on the plane, the triangle has zero area, or a coordinate of the three
 * points or the light is NaN or infinite; -1 behind. Exact for every finite
 * float input (Shewchuk-style: a double-precision filter with a proven
 * error bound decides almost every case; the rest is evaluated exactly in
 * floating-point expansion arithmetic). */
int sv_facing_exact_sign(const float p0[3], const float p1[3], const float p2[3],
                         const Vec4 *light);

/* facing[t] = sv_facing_exact_sign(triangle t) > 0 for the triangles
 *   positions  xyz floats per vertex (sv::PreparedSurface::positions);
 *   indices    3 * numTriangles vertex numbers, each valid.
 * Returns how many triangles the filter left to the exact stage (0 for a
 * negative count). */
int sv_calculate_facing_exact(const float *positions, const int *indices, int numTriangles,
                              const Vec4 *light, uint8_t *facing);
/* The same decisions with the filter evaluated four triangles at a time
 * (AVX2, FMA unused); the exact stage is the scalar one. */
int sv_calculate_facing_exact_avx2(const float *positions, const int *indices, int numTriangles,
                                   const Vec4 *light, uint8_t *facing);

/* ---- fma: the reference's planes, fused dot product ----------------------
 *   s = fma(d, w, fma(c, z, fma(b, y, a * x)));  facing = s > 0
 * One rounding per step instead of two. The scalar one calls fmaf (exact by
 * definition on every CPU; slow where the CPU has no FMA); the AVX2 one is
 * bit-identical to it. Bound: B_fma (same form as the reference's). */
void sv_calculate_facing_fma(const Plane *planes, int numTriangles, const Vec4 *light,
                             uint8_t *facing);
void sv_calculate_facing_fma_avx2(const Plane *planes, int numTriangles, const Vec4 *light,
                                  uint8_t *facing);

/* ---- double: planes and dot product in double -----------------------------
 * The plane as sv::triangle_plane computes it, before its rounding to
 * float, 32 bytes per triangle:
 *   s = ((a*x + b*y) + c*z) + d*w  in double, light converted exactly;
 *   facing = s > 0.
 * The AVX2 one is bit-identical (same operations, no FMA). */
typedef struct PlaneD {
    double a, b, c, d;
} PlaneD;
void sv_calculate_facing_double(const PlaneD *planes, int numTriangles, const Vec4 *light,
                                uint8_t *facing);
void sv_calculate_facing_double_avx2(const PlaneD *planes, int numTriangles, const Vec4 *light,
                                     uint8_t *facing);

/* ---- fixed16: compact fixed-point normals (seed 001) ----------------------
 * Per triangle a normal q of three int16 components, scaled so that its
 * largest component is +-32767 (a positive scale changes no sign, and this
 * one uses the whole 16 bits), and tn = (q / 32767) . centroid in float:
 * 10 bytes per triangle (16 for a float Plane). Stored in blocks of eight
 * triangles, structure of arrays, so the SIMD routine loads each field with
 * one instruction and the scalar one reads the same memory:
 *   l      = (x, y, z) / 32767            (float, once per call)
 *   s      = ((qx*lx + qy*ly) + qz*lz) - tn*w      (float)
 *   facing = s > 0
 * The last block's unused entries are zero (never read as triangles). The
 * AVX2 routines are bit-identical to the scalar one; _prefetch adds
 * prefetcht0 four blocks ahead (seed 001's fourth method). */
#define SV_PLANE16_BLOCK 8
typedef struct sv_plane16_block {
    float tn[SV_PLANE16_BLOCK];
    int16_t nx[SV_PLANE16_BLOCK], ny[SV_PLANE16_BLOCK], nz[SV_PLANE16_BLOCK];
} sv_plane16_block;
void sv_calculate_facing_fixed16(const sv_plane16_block *blocks, int numTriangles,
                                 const Vec4 *light, uint8_t *facing);
void sv_calculate_facing_fixed16_avx2(const sv_plane16_block *blocks, int numTriangles,
                                      const Vec4 *light, uint8_t *facing);
void sv_calculate_facing_fixed16_avx2_prefetch(const sv_plane16_block *blocks, int numTriangles,
                                               const Vec4 *light, uint8_t *facing);

/* ---- eps_bias: a threshold, optionally with hysteresis --------------------
 * The reference's planes and dot product s (the same operations), compared
 * with a threshold instead of 0:
 *   previous == NULL:  facing = s > threshold
 *   previous != NULL:  facing = s > (previous[t] ? -threshold : threshold)
 * With a threshold of a few error bounds, a triangle whose plane passes
 * near the light is classified as casting (not facing) whatever the
 * rounding; with previous (last frame's facing bytes, 0 or 1; it may be
 * facing itself, updated in place) a triangle changes side only when the
 * light moves through a band of 2 * threshold around its plane, so noise
 * and small light movements do not make it flicker. threshold >= 0
 * (sv_eps_bias_threshold). */
void sv_calculate_facing_eps_bias(const Plane *planes, int numTriangles, const Vec4 *light,
                                  float threshold, const uint8_t *previous, uint8_t *facing);
/* The threshold for one light, in the units of plane . light:
 *   distance * |w| + angle * |(x, y, z) - w * center|
 * distance (model units): the half-width of the band around each plane for
 * a point light; angle (radians): the band's angular half-width as seen
 * from the surface's center, the only part left for a directional light.
 * Rounded up to float. center: the surface's center (sv::surface_bounds).
 * NaN for a non-finite light or a negative or NaN bias (the routine then
 * gives 0 for every triangle). */
float sv_eps_bias_threshold(float distance, float angle, const float center[3], const Vec4 *light);

#ifdef __cplusplus
}
#endif

#ifdef __cplusplus

#include <string>
#include <vector>

#include "shadowvol_mesh.h"

namespace sv {

/* ---- Per-surface data of the variants ------------------------------------
 * Built once per surface (again when its positions change). A triangle
 * whose positions are not all finite gets the zero plane (never facing),
 * as does a zero-area one. */
PlaneD triangle_plane_double(const float p0[3], const float p1[3], const float p2[3]);
AlignedVector<PlaneD> double_planes(const PreparedSurface &s);

/* q and tn of one triangle (fixed16, above). */
void triangle_plane16(const float p0[3], const float p1[3], const float p2[3], int16_t q[3],
                      float *tn);
/* (numTriangles + 7) / 8 blocks. */
AlignedVector<sv_plane16_block> fixed16_planes(const PreparedSurface &s);

/* ---- Error bounds ----------------------------------------------------------
 * The families of inexact arithmetic, one bound each. */
enum class FacingArithmetic {
    float_planes,     /* sv_calculate_facing_c_ref and its SIMD twins, eps_bias's s */
    float_planes_fma, /* sv_calculate_facing_fma* */
    double_planes,    /* sv_calculate_facing_double* */
    fixed16           /* sv_calculate_facing_fixed16* */
};
const char *facing_arithmetic_name(FacingArithmetic a);

/* What the bounds need of a triangle, independent of the light. */
struct TriangleErrorModel {
    double p0[3] = {0, 0, 0};      /* where the float and double planes are anchored */
    double c[3] = {0, 0, 0};       /* centroid as fixed16's preparation computes it */
    double abs_sum[3] = {0, 0, 0}; /* |p0_i| + |p1_i| + |p2_i| */
    double alpha = 0;              /* |n_double - n_exact/|n_exact||, or +inf */
    Plane plane{};                 /* sv::triangle_plane */
    PlaneD plane_d{};              /* triangle_plane_double */
    int16_t q[3] = {0, 0, 0};      /* triangle_plane16 */
    float tn = 0;
    bool finite = true; /* every coordinate finite */
};
TriangleErrorModel triangle_error_model(const float p0[3], const float p1[3], const float p2[3]);

/* B_V in units of D: facing_V == exact facing whenever |D| > B_V (+inf:
 * no promise). caller_ftz_daz: float_planes only, the reference runs in the
 * caller's MXCSR: true covers FTZ/DAZ set there. eps_bias with threshold
 * t (previous byte p) equals (D > (p ? -t : t)) wherever |D -+ t| exceeds
 * the float_planes bound. Typical sizes for well-shaped triangles:
 * float_planes and fma about 3e-7 (|L| + |d w|), the light's and the
 * plane's distances from the origin; double_planes about 1e-15 of the
 * same; fixed16 about 3e-5 |L - w c|, the light's distance from the
 * triangle. Slivers raise every bound by their aspect ratio (alpha). The
 * model is
 * built under the default MXCSR, as the planes it describes are assumed
 * to have been. */
double facing_error_bound(FacingArithmetic a, const TriangleErrorModel &m, const Vec4 &light,
                          bool caller_ftz_daz = false);

/* D for the triangle and light, with a relative error below 2^-44: 0 when
 * det = 0 (so for every zero-area triangle), NaN for non-finite input.
 * Exact arithmetic where the double filter is not precise enough; for
 * tests and reports. */
double exact_signed_distance(const float p0[3], const float p1[3], const float p2[3],
                             const Vec4 &light);

} // namespace sv

#endif /* __cplusplus */

#endif /* SHADOWVOL_ACCURACY_H */
