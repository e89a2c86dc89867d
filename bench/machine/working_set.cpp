/*
 * Copyright (C) 2026 the shadowvol authors. LGPL-2.1-or-later.
 */
#include "working_set.h"

#include <cstdio>

namespace svbench {

namespace {

constexpr double kFacingByte = 1;
constexpr double kPlaneBytes = sizeof(Plane);
constexpr double kPositionBytes = sizeof(Vec4);
constexpr double kCullByte = 1;
constexpr double kTriangleIndexBytes = 3 * sizeof(int);
constexpr double kSilEdgeBytes = sizeof(SilEdge);
constexpr double kQuadBytes = 6 * sizeof(int); /* two triangles of output */

static_assert(sizeof(Plane) == 16 && sizeof(Vec4) == 16 && sizeof(SilEdge) == 16,
              "the working-set figures in working_set.h assume 16-byte planes, vertices "
              "and SilEdges");

} // namespace

MeshShape paper_shape() { return MeshShape{}; }

MeshShape shape_of(const Workload &w) {
    MeshShape s;
    if (w.numTriangles <= 0) {
        return s;
    }
    s.edgesPerTriangle = (double)w.numSilEdges / w.numTriangles;
    s.verticesPerTriangle = (double)w.numVerts / w.numTriangles;
    s.facing = ratio_stats(w, Ratio::facing).mean;
    s.silhouette = ratio_stats(w, Ratio::silhouette).mean;
    double turned = 0;
    for (int i = 0; i < w.numMoving; i++) {
        turned += w.lights[(size_t)i].numTurned;
    }
    s.culled = w.numMoving ? turned / w.numMoving / w.numTriangles : 0;
    return s;
}

WorkingSet working_set(Routine r, const MeshShape &s) {
    WorkingSet ws;
    const double silQuads = s.edgesPerTriangle * s.silhouette * kQuadBytes;
    auto caps = [&](double culled) { return (1 - s.facing - culled) * kQuadBytes; };
    switch (r) {
    case Routine::calculate_facing:
        ws.terms = {{"planes", kPlaneBytes}, {"facing", kFacingByte}};
        break;
    case Routine::calculate_cull_bits:
        ws.terms = {{"positions", s.verticesPerTriangle * kPositionBytes},
                    {"cull bits", s.verticesPerTriangle * kCullByte}};
        break;
    case Routine::count_facing: ws.terms = {{"facing", kFacingByte}}; break;
    case Routine::count_facing_cull:
        ws.terms = {{"facing", kFacingByte},
                    {"indices", kTriangleIndexBytes},
                    {"cull bits", s.verticesPerTriangle * kCullByte}};
        break;
    case Routine::create_sil_triangles:
        ws.terms = {{"facing", kFacingByte},
                    {"SilEdges", s.edgesPerTriangle * kSilEdgeBytes},
                    {"silhouette", silQuads}};
        break;
    case Routine::create_cap_triangles:
        ws.terms = {{"facing", kFacingByte}, {"indices", kTriangleIndexBytes}, {"caps", caps(0)}};
        break;
    case Routine::create_shadow_volume:
        ws.terms = {{"facing", kFacingByte},
                    {"indices", kTriangleIndexBytes},
                    {"SilEdges", s.edgesPerTriangle * kSilEdgeBytes},
                    {"silhouette", silQuads},
                    {"caps", caps(0)}};
        break;
    case Routine::create_shadow_volume_cull:
        ws.terms = {{"facing", kFacingByte},
                    {"indices", kTriangleIndexBytes},
                    {"cull bits", s.verticesPerTriangle * kCullByte},
                    {"SilEdges", s.edgesPerTriangle * kSilEdgeBytes},
                    {"silhouette", silQuads},
                    {"caps", caps(s.culled)}};
        break;
    case Routine::pipeline: /* A writes the facing bytes the volume reads */
        ws.terms = {{"planes", kPlaneBytes},
                    {"facing", kFacingByte},
                    {"indices", kTriangleIndexBytes},
                    {"SilEdges", s.edgesPerTriangle * kSilEdgeBytes},
                    {"silhouette", silQuads},
                    {"caps", caps(0)}};
        break;
    case Routine::pipeline_cull:
        ws.terms = {{"planes", kPlaneBytes},
                    {"positions", s.verticesPerTriangle * kPositionBytes},
                    {"facing", kFacingByte},
                    {"indices", kTriangleIndexBytes},
                    {"cull bits", s.verticesPerTriangle * kCullByte},
                    {"SilEdges", s.edgesPerTriangle * kSilEdgeBytes},
                    {"silhouette", silQuads},
                    {"caps", caps(s.culled)}};
        break;
    }
    for (const WorkingSetTerm &t : ws.terms) {
        ws.total += t.bytes;
    }
    return ws;
}

std::string working_set_formula(const WorkingSet &ws) {
    std::string s;
    char buf[64];
    for (const WorkingSetTerm &t : ws.terms) {
        std::snprintf(buf, sizeof buf, "%s%.3g %s", s.empty() ? "" : " + ", t.bytes, t.what);
        s += buf;
    }
    std::snprintf(buf, sizeof buf, "%s%.3g bytes per triangle", ws.terms.size() > 1 ? " = " : " ",
                  ws.total);
    if (ws.terms.size() == 1) {
        /* "1 facing byte per triangle" reads better than "1 facing = 1". */
        std::snprintf(buf, sizeof buf, " byte%s per triangle", ws.total == 1 ? "" : "s");
    }
    return s + buf;
}

double working_set_bytes(Routine r, const Workload &w) {
    return working_set(r, shape_of(w)).total * w.numTriangles;
}

} // namespace svbench
