/*
 * A second computation of appendices A and B, the check of their rows.
 *
 * The C-F kernels are checked against the paper's C (c_ref). For A and B
 * the paper's C IS c_ref, the row under test, so these are written afresh
 * from the contract in include/shadowvol.h, with another loop structure
 * (App. B: vertex by vertex, all planes at once, where the reference goes
 * plane by plane), but the same float operations in the same order:
 *   facing:    ((a*x + b*y) + c*z) + d*w > 0
 *   cull bit:  ((a*x + b*y) + c*z) + d < 0
 *   box test:  ((a*cx + b*cy) + c*cz + d) - (|a*ex| + |b*ey| + |c*ez|) >= 0
 * so that they agree with any correct implementation bit for bit. This file
 * is compiled with -ffp-contract=off, as the reference is.
 *
 * Copyright (C) 2026 the shadowvol authors. LGPL-2.1-or-later.
 */
#ifndef SV_BENCH_ORACLE_H
#define SV_BENCH_ORACLE_H

#include <cstdint>

#include "shadowvol.h"

namespace svbench {

/* facing[0 .. numTriangles) and facing[numTriangles] = 1. */
void oracle_facing(const Plane *planes, int numTriangles, const Vec4 &light, uint8_t *facing);

/* Returns 1, writing nothing, when the bounds are in front of all six
 * planes; else writes numVerts cull bytes and returns 0. */
int oracle_cull_bits(const Vec4 *positions, int numVerts, const Bounds &bounds,
                     const Plane planes[SV_NUM_LIGHT_PLANES], uint8_t *cullBits);

} // namespace svbench

#endif
