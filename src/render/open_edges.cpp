/*
 * Open edges of a shadow volume (open_edges.h): every directed edge's use
 * counted +1 one way and -1 the other on a key of its two vertices; an
 * edge whose sum is not 0 is open.
 *
 * Copyright (C) 2026 the shadowvol authors. LGPL-2.1-or-later.
 */
#include "open_edges.h"

#include <algorithm>

namespace sv::render::detail {
namespace {

/* The vertex an index names: a directional light's extruded vertices are
 * one point. */
inline uint32_t vertex_key(int index, bool extruded_shared) {
    return (extruded_shared && (index & 1)) ? UINT32_MAX : (uint32_t)index;
}

inline uint64_t edge_key(uint32_t a, uint32_t b) {
    const uint32_t lo = std::min(a, b), hi = std::max(a, b);
    return ((uint64_t)lo << 32) | hi;
}

} // namespace

std::vector<uint8_t> triangles_on_open_edges(const int *indices, int num_triangles,
                                             const std::vector<uint8_t> &skip,
                                             bool extruded_shared) {
    struct Use {
        uint64_t key;
        int sign;
    };
    std::vector<Use> uses;
    uses.reserve(3 * (std::size_t)num_triangles);
    for (int t = 0; t < num_triangles; t++) {
        if (skip[(std::size_t)t]) continue;
        const int *i = indices + 3 * (std::size_t)t;
        for (int e = 0; e < 3; e++) {
            const uint32_t a = vertex_key(i[e], extruded_shared),
                           b = vertex_key(i[(e + 1) % 3], extruded_shared);
            if (a != b) uses.push_back({edge_key(a, b), a < b ? 1 : -1});
        }
    }
    std::sort(uses.begin(), uses.end(), [](const Use &x, const Use &y) { return x.key < y.key; });
    std::vector<uint64_t> open;
    for (std::size_t i = 0; i < uses.size();) {
        std::size_t j = i;
        int sum = 0;
        for (; j < uses.size() && uses[j].key == uses[i].key; j++) sum += uses[j].sign;
        if (sum != 0) open.push_back(uses[i].key);
        i = j;
    }
    std::vector<uint8_t> on_open((std::size_t)num_triangles, 0);
    if (open.empty()) return on_open;
    for (int t = 0; t < num_triangles; t++) {
        const int *i = indices + 3 * (std::size_t)t;
        for (int e = 0; e < 3; e++) {
            const uint32_t a = vertex_key(i[e], extruded_shared),
                           b = vertex_key(i[(e + 1) % 3], extruded_shared);
            if (a != b && std::binary_search(open.begin(), open.end(), edge_key(a, b))) {
                on_open[(std::size_t)t] |= (uint8_t)(1u << e);
            }
        }
    }
    return on_open;
}

} // namespace sv::render::detail
