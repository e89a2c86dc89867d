/*
 * shadowvol: per-frame triangle planes for deforming (skinned) surfaces, and
 * facing straight from positions (id's 2012 BFG engine), in C and SIMD.
 *
 * The paper (section 3): a static surface stores its triangle planes; a
 * deforming one gets new positions every frame, so its planes are derived
 * once per frame and then shared by every light (sv_calculate_facing per
 * light). The other way, BFG's: no stored planes, and every light's facing
 * computed from the positions again (one cross product per triangle and
 * light). Both are here, with their C references and SIMD variants; the
 * benchmark (`shadowvol bench --planes`, docs/PLANES.md) times both.
 *
 * How this differs from sv::triangle_plane (shadowvol_mesh.h): that one is
 * the mesh-preparation path, computed in DOUBLE and rounded once, with a
 * rescue for cross products that under- or overflow; it is exact enough to
 * keep slivers. This is the per-frame FLOAT path, every operation rounded
 * to float in the order below, so that SIMD can reproduce it bit for bit.
 * The two may differ in the last bits of any plane, and where the float
 * cross product under- or overflows (coordinates below about 1e-19 or above
 * about 1e19 apart) this one gives the zero plane where the double one
 * still finds a normal.
 *
 * Copyright (C) 2026 the shadowvol authors. LGPL-2.1-or-later.
 */
#ifndef SHADOWVOL_PLANES_H
#define SHADOWVOL_PLANES_H

#include <stdint.h>

#include "shadowvol.h"

#ifdef __cplusplus
extern "C" {
#endif

/* ---- Plane derivation ----------------------------------------------------
 * For triangle t with corners p0 = positions[3*indices[3t]], p1, p2 (x, y, z
 * each, counter-clockwise seen from the front), every operation in float,
 * rounded one at a time (the C is built with -ffp-contract=off; no FMA):
 *   e1 = p1 - p0,  e2 = p2 - p0                    (per component)
 *   nx = e1y*e2z - e1z*e2y
 *   ny = e1z*e2x - e1x*e2z
 *   nz = e1x*e2y - e1y*e2x
 *   len2 = (nx*nx + ny*ny) + nz*nz
 *   if !(0 < len2 < +inf):  plane = (0, 0, 0, 0)     (see below)
 *   len = sqrtf(len2),  inv = 1.0f / len             (one division)
 *   a = nx*inv,  b = ny*inv,  c = nz*inv
 *   d = -((a*p0x + b*p0y) + c*p0z)
 * (n * (1/len), not n / len: one correctly rounded division instead of
 * three; a, b, c are then within 1.5 ulp of the exact unit normal's
 * rounding instead of 1 ulp, so |(a,b,c)| may differ from 1 by a few
 * float ulps.)
 * The zero plane (0, 0, 0, 0): when len2 is 0 (collinear or coincident
 * corners, or a cross product too small for float: every n*n underflows),
 * +inf (too large for float) or NaN (a NaN or infinite coordinate). Its
 * facing is 0 for every light (0 > 0 is false), as sv::triangle_plane's
 * zero plane. So no plane written holds a NaN, and a, b, c are in
 * [-1, 1]; d is finite unless |p0| is near FLT_MAX (then it may be +-inf).
 *   positions     3 floats per vertex (x, y, z), no padding, no alignment.
 *                 The SIMD variants read only the 12 bytes of each vertex
 *                 an index names (masked loads), never past the array.
 *   indices       3 * numTriangles vertex numbers, each >= 0 and below the
 *                 vertex count (not checked).
 *   numTriangles  >= 0; a negative count writes nothing.
 *   planes        numTriangles planes; nothing after planes[numTriangles-1]
 *                 is written. No alignment needed.
 * Every variant is BIT-IDENTICAL to sv_derive_planes_c_ref, for every input
 * (subnormals, huge and tiny coordinates, zero-area triangles), under the
 * same MXCSR. */
typedef void (*sv_derive_planes_fn)(const float *positions, const int *indices, int numTriangles,
                                    Plane *planes);

void sv_derive_planes_c_ref(const float *positions, const int *indices, int numTriangles,
                            Plane *planes);
/* SSE2: 4 triangles a step, corners loaded as 8 + 4 bytes, 4x4 transposes. */
void sv_derive_planes_sse2(const float *positions, const int *indices, int numTriangles,
                           Plane *planes);
/* AVX2 with vgatherdps: 9 gathers per 8 triangles (x, y, z of 3 corners).
 * Its gathers take 32-bit signed float offsets 3 * index: vertex numbers
 * must be below 2^31 / 3 = 715,827,882 (8.6 GB of positions). */
void sv_derive_planes_avx2_gather(const float *positions, const int *indices, int numTriangles,
                                  Plane *planes);
/* AVX2 without gathers: every corner one masked 16-byte load from one float
 * before the vertex (vmaskmovps with mask (0,1,1,1): it reads the vertex's
 * 12 bytes only and cannot fault on its masked-out float), 4x4 transposes,
 * and blocks of up to 256 triangles in two passes over an 8 KiB stack
 * buffer, so that the square root and division leave the load chain
 * (src/planes/planes_simd.c; docs/PLANES.md has the measurements). */
void sv_derive_planes_avx2(const float *positions, const int *indices, int numTriangles,
                           Plane *planes);
/* AVX-512 (F, VL, DQ): the AVX2 scheme on 16 triangles, masked loads. */
void sv_derive_planes_avx512(const float *positions, const int *indices, int numTriangles,
                             Plane *planes);

/* ---- Planes by clusters ---------------------------------------------------
 * The same planes, bit for bit, with the corners taken from registers
 * instead of memory. Every triangle's three corners are a gather from
 * random vertices, and that gather (masked loads and transposes), not the
 * arithmetic, is most of the time of the variants above (docs/PLANES.md
 * measures both). So the triangles are grouped once per index list into
 * clusters of at most SV_PLANE_CLUSTER_VERTICES vertices; a kernel loads a
 * cluster's vertices once into registers (x, y and z of 32 vertices in six
 * 512-bit registers) and takes each corner by one two-register permute
 * (vpermt2ps), 16 triangles at a time. A vertex shared by six triangles is
 * loaded about once per cluster instead of six times.
 * sv::plane_clusters (include/shadowvol_mesh.h) builds them.
 *
 * Cluster c has the vertex list vertex_offsets[vertex_begin[c] ..
 * vertex_begin[c+1]): 16 or 32 entries, its vertices (at most 32) and then
 * copies of its first (so a kernel loads whole halves, no count), each as
 * the byte offset of the vertex in the positions (12 * vertex: one load
 * and no arithmetic per address). Its triangles come in groups of 16,
 * groups group_begin[c] .. group_begin[c+1]) (at least one); group g has
 * the byte offsets of the triangles' planes (16 * triangle)
 * plane_offsets[16g .. 16g + 16) and their corners, places in the
 * cluster's vertex list, at corners + 48g: the 16 first corners, then the
 * 16 second, then the 16 third, each triangle's in its index order (so
 * the planes are the same). A cluster's last group is filled up by
 * repeating its last triangle with its corners: that plane is written
 * again, with the same bits, so a kernel needs no count. Every triangle of
 * the index list is in exactly one cluster, in any order. Offsets are
 * 32-bit unsigned: at most 357,913,941 vertices and 268,435,455 triangles
 * (sv::plane_clusters refuses more).
 * Clusters come from sv::plane_clusters and are trusted (not checked by
 * the kernels: a place beyond the list reads a wrong vertex). */
#define SV_PLANE_CLUSTER_VERTICES 32
typedef struct sv_plane_clusters {
    int num_clusters;
    const int *vertex_begin;        /* num_clusters + 1, multiples of 16 */
    const uint32_t *vertex_offsets; /* 12 * vertex number */
    const int *group_begin;         /* num_clusters + 1 */
    const uint32_t *plane_offsets;  /* 16 per group: 16 * triangle number */
    const uint8_t *corners;         /* 48 bytes per group */
} sv_plane_clusters;

/* Plane t = sv_derive_planes_c_ref's plane t for every triangle of the
 * clusters, BIT-IDENTICAL to it (the same float sequence, the zero plane
 * the same). The kernels read each cluster vertex's 12 bytes only (masked
 * loads) and write the triangles' planes only. */
typedef void (*sv_derive_planes_clustered_fn)(const float *positions,
                                              const sv_plane_clusters *clusters, Plane *planes);
/* Cluster by cluster, triangle by triangle, sv_derive_planes_c_ref's
 * expression on the cluster's vertex numbers: the definition. */
void sv_derive_planes_clustered_c_ref(const float *positions, const sv_plane_clusters *clusters,
                                      Plane *planes);
/* AVX-512 (F, VL, BW): a cluster's vertices transposed into x, y, z of 32
 * lanes, corners by vpermt2ps, 16 planes a step, stored one by one to
 * their triangles. No AVX2 variant: AVX2 has no two-register permute, and
 * a 32-entry lookup by four vpermps and three blends costs more than the
 * loads it replaces. */
void sv_derive_planes_clustered_avx512(const float *positions, const sv_plane_clusters *clusters,
                                       Plane *planes);

typedef struct sv_planes_clustered_variant {
    const char *name; /* "c_ref", "avx512" (the same names as the planes variants') */
    unsigned isa;
    sv_derive_planes_clustered_fn derive_planes;
} sv_planes_clustered_variant;
const sv_planes_clustered_variant *sv_planes_clustered_variants(int *count);
const sv_planes_clustered_variant *sv_planes_clustered_variant_by_name(const char *name);

/* ---- Facing straight from positions (BFG) --------------------------------
 * No stored planes: for triangle t (corners as above) and LIGHT (x,y,z,w as
 * sv_calculate_facing takes it),
 *   e1, e2, nx, ny, nz as above (the unnormalised cross product)
 *   vx = L.x - p0x*L.w,  vy = L.y - p0y*L.w,  vz = L.z - p0z*L.w
 *   facing[t] = ((nx*vx + ny*vy) + nz*vz) > 0.0f
 * (strict, a NaN gives 0), then facing[numTriangles] = 1, as
 * sv_calculate_facing. It may differ from the facing of the derived planes
 * for a light very near a triangle's plane: the roundings differ (the
 * benchmark counts the disagreements on the real meshes).
 *   facing        numTriangles + 1 bytes, each written 0 or 1.
 *   numTriangles  >= 0; a negative count writes nothing.
 * Every variant is BIT-IDENTICAL (the same bytes) to the C reference. */
typedef void (*sv_facing_from_positions_fn)(const float *positions, const int *indices,
                                            int numTriangles, const Vec4 *light, uint8_t *facing);

void sv_facing_from_positions_c_ref(const float *positions, const int *indices, int numTriangles,
                                    const Vec4 *light, uint8_t *facing);
void sv_facing_from_positions_sse2(const float *positions, const int *indices, int numTriangles,
                                   const Vec4 *light, uint8_t *facing);
void sv_facing_from_positions_avx2_gather(const float *positions, const int *indices,
                                          int numTriangles, const Vec4 *light, uint8_t *facing);
void sv_facing_from_positions_avx2(const float *positions, const int *indices, int numTriangles,
                                   const Vec4 *light, uint8_t *facing);
void sv_facing_from_positions_avx512(const float *positions, const int *indices, int numTriangles,
                                     const Vec4 *light, uint8_t *facing);

/* ---- The table -----------------------------------------------------------
 * c_ref, sse2, avx2_gather, avx2, avx512: the reference first, then from
 * the slowest to the fastest. Check isa against sv_cpu_isa() first. */
typedef struct sv_planes_variant {
    const char *name;
    unsigned isa; /* SV_ISA_* bits the CPU must have */
    sv_derive_planes_fn derive_planes;
    sv_facing_from_positions_fn facing_from_positions;
} sv_planes_variant;

const sv_planes_variant *sv_planes_variants(int *count);
const sv_planes_variant *sv_planes_variant_by_name(const char *name);
/* The last entry sv_cpu_isa() allows (never NULL). */
const sv_planes_variant *sv_best_planes_variant(void);

#ifdef __cplusplus
}
#endif

#endif /* SHADOWVOL_PLANES_H */
