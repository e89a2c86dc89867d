/*
 * Shared by the appendix A/B implementations (reference and SIMD); not
 * part of the public API.
 *
 * Copyright (C) 2026 the shadowvol authors. LGPL-2.1-or-later.
 */
#ifndef SV_FACING_INTERNAL_H
#define SV_FACING_INTERNAL_H

#include "shadowvol.h"

/* Appendix B's first half: bit i set when the surface box is entirely in
 * front of light plane i (src/core/ref/reference_facing_cull.c). */
int sv_cull_front_bits(const Bounds *surfaceBounds, const Plane lightPlanes[SV_NUM_LIGHT_PLANES]);

#endif
