/*
 * The eps_bias variant of appendix A: the reference's plane . light, in the
 * reference's operation order, against a threshold instead of 0, with
 * optional hysteresis.
 *
 * Why. A triangle whose plane passes within the reference's rounding error
 * of the light (error bound B, sv::facing_error_bound) gets a facing byte
 * that depends on the last bits of the arithmetic: as the light moves by
 * tiny steps, or the mesh is re-skinned, such a triangle can flip from
 * frame to frame, and its silhouette quads and caps with it. A threshold
 * tau > B makes the decision for those triangles deterministic ("casts");
 * hysteresis (the previous frame's byte picks -tau or +tau) makes a
 * triangle change side only when the light crosses a band of 2 tau around
 * its plane, which no rounding noise and no movement smaller than the band
 * can do. The price: triangles with 0 < D <= tau (resp. |D| <= tau with
 * hysteresis) are classified against the geometry; the volume stays closed
 * (closure holds for any facing bytes) and its shadow is the one of a
 * slightly moved light.
 *
 * Units: plane . light is the light's signed distance from the plane in
 * model units for w = 1 (unit normals), w times it for other w, and the
 * cosine of the angle to the normal times |(x, y, z)| for w = 0; the
 * threshold (sv_eps_bias_threshold) is built in those units from a
 * distance in model units and an angle in radians.
 *
 * Compiled with -ffp-contract=off: s is rounded exactly as the reference's.
 *
 * Copyright (C) 2026 the shadowvol authors. LGPL-2.1-or-later.
 */
#include <math.h>

#include "mxcsr_guard.h"
#include "shadowvol_accuracy.h"

__attribute__((noinline)) static void eps_bias_body(const Plane *planes, int numTriangles,
                                                    const Vec4 *light, float threshold,
                                                    const uint8_t *previous, uint8_t *facing) {
    const float x = light->x, y = light->y, z = light->z, w = light->w;
    for (int i = 0; i < numTriangles; i++) {
        const Plane *p = &planes[i];
        const float s = p->a * x + p->b * y + p->c * z + p->d * w;
        /* previous may be facing: read before the write. */
        const float t = previous && previous[i] ? -threshold : threshold;
        facing[i] = s > t;
    }
    facing[numTriangles] = 1;
}

void sv_calculate_facing_eps_bias(const Plane *planes, int numTriangles, const Vec4 *light,
                                  float threshold, const uint8_t *previous, uint8_t *facing) {
    if (numTriangles < 0) return;
    const unsigned saved = sv_mxcsr_enter();
    eps_bias_body(planes, numTriangles, light, threshold, previous, facing);
    sv_mxcsr_leave(saved);
}

__attribute__((noinline)) static float threshold_body(float distance, float angle,
                                                      const float center[3], const Vec4 *light) {
    if (!(distance >= 0.0f) || !(angle >= 0.0f) || !isfinite(light->x) || !isfinite(light->y) ||
        !isfinite(light->z) || !isfinite(light->w)) {
        return NAN;
    }
    const double w = light->w;
    const double rx = (double)light->x - w * center[0];
    const double ry = (double)light->y - w * center[1];
    const double rz = (double)light->z - w * center[2];
    const double t = (double)distance * fabs(w) + (double)angle * sqrt(rx * rx + ry * ry + rz * rz);
    float f = (float)t;
    /* Round up: the band must be at least what was asked for. */
    if ((double)f < t) f = nextafterf(f, INFINITY);
    return f;
}

float sv_eps_bias_threshold(float distance, float angle, const float center[3], const Vec4 *light) {
    const unsigned saved = sv_mxcsr_enter();
    const float t = threshold_body(distance, angle, center, light);
    sv_mxcsr_leave(saved);
    return t;
}
