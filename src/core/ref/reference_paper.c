/*
 * The paper's C, as printed in sections 4-7 of J.M.P. van Waveren,
 * "Shadow Volume Construction" (Id Software, 2005): the oracle that every
 * other variant is tested against. Kept as close to the listings as C
 * allows; the only changes are the sv_ names, uint8_t for byte, and the
 * SilEdge type name (section 6 declares `const silEdge_t *sil`, a type the
 * paper never defines; see docs/ERRATA.md).
 *
 * Compiled with -ffp-contract=off like every reference file (no float here,
 * but the rule is per directory, not per file).
 *
 * Copyright (C) 2005 Id Software, Inc. Written by J.M.P. van Waveren.
 * Port: Copyright (C) 2026 the shadowvol authors.
 * This code is free software; you can redistribute it and/or modify it
 * under the terms of the GNU Lesser General Public License as published by
 * the Free Software Foundation; either version 2.1 of the License, or (at
 * your option) any later version.
 */
#include "shadowvol.h"

/* Section 4. */
int sv_count_facing_c_ref(const uint8_t *facing, int numTriangles) {
    int i, n;

    n = 0;
    for (i = 0; i < numTriangles; i++) {
        if (facing[i]) {
            n++;
        }
    }
    return n;
}

/* Section 5. */
int sv_count_facing_cull_c_ref(uint8_t *facing, int numTriangles, const int *indices,
                               const uint8_t *cullBits) {
    int i, n;

    n = 0;
    for (i = 0; i < numTriangles; i++) {
        if (!facing[i]) {
            int i1 = indices[0];
            int i2 = indices[1];
            int i3 = indices[2];
            if (cullBits[i1] & cullBits[i2] & cullBits[i3]) {
                facing[i] = 1;
                n++;
            }
        } else {
            n++;
        }
        indices += 3;
    }
    return n;
}

/* Section 6. */
int sv_create_sil_triangles_c_ref(int *shadowIndices, const uint8_t *facing,
                                  const SilEdge *silEdges, int numSilEdges) {
    int i;
    const SilEdge *sil;
    int *si;

    si = shadowIndices;
    for (sil = silEdges, i = numSilEdges; i > 0; i--, sil++) {

        uint8_t f1 = facing[sil->p1];
        uint8_t f2 = facing[sil->p2];

        if (f1 != f2) {

            int v1 = sil->v1;
            int v2 = sil->v2;

            if (f1) {
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
            si += 6;
        }
    }
    return (int)(si - shadowIndices);
}

/* Section 7. */
int sv_create_cap_triangles_c_ref(int *shadowIndices, const uint8_t *facing, const int *indices,
                                  int numIndices) {
    int i, j;
    int *si;

    si = shadowIndices;
    for (i = 0, j = 0; i < numIndices; i += 3, j++) {
        if (facing[j]) {
            continue;
        }

        int i0 = indices[i + 0] * 2;
        int i1 = indices[i + 1] * 2;
        int i2 = indices[i + 2] * 2;

        si[0] = i2;
        si[1] = i1;
        si[2] = i0;

        si[3] = i0 + 1;
        si[4] = i1 + 1;
        si[5] = i2 + 1;

        si += 6;
    }
    return (int)(si - shadowIndices);
}
