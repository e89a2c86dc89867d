/*
 * The branch-free C that the paper's text derives (sections 4-7) before it
 * turns to SSE2. Each function computes exactly what the reference computes
 * on in-contract input (facing bytes 0 or 1, even SilEdge vertex numbers).
 *
 * The sil and cap routines always write six indices and advance the output
 * only when the element casts, so they may write up to six ints past the
 * returned count (never past the documented capacity): that is the price of
 * replacing an unpredictable branch with arithmetic.
 *
 * Copyright (C) 2026 the shadowvol authors. LGPL-2.1-or-later.
 * Derived from J.M.P. van Waveren, "Shadow Volume Construction",
 * Copyright (C) 2005 Id Software, Inc., LGPL-2.1.
 */
#include "shadowvol.h"

/* Section 4: "n += facing[i]", unrolled four times into independent
 * counters so consecutive adds do not wait on each other. */
int sv_count_facing_c_branchless(const uint8_t *facing, int numTriangles) {
    int n0 = 0, n1 = 0, n2 = 0, n3 = 0;
    int i = 0;

    for (; i + 4 <= numTriangles; i += 4) {
        n0 += facing[i + 0];
        n1 += facing[i + 1];
        n2 += facing[i + 2];
        n3 += facing[i + 3];
    }
    for (; i < numTriangles; i++) {
        n0 += facing[i];
    }
    return n0 + n1 + n2 + n3;
}

/* Section 5: c != 0 exactly when the triangle lies outside one light plane;
 * (-c) >> 31 is then all ones (c is 1..255, so -c is negative), else 0. The
 * right shift of a negative int is arithmetic on every compiler this
 * project supports (GCC and Clang document it). */
int sv_count_facing_cull_c_branchless(uint8_t *facing, int numTriangles, const int *indices,
                                      const uint8_t *cullBits) {
    int i, n = 0;

    for (i = 0; i < numTriangles; i++) {
        int c = cullBits[indices[0]] & cullBits[indices[1]] & cullBits[indices[2]];
        facing[i] |= (uint8_t)(((-c) >> 31) & 1);
        n += facing[i];
        indices += 3;
    }
    return n;
}

/* Section 6: with v1, v2 even, v ^ 1 == v + 1; on a silhouette edge exactly
 * one of f1, f2 is 1, which selects the winding without a branch. */
int sv_create_sil_triangles_c_branchless(int *shadowIndices, const uint8_t *facing,
                                         const SilEdge *silEdges, int numSilEdges) {
    int *si = shadowIndices;
    int i;

    for (i = 0; i < numSilEdges; i++) {
        const SilEdge *sil = &silEdges[i];
        int f1 = facing[sil->p1];
        int f2 = facing[sil->p2];
        int v1 = sil->v1;
        int v2 = sil->v2;

        si[0] = v1;
        si[1] = v2 ^ f1;
        si[2] = v2 ^ f2;
        si[3] = v1 ^ f2;
        si[4] = v1 ^ f1;
        si[5] = v2 ^ 1;
        si += 6 * (f1 ^ f2);
    }
    return (int)(si - shadowIndices);
}

/* Section 7, "the same strategy": write both caps for every triangle and
 * advance by six only when the triangle faces away (facing byte 0). The
 * doubled numbers are even, so +1 is ^1. */
int sv_create_cap_triangles_c_branchless(int *shadowIndices, const uint8_t *facing,
                                         const int *indices, int numIndices) {
    int *si = shadowIndices;
    int i, j;

    for (i = 0, j = 0; i < numIndices; i += 3, j++) {
        int i0 = indices[i + 0] * 2;
        int i1 = indices[i + 1] * 2;
        int i2 = indices[i + 2] * 2;

        si[0] = i2;
        si[1] = i1;
        si[2] = i0;
        si[3] = i0 ^ 1;
        si[4] = i1 ^ 1;
        si[5] = i2 ^ 1;
        si += 6 * (facing[j] ^ 1);
    }
    return (int)(si - shadowIndices);
}
