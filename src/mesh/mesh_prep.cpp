/*
 * Per-surface preparation: weld by exact position, drop degenerate
 * triangles, build the paper's SilEdges with a pairing rule that keeps every
 * shadow volume closed, one plane per triangle. See include/shadowvol_mesh.h.
 *
 * WHY THE VOLUME IS CLOSED (for any facing bytes, hence for every light and
 * with or without cull bits, which only turn more bytes to 1):
 *
 * Count directed edges in the index list sv_create_shadow_volume returns.
 * Every directed use h = (a->b in kept triangle t) is in exactly one
 * SilEdge: paired with an opposite use (b->a in t') or dangling (its
 * partner is the virtual triangle numTriangles, facing 1). Write x' for the
 * extruded copy (odd vertex) of x. The kernels (sections 6 and 7) give:
 *  - a triangle t with facing 0: near cap (i2,i1,i0) = every use a->b of t
 *    reversed, b->a, on even vertices; far cap (i0',i1',i2') = every use
 *    a'->b' on odd vertices;
 *  - a SilEdge whose two sides differ: with x->y its direction in the side
 *    whose facing is 0, the quad's boundary is x->y (even), y'->x' (odd),
 *    and the verticals y->y' and x'->x (the two triangles' shared diagonal
 *    cancels).
 * Per SilEdge with uses h (a->b, side p) and its partner (b->a, side q):
 *  - both facing 1: nothing at all;
 *  - both facing 0: caps give b->a, a'->b' from h and a->b, b'->a' from the
 *    partner: they cancel;
 *  - one facing 0, say h's side p: p's caps give b->a and a'->b', the quad
 *    gives a->b and b'->a': they cancel, leaving the verticals b->b', a'->a.
 * (A dangling SilEdge is the last two cases with the virtual side facing 1.)
 * So all even and odd edges cancel, and what remains are the verticals: for
 * each silhouette use x->y (a use in a facing-0 triangle whose partner faces
 * 1), y->y' and x'->x. These silhouette uses are the boundary of the 2-chain
 * "sum of facing-0 triangles" minus pairs of opposite uses that both face 0;
 * a boundary is a cycle (every vertex has as many incoming as outgoing uses)
 * and removing opposite pairs keeps it one. Hence at every vertex v the
 * number of v->v' (silhouette uses ending at v) equals the number of v'->v
 * (uses starting at v): every directed edge appears as often as its reverse.
 * Nothing here needs the mesh to be manifold or consistently wound: only
 * that each use is in exactly one SilEdge, in its own direction, which the
 * pairing guarantees. tests/unit/test_mesh_prep.cpp checks it on every variant.
 *
 * Copyright (C) 2026 the shadowvol authors. LGPL-2.1-or-later.
 */
#include "shadowvol_mesh.h"

#include <algorithm>
#include <climits>
#include <cmath>
#include <cstring>
#include <string>

namespace sv {

namespace {

uint32_t canonical_bits(float f) {
    if (f == 0.0f) {
        f = 0.0f; // -0.0 welds with +0.0
    }
    uint32_t u;
    std::memcpy(&u, &f, sizeof u);
    return u;
}

struct WeldKey {
    uint32_t x, y, z;
    int index;
};

struct HalfEdge {
    uint64_t key; // (min vertex << 32) | max vertex
    int use;      // 3 * triangle + corner: the use a->b is corner -> corner + 1
};

} // namespace

PreparedSurface prepare_surface(const float *positions, std::size_t num_vertices,
                                const uint32_t *indices, std::size_t num_indices) {
    if (num_vertices > 0 && positions == nullptr) {
        throw PrepareError("positions is NULL but there are " + std::to_string(num_vertices) +
                           " vertices");
    }
    if (num_indices > 0 && indices == nullptr) {
        throw PrepareError("indices is NULL but there are " + std::to_string(num_indices) +
                           " indices");
    }
    if (num_indices % 3 != 0) {
        throw PrepareError("the index count " + std::to_string(num_indices) +
                           " is not a multiple of 3");
    }
    if (num_vertices > (std::size_t)INT_MAX) {
        throw PrepareError("too many vertices: " + std::to_string(num_vertices) + " (at most " +
                           std::to_string(INT_MAX) + ")");
    }
    if (num_indices > (std::size_t)INT_MAX) {
        throw PrepareError("too many indices: " + std::to_string(num_indices));
    }
    for (std::size_t i = 0; i < 3 * num_vertices; i++) {
        if (!std::isfinite(positions[i])) {
            throw PrepareError("vertex " + std::to_string(i / 3) + " has a " +
                               (std::isnan(positions[i]) ? "NaN" : "infinite") + " coordinate " +
                               "xyz"[i % 3]);
        }
    }
    for (std::size_t i = 0; i < num_indices; i++) {
        if (indices[i] >= num_vertices) {
            throw PrepareError("triangle " + std::to_string(i / 3) + " uses vertex " +
                               std::to_string(indices[i]) + ", but there are only " +
                               std::to_string(num_vertices) + " vertices");
        }
    }

    PreparedSurface s;
    PrepareReport &r = s.report;
    r.vertices_in = (int64_t)num_vertices;
    r.triangles_in = (int64_t)(num_indices / 3);
    const int nv = (int)num_vertices;

    // ---- Weld: sort by canonical bits, number groups by first input vertex.
    std::vector<WeldKey> keys(num_vertices);
    for (int i = 0; i < nv; i++) {
        // size_t: 3 * i overflows int above 715,827,882 vertices.
        const std::size_t k = 3 * (std::size_t)i;
        keys[i] = {canonical_bits(positions[k]), canonical_bits(positions[k + 1]),
                   canonical_bits(positions[k + 2]), i};
    }
    std::sort(keys.begin(), keys.end(), [](const WeldKey &a, const WeldKey &b) {
        if (a.x != b.x) return a.x < b.x;
        if (a.y != b.y) return a.y < b.y;
        if (a.z != b.z) return a.z < b.z;
        return a.index < b.index;
    });
    // leader[i]: the first input vertex with i's position.
    std::vector<int> leader(num_vertices);
    for (std::size_t k = 0; k < keys.size();) {
        std::size_t e = k;
        while (e < keys.size() && keys[e].x == keys[k].x && keys[e].y == keys[k].y &&
               keys[e].z == keys[k].z) {
            leader[keys[e].index] = keys[k].index; // sorted by index within a group
            e++;
        }
        k = e;
    }
    keys.clear();
    keys.shrink_to_fit();
    s.remap.assign(num_vertices, -1);
    int welded = 0;
    for (int i = 0; i < nv; i++) {
        if (leader[i] == i) {
            s.remap[i] = welded++;
            for (int c = 0; c < 3; c++) {
                float f = positions[3 * (std::size_t)i + (std::size_t)c];
                s.positions.push_back(f == 0.0f ? 0.0f : f);
            }
        } else {
            s.remap[i] = s.remap[leader[i]];
        }
    }
    r.welded_vertices = welded;
    if (welded >= (1 << 30)) {
        throw PrepareError("too many distinct positions: " + std::to_string(welded) +
                           " (vertex numbers are doubled: at most 2^30 - 1)");
    }

    // ---- Triangles: drop degenerate ones.
    s.indices.reserve(num_indices);
    for (std::size_t t = 0; t < num_indices / 3; t++) {
        int a = s.remap[indices[3 * t]], b = s.remap[indices[3 * t + 1]],
            c = s.remap[indices[3 * t + 2]];
        if (a == b || b == c || c == a) {
            r.degenerate_dropped++;
            continue;
        }
        s.indices.push_back(a);
        s.indices.push_back(b);
        s.indices.push_back(c);
        s.triangle_source.push_back((int)t);
    }
    const int nt = s.num_triangles();
    r.triangles = nt;

    // ---- Planes.
    s.planes.resize(nt);
    for (int t = 0; t < nt; t++) {
        const std::size_t i3 = 3 * (std::size_t)t;
        const float *p0 = &s.positions[3 * (std::size_t)s.indices[i3]];
        const float *p1 = &s.positions[3 * (std::size_t)s.indices[i3 + 1]];
        const float *p2 = &s.positions[3 * (std::size_t)s.indices[i3 + 2]];
        s.planes[t] = triangle_plane(p0, p1, p2);
        const Plane &p = s.planes[t];
        if (p.a == 0.0f && p.b == 0.0f && p.c == 0.0f && p.d == 0.0f) {
            r.zero_normal_triangles++;
        }
    }

    // ---- SilEdges: group the uses by undirected edge, pair opposite uses.
    std::vector<HalfEdge> he((std::size_t)nt * 3);
    for (int u = 0; u < 3 * nt; u++) {
        uint32_t a = (uint32_t)s.indices[u];
        uint32_t b = (uint32_t)s.indices[u % 3 == 2 ? u - 2 : u + 1];
        he[u] = {a < b ? ((uint64_t)a << 32 | b) : ((uint64_t)b << 32 | a), u};
    }
    std::sort(he.begin(), he.end(), [](const HalfEdge &x, const HalfEdge &y) {
        return x.key != y.key ? x.key < y.key : x.use < y.use;
    });
    struct Built {
        int first_use; // the use of p1 (for the final order)
        SilEdge e;
    };
    std::vector<Built> built;
    built.reserve(he.size());
    std::vector<int> fwd, bwd; // uses a->b with a < b, and with a > b
    auto from = [&](int u) { return s.indices[u]; };
    auto to = [&](int u) { return s.indices[u % 3 == 2 ? u - 2 : u + 1]; };
    for (std::size_t k = 0; k < he.size();) {
        std::size_t e = k;
        fwd.clear();
        bwd.clear();
        while (e < he.size() && he[e].key == he[k].key) {
            int u = he[e].use;
            (from(u) < to(u) ? fwd : bwd).push_back(u);
            e++;
        }
        const std::size_t uses = e - k;
        r.edges++;
        if (uses == 1) {
            r.boundary_edges++;
        } else if (uses == 2) {
            (fwd.size() == 1 ? r.manifold_edges : r.same_direction_edges)++;
        } else {
            r.non_manifold_edges++;
        }
        const std::size_t pairs = std::min(fwd.size(), bwd.size());
        for (std::size_t i = 0; i < pairs; i++) {
            int u1 = std::min(fwd[i], bwd[i]), u2 = std::max(fwd[i], bwd[i]);
            built.push_back({u1, {u1 / 3, u2 / 3, 2 * from(u1), 2 * to(u1)}});
        }
        for (const std::vector<int> *side : {&fwd, &bwd}) {
            for (std::size_t i = pairs; i < side->size(); i++) {
                int u = (*side)[i];
                built.push_back({u, {u / 3, nt, 2 * from(u), 2 * to(u)}});
                r.dangling_sil_edges++;
            }
        }
        k = e;
    }
    he.clear();
    he.shrink_to_fit();
    std::sort(built.begin(), built.end(),
              [](const Built &x, const Built &y) { return x.first_use < y.first_use; });
    s.sil_edges.reserve(built.size());
    for (const Built &b : built) {
        s.sil_edges.push_back(b.e);
    }
    r.sil_edges = (int64_t)s.sil_edges.size();

    if (sv_shadow_volume_capacity(s.num_indices(), s.num_sil_edges()) > (std::size_t)INT_MAX) {
        throw PrepareError("mesh too large: its shadow volume could need more than INT_MAX "
                           "indices (" +
                           std::to_string(nt) + " triangles, " +
                           std::to_string(s.sil_edges.size()) + " SilEdges)");
    }
    return s;
}

} // namespace sv
