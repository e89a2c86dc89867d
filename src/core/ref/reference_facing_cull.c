/*
 * The paper's C for appendices A (CalculateFacing) and B (CalculateCullBits)
 * of J.M.P. van Waveren, "Shadow Volume Construction" (Id Software, 2005).
 * The oracle of every future SIMD variant of these two routines: compiled
 * with -ffp-contract=off (no FMA), every sum evaluated left to right in
 * float exactly as printed.
 *
 * Changes from the listings, all recorded in include/shadowvol.h:
 *  - sv_ names, uint8_t for byte, pointers for C++ references, int for bool;
 *  - appendix B takes a plain Vec4 array of positions instead of the paper's
 *    32-byte Vertex {position, normal};
 *  - appendix B's fabs() on floats is C++'s float overload; in C that is
 *    fabsf (fabs would promote the sum to double and round differently);
 *  - a negative count writes nothing (appendix A would write facing[-1]).
 *
 * Copyright (C) 2005 Id Software, Inc. Written by J.M.P. van Waveren.
 * Port: Copyright (C) 2026 the shadowvol authors.
 * This code is free software; you can redistribute it and/or modify it
 * under the terms of the GNU Lesser General Public License as published by
 * the Free Software Foundation; either version 2.1 of the License, or (at
 * your option) any later version.
 */
#include "shadowvol.h"
#include "../facing_internal.h"

#include <math.h>
#include <string.h>

/* Appendix A. */
void sv_calculate_facing_c_ref(const Plane *planes, int numTriangles, const Vec4 *light,
                               uint8_t *facing) {
    int i;

    if (numTriangles < 0) {
        return;
    }
    for (i = 0; i < numTriangles; i++) {
        facing[i] = planes[i].a * light->x + planes[i].b * light->y + planes[i].c * light->z +
                        planes[i].d * light->w >
                    0.0f;
    }
    facing[numTriangles] = 1; /* for dangling edges to reference */
}

/* Appendix B. */
#define CULL_EPSILON 0.0f
#define NUM_LIGHT_PLANES SV_NUM_LIGHT_PLANES

_Static_assert(NUM_LIGHT_PLANES <= sizeof(uint8_t) * 8, "one cull bit per light plane");

/* The surface box against the light planes: bit i set when the whole box
 * is in front of plane i. The first half of appendix B, shared with the
 * SIMD variants (src/core/facing_internal.h) so that all of them decide
 * "completely inside" from the same bits. */
int sv_cull_front_bits(const Bounds *surfaceBounds, const Plane lightPlanes[SV_NUM_LIGHT_PLANES]) {
    int i, frontBits = 0;

    /* cull the triangle surface bounding box */
    for (i = 0; i < NUM_LIGHT_PLANES; i++) {
        const Plane *plane = &lightPlanes[i];
        float d1 = plane->a * surfaceBounds->center.x + plane->b * surfaceBounds->center.y +
                   plane->c * surfaceBounds->center.z + plane->d;
        float d2 = fabsf(plane->a * surfaceBounds->extents.x) +
                   fabsf(plane->b * surfaceBounds->extents.y) +
                   fabsf(plane->c * surfaceBounds->extents.z);

        if (d1 - d2 >= CULL_EPSILON) {
            frontBits |= 1 << i; /* front bits for the whole surface */
        }
    }
    return frontBits;
}

int sv_calculate_cull_bits_c_ref(const Vec4 *positions, int numVerts, const Bounds *surfaceBounds,
                                 const Plane lightPlanes[SV_NUM_LIGHT_PLANES], uint8_t *cullBits) {
    int i, j, frontBits;

    if (numVerts < 0) {
        return 0;
    }

    frontBits = sv_cull_front_bits(surfaceBounds, lightPlanes);

    /* if the surface is completely inside the light frustum */
    if (frontBits == ((1 << NUM_LIGHT_PLANES) - 1)) {
        return 1; /* return true if completely inside */
    }

    if (numVerts > 0) { /* memset(NULL, 0, 0) is undefined in C */
        memset(cullBits, 0, (size_t)numVerts * sizeof(cullBits[0]));
    }

    for (i = 0; i < NUM_LIGHT_PLANES; i++) {
        /* if completely in front of this clipping plane */
        if (frontBits & (1 << i)) {
            continue;
        }
        const Plane *plane = &lightPlanes[i];
        for (j = 0; j < numVerts; j++) {
            int bit = plane->a * positions[j].x + plane->b * positions[j].y +
                          plane->c * positions[j].z + plane->d <
                      CULL_EPSILON;
            cullBits[j] |= (uint8_t)(bit << i);
        }
    }
    return 0; /* return false if not completely inside */
}
