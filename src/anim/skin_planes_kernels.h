/*
 * Skinning and planes in one pass (include/shadowvol_anim.h, "Skinning
 * and planes in one pass", gives the contract): the C reference and its
 * SIMD versions. Their arguments travel in one structure, so that every
 * kernel goes through the ABI checker (which passes at most 8 words).
 *
 * Copyright (C) 2026 the shadowvol authors. LGPL-2.1-or-later.
 */
#ifndef SV_SKIN_PLANES_KERNELS_H
#define SV_SKIN_PLANES_KERNELS_H

#include <stddef.h>
#include <stdint.h>

#include "shadowvol.h"

#ifdef __cplusplus
extern "C" {
#endif

typedef struct sv_skin_planes_args {
    /* Skinning (sv::SkinningFn's arguments). */
    const float *joint_matrices;
    const float *rest;
    const uint16_t *joints;
    const float *weights;
    int influences;
    size_t num_vertices;
    /* Planes (sv_derive_planes_fn's). */
    const int *indices;
    int num_triangles;
    /* The schedule: segment s skins vertices [vertex_end[s-1], vertex_end[s])
     * (from 0 for s = 0), then derives the planes of triangles
     * [triangle_end[s-1], triangle_end[s]), whose corners are all below
     * vertex_end[s]. Both nondecreasing, the last ones num_vertices and
     * num_triangles. segments 0: one segment, the whole surface. */
    int segments;
    const size_t *vertex_end;
    const int *triangle_end;
    /* Outputs: 3 floats per vertex; num_triangles planes. */
    float *out;
    Plane *planes;
} sv_skin_planes_args;

/* Skin, then sv_derive_planes_c_ref: the definition every kernel matches
 * bit for bit (it ignores the schedule). */
void sv_skin_planes_c_ref(const sv_skin_planes_args *a);
/* Segment by segment: skinning and planes of the named ISA. */
void sv_skin_planes_avx2(const sv_skin_planes_args *a);
void sv_skin_planes_avx512(const sv_skin_planes_args *a);
/* AVX-512 skinning, AVX2 planes (on some cores the AVX2 planes are the
 * faster: the planner measures which). */
void sv_skin_planes_avx512_avx2(const sv_skin_planes_args *a);

#ifdef __cplusplus
}
#endif

#endif
