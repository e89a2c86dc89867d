/*
 * sv_shadow_volume_for_light (include/shadowvol_plan.h): one light's whole
 * job in one call, with the plan's kernels.
 *
 * What is fused: CalculateFacing and CountFacing. The paper's pipeline
 * writes the facing bytes, then reads them all again only to count them
 * (appendix C); the fused facing kernels count the compare masks while
 * they are still in registers. The silhouette and cap passes still read
 * the facing bytes: their lookups are by triangle number (p1, p2 of a
 * SilEdge, in edge order), so they need every decision first, and the
 * output order (silhouette quads, then caps) is the unfused one.
 *
 * The culling decision: appendix B's box test returns 1 when the surface
 * lies inside the light volume; the volume is then the one without
 * culling (cull bits not written, CountFacingCull not run), as
 * sv_calculate_cull_bits_c_ref's contract says.
 *
 * Copyright (C) 2026 the shadowvol authors. LGPL-2.1-or-later.
 */
#include <stdint.h>

#include "shadowvol_plan.h"

static int aligned_to(const void *p, unsigned align) {
    return align <= 1 || ((uintptr_t)p % align) == 0;
}

/* The highest variant of the table (it ascends towards the widest ISA)
 * that the CPU runs and that needs no alignment beyond what the buffers
 * have: the stand-in for a plan kernel whose need they do not meet. c_ref
 * needs none, so there is always one. */
static const sv_variant *unaligned_stand_in(const void *facing, const int *indices,
                                            const int *out) {
    int n = 0;
    const sv_variant *v = sv_variants(&n);
    const unsigned isa = sv_cpu_isa();
    for (int i = n - 1; i > 0; i--) {
        if ((v[i].isa & isa) != v[i].isa) continue;
        if (aligned_to(facing, v[i].align_facing) && aligned_to(indices, v[i].align_indices) &&
            aligned_to(out, v[i].align_shadow_indices)) {
            return &v[i];
        }
    }
    return &v[0];
}

int sv_shadow_volume_for_light(const sv_plan *plan, const sv_surface *surface, const Vec4 *light,
                               const Plane *lightPlanes, int *shadowIndices, size_t capacity,
                               uint8_t *facing, uint8_t *cullBits) {
    if (!surface || !light || !shadowIndices || !facing) return SV_E_NULL;
    const sv_surface *s = surface;
    if (s->numIndices < 0 || s->numIndices % 3 != 0 || s->numSilEdges < 0 || s->numVerts < 0) {
        return SV_E_COUNT;
    }
    const int numTriangles = s->numIndices / 3;
    if ((numTriangles && (!s->planes || !s->indices)) || (s->numSilEdges && !s->silEdges)) {
        return SV_E_NULL;
    }
    if (lightPlanes && (!cullBits || (s->numVerts && !s->positions))) return SV_E_NULL;
    const size_t need = sv_shadow_volume_capacity(s->numIndices, s->numSilEdges);
    /* The returned count is an int: 6 per SilEdge + 6 per triangle must fit. */
    if (need > (size_t)INT32_MAX) return SV_E_OVERFLOW;
    if (capacity < need) return SV_E_CAPACITY;

    if (!plan) plan = sv_plan_for(numTriangles, SV_PLAN_ESTIMATE);
    sv_variant k = plan->kernels;
    if (!aligned_to(s->indices, k.align_indices) ||
        !aligned_to(shadowIndices, k.align_shadow_indices)) {
        const sv_variant *alt = unaligned_stand_in(facing, s->indices, shadowIndices);
        k.create_sil_triangles = alt->create_sil_triangles;
        k.create_cap_triangles = alt->create_cap_triangles;
    }

    int useCull = 0;
    if (lightPlanes) {
        /* 1: the box is inside the light volume; cull bits are not written. */
        useCull = plan->calculate_cull_bits(s->positions, s->numVerts, &s->bounds, lightPlanes,
                                            cullBits) == 0;
    }
    int numFacing;
    if (useCull) {
        plan->calculate_facing(s->planes, numTriangles, light, facing);
        /* CountFacingCull writes facing and needs no alignment of it in any
         * variant; it returns the count after culling. */
        numFacing = k.count_facing_cull(facing, numTriangles, s->indices, cullBits);
    } else if (plan->calculate_facing_count) {
        numFacing = plan->calculate_facing_count(s->planes, numTriangles, light, facing);
    } else {
        plan->calculate_facing(s->planes, numTriangles, light, facing);
        if (!aligned_to(facing, k.align_facing)) {
            k.count_facing = unaligned_stand_in(facing, s->indices, shadowIndices)->count_facing;
        }
        numFacing = k.count_facing(facing, numTriangles);
    }
    if (numFacing == numTriangles) return 0; /* nothing casts */

    const int numSil = k.create_sil_triangles(shadowIndices, facing, s->silEdges, s->numSilEdges);
    return numSil +
           k.create_cap_triangles(shadowIndices + numSil, facing, s->indices, s->numIndices);
}
