/*
 * The bytes one call of a routine touches, per triangle of the mesh: where
 * the scaling plot marks the caches. A mesh of T triangles whose working
 * set is B bytes per triangle fills a cache of C bytes at T = C / B.
 *
 * Counted: every array the call reads or writes, once (a second pass over
 * an array already touched, as CreateShadowVolume's kernels make over the
 * facing bytes, adds nothing), at the sizes the routines use:
 *
 *   facing     1 byte per triangle (numTriangles + 1 in all)
 *   planes     16 bytes per triangle (Plane: 4 floats), App. A
 *   positions  16 bytes per vertex (Vec4), App. B
 *   cull bits  1 byte per vertex, App. B (written) and D (read)
 *   indices    12 bytes per triangle (3 ints), App. D and F
 *   SilEdges   16 bytes per SilEdge (4 ints), App. E
 *   output     4 bytes per shadow index written: 6 per silhouette edge
 *              (App. E) and 6 per back-facing triangle (App. F). The
 *              kernels also store 6 indices past the last that advanced
 *              the pointer (the branch-free trick); 24 bytes, not per
 *              triangle, left out.
 *
 * On a closed mesh every edge has two triangles, so there are 1.5 SilEdges
 * per triangle, and (Euler, genus g: V = T/2 + 2 - 2g) about 0.5 vertices.
 * At the paper's ratios (50% facing, 20% of the SilEdges on the
 * silhouette), CreateShadowVolume touches
 *   1 (facing) + 12 (indices) + 1.5 x 16 (SilEdges)
 *     + 1.5 x 0.2 x 6 x 4 (silhouette quads) + 0.5 x 6 x 4 (caps)
 *   = 1 + 12 + 24 + 7.2 + 12 = 56.2 bytes per triangle.
 * A finely tessellated mesh has fewer silhouette edges (the 1M-triangle
 * generated character about 0.5%), so its figure is lower, down to 49:
 * working_set_of() evaluates the same sums with a workload's own counts.
 *
 * Copyright (C) 2026 the shadowvol authors. LGPL-2.1-or-later.
 */
#ifndef SV_BENCH_WORKING_SET_H
#define SV_BENCH_WORKING_SET_H

#include <string>
#include <vector>

#include "routines.h"
#include "workload.h"

namespace svbench {

/* The shape of a mesh and its lights, per triangle. */
struct MeshShape {
    double edgesPerTriangle = 1.5;    /* SilEdges / triangles */
    double verticesPerTriangle = 0.5; /* vertices / triangles */
    double facing = 0.5;              /* facing triangles / triangles */
    double silhouette = 0.2;          /* silhouette SilEdges / SilEdges */
    double culled = 0.0;              /* triangles the culling turns facing /
                                         triangles (App. D: no caps for them) */
};

/* The paper's character: closed, 50% facing, 20% silhouette. */
MeshShape paper_shape();
/* W's own: its counts and the mean ratios over its moving lights. */
MeshShape shape_of(const Workload &w);

struct WorkingSetTerm {
    const char *what; /* "facing", "indices", ... */
    double bytes;     /* per triangle */
};

struct WorkingSet {
    std::vector<WorkingSetTerm> terms;
    double total = 0; /* bytes per triangle */
};

WorkingSet working_set(Routine r, const MeshShape &s);

/* "1 facing + 12 indices + 24 SilEdges + 7.2 silhouette + 12 caps = 56.2
 * bytes per triangle". */
std::string working_set_formula(const WorkingSet &ws);

/* Bytes a call of R touches on W in all (per triangle x triangles). */
double working_set_bytes(Routine r, const Workload &w);

} // namespace svbench

#endif
