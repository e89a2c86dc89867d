/*
 * shadowvol: CPU shadow-volume construction after J.M.P. van Waveren,
 * "Shadow Volume Construction", Id Software, 2005.
 *
 * Public C API (usable from C and C++). Every routine exists in several
 * variants (the paper's C, the branch-free C the text derives, the faithful
 * SSE2 port of the listing, ...) that compute exactly the same result on
 * in-contract input. The contracts are written next to each signature; the
 * sv_check_* functions test them, and the *_checked entry points refuse
 * out-of-contract input with a negative SV_E_* code instead of running.
 *
 * Copyright (C) 2026 the shadowvol authors. LGPL-2.1-or-later.
 */
#ifndef SHADOWVOL_H
#define SHADOWVOL_H

#include <stddef.h>
#include <stdint.h>

#ifdef __cplusplus
extern "C" {
#endif

/* ---- The paper's types (section 3, appendices A and B) ----------------- */

/* A potential silhouette edge. Convention (paper, section 3): the edge
 * v1 -> v2 winds counter-clockwise in triangle p1 and clockwise in p2.
 * v1 and v2 are vertex numbers MULTIPLIED BY TWO: they address the even
 * (x,y,z,1) vertices of the double-length shadow vertex buffer; v + 1 is the
 * extruded (x,y,z,0) copy. An edge used by one triangle only ("dangling")
 * has p2 = numTriangles, whose facing byte is always 1. */
typedef struct SilEdge {
    int p1, p2; /* triangles (planes) sharing the edge */
    int v1, v2; /* doubled vertex numbers: even, in [0, 2^31 - 2] */
} SilEdge;

typedef struct Plane {
    float a, b, c, d; /* a*x + b*y + c*z + d = 0 */
} Plane;

typedef struct Vec4 {
    float x, y, z, w; /* w = 1: point light origin; w = 0: direction */
} Vec4;

/* Axis-aligned bounds of a surface, as appendix B takes them: the box
 * center +- extents (w of both ignored). extents are half sizes, >= 0. */
typedef struct Bounds {
    Vec4 center;
    Vec4 extents;
} Bounds;

/* Appendix B: the number of light-volume bounding planes, one cull bit each. */
#define SV_NUM_LIGHT_PLANES 6

/* ---- Appendices A and B: facing and cull bits (the paper's C) ----------
 * Reference C, compiled with -ffp-contract=off and evaluated in exactly the
 * paper's operation order, left to right in float:
 *   ((a*x + b*y) + c*z) + d*w
 * so they are the bit-exact oracle of any SIMD variant. */

/* CalculateFacing (appendix A):
 *   facing[i] = planes[i].a * light.x + planes[i].b * light.y +
 *               planes[i].c * light.z + planes[i].d * light.w > 0.0f
 * for i in [0, numTriangles), then facing[numTriangles] = 1 (the byte that
 * dangling SilEdges point at). So facing needs numTriangles + 1 bytes.
 *   light   (x,y,z,1): a point (or spot) light's origin; (x,y,z,0): a
 *           directional light, (x,y,z) pointing TOWARDS the light. The test
 *           is strict: a light exactly on a triangle's plane (sum == 0, also
 *           -0.0) makes the triangle NOT facing (0), so it casts; a NaN sum
 *           gives 0 as well.
 *   numTriangles >= 0. A negative count writes nothing (the paper would
 *           write facing[numTriangles], out of bounds).
 * Every facing byte written is exactly 0 or 1. */
void sv_calculate_facing_c_ref(const Plane *planes, int numTriangles, const Vec4 *light,
                               uint8_t *facing);

/* CalculateCullBits (appendix B): bit i of cullBits[j] is set when vertex j
 * is strictly behind light plane i (a*x + b*y + c*z + d < 0.0f, the paper's
 * CULL_EPSILON = 0): light planes point INTO the light volume, and a vertex
 * with any bit set is outside it. Bits 6 and 7 are always 0.
 *   positions     numVerts vertices as Vec4; only x, y, z are read (the
 *                 paper's Vertex is {Vec4 position; Vec4 normal;}, 32 bytes;
 *                 this port takes a plain 16-byte Vec4 array of positions).
 *   surfaceBounds a box containing every vertex (center +- extents).
 *   lightPlanes   SV_NUM_LIGHT_PLANES (6) planes; plane i <-> bit i.
 * First the surface box is tested against each plane: where
 *   (a*cx + b*cy + c*cz + d) - (|a*ex| + |b*ey| + |c*ez|) >= 0.0f
 * the whole box is in front of plane i and bit i stays 0 for every vertex
 * (that plane is not evaluated per vertex).
 * Returns 1 when the box is in front of all six planes: the surface is
 * completely inside the light volume, and cullBits is NOT WRITTEN (not even
 * cleared). The caller must then pass cullBits = NULL to
 * sv_create_shadow_volume (no culling needed). Returns 0 otherwise, after
 * writing all numVerts bytes of cullBits.
 *   numVerts >= 0 (a negative count writes nothing and returns 0). */
int sv_calculate_cull_bits_c_ref(const Vec4 *positions, int numVerts, const Bounds *surfaceBounds,
                                 const Plane lightPlanes[SV_NUM_LIGHT_PLANES], uint8_t *cullBits);

/* ---- Appendices A and B in SIMD, and their table -------------------------
 * Each is BIT-IDENTICAL to the reference above (same operations in the same
 * order, no FMA; see src/core/x86/facing_simd.c), with the same contract. */
typedef void (*sv_calculate_facing_fn)(const Plane *planes, int numTriangles, const Vec4 *light,
                                       uint8_t *facing);
typedef int (*sv_calculate_cull_bits_fn)(const Vec4 *positions, int numVerts,
                                         const Bounds *surfaceBounds,
                                         const Plane lightPlanes[SV_NUM_LIGHT_PLANES],
                                         uint8_t *cullBits);

void sv_calculate_facing_sse2(const Plane *planes, int numTriangles, const Vec4 *light,
                              uint8_t *facing);
void sv_calculate_facing_avx2(const Plane *planes, int numTriangles, const Vec4 *light,
                              uint8_t *facing);
void sv_calculate_facing_avx512(const Plane *planes, int numTriangles, const Vec4 *light,
                                uint8_t *facing);
/* CalculateFacing fused with CountFacing (issue 15): writes exactly what
 * the routine of the same variant writes and returns the number of facing
 * triangles (what CountFacing would return on the result), counted from
 * the compare masks while they are still in registers: no second pass
 * over the facing bytes. A negative count writes nothing and returns 0. */
typedef int (*sv_calculate_facing_count_fn)(const Plane *planes, int numTriangles,
                                            const Vec4 *light, uint8_t *facing);
int sv_calculate_facing_count_c(const Plane *planes, int numTriangles, const Vec4 *light,
                                uint8_t *facing);
int sv_calculate_facing_count_sse2(const Plane *planes, int numTriangles, const Vec4 *light,
                                   uint8_t *facing);
int sv_calculate_facing_count_avx2(const Plane *planes, int numTriangles, const Vec4 *light,
                                   uint8_t *facing);
int sv_calculate_facing_count_avx512(const Plane *planes, int numTriangles, const Vec4 *light,
                                     uint8_t *facing);
int sv_calculate_cull_bits_sse2(const Vec4 *positions, int numVerts, const Bounds *surfaceBounds,
                                const Plane lightPlanes[SV_NUM_LIGHT_PLANES], uint8_t *cullBits);
int sv_calculate_cull_bits_avx2(const Vec4 *positions, int numVerts, const Bounds *surfaceBounds,
                                const Plane lightPlanes[SV_NUM_LIGHT_PLANES], uint8_t *cullBits);
int sv_calculate_cull_bits_avx512(const Vec4 *positions, int numVerts, const Bounds *surfaceBounds,
                                  const Plane lightPlanes[SV_NUM_LIGHT_PLANES], uint8_t *cullBits);

/* The implementations of appendices A and B, by name, from the reference to
 * the fastest (c_ref, sse2, avx2, avx512). Not every SIMD level is needed:
 * check isa against sv_cpu_isa() before calling. */
typedef struct sv_facing_variant {
    const char *name;
    unsigned isa; /* SV_ISA_* bits the CPU must have */
    sv_calculate_facing_fn calculate_facing;
    sv_calculate_cull_bits_fn calculate_cull_bits;
    sv_calculate_facing_count_fn calculate_facing_count; /* the fused A + C */
} sv_facing_variant;

const sv_facing_variant *sv_facing_variants(int *count);
const sv_facing_variant *sv_facing_variant_by_name(const char *name);
/* The last entry sv_cpu_isa() allows (never NULL). */
const sv_facing_variant *sv_best_facing_variant(void);

/* ---- Routine signatures ------------------------------------------------- */

/* CountFacing (section 4, appendix C): number of facing bytes that are set.
 *   facing       numTriangles bytes, each exactly 0 or 1.
 *                sse2_paper: 16-byte aligned (movdqa / paddusb m128).
 *   numTriangles >= 0 (a negative count returns 0 and reads nothing).
 *   Reads facing[0 .. numTriangles-1] only; writes nothing. */
typedef int (*sv_count_facing_fn)(const uint8_t *facing, int numTriangles);

/* CountFacingCull (section 5, appendix D): for every triangle whose three
 * vertices share a set cull bit (outside one light-volume plane), set its
 * facing byte to 1; return the number of facing bytes set afterwards.
 *   facing       numTriangles bytes, each 0 or 1; modified in place.
 *   indices      3 * numTriangles vertex numbers (not doubled), each a valid
 *                index into cullBits. No alignment needed.
 *   cullBits     one byte per vertex.
 *                sse2_paper limit (faithful, see docs/ERRATA.md): in its
 *                four-triangle loop the AND of the cull bytes is compared
 *                SIGNED with pcmpgtb, so a triangle whose only shared cull
 *                bit is bit 7 is not culled there. Use bits 0..6 only
 *                (six light planes use bits 0..5); the checked entry
 *                points refuse bit 7 for it (SV_E_CULL_BITS).
 *   numTriangles >= 0 (negative returns 0, touches nothing). */
typedef int (*sv_count_facing_cull_fn)(uint8_t *facing, int numTriangles, const int *indices,
                                       const uint8_t *cullBits);

/* CreateSilTriangles (section 6, appendix E): two triangles (6 indices) per
 * edge whose two facing bytes differ; returns the number of indices written
 * (a multiple of 6).
 *   shadowIndices  room for 6 * numSilEdges ints. Branch-free variants
 *                  write 6 indices for EVERY edge, at the current output
 *                  position, advancing only for silhouette edges: so they
 *                  may write up to 6 ints past the returned count, never
 *                  past 6 * numSilEdges.
 *                  sse2_paper: 8-byte aligned (the listing keeps the output
 *                  pointer divided by 8 and addresses [reg*8]).
 *   facing         indexed by p1 and p2: each byte 0 or 1, so it needs
 *                  numTriangles + 1 bytes with facing[numTriangles] = 1
 *                  (the checked entry points refuse any other last byte:
 *                  SV_E_FACING_SENTINEL).
 *   silEdges       numSilEdges edges, 0 <= p1, p2 <= numTriangles, v1 and
 *                  v2 even (the xor-by-one trick relies on it).
 *   numSilEdges    >= 0 (negative returns 0 and writes nothing). */
typedef int (*sv_create_sil_triangles_fn)(int *shadowIndices, const uint8_t *facing,
                                          const SilEdge *silEdges, int numSilEdges);

/* CreateCapTriangles (section 7, appendix F): for every triangle whose
 * facing byte is 0, a near cap triangle (i2, i1, i0) and a far cap triangle
 * (i0+1, i1+1, i2+1) with doubled vertex numbers; returns the number of
 * indices written (a multiple of 6).
 *   shadowIndices  room for 2 * numIndices ints (6 per triangle). Branch-
 *                  free variants write 6 ints for every triangle, so up to 6
 *                  past the returned count, never past 2 * numIndices.
 *                  sse2_paper: 8-byte aligned.
 *   facing         numIndices / 3 bytes, each 0 or 1.
 *   indices        numIndices vertex numbers in [0, 2^30) (they are doubled).
 *                  sse2_paper: 16-byte aligned (movdqa).
 *   numIndices     a multiple of 3, >= 0. */
typedef int (*sv_create_cap_triangles_fn)(int *shadowIndices, const uint8_t *facing,
                                          const int *indices, int numIndices);

/* ---- Variants ----------------------------------------------------------- */

enum {
    SV_ISA_NONE = 0,               /* portable C */
    SV_ISA_SSE2 = 1u << 0,         /* baseline of every x86-64 CPU */
    SV_ISA_AVX2 = 1u << 1,         /* x86-64-v3: AVX, AVX2, BMI1, BMI2, FMA, POPCNT,
                                 and the OS saves the YMM state */
    SV_ISA_AVX512 = 1u << 2,       /* x86-64-v4: AVX-512 F, BW, VL, DQ, CD, and the
                                 OS saves the opmask and ZMM state */
    SV_ISA_AVX512_VBMI2 = 1u << 3, /* vpcompressb/w, vpexpandb/w (Ice Lake, Zen 4) */
    SV_ISA_AVX512_VBMI = 1u << 4   /* vpermb, vpermi2b/vpermt2b (Cannon Lake, Ice
                                      Lake, Zen 4) */
};

/* One named set of the four kernels. c_ref: the paper's C; c_branchless:
 * the branch-free C of sections 4-7; sse2_paper: the faithful NASM ports of
 * appendices C-F. */
typedef struct sv_variant {
    const char *name;
    unsigned isa; /* SV_ISA_* bits the CPU must have */
    sv_count_facing_fn count_facing;
    sv_count_facing_cull_fn count_facing_cull;
    sv_create_sil_triangles_fn create_sil_triangles;
    sv_create_cap_triangles_fn create_cap_triangles;
    /* Alignment the variant needs, in bytes (1 = none). */
    unsigned align_facing;         /* CountFacing's facing array */
    unsigned align_indices;        /* CreateCapTriangles' indices */
    unsigned align_shadow_indices; /* output of Sil/Cap triangles */
} sv_variant;

/* All variants compiled in, the reference first. *count receives their
 * number. Variants whose ISA the CPU lacks are included: check isa against
 * sv_cpu_isa() before calling them. */
const sv_variant *sv_variants(int *count);
/* The variant called NAME, or NULL. */
const sv_variant *sv_variant_by_name(const char *name);
/* Runtime dispatch: the fastest variant sv_cpu_isa() allows (the table is
 * ordered from the reference to the fastest; this is the last entry whose
 * isa the CPU has). Never NULL: c_ref runs everywhere. */
const sv_variant *sv_best_variant(void);
/* SV_ISA_* bits this CPU and OS run, capped by the ISA limit (below).
 * Tests, benchmark and dispatch use this one. */
unsigned sv_cpu_isa(void);
/* The same bits without the limit. */
unsigned sv_cpu_isa_detected(void);
/* The ISA limit: "c" (C variants only), "sse2", "avx2" or "avx512" caps
 * sv_cpu_isa() at that level; NULL removes the cap. Returns 0, or -1 for
 * an unknown level (nothing changes). The environment variable SV_ISA sets
 * the initial limit (an unknown value there means "c", and
 * sv_isa_limit_name() reports it). Not thread-safe against concurrent
 * dispatch: set it before starting threads. */
int sv_set_isa_limit(const char *level);
/* The limit's level name, or NULL when there is none. */
const char *sv_isa_limit_name(void);
/* The highest level sv_cpu_isa() reaches: "c", "sse2", "avx2", "avx512". */
const char *sv_isa_level_name(void);
/* ISA bits as space-separated names ("sse2 avx2 ...") in BUF; returns BUF. */
const char *sv_isa_names(unsigned isa, char *buf, size_t size);

/* ---- CreateShadowVolume (section 3) --------------------------------------
 * Builds the index list of the shadow volume: silhouette quads first, then
 * near and far caps, with the kernels of VARIANT. If cullBits is not NULL,
 * triangles outside the light volume are first made facing (so facing is
 * modified). Returns the number of indices, 0 when no triangle casts.
 *   shadowIndices  room for sv_shadow_volume_capacity(numIndices,
 *                  numSilEdges) ints; aligned as the variant needs.
 *   indices        numIndices (multiple of 3) vertex numbers, aligned as
 *                  the variant needs; facing: numIndices / 3 + 1 bytes of
 *                  0 or 1, the last one 1, aligned as the variant needs. */
int sv_create_shadow_volume(const sv_variant *variant, int *shadowIndices, const int *indices,
                            int numIndices, const SilEdge *silEdges, int numSilEdges,
                            uint8_t *facing, const uint8_t *cullBits);

/* Ints of output a shadow volume may need: 6 per SilEdge + 6 per triangle.
 * Returns 0 for negative counts, SIZE_MAX on overflow. */
size_t sv_shadow_volume_capacity(int numIndices, int numSilEdges);

/* ---- The variants by name (for users who link one directly) ------------- */

int sv_count_facing_c_ref(const uint8_t *facing, int numTriangles);
int sv_count_facing_c_branchless(const uint8_t *facing, int numTriangles);
int sv_count_facing_sse2_paper(const uint8_t *facing, int numTriangles);

int sv_count_facing_cull_c_ref(uint8_t *facing, int numTriangles, const int *indices,
                               const uint8_t *cullBits);
int sv_count_facing_cull_c_branchless(uint8_t *facing, int numTriangles, const int *indices,
                                      const uint8_t *cullBits);
int sv_count_facing_cull_sse2_paper(uint8_t *facing, int numTriangles, const int *indices,
                                    const uint8_t *cullBits);

int sv_create_sil_triangles_c_ref(int *shadowIndices, const uint8_t *facing,
                                  const SilEdge *silEdges, int numSilEdges);
int sv_create_sil_triangles_c_branchless(int *shadowIndices, const uint8_t *facing,
                                         const SilEdge *silEdges, int numSilEdges);
int sv_create_sil_triangles_sse2_paper(int *shadowIndices, const uint8_t *facing,
                                       const SilEdge *silEdges, int numSilEdges);

int sv_create_cap_triangles_c_ref(int *shadowIndices, const uint8_t *facing, const int *indices,
                                  int numIndices);
int sv_create_cap_triangles_c_branchless(int *shadowIndices, const uint8_t *facing,
                                         const int *indices, int numIndices);
int sv_create_cap_triangles_sse2_paper(int *shadowIndices, const uint8_t *facing,
                                       const int *indices, int numIndices);

/* AVX2 variant (x86-64-v3, asm/..._avx2.asm): no alignment needed; all 8 cull bits. */
int sv_count_facing_avx2(const uint8_t *facing, int numTriangles);
int sv_count_facing_cull_avx2(uint8_t *facing, int numTriangles, const int *indices,
                              const uint8_t *cullBits);
int sv_create_sil_triangles_avx2(int *shadowIndices, const uint8_t *facing, const SilEdge *silEdges,
                                 int numSilEdges);
int sv_create_cap_triangles_avx2(int *shadowIndices, const uint8_t *facing, const int *indices,
                                 int numIndices);

/* AVX-512 variant (asm/..._avx512.asm; x86-64-v4, no alignment needs). */
int sv_count_facing_avx512(const uint8_t *facing, int numTriangles);
int sv_count_facing_cull_avx512(uint8_t *facing, int numTriangles, const int *indices,
                                const uint8_t *cullBits);
int sv_create_sil_triangles_avx512(int *shadowIndices, const uint8_t *facing,
                                   const SilEdge *silEdges, int numSilEdges);
int sv_create_cap_triangles_avx512(int *shadowIndices, const uint8_t *facing, const int *indices,
                                   int numIndices);
/* AVX-512 with VBMI (asm/count_facing_cull_avx512vbmi.asm): the cull bytes
 * of meshes of up to 1024 vertices in registers; more go to
 * sv_count_facing_cull_avx512. The avx512vbmi variant is the AVX-512 one
 * with this CountFacingCull. */
int sv_count_facing_cull_avx512vbmi(uint8_t *facing, int numTriangles, const int *indices,
                                    const uint8_t *cullBits);

/* ---- The general rule (issue 27, docs/CASTERS.md) -------------------------
 * The paper's volume is the exact shadow of closed shells only. The general
 * rule is exact for any triangle set: every triangle t casts its own prism
 * V_t, so the stencil counts the triangles between a point and the light.
 * With sigma_t = +1 for a triangle that faces away from the light, -1 for
 * one that faces it (its reverse casts), 0 for one that casts nothing, an
 * edge's quad Q(v1 -> v2) (the paper's quad for a dark triangle running
 * v1 -> v2) is drawn m times, m = the sum over the edge's triangles of
 * sigma_t * (+1 when t runs v1 -> v2, -1 when it runs v2 -> v1): |m|
 * copies in the direction of sign(m). Every triangle that casts gives
 * caps: a dark one the paper's, a lit one reversed.
 *
 * The facing bytes of the general rule, one per triangle of the surface
 * (not doubled), from sv_calculate_facing's 0/1 (see
 * sv_general_facing_from_calculated):
 *   SV_GENERAL_DARK 0  faces away from the light: casts V_t (sigma +1);
 *   SV_GENERAL_NONE 1  casts nothing (sigma 0): culled, or facing the
 *                      light in a shell under the paper's rule;
 *   SV_GENERAL_LIT  2  faces the light in a shell under the general
 *                      rule: its reverse casts (sigma -1).
 * The paper's routines read bytes 0 and 1 exactly as they always have, so
 * the shells under the paper's rule take the same bytes. */
enum { SV_GENERAL_DARK = 0, SV_GENERAL_NONE = 1, SV_GENERAL_LIT = 2 };

/* An edge of three or more triangles, or of two that run it the same way:
 * its uses are sharedUses[firstUse .. firstUse + numUses - 1], each
 * 2 * t + d: triangle t, d = 0 when t runs v1 -> v2, 1 when v2 -> v1. */
typedef struct sv_shared_edge {
    int v1, v2; /* doubled vertex numbers, as in SilEdge */
    int firstUse, numUses;
} sv_shared_edge;

/* The general edge table of a surface (sv::general_edge_table builds it
 * once per surface topology), every welded edge once, in four classes:
 *   paper   edges of the shells under the paper's rule: the paper's
 *           SilEdges, drawn by CreateSilTriangles (p2 may be the
 *           sentinel numTriangles);
 *   pairs   two triangles running the edge in opposite directions, p1
 *           v1 -> v2 and p2 v2 -> v1 (a SilEdge): m = sigma_p1 - sigma_p2
 *           in -2 .. 2;
 *   opens   one triangle p1 running v1 -> v2 (p2 == p1): m = sigma_p1;
 *   shared  every other edge (sv_shared_edge).
 * A closed 2-manifold surface under the paper's rule is all `paper`: its
 * SilEdges, its index list. */
typedef struct sv_general_edges {
    const SilEdge *paper;
    int numPaper;
    const SilEdge *pairs;
    int numPairs;
    const SilEdge *opens;
    int numOpens;
    const sv_shared_edge *shared;
    int numShared;
    const int *sharedUses;
    int numSharedUses;
} sv_general_edges;

/* Ints of output the silhouette part may need: 6 per edge of the paper's
 * class, and 6 * k for an edge of k triangles (|m| <= k): 12 per pair, 6
 * per open edge, 6 per shared use. SIZE_MAX for negative counts. */
size_t sv_general_sil_capacity(const sv_general_edges *edges);

/* The silhouette quads of the general rule; returns the number of indices
 * written (a multiple of 6). For each class, in the order paper, pairs,
 * opens, shared (the order of the quads is not part of the contract; the
 * multiset is):
 *   paper   the paper's quad when the facing bytes differ (section 6);
 *   pairs   with f = (byte != 0) and g = (byte != 2) (the triangle's and
 *           its reverse's paper facing): the paper's quad of (p1, p2,
 *           v1, v2) when f differs, and that of the reverses (v2, v1 run
 *           by p1's reverse) when g differs: exactly the quads the
 *           two-sided caster draws for the edge;
 *   opens   the paper's quad of p1 against its own reverse, unless p1
 *           casts nothing;
 *   shared  |m| copies of Q(v1 -> v2) (m > 0) or of its reverse (m < 0).
 *   shadowIndices  room for sv_general_sil_capacity(edges) ints; branch-
 *                  free variants may write up to that bound past the count.
 *   facing         the general bytes (0, 1, 2) of the numTriangles
 *                  triangles, then facing[numTriangles] = 1 when the
 *                  paper's class has dangling edges. Triangles named by the
 *                  paper's class have bytes 0 or 1. */
typedef int (*sv_create_general_sil_triangles_fn)(int *shadowIndices, const uint8_t *facing,
                                                  const sv_general_edges *edges);
/* The caps of the general rule: for byte 0 the paper's near cap (i2, i1,
 * i0) and far cap (i0+1, i1+1, i2+1); for byte 2 the caps of the reverse:
 * (i0, i1, i2) and (i2+1, i1+1, i0+1); for byte 1 nothing. Returns the
 * number of indices (6 per casting triangle).
 *   shadowIndices  room for 2 * numIndices ints (branch-free variants may
 *                  write 6 past the count, never past 2 * numIndices).
 *   indices        numIndices (a multiple of 3) vertex numbers < 2^30. */
typedef int (*sv_create_general_cap_triangles_fn)(int *shadowIndices, const uint8_t *facing,
                                                  const int *indices, int numIndices);

int sv_create_general_sil_triangles_c_ref(int *shadowIndices, const uint8_t *facing,
                                          const sv_general_edges *edges);
int sv_create_general_cap_triangles_c_ref(int *shadowIndices, const uint8_t *facing,
                                          const int *indices, int numIndices);
/* AVX2 and AVX-512 (src/core/x86/general_simd.c): the reference's list, in
 * its order (they may write up to the bound past the count, as branch-free
 * variants do). The paper's class goes to the paper's kernel of the same
 * ISA. Like the reference they read no facing byte outside the array
 * (AVX-512 gathers each pair's byte as the last of the 4 bytes ending at
 * it). */
int sv_create_general_sil_triangles_avx2(int *shadowIndices, const uint8_t *facing,
                                         const sv_general_edges *edges);
int sv_create_general_cap_triangles_avx2(int *shadowIndices, const uint8_t *facing,
                                         const int *indices, int numIndices);
int sv_create_general_sil_triangles_avx512(int *shadowIndices, const uint8_t *facing,
                                           const sv_general_edges *edges);
int sv_create_general_cap_triangles_avx512(int *shadowIndices, const uint8_t *facing,
                                           const int *indices, int numIndices);

/* The general bytes from sv_calculate_facing's: byte t becomes 0 where
 * calculated[t] is 0, else litByte[t] (SV_GENERAL_LIT for a triangle of a
 * general shell, SV_GENERAL_NONE for one under the paper's rule; NULL:
 * SV_GENERAL_LIT for all). Returns the triangles that cast (bytes != 1). */
int sv_general_facing_from_calculated(uint8_t *facing, const uint8_t *calculated,
                                      const uint8_t *litByte, int numTriangles);
/* CountFacingCull for the general rule: a triangle whose three vertices
 * share a set cull bit casts nothing, lit or dark (byte 1). Returns the
 * triangles that cast afterwards (bytes != 1). */
int sv_general_cull_c_ref(uint8_t *facing, int numTriangles, const int *indices,
                          const uint8_t *cullBits);

/* The implementations of the general rule, from the reference to the
 * fastest (as sv_variants). */
typedef struct sv_general_variant {
    const char *name;
    unsigned isa; /* SV_ISA_* bits the CPU must have */
    sv_create_general_sil_triangles_fn create_general_sil_triangles;
    sv_create_general_cap_triangles_fn create_general_cap_triangles;
} sv_general_variant;

const sv_general_variant *sv_general_variants(int *count);
const sv_general_variant *sv_general_variant_by_name(const char *name);
/* The last entry whose isa is within ISA (c_ref at least): the general
 * kernels that go with a variant of the paper's, sv_general_variant_for_isa
 * (variant->isa). */
const sv_general_variant *sv_general_variant_for_isa(unsigned isa);
/* The last entry sv_cpu_isa() allows. */
const sv_general_variant *sv_best_general_variant(void);

/* ---- Contracts -----------------------------------------------------------
 * Each sv_check_* returns SV_OK or the first violated contract (SV_E_*), for
 * the named variant (its alignment needs) and the given buffers. The
 * *_checked entry points run the check, then the kernel; they return the
 * kernel's result or the negative SV_E_* code, and never write outside
 * [shadowIndices, shadowIndices + capacity). */
enum sv_status {
    SV_OK = 0,
    SV_E_NULL = -1,            /* a required pointer is NULL */
    SV_E_COUNT = -2,           /* negative count, or numIndices % 3 != 0 */
    SV_E_ALIGNMENT = -3,       /* an array is less aligned than the variant needs */
    SV_E_FACING_NOT_BOOL = -4, /* a facing byte other than 0 or 1 */
    SV_E_INDEX_RANGE = -5,     /* a triangle/vertex number outside its array */
    SV_E_ODD_VERTEX = -6,      /* a SilEdge vertex number is odd */
    SV_E_CAPACITY = -7,        /* output room below the documented bound */
    SV_E_OVERFLOW =
        -8, /* an index count (input 3 * numTriangles, or the output) does not fit in an int */
    SV_E_CPU = -9,              /* the CPU lacks the variant's instruction set */
    SV_E_FACING_SENTINEL = -10, /* facing[numTriangles] is 0 (it must be 1) */
    SV_E_CULL_BITS = -11,       /* sse2_paper: a cull byte with bit 7 set (its
                                  documented limit is bits 0..6, erratum D-5) */
    SV_E_GENERAL_FACING = -12   /* a general facing byte above 2, or 2 on a
                                   triangle of the paper's class */
};
const char *sv_status_string(int status);

int sv_count_facing_checked(const sv_variant *v, const uint8_t *facing, int numTriangles);
int sv_count_facing_cull_checked(const sv_variant *v, uint8_t *facing, int numTriangles,
                                 const int *indices, const uint8_t *cullBits, int numVerts);
int sv_create_sil_triangles_checked(const sv_variant *v, int *shadowIndices, size_t capacity,
                                    const uint8_t *facing, int numTriangles,
                                    const SilEdge *silEdges, int numSilEdges);
int sv_create_cap_triangles_checked(const sv_variant *v, int *shadowIndices, size_t capacity,
                                    const uint8_t *facing, const int *indices, int numIndices,
                                    int numVerts);
/* numVerts: vertices of the mesh (indices < numVerts, SilEdge v < 2 *
 * numVerts); facing: numIndices / 3 + 1 bytes, the last exactly 1
 * (SV_E_FACING_SENTINEL otherwise; sv_create_sil_triangles_checked checks
 * facing[numTriangles] the same way); cullBits, when not NULL: numVerts
 * bytes (for sse2_paper each without bit 7, SV_E_CULL_BITS, as for
 * sv_count_facing_cull_checked). */
int sv_create_shadow_volume_checked(const sv_variant *v, int *shadowIndices, size_t capacity,
                                    const int *indices, int numIndices, int numVerts,
                                    const SilEdge *silEdges, int numSilEdges, uint8_t *facing,
                                    const uint8_t *cullBits);

/* The general rule's entry points, checked: numVerts vertices (every v1,
 * v2 below 2 * numVerts, even), the table's triangles below numTriangles
 * (the paper's class may name numTriangles, with facing[numTriangles] =
 * 1), every shared use inside sharedUses, capacity at least
 * sv_general_sil_capacity (SV_E_CAPACITY) and that bound an int
 * (SV_E_OVERFLOW); facing bytes 0, 1 or 2, and 0 or 1 on the paper's
 * class (SV_E_GENERAL_FACING). */
int sv_create_general_sil_triangles_checked(const sv_general_variant *v, int *shadowIndices,
                                            size_t capacity, const uint8_t *facing,
                                            int numTriangles, int numVerts,
                                            const sv_general_edges *edges);
int sv_create_general_cap_triangles_checked(const sv_general_variant *v, int *shadowIndices,
                                            size_t capacity, const uint8_t *facing,
                                            const int *indices, int numIndices, int numVerts);

#ifdef __cplusplus
}
#endif

#endif /* SHADOWVOL_H */
