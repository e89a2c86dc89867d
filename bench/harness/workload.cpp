/*
 * Copyright (C) 2026 the shadowvol authors. LGPL-2.1-or-later.
 */
#include "workload.h"

#include <algorithm>

#include "shadowvol_mesh.h"

namespace svbench {

void light_box_planes(const LightBox &b, Plane planes[SV_NUM_LIGHT_PLANES]) {
    /* a*x + b*y + c*z + d >= 0 inside: x - xmin, xmax - x, ... Each is one
     * float subtraction, exact in sign, so bit 0 is set exactly when
     * x < xmin, and so on. */
    planes[0] = Plane{1, 0, 0, -b.xmin};
    planes[1] = Plane{-1, 0, 0, b.xmax};
    planes[2] = Plane{0, 1, 0, -b.ymin};
    planes[3] = Plane{0, -1, 0, b.ymax};
    planes[4] = Plane{0, 0, 1, -b.zmin};
    planes[5] = Plane{0, 0, -1, b.zmax};
}

Workload workload_from_surface(const sv::PreparedSurface &s, const std::string &name,
                               const std::string &source) {
    Workload w;
    w.name = name;
    w.source = source;
    w.numVerts = s.num_vertices();
    w.numTriangles = s.num_triangles();
    w.numIndices = s.num_indices();
    w.numSilEdges = s.num_sil_edges();
    w.numDangling = (int)s.report.dangling_sil_edges;
    w.degenerateDropped = (int)s.report.degenerate_dropped;
    w.closed = s.report.boundary_edges == 0 && s.report.same_direction_edges == 0 &&
               s.report.non_manifold_edges == 0;

    w.positions = AlignedArray<Vec4>((size_t)w.numVerts);
    for (int v = 0; v < w.numVerts; v++) {
        const float *p = &s.positions[3 * (size_t)v];
        w.positions[(size_t)v] = Vec4{p[0], p[1], p[2], 1.0f};
    }
    w.planes = AlignedArray<Plane>((size_t)w.numTriangles);
    std::copy(s.planes.begin(), s.planes.end(), w.planes.data());
    w.indices = AlignedArray<int>((size_t)w.numIndices);
    std::copy(s.indices.begin(), s.indices.end(), w.indices.data());
    w.silEdges = AlignedArray<SilEdge>((size_t)w.numSilEdges);
    std::copy(s.sil_edges.begin(), s.sil_edges.end(), w.silEdges.data());
    w.bounds = sv::surface_bounds(s);
    return w;
}

void count_light(const Workload &w, Light &l) {
    const uint8_t *f = l.facing.data();
    const uint8_t *c = l.cullBits.data();
    l.numFacing = 0;
    l.numCulled = 0;
    l.numTurned = 0;
    for (int t = 0; t < w.numTriangles; t++) {
        const int *i = &w.indices[3 * (size_t)t];
        const bool culled = (c[i[0]] & c[i[1]] & c[i[2]]) != 0;
        l.numFacing += f[t];
        l.numCulled += culled;
        l.numTurned += culled && !f[t];
    }
    l.numSilhouette = 0;
    for (int e = 0; e < w.numSilEdges; e++) {
        const SilEdge &s = w.silEdges[(size_t)e];
        l.numSilhouette += f[s.p1] != f[s.p2];
    }
}

double light_ratio(const Workload &w, const Light &l, Ratio which) {
    auto ratio = [](int part, int whole) { return whole > 0 ? (double)part / whole : 0.0; };
    switch (which) {
    case Ratio::facing: return ratio(l.numFacing, w.numTriangles);
    case Ratio::silhouette: return ratio(l.numSilhouette, w.numSilEdges);
    case Ratio::culled: return ratio(l.numCulled, w.numTriangles);
    case Ratio::turned: return ratio(l.numTurned, w.numTriangles - l.numFacing);
    }
    return 0;
}

RatioStats ratio_stats(const Workload &w, Ratio which) {
    RatioStats s;
    if (w.numMoving == 0) {
        return s;
    }
    s.min = s.max = light_ratio(w, w.lights[0], which);
    double sum = 0;
    for (int i = 0; i < w.numMoving; i++) {
        const double r = light_ratio(w, w.lights[(size_t)i], which);
        sum += r;
        s.min = std::min(s.min, r);
        s.max = std::max(s.max, r);
    }
    s.mean = sum / w.numMoving;
    return s;
}

} // namespace svbench
