/*
 * Open edges of a shadow volume (open_edges.h): every directed edge's use
 * counted +1 one way and -1 the other on its two vertices; an edge whose
 * sum is not 0 is open.
 *
 * The uses are grouped by their lower vertex with a counting sort (linear
 * in the triangles and the vertices), and each group, a vertex's few
 * edges, summed by its upper vertex: the general sort of all uses by key
 * this replaces was a third of the hierarchical stencil pass's time on
 * the demo scene's terrain (about 60,000 volume triangles a light).
 *
 * Copyright (C) 2026 the shadowvol authors. LGPL-2.1-or-later.
 */
#include "open_edges.h"

#include <algorithm>

namespace sv::render::detail {

std::vector<uint8_t> triangles_on_open_edges(const int *indices, int num_triangles,
                                             const std::vector<uint8_t> &skip,
                                             bool extruded_shared) {
    std::vector<uint8_t> on_open((std::size_t)num_triangles, 0);
    if (num_triangles <= 0) return on_open;
    int max_index = 0;
    for (std::size_t k = 0; k < 3 * (std::size_t)num_triangles; k++) {
        max_index = std::max(max_index, indices[k]);
    }
    /* The vertices the triangles use, numbered densely in order of first
     * use: a volume uses few of its surface's vertices (the demo terrain's
     * 106k shadow vertices against a volume of a few thousand), so the
     * counting sort below runs over those, not over every index up to the
     * largest. The numbering is kept per thread, sized to the largest
     * index seen, and only the entries used are reset. A directional
     * light's extruded vertices are one point: one number for all. */
    thread_local std::vector<uint32_t> dense_of;
    constexpr uint32_t kUnnumbered = UINT32_MAX;
    if (dense_of.size() < (std::size_t)max_index + 2) {
        dense_of.assign((std::size_t)max_index + 2, kUnnumbered);
    }
    const std::size_t shared_slot = (std::size_t)max_index + 1;
    std::vector<uint32_t> dense((std::size_t)3 * (std::size_t)num_triangles);
    std::vector<uint32_t> numbered; /* the entries of DENSE_OF to reset */
    for (std::size_t k = 0; k < dense.size(); k++) {
        const std::size_t slot = (extruded_shared && (indices[k] & 1)) ? shared_slot
                                                                       : (std::size_t)indices[k];
        if (dense_of[slot] == kUnnumbered) {
            dense_of[slot] = (uint32_t)numbered.size();
            numbered.push_back((uint32_t)slot);
        }
        dense[k] = dense_of[slot];
    }
    for (uint32_t slot : numbered) dense_of[slot] = kUnnumbered;
    const uint32_t vertices = (uint32_t)numbered.size();
    auto vertex_of = [&](int t, int corner) {
        return dense[3 * (std::size_t)t + (std::size_t)corner];
    };
    /* Every use of an edge, grouped by its lower vertex (a counting
     * sort): its upper vertex and its sign, 0 for a skipped triangle's
     * (it closes nothing, but its edges are asked about too). USE_AT: the
     * slot of triangle t's edge e (3t + e), kNoSlot where its ends are
     * one vertex. */
    constexpr uint32_t kNoSlot = UINT32_MAX;
    std::vector<uint32_t> first((std::size_t)vertices + 1, 0);
    for (int t = 0; t < num_triangles; t++) {
        for (int e = 0; e < 3; e++) {
            const uint32_t a = vertex_of(t, e), b = vertex_of(t, (e + 1) % 3);
            if (a != b) first[(std::size_t)std::min(a, b) + 1]++;
        }
    }
    for (std::size_t v = 1; v < first.size(); v++) first[v] += first[v - 1];
    std::vector<uint32_t> fill(first.begin(), first.end() - 1);
    std::vector<uint32_t> upper(first.back()), use_at(dense.size(), kNoSlot);
    std::vector<int8_t> sign(first.back());
    for (int t = 0; t < num_triangles; t++) {
        const bool closes = skip[(std::size_t)t] == 0;
        for (int e = 0; e < 3; e++) {
            const uint32_t a = vertex_of(t, e), b = vertex_of(t, (e + 1) % 3);
            if (a == b) continue;
            const uint32_t at = fill[std::min(a, b)]++;
            upper[at] = std::max(a, b);
            sign[at] = (int8_t)(!closes ? 0 : a < b ? 1 : -1);
            use_at[3 * (std::size_t)t + (std::size_t)e] = at;
        }
    }
    /* Per group, each edge's sum of signs in a table by upper vertex
     * (added, read, then cleared by the same group): every use's edge is
     * open where its sum is not 0. Linear in the uses, whatever a
     * vertex's degree (a fan's centre, a directional light's shared
     * point). */
    std::vector<int> sum_by_upper(vertices, 0);
    std::vector<uint8_t> use_open(upper.size(), 0);
    for (std::size_t v = 0; v + 1 < first.size(); v++) {
        const uint32_t begin = first[v], end = first[v + 1];
        for (uint32_t k = begin; k < end; k++) sum_by_upper[upper[k]] += sign[k];
        for (uint32_t k = begin; k < end; k++) use_open[k] = sum_by_upper[upper[k]] != 0;
        for (uint32_t k = begin; k < end; k++) sum_by_upper[upper[k]] = 0;
    }
    for (int t = 0; t < num_triangles; t++) {
        for (int e = 0; e < 3; e++) {
            const uint32_t at = use_at[3 * (std::size_t)t + (std::size_t)e];
            if (at != kNoSlot && use_open[at]) on_open[(std::size_t)t] |= (uint8_t)(1u << e);
        }
    }
    return on_open;
}

} // namespace sv::render::detail
