/*
 * The clusters of the clustered plane kernels (include/shadowvol_mesh.h,
 * plane_clusters; include/shadowvol_planes.h, "Planes by clusters").
 *
 * Why greedy by shared corners: a cluster's cost is its vertex loads, its
 * benefit its triangles, so each step takes the triangle that adds the
 * fewest new vertices. On a closed mesh a vertex has about six triangles
 * and a patch of 32 vertices holds about 40 of them; clusters of
 * consecutive triangles hold far fewer on meshes whose triangle order has
 * little locality (docs/PLANES.md has the counts per model).
 *
 * Copyright (C) 2026 the shadowvol authors. LGPL-2.1-or-later.
 */
#include <string>

#include "shadowvol_mesh.h"

namespace sv {

namespace {

constexpr int kGroup = 16; /* triangles per kernel step */

/* The triangles of each vertex (CSR). */
struct VertexTriangles {
    std::vector<int> begin, triangles;
    VertexTriangles(const int *indices, int num_triangles, int num_vertices)
        : begin((std::size_t)num_vertices + 1, 0), triangles(3 * (std::size_t)num_triangles) {
        for (std::size_t i = 0; i < triangles.size(); i++) begin[(std::size_t)indices[i] + 1]++;
        for (std::size_t v = 0; v < (std::size_t)num_vertices; v++) begin[v + 1] += begin[v];
        std::vector<int> fill(begin.begin(), begin.end() - 1);
        for (std::size_t i = 0; i < triangles.size(); i++) {
            triangles[(std::size_t)fill[(std::size_t)indices[i]]++] = (int)(i / 3);
        }
    }
};

} // namespace

sv_plane_clusters PlaneClusters::view() const {
    return sv_plane_clusters{num_clusters(),     vertex_begin.data(),  vertex_offsets.data(),
                             group_begin.data(), plane_offsets.data(), corners.data()};
}

PlaneClusters plane_clusters(const int *indices, int num_triangles, int num_vertices) {
    if (num_triangles < 0 || num_vertices < 0) {
        throw PrepareError("plane_clusters: a negative count");
    }
    if (num_triangles > 0 && !indices) throw PrepareError("plane_clusters: no indices");
    if ((uint64_t)num_vertices * 12 > UINT32_MAX || (uint64_t)num_triangles * 16 > UINT32_MAX) {
        throw PrepareError("plane_clusters: more vertices or triangles than 32-bit byte offsets "
                           "reach");
    }
    for (std::size_t i = 0; i < 3 * (std::size_t)num_triangles; i++) {
        if (indices[i] < 0 || indices[i] >= num_vertices) {
            throw PrepareError("plane_clusters: index " + std::to_string(i) + " is " +
                               std::to_string(indices[i]) + ", not below the vertex count " +
                               std::to_string(num_vertices));
        }
    }
    PlaneClusters out;
    out.vertex_begin.push_back(0);
    out.group_begin.push_back(0);
    const VertexTriangles adjacent(indices, num_triangles, num_vertices);
    std::vector<uint8_t> done((std::size_t)num_triangles, 0);
    std::vector<int> place((std::size_t)num_vertices, -1); /* in the current cluster */
    std::vector<int> met((std::size_t)num_triangles, -1);  /* the cluster that met it */
    std::vector<int> members, candidates, kept;
    std::vector<int> cluster_vertices;
    auto corner = [&](int t, int c) { return indices[3 * (std::size_t)t + (std::size_t)c]; };
    /* The distinct corners of T not yet in the cluster. */
    auto new_vertices = [&](int t) {
        const int a = corner(t, 0), b = corner(t, 1), c = corner(t, 2);
        return (place[(std::size_t)a] < 0) + (place[(std::size_t)b] < 0 && b != a) +
               (place[(std::size_t)c] < 0 && c != a && c != b);
    };
    int seed = 0;
    for (int cluster = 0;; cluster++) {
        while (seed < num_triangles && done[(std::size_t)seed]) seed++;
        if (seed == num_triangles) break;
        members.clear();
        candidates.clear();
        cluster_vertices.clear();
        auto take = [&](int t) {
            done[(std::size_t)t] = 1;
            members.push_back(t);
            for (int c = 0; c < 3; c++) {
                const int v = corner(t, c);
                if (place[(std::size_t)v] >= 0) continue;
                place[(std::size_t)v] = (int)cluster_vertices.size();
                cluster_vertices.push_back(v);
                for (int k = adjacent.begin[(std::size_t)v]; k < adjacent.begin[(std::size_t)v + 1];
                     k++) {
                    const int n = adjacent.triangles[(std::size_t)k];
                    if (!done[(std::size_t)n] && met[(std::size_t)n] != cluster) {
                        met[(std::size_t)n] = cluster;
                        candidates.push_back(n);
                    }
                }
            }
        };
        take(seed);
        for (;;) {
            int best = -1, best_new = 4;
            kept.clear();
            for (int t : candidates) {
                if (done[(std::size_t)t]) continue;
                kept.push_back(t);
                const int n = new_vertices(t);
                if (n < best_new) best = t, best_new = n;
            }
            candidates.swap(kept);
            if (best < 0 || (int)cluster_vertices.size() + best_new > SV_PLANE_CLUSTER_VERTICES) {
                break;
            }
            take(best);
        }
        /* The list in halves of 16, filled up with its first vertex. */
        const std::size_t half = cluster_vertices.size() > kGroup ? 2 * kGroup : kGroup;
        for (std::size_t i = 0; i < half; i++) {
            const int v = i < cluster_vertices.size() ? cluster_vertices[i] : cluster_vertices[0];
            out.vertex_offsets.push_back(12u * (uint32_t)v);
        }
        out.vertex_begin.push_back((int)out.vertex_offsets.size());
        /* Groups of 16, the last filled up with the last triangle. */
        while (members.size() % kGroup) members.push_back(members.back());
        for (std::size_t g = 0; g < members.size(); g += kGroup) {
            uint8_t group[3 * kGroup];
            for (std::size_t i = 0; i < (std::size_t)kGroup; i++) {
                for (int c = 0; c < 3; c++) {
                    group[(std::size_t)c * kGroup + i] =
                        (uint8_t)place[(std::size_t)corner(members[g + i], c)];
                }
            }
            out.corners.insert(out.corners.end(), group, group + 3 * kGroup);
        }
        for (int t : members) out.plane_offsets.push_back(16u * (uint32_t)t);
        out.group_begin.push_back((int)(out.plane_offsets.size() / kGroup));
        for (int v : cluster_vertices) place[(std::size_t)v] = -1;
    }
    return out;
}

} // namespace sv
