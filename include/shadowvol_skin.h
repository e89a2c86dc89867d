/*
 * shadowvol: CPU skinning of positions, and skinning with the triangle
 * planes in one pass, in C and SIMD (the C kernels behind
 * include/shadowvol_anim.h's sv::skinning_kernels and
 * sv::skin_planes_kernels, and what `shadowvol check` checks).
 *
 * Copyright (C) 2026 the shadowvol authors. LGPL-2.1-or-later.
 */
#ifndef SHADOWVOL_SKIN_H
#define SHADOWVOL_SKIN_H

#include <stddef.h>
#include <stdint.h>

#include "shadowvol.h"

#ifdef __cplusplus
extern "C" {
#endif

/* ---- Skinning ------------------------------------------------------------
 * out[v] = B_v * (rest[v], 1), B_v = sum over k < influences of
 * weights[v*influences+k] * M[joints[v*influences+k]], where M holds 16
 * floats per joint, column-major (column c at M + 16 j + 4 c; row 3 is
 * ignored: the SIMD kernels load it, so all 16 must be there). The exact
 * order of operations, which every kernel keeps:
 *   B = w_0 * M_0;  B = B + w_k * M_k  for k = 1, 2, ...   (each element)
 *   out.r = ((B[0][r]*x + B[1][r]*y) + B[2][r]*z) + B[3][r]
 * in float, each operation rounded (no FMA): so every kernel gives the C
 * reference's bits. influences: 1..8 (the loader gives 4 or 8). out: 3
 * floats per vertex, nothing written past. No alignment required. */
typedef void (*sv_skin_fn)(const float *joint_matrices, const float *rest, const uint16_t *joints,
                           const float *weights, int influences, size_t num_vertices, float *out);

void sv_skin_c_ref(const float *joint_matrices, const float *rest, const uint16_t *joints,
                   const float *weights, int influences, size_t num_vertices, float *out);
void sv_skin_sse2(const float *joint_matrices, const float *rest, const uint16_t *joints,
                  const float *weights, int influences, size_t num_vertices, float *out);
void sv_skin_avx2(const float *joint_matrices, const float *rest, const uint16_t *joints,
                  const float *weights, int influences, size_t num_vertices, float *out);
void sv_skin_avx512(const float *joint_matrices, const float *rest, const uint16_t *joints,
                    const float *weights, int influences, size_t num_vertices, float *out);

typedef struct sv_skin_variant {
    const char *name; /* "c_ref", "sse2", "avx2", "avx512" */
    unsigned isa;     /* SV_ISA_* bits the CPU must have */
    sv_skin_fn fn;
} sv_skin_variant;
/* From the C reference to the widest; check isa against sv_cpu_isa(). */
const sv_skin_variant *sv_skin_variants(int *count);
const sv_skin_variant *sv_skin_variant_by_name(const char *name);

/* ---- Skinning and planes in one pass -------------------------------------
 * The skinned positions (as sv_skin_c_ref) and the planes of
 * sv_derive_planes_c_ref on them (include/shadowvol_planes.h), segment by
 * segment: each skins the vertices the next run of triangles completes,
 * then derives those triangles' planes while the positions are in the
 * first-level cache. The arguments travel in one structure (a kernel goes
 * through the ABI checker, which passes at most 8 words). */
typedef struct sv_skin_planes_args {
    /* Skinning (sv_skin_fn's arguments). */
    const float *joint_matrices;
    const float *rest;
    const uint16_t *joints;
    const float *weights;
    int influences;
    size_t num_vertices;
    /* Planes (sv_derive_planes_fn's). */
    const int *indices;
    int num_triangles; /* a negative count derives no plane */
    /* The schedule: segment s skins vertices [vertex_end[s-1], vertex_end[s])
     * (from 0 for s = 0), then derives the planes of triangles
     * [triangle_end[s-1], triangle_end[s]), whose corners must all be below
     * vertex_end[s]. Both nondecreasing, the last ones num_vertices and
     * num_triangles (sv::skin_planes_schedule builds it). segments 0: one
     * segment, the whole surface. */
    int segments;
    const size_t *vertex_end;
    const int *triangle_end;
    /* Outputs: 3 floats per vertex; num_triangles planes; nothing written
     * past either. */
    float *out;
    Plane *planes;
} sv_skin_planes_args;
typedef void (*sv_skin_planes_fn)(const sv_skin_planes_args *args);

/* The schedule for NUMTRIANGLES triangles (INDICES, 3 each) over
 * NUMVERTICES vertices: runs of SEGMENTTRIANGLES triangles (the last may be
 * shorter; <= 0: one run of all), each with the vertex count its corners
 * need (the running maximum of its indices + 1), then, when vertices
 * remain that no triangle uses, a last segment skinning them. Writes up to
 * CAPACITY segments to VERTEXEND and TRIANGLEEND; returns the number of
 * segments the schedule has (more than CAPACITY: call again with room for
 * them; at most numTriangles / max(segmentTriangles, 1) + 2), or
 * SV_E_INDEX_RANGE when an index is negative or not below NUMVERTICES,
 * SV_E_COUNT for a negative NUMTRIANGLES, SV_E_NULL for NULL INDICES with
 * triangles or NULL outputs with CAPACITY > 0. */
int sv_skin_planes_schedule(const int *indices, int numTriangles, size_t numVertices,
                            int segmentTriangles, size_t *vertexEnd, int *triangleEnd,
                            int capacity);

/* Skin, then sv_derive_planes_c_ref: the definition every kernel matches
 * bit for bit (it ignores the schedule). */
void sv_skin_planes_c_ref(const sv_skin_planes_args *args);
/* Segment by segment with the skinning and planes kernels of the named
 * ISA; avx512_avx2: AVX-512 skinning, AVX2 planes (on some cores the AVX2
 * planes are the faster: the planner measures which). */
void sv_skin_planes_avx2(const sv_skin_planes_args *args);
void sv_skin_planes_avx512(const sv_skin_planes_args *args);
void sv_skin_planes_avx512_avx2(const sv_skin_planes_args *args);

typedef struct sv_skin_planes_variant {
    const char *name;              /* "c_ref", "avx2", "avx512", "avx512_avx2" */
    unsigned isa;                  /* SV_ISA_* bits of both kernels it runs */
    const char *skinning, *planes; /* the kernels it runs: sv_skin_variant_by_name,
                                      sv_planes_variant_by_name */
    sv_skin_planes_fn fn;
} sv_skin_planes_variant;
const sv_skin_planes_variant *sv_skin_planes_variants(int *count);
const sv_skin_planes_variant *sv_skin_planes_variant_by_name(const char *name);

#ifdef __cplusplus
}
#endif

#endif /* SHADOWVOL_SKIN_H */
