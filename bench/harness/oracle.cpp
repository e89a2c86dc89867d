/*
 * Copyright (C) 2026 the shadowvol authors. LGPL-2.1-or-later.
 */
#include "oracle.h"

#include <cmath>

namespace svbench {

namespace {

/* One term at a time, so the order of the additions is explicit. */
float plane_distance(const Plane &p, float x, float y, float z, float w) {
    float s = p.a * x;
    s += p.b * y;
    s += p.c * z;
    s += p.d * w;
    return s;
}

} // namespace

void oracle_facing(const Plane *planes, int numTriangles, const Vec4 &light, uint8_t *facing) {
    for (int t = 0; t < numTriangles; t++) {
        facing[t] = plane_distance(planes[t], light.x, light.y, light.z, light.w) > 0.0f;
    }
    facing[numTriangles] = 1;
}

int oracle_cull_bits(const Vec4 *positions, int numVerts, const Bounds &bounds,
                     const Plane planes[SV_NUM_LIGHT_PLANES], uint8_t *cullBits) {
    /* Planes the whole box is in front of need no per-vertex test. */
    unsigned tested = 0;
    for (int i = 0; i < SV_NUM_LIGHT_PLANES; i++) {
        const Plane &p = planes[i];
        float reach = std::fabs(p.a * bounds.extents.x);
        reach += std::fabs(p.b * bounds.extents.y);
        reach += std::fabs(p.c * bounds.extents.z);
        /* d * 1.0f is d: the centre's distance, as the contract writes it. */
        const float centre = plane_distance(p, bounds.center.x, bounds.center.y, bounds.center.z,
                                            1.0f);
        if (!(centre - reach >= 0.0f)) {
            tested |= 1u << i;
        }
    }
    if (tested == 0) {
        return 1;
    }
    for (int v = 0; v < numVerts; v++) {
        const Vec4 &q = positions[v];
        unsigned bits = 0;
        for (int i = 0; i < SV_NUM_LIGHT_PLANES; i++) {
            if ((tested >> i) & 1u) {
                bits |= (unsigned)(plane_distance(planes[i], q.x, q.y, q.z, 1.0f) < 0.0f) << i;
            }
        }
        cullBits[v] = (uint8_t)bits;
    }
    return 0;
}

} // namespace svbench
