/*
 * The planes' floor (planes_floor.cpp): the arithmetic of
 * sv_derive_planes_c_ref with the corners' gather taken away. The corners
 * of every triangle are copied beforehand, untimed, into nine arrays (x, y,
 * z of corner 0, 1, 2), so the timed loop does nine plain loads per 8
 * triangles and the reference's operations, and nothing else. It is a
 * measuring instrument, not a kernel: no skinning pass or index list hands
 * the planes their corners this way, and the copy costs more than it saves.
 * Beside the kernels in `bench --planes`, it says how much of a kernel's
 * time is the gather (on this CPU), and so how low a planes pass over
 * indexed positions could go.
 *
 * Copyright (C) 2026 the shadowvol authors. LGPL-2.1-or-later.
 */
#ifndef SV_BENCH_PLANES_FLOOR_H
#define SV_BENCH_PLANES_FLOOR_H

#include <vector>

#include "shadowvol.h"

namespace svbench {

/* Corner c's coordinate k of triangle t at corner[3 * c + k][t]; every
 * array padded with zeros to a multiple of 8 triangles. */
struct GatheredCorners {
    std::vector<float> corner[9];
    int triangles = 0;
};

GatheredCorners gather_corners(const float *positions, const int *indices, int numTriangles);

/* Whether planes_from_gathered_avx2 runs on this CPU. */
bool planes_floor_runs();

/* The planes of G's triangles, bit-identical to sv_derive_planes_c_ref on
 * the positions and indices G was gathered from (the same operations in
 * the same order, no FMA; a triangle outside 0 < len2 < inf gets the
 * reference's zero plane). Writes G.triangles planes. */
void planes_from_gathered_avx2(const GatheredCorners &g, Plane *planes);

} // namespace svbench

#endif
