/*
 * A surface's triangles grouped by their lowest vertex, and the cache of
 * those groupings (surface_triangles.h).
 *
 * Copyright (C) 2026 the shadowvol authors. LGPL-2.1-or-later.
 */
#include "surface_triangles.h"

#include <algorithm>
#include <cstring>

namespace sv::render::detail {
namespace {

void sorted3(int a, int b, int c, int v[3]) {
    v[0] = a, v[1] = b, v[2] = c;
    if (v[0] > v[1]) std::swap(v[0], v[1]);
    if (v[1] > v[2]) std::swap(v[1], v[2]);
    if (v[0] > v[1]) std::swap(v[0], v[1]);
}

} // namespace

SurfaceTriangles group_surface_triangles(const PreparedSurface &surface) {
    SurfaceTriangles g;
    const int nv = surface.num_vertices(), nt = surface.num_triangles();
    g.vertices = nv;
    /* A counting sort by lowest vertex. */
    g.first.assign((std::size_t)nv + 2, 0);
    for (int t = 0; t < nt; t++) {
        const int *i = &surface.indices[3 * (std::size_t)t];
        g.first[(std::size_t)std::min({i[0], i[1], i[2]}) + 1]++;
    }
    for (std::size_t v = 1; v < g.first.size(); v++) g.first[v] += g.first[v - 1];
    std::vector<int> fill(g.first.begin(), g.first.end() - 1);
    g.others.resize((std::size_t)g.first.back());
    for (int t = 0; t < nt; t++) {
        const int *i = &surface.indices[3 * (std::size_t)t];
        int v[3];
        sorted3(i[0], i[1], i[2], v);
        g.others[(std::size_t)fill[(std::size_t)v[0]]++] = {v[1], v[2]};
    }
    /* A vertex in many triangles (a fan's centre) has its group sorted
     * and searched, so no mesh makes the lookups quadratic. */
    for (std::size_t v = 0; v + 1 < g.first.size(); v++) {
        if (g.first[v + 1] - g.first[v] > SurfaceTriangles::kScan) {
            std::sort(g.others.begin() + g.first[v], g.others.begin() + g.first[v + 1]);
        }
    }
    return g;
}

bool SurfaceTriangles::contains(int a, int b, int c) const {
    int v[3];
    sorted3(a, b, c, v);
    if (v[0] < 0 || v[2] >= vertices) return false;
    const auto begin = others.begin() + first[(std::size_t)v[0]],
               end = others.begin() + first[(std::size_t)v[0] + 1];
    const std::pair<int, int> want{v[1], v[2]};
    return end - begin > kScan ? std::binary_search(begin, end, want)
                               : std::find(begin, end, want) != end;
}

void SurfaceTrianglesCache::fit(int surfaces) {
    if (entries_.size() < (std::size_t)surfaces) entries_.resize((std::size_t)surfaces);
}

void SurfaceTrianglesCache::begin_frame() {
    for (Entry &e : entries_) e.checked = false;
}

const SurfaceTriangles &SurfaceTrianglesCache::get(int surface, const PreparedSurface &p) {
    Entry &e = entries_.at((std::size_t)surface);
    const bool same = e.valid && (e.checked || (e.triangles.vertices == p.num_vertices() &&
                                                e.indices.size() == p.indices.size() &&
                                                std::memcmp(e.indices.data(), p.indices.data(),
                                                            e.indices.size() * sizeof(int)) == 0));
    if (!same) {
        e.triangles = group_surface_triangles(p);
        e.indices.assign(p.indices.begin(), p.indices.end());
        e.valid = true;
    }
    e.checked = true;
    return e.triangles;
}

} // namespace sv::render::detail
