// The seed's preprocessing (include/shadowvol_extrude.h): per face three
// vertices of its own carrying the face's normal, a degenerate quad for
// every shared edge, the open edges counted and flagged. Seed 002 (Brennan,
// ShaderX 2002), its pseudo code:
//   for each face: calculate the face normal, create 3 new vertices for it,
//   insert the face into the draw list; for each edge of the face: if the
//   edge has been seen before, insert a degenerate quad and remove it from
//   the checklist, else insert it into the checklist. Edges left in the
//   checklist: "the geometry is not a closed volume".
// The checklist's pairing is prepare_surface's SilEdges (an edge's uses
// paired first with first, the extra uses of a non-manifold edge two by
// two), so the quads are the paper's silhouette edges, and the caster rule
// (shadowvol_casters.h) applies unchanged.
//
// Copyright (C) 2026 the shadowvol authors. LGPL-2.1-or-later.
#include "shadowvol_extrude.h"

#include <algorithm>
#include <climits>
#include <cstddef>
#include <string>
#include <utility>

namespace sv {

namespace {

// The corner c of triangle T (0..2) whose edge c -> c+1 runs FROM -> TO, or
// -1.
int corner_of_edge(const PreparedSurface &s, int t, int from, int to) {
    const int *tri = s.indices.data() + 3 * (std::ptrdiff_t)t;
    for (int c = 0; c < 3; c++)
        if (tri[c] == from && tri[(c + 1) % 3] == to) return c;
    return -1;
}

} // namespace

ShadowMesh build_shadow_mesh(const PreparedSurface &caster) {
    const int faces = caster.num_triangles();
    ShadowMesh m;
    m.faces = faces;

    // The quads, keyed by where the seed inserts them: face p2 (the later
    // face, which finds the edge in the checklist) and p2's corner.
    struct Quad {
        int64_t key; // 3 * p2 + corner of p2
        int v[6];
    };
    std::vector<Quad> quads;
    quads.reserve(caster.sil_edges.size());
    for (const SilEdge &e : caster.sil_edges) {
        if (e.p2 >= faces) {
            m.open_edges++;
            continue;
        }
        const int v1 = e.v1 / 2, v2 = e.v2 / 2;
        const int i = corner_of_edge(caster, e.p1, v1, v2);
        const int j = corner_of_edge(caster, e.p2, v2, v1);
        if (i < 0 || j < 0)
            throw PrepareError("build_shadow_mesh: SilEdge " + std::to_string(v1) + "-" +
                               std::to_string(v2) + " is not in the winding of its triangles");
        const int a1 = 3 * e.p1 + i, b1 = 3 * e.p1 + (i + 1) % 3;
        const int b2 = 3 * e.p2 + j, a2 = 3 * e.p2 + (j + 1) % 3;
        quads.push_back({3 * (int64_t)e.p2 + j, {a1, b2, b1, a1, a2, b2}});
    }
    m.quads = (int64_t)quads.size();
    m.closed_volume = m.open_edges == 0;
    if (3 * (int64_t)faces + 6 * m.quads > INT_MAX)
        throw PrepareError("build_shadow_mesh: " + std::to_string(faces) +
                           " faces: the shadow mesh's index list does not fit an int");
    std::sort(quads.begin(), quads.end(),
              [](const Quad &a, const Quad &b) { return a.key < b.key; });

    m.stream.resize((std::size_t)faces * 3 * SV_EXTRUDE_STREAM_FLOATS);
    m.indices.reserve((std::size_t)(3 * (int64_t)faces + 6 * m.quads));
    std::size_t q = 0;
    for (int t = 0; t < faces; t++) {
        const Plane &pl = caster.planes[(std::size_t)t];
        for (int k = 0; k < 3; k++) {
            const int v = caster.indices[3 * (std::size_t)t + (std::size_t)k];
            float *out = m.stream.data() +
                         (3 * (std::size_t)t + (std::size_t)k) * SV_EXTRUDE_STREAM_FLOATS;
            const float *p = caster.positions.data() + 3 * (std::size_t)v;
            out[0] = p[0], out[1] = p[1], out[2] = p[2];
            out[3] = pl.a, out[4] = pl.b, out[5] = pl.c;
            m.indices.push_back(3 * t + k);
        }
        for (; q < quads.size() && quads[q].key < 3 * (int64_t)t + 3; q++)
            m.indices.insert(m.indices.end(), quads[q].v, quads[q].v + 6);
    }
    return m;
}

ShadowMesh build_shadow_mesh(const PreparedSurface &s, CasterRule rule) {
    const ShellMap shells = find_shells(s);
    const std::shared_ptr<PreparedSurface> two_sided = two_sided_caster(s, shells, rule);
    return build_shadow_mesh(two_sided ? *two_sided : s);
}

} // namespace sv
