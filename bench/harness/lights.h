/*
 * Lights for a model, as the paper's section 8 describes its workload: about
 * 50% of the triangles facing the light, about 20% of the SilEdges on the
 * silhouette, and (for the culling rows) a light volume that leaves about a
 * quarter of the triangles outside.
 *
 * Search: point lights at random directions around the centre of the
 * model's bounds, at distances from 1 to 16 times the bounding-sphere
 * radius r, log-uniform (never inside the bounding sphere, so never inside
 * the model; near lights give fewer facing triangles, far ones tend to a
 * directional light). Each candidate's facing comes from
 * sv_calculate_facing_c_ref with the prepared surface's planes; the
 * candidates kept are those nearest the targets, by the sum of the squared
 * RELATIVE misses ((f - F) / F)^2 + ((s - S) / S)^2, so a miss of 5 points
 * on 20% weighs as much as one of 12.5 points on 50%. They are ordered by
 * that score: the moving light rotates through them, the fixed light is
 * the best (unless --light gives one).
 *
 * Not every mesh can reach 20%: a smooth or finely tessellated mesh has
 * few silhouette edges per edge (the project's character tops out near
 * 13%, spot.glb near 3%). The search takes the nearest it finds and the
 * table prints the actual ratios.
 *
 * Light volume: the axis-aligned cube a point light's bounds make in Doom 3,
 * centred on the light (for a directional light, on the point 4r from the
 * model's centre towards it), its half size chosen by bisection so that the
 * number of triangles outside it (all three corners sharing a cull bit, by
 * sv_calculate_cull_bits_c_ref) is nearest the target. Culled triangles are
 * those farthest from the light, so most of them face away from it; the
 * culling routines turn those facing.
 *
 * Copyright (C) 2026 the shadowvol authors. LGPL-2.1-or-later.
 */
#ifndef SV_BENCH_LIGHTS_H
#define SV_BENCH_LIGHTS_H

#include <cstdint>

#include "workload.h"

namespace svbench {

struct LightTargets {
    double facing = 0.5; /* the paper's ratios */
    double silhouette = 0.2;
    double culled = 0.25;
};

/* Candidate positions tried for a mesh of NUM_TRIANGLES and NUM_SIL_EDGES:
 * 4096 for small meshes, fewer for large ones (the search costs about
 * candidates x (triangles + edges)), never fewer than 256. */
int light_candidates(int numTriangles, int numSilEdges);

/* Fills W's lights: COUNT searched lights (from SEED) for the moving light;
 * the fixed light is the best of them, or FIXED when not null (appended
 * after them). W needs its mesh arrays (workload_from_surface). */
void place_lights(Workload &w, const LightTargets &targets, int count, uint64_t seed,
                  const Vec4 *fixed);

} // namespace svbench

#endif
