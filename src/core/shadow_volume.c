/*
 * CreateShadowVolume (paper, section 3): counts the triangles that cast,
 * then writes the silhouette quads followed by the near and far caps, with
 * the four kernels of one variant.
 *
 * Copyright (C) 2005 Id Software, Inc. Written by J.M.P. van Waveren.
 * Port: Copyright (C) 2026 the shadowvol authors. LGPL-2.1-or-later.
 */
#include "shadowvol.h"

int sv_create_shadow_volume(const sv_variant *variant, int *shadowIndices, const int *indices,
                            int numIndices, const SilEdge *silEdges, int numSilEdges,
                            uint8_t *facing, const uint8_t *cullBits) {
    int numShadowingTriangles, numSilhouetteIndices, numCapIndices;
    int numTriangles = numIndices / 3;

    if (cullBits == NULL) {
        /* count the number of shadowing triangles */
        numShadowingTriangles = numTriangles - variant->count_facing(facing, numTriangles);
    } else {
        /* count the number of shadowing triangles and make all triangles
         * that are outside the light frustum "facing" so they won't cast
         * shadows */
        numShadowingTriangles = numTriangles -
                                variant->count_facing_cull(facing, numTriangles, indices, cullBits);
    }

    if (!numShadowingTriangles) {
        /* no triangles are inside the light frustum and still facing the
         * right way */
        return 0;
    }

    /* create triangles along silhouette planes */
    numSilhouetteIndices = variant->create_sil_triangles(shadowIndices, facing, silEdges,
                                                         numSilEdges);

    /* put some triangles on the model and some on the distant projection */
    numCapIndices = variant->create_cap_triangles(shadowIndices + numSilhouetteIndices, facing,
                                                  indices, numIndices);

    return numSilhouetteIndices + numCapIndices;
}

size_t sv_shadow_volume_capacity(int numIndices, int numSilEdges) {
    if (numIndices < 0 || numSilEdges < 0) {
        return 0;
    }
    /* 6 per edge + 6 per triangle = 6 * numSilEdges + 2 * numIndices; both
     * terms are below 2^34, so the sum fits size_t on 64-bit targets. */
    unsigned long long n = 6ull * (unsigned)numSilEdges + 2ull * (unsigned)numIndices;
    if (n > (unsigned long long)SIZE_MAX) {
        return SIZE_MAX;
    }
    return (size_t)n;
}
