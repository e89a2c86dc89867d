/*
 * The general rule's C reference (issue 27): the silhouette quads and caps
 * of the shadow volume that is exact for ANY triangle set, built directly
 * from the general edge table (shadowvol.h, sv_general_edges) and the
 * general facing bytes of the surface's own triangles: no doubled mesh, no
 * dangling sentinel for the general shells. New, not a listing of the
 * paper; it reuses the paper's quad (section 6) and caps (section 7)
 * exactly, so that its output is made of the same triangles, vertex for
 * vertex, as the two-sided caster's (docs/CASTERS.md derives both).
 *
 * The oracle of the general SIMD kernels (src/core/x86/general_simd.c).
 *
 * Copyright (C) 2026 the shadowvol authors. LGPL-2.1-or-later.
 */
#include <stdint.h>

#include "shadowvol.h"

/* The paper's quad for the edge v1 -> v2 (section 6): F is the facing byte
 * of the triangle that runs v1 -> v2; F = 0 gives Q(v1 -> v2), F = 1 its
 * reverse. */
static int *put_quad(int *si, int f, int v1, int v2) {
    if (f) {
        si[0] = v1;
        si[1] = v2 + 1;
        si[2] = v2;
        si[3] = v1;
        si[4] = v1 + 1;
        si[5] = v2 + 1;
    } else {
        si[0] = v1;
        si[1] = v2;
        si[2] = v2 + 1;
        si[3] = v1 + 1;
        si[4] = v1;
        si[5] = v2 + 1;
    }
    return si + 6;
}

size_t sv_general_sil_capacity(const sv_general_edges *e) {
    if (!e || e->numPaper < 0 || e->numPairs < 0 || e->numOpens < 0 || e->numShared < 0 ||
        e->numSharedUses < 0) {
        return SIZE_MAX;
    }
    return 6u * (size_t)e->numPaper + 12u * (size_t)e->numPairs + 6u * (size_t)e->numOpens +
           6u * (size_t)e->numSharedUses;
}

/* The signed multiplicity of a shared edge: sigma_t = +1, 0, -1 for bytes
 * 0, 1, 2, times +1 or -1 for the direction t runs the edge. */
static int shared_multiplicity(const uint8_t *facing, const int *uses, int n) {
    int m = 0, k;
    for (k = 0; k < n; k++) {
        const int t = uses[k] >> 1;
        const int sigma = 1 - (int)facing[t];
        m += (uses[k] & 1) ? -sigma : sigma;
    }
    return m;
}

int sv_create_general_sil_triangles_c_ref(int *shadowIndices, const uint8_t *facing,
                                          const sv_general_edges *edges) {
    int *si = shadowIndices;
    int i;
    /* The shells under the paper's rule: the paper's routine, unchanged. */
    si += sv_create_sil_triangles_c_ref(si, facing, edges->paper, edges->numPaper);
    /* Two triangles, opposite ways. Written as the two-sided caster pairs
     * them: p1 with p2 (paper facing f = byte != 0), and p1's reverse
     * (running v2 -> v1) with p2's (paper facing g = byte != 2). */
    for (i = 0; i < edges->numPairs; i++) {
        const SilEdge *e = &edges->pairs[i];
        const int b1 = facing[e->p1], b2 = facing[e->p2];
        const int f1 = b1 != SV_GENERAL_DARK, f2 = b2 != SV_GENERAL_DARK;
        const int g1 = b1 != SV_GENERAL_LIT, g2 = b2 != SV_GENERAL_LIT;
        if (f1 != f2) si = put_quad(si, f1, e->v1, e->v2);
        if (g1 != g2) si = put_quad(si, g1, e->v2, e->v1);
    }
    /* One triangle: it against its own reverse, which always differ unless
     * it casts nothing. */
    for (i = 0; i < edges->numOpens; i++) {
        const SilEdge *e = &edges->opens[i];
        const int b = facing[e->p1];
        if (b != SV_GENERAL_NONE) si = put_quad(si, b == SV_GENERAL_LIT, e->v1, e->v2);
    }
    /* Everything else: the multiplicity, summed. */
    for (i = 0; i < edges->numShared; i++) {
        const sv_shared_edge *e = &edges->shared[i];
        int m = shared_multiplicity(facing, edges->sharedUses + e->firstUse, e->numUses);
        const int reverse = m < 0;
        if (reverse) m = -m;
        while (m-- > 0) si = put_quad(si, reverse, e->v1, e->v2);
    }
    return (int)(si - shadowIndices);
}

int sv_create_general_cap_triangles_c_ref(int *shadowIndices, const uint8_t *facing,
                                          const int *indices, int numIndices) {
    int *si = shadowIndices;
    int i, j;
    for (i = 0, j = 0; i < numIndices; i += 3, j++) {
        const int i0 = indices[i] * 2, i1 = indices[i + 1] * 2, i2 = indices[i + 2] * 2;
        if (facing[j] == SV_GENERAL_DARK) {
            /* The paper's caps (section 7). */
            si[0] = i2;
            si[1] = i1;
            si[2] = i0;
            si[3] = i0 + 1;
            si[4] = i1 + 1;
            si[5] = i2 + 1;
            si += 6;
        } else if (facing[j] == SV_GENERAL_LIT) {
            /* The paper's caps of the reverse (i2, i1, i0): the near cap is
             * the triangle itself, vertex for vertex, so it rasterises to
             * the depths the depth pass stored (the tie docs/CASTERS.md
             * resolves). */
            si[0] = i0;
            si[1] = i1;
            si[2] = i2;
            si[3] = i2 + 1;
            si[4] = i1 + 1;
            si[5] = i0 + 1;
            si += 6;
        }
    }
    return (int)(si - shadowIndices);
}

int sv_general_facing_from_calculated(uint8_t *facing, const uint8_t *calculated,
                                      const uint8_t *litByte, int numTriangles) {
    int t, casting = 0;
    for (t = 0; t < numTriangles; t++) {
        const uint8_t lit = litByte ? litByte[t] : (uint8_t)SV_GENERAL_LIT;
        const uint8_t b = calculated[t] ? lit : (uint8_t)SV_GENERAL_DARK;
        facing[t] = b;
        casting += b != SV_GENERAL_NONE;
    }
    return casting;
}

int sv_general_cull_c_ref(uint8_t *facing, int numTriangles, const int *indices,
                          const uint8_t *cullBits) {
    int t, casting = 0;
    for (t = 0; t < numTriangles; t++) {
        const int *tri = indices + 3 * (size_t)t;
        if (cullBits[tri[0]] & cullBits[tri[1]] & cullBits[tri[2]]) facing[t] = SV_GENERAL_NONE;
        casting += facing[t] != SV_GENERAL_NONE;
    }
    return casting;
}
