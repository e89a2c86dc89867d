/*
 * Skinning and planes in one pass (include/shadowvol_skin.h): each segment of a schedule skins its
 * vertices and at once derives the planes of the triangles those vertices
 * complete, while they are in the first-level cache; the C reference skins
 * everything and then derives every plane.
 *
 * Why segments and not one loop: a triangle's plane needs its three
 * corners skinned, and the corners are wherever the index list says. The
 * schedule (sv::skin_planes_schedule) cuts the triangle list into runs and
 * records, for each run, how far the skinning must have gone for all of
 * its corners. On a mesh whose vertices are numbered in order of first use
 * (most exported meshes), a run of a few hundred triangles needs only the
 * next few hundred vertices: the plane pass then reads positions written a
 * moment before. On a mesh numbered at random the first segment skins
 * almost everything, and the pass is "skin, then planes" again.
 *
 * Bit identity: every segment runs the same skinning and plane kernels as
 * the separate passes, on the same vertices and triangles, and neither
 * depends on where a call starts (each vertex and each triangle is
 * computed on its own, with the same operations at any position in a
 * vector); so the outputs are the reference's bits. The tests compare
 * them with ==, at every tail length and every segment length.
 *
 * Copyright (C) 2026 the shadowvol authors. LGPL-2.1-or-later.
 */
#include <string.h>

#include "shadowvol_planes.h"
#include "shadowvol_skin.h"

static void run_segments(const sv_skin_planes_args *a, sv_skin_fn skin,
                         sv_derive_planes_fn planes) {
    const size_t n = (size_t)a->influences;
    if (a->segments <= 0) {
        skin(a->joint_matrices, a->rest, a->joints, a->weights, a->influences, a->num_vertices,
             a->out);
        planes(a->out, a->indices, a->num_triangles, a->planes);
        return;
    }
    size_t v0 = 0;
    int t0 = 0;
    for (int s = 0; s < a->segments; s++) {
        const size_t v1 = a->vertex_end[s];
        const int t1 = a->triangle_end[s];
        if (v1 > v0) {
            skin(a->joint_matrices, a->rest + 3 * v0, a->joints + n * v0, a->weights + n * v0,
                 a->influences, v1 - v0, a->out + 3 * v0);
            v0 = v1;
        }
        if (t1 > t0) {
            planes(a->out, a->indices + 3 * (ptrdiff_t)t0, t1 - t0, a->planes + t0);
            t0 = t1;
        }
    }
}

void sv_skin_planes_c_ref(const sv_skin_planes_args *a) {
    sv_skin_c_ref(a->joint_matrices, a->rest, a->joints, a->weights, a->influences, a->num_vertices,
                  a->out);
    sv_derive_planes_c_ref(a->out, a->indices, a->num_triangles, a->planes);
}

void sv_skin_planes_avx2(const sv_skin_planes_args *a) {
    run_segments(a, sv_skin_avx2, sv_derive_planes_avx2);
}

void sv_skin_planes_avx512(const sv_skin_planes_args *a) {
    run_segments(a, sv_skin_avx512, sv_derive_planes_avx512);
}

void sv_skin_planes_avx512_avx2(const sv_skin_planes_args *a) {
    run_segments(a, sv_skin_avx512, sv_derive_planes_avx2);
}

const sv_skin_planes_variant *sv_skin_planes_variants(int *count) {
    static const sv_skin_planes_variant kVariants[] = {
        {"c_ref", SV_ISA_NONE, "c_ref", "c_ref", &sv_skin_planes_c_ref},
        /* The ISA bits of both kernels it runs (the planes' include SSE2:
         * their tails). */
        {"avx2", SV_ISA_SSE2 | SV_ISA_AVX2, "avx2", "avx2", &sv_skin_planes_avx2},
        {"avx512", SV_ISA_SSE2 | SV_ISA_AVX2 | SV_ISA_AVX512, "avx512", "avx512",
         &sv_skin_planes_avx512},
        {"avx512_avx2", SV_ISA_SSE2 | SV_ISA_AVX2 | SV_ISA_AVX512, "avx512", "avx2",
         &sv_skin_planes_avx512_avx2},
    };
    if (count) *count = (int)(sizeof kVariants / sizeof kVariants[0]);
    return kVariants;
}

const sv_skin_planes_variant *sv_skin_planes_variant_by_name(const char *name) {
    int n = 0;
    const sv_skin_planes_variant *v = sv_skin_planes_variants(&n);
    for (int i = 0; name && i < n; i++) {
        if (strcmp(v[i].name, name) == 0) return &v[i];
    }
    return NULL;
}

int sv_skin_planes_schedule(const int *indices, int numTriangles, size_t numVertices,
                            int segmentTriangles, size_t *vertexEnd, int *triangleEnd,
                            int capacity) {
    if (numTriangles < 0) return SV_E_COUNT;
    if ((numTriangles > 0 && !indices) || (capacity > 0 && (!vertexEnd || !triangleEnd))) {
        return SV_E_NULL;
    }
    const int run = segmentTriangles > 0 ? segmentTriangles : (numTriangles > 0 ? numTriangles : 1);
    size_t need = 0; /* vertices the triangles so far need */
    int segments = 0;
    for (int t0 = 0; t0 < numTriangles; t0 += run) {
        const int t1 = numTriangles - t0 > run ? t0 + run : numTriangles;
        for (long i = 3L * t0; i < 3L * t1; i++) {
            const int v = indices[i];
            if (v < 0 || (size_t)v >= numVertices) return SV_E_INDEX_RANGE;
            if ((size_t)v + 1 > need) need = (size_t)v + 1;
        }
        if (segments < capacity) {
            vertexEnd[segments] = need;
            triangleEnd[segments] = t1;
        }
        segments++;
    }
    /* Vertices no triangle uses are skinned too (the positions are the
     * surface's, all of them). */
    if (segments == 0 || need < numVertices) {
        if (segments < capacity) {
            vertexEnd[segments] = numVertices;
            triangleEnd[segments] = numTriangles;
        }
        segments++;
    }
    return segments;
}
