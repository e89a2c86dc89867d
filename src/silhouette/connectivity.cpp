/*
 * Seed 003's connectivity table: its O(n^2) precomputation, our O(n) one,
 * and the scalar finders over it (the SIMD ones: connectivity_simd.cpp).
 * Contracts: include/shadowvol_silhouette.h.
 *
 * Why both precomputations give the project's pairing: mesh_prep.cpp pairs,
 * per undirected edge, the k-th use a -> b with the k-th use b -> a (uses
 * in triangle order). The greedy scan here takes the earliest unpaired use
 * overall and pairs it with the earliest unpaired reverse use after it;
 * since every unpaired use lies after it, that is the earliest unpaired use
 * of each direction, so by induction the k-th of one direction meets the
 * k-th of the other. Uses left over (the surplus of one direction, and both
 * uses of an edge used twice in one direction) are dangling, as there.
 *
 * Copyright (C) 2026 the shadowvol authors. LGPL-2.1-or-later.
 */
#include "shadowvol_silhouette.h"

#include <climits>

#include "silhouette_internal.h"

namespace sv {

namespace {

void check_mesh(const int *indices, int numTriangles) {
    if (numTriangles < 0 || numTriangles > INT_MAX / 3 || (numTriangles > 0 && !indices)) {
        throw SilhouetteError("connectivity table: " + std::to_string(numTriangles) +
                              " triangles (a count from 0 to INT_MAX / 3 with indices)");
    }
}

void finish_dangling(ConnectivityTable &c, int numTriangles) {
    for (int u = 0; u < 3 * numTriangles; u++) {
        if (c.neighbour[u] == numTriangles) c.dangling_uses.push_back(u);
    }
}

} // namespace

ConnectivityTable connectivity_quadratic(const int *indices, int numTriangles) {
    check_mesh(indices, numTriangles);
    const int uses = 3 * numTriangles;
    ConnectivityTable c;
    c.neighbour.assign((std::size_t)uses, -1);
    for (int u = 0; u < uses; u++) {
        if (c.neighbour[u] >= 0) continue;
        const int a = indices[u], b = indices[silhouette_next_use(u)];
        c.neighbour[u] = numTriangles; /* dangling unless a reverse use turns up */
        for (int v = u + 1; v < uses; v++) {
            if (c.neighbour[v] < 0 && indices[v] == b && indices[silhouette_next_use(v)] == a) {
                c.neighbour[u] = v / 3;
                c.neighbour[v] = u / 3;
                break;
            }
        }
    }
    finish_dangling(c, numTriangles);
    return c;
}

ConnectivityTable connectivity_linear(const int *indices, int numTriangles, int numVertices) {
    check_mesh(indices, numTriangles);
    const int uses = 3 * numTriangles;
    for (int u = 0; u < uses; u++) {
        if (indices[u] < 0 || indices[u] >= numVertices) {
            throw SilhouetteError("connectivity table: index " + std::to_string(indices[u]) +
                                  " of use " + std::to_string(u) + " is not below " +
                                  std::to_string(numVertices) + " vertices");
        }
    }
    /* Counting sort of the uses by their smaller vertex, stable (use order
     * kept inside a bucket). */
    std::vector<int> start((std::size_t)numVertices + 1, 0);
    auto key = [&](int u) {
        const int a = indices[u], b = indices[silhouette_next_use(u)];
        return a < b ? a : b;
    };
    for (int u = 0; u < uses; u++) start[(std::size_t)key(u) + 1]++;
    for (int v = 0; v < numVertices; v++) start[(std::size_t)v + 1] += start[(std::size_t)v];
    std::vector<int> bucket((std::size_t)uses);
    {
        std::vector<int> fill(start.begin(), start.end() - 1);
        for (int u = 0; u < uses; u++) bucket[(std::size_t)fill[(std::size_t)key(u)]++] = u;
    }
    ConnectivityTable c;
    c.neighbour.assign((std::size_t)uses, -1);
    for (int v = 0; v < numVertices; v++) {
        const int lo = start[(std::size_t)v], hi = start[(std::size_t)v + 1];
        for (int i = lo; i < hi; i++) {
            const int u = bucket[(std::size_t)i];
            if (c.neighbour[u] >= 0) continue;
            const int a = indices[u], b = indices[silhouette_next_use(u)];
            c.neighbour[u] = numTriangles;
            for (int j = i + 1; j < hi; j++) {
                const int w = bucket[(std::size_t)j];
                if (c.neighbour[w] < 0 && indices[w] == b && indices[silhouette_next_use(w)] == a) {
                    c.neighbour[u] = w / 3;
                    c.neighbour[w] = u / 3;
                    break;
                }
            }
        }
    }
    finish_dangling(c, numTriangles);
    return c;
}

std::size_t silhouette_dangling(const ConnectivityTable &c, const int *indices,
                                const uint8_t *facing, DirectedEdge *out, std::size_t n) {
    /* The virtual lit triangle across a dangling use of an unlit triangle
     * casts the edge in its own winding: b -> a. */
    for (int u : c.dangling_uses) {
        if (!facing[u / 3]) {
            out[n++] = {(uint32_t)indices[silhouette_next_use(u)], (uint32_t)indices[u]};
        }
    }
    return n;
}

std::size_t find_silhouette_connectivity(const ConnectivityTable &c, const int *indices,
                                         int numTriangles, const uint8_t *facing,
                                         DirectedEdge *out) {
    std::size_t n = 0;
    const int *nb = c.neighbour.data();
    for (int t = 0; t < numTriangles; t++) {
        if (!facing[t]) continue; /* the seed's early out: an unlit triangle emits nothing */
        for (int u = 3 * t; u < 3 * t + 3; u++) {
            if (!facing[nb[u]]) {
                out[n++] = {(uint32_t)indices[u], (uint32_t)indices[silhouette_next_use(u)]};
            }
        }
    }
    return silhouette_dangling(c, indices, facing, out, n);
}

std::size_t silhouette_connectivity_tail(const ConnectivityTable &c, const int *indices,
                                         int firstTriangle, int numTriangles, const uint8_t *facing,
                                         DirectedEdge *out, std::size_t n) {
    const int *nb = c.neighbour.data();
    for (int t = firstTriangle; t < numTriangles; t++) {
        const uint8_t lit = facing[t];
        const int i0 = indices[3 * t], i1 = indices[3 * t + 1], i2 = indices[3 * t + 2];
        /* Write always, advance only for a silhouette use (section 6's trick). */
        out[n] = {(uint32_t)i0, (uint32_t)i1};
        n += lit & (facing[nb[3 * t]] ^ 1u);
        out[n] = {(uint32_t)i1, (uint32_t)i2};
        n += lit & (facing[nb[3 * t + 1]] ^ 1u);
        out[n] = {(uint32_t)i2, (uint32_t)i0};
        n += lit & (facing[nb[3 * t + 2]] ^ 1u);
    }
    return n;
}

std::size_t find_silhouette_connectivity_branchless(const ConnectivityTable &c, const int *indices,
                                                    int numTriangles, const uint8_t *facing,
                                                    DirectedEdge *out) {
    std::size_t n = silhouette_connectivity_tail(c, indices, 0, numTriangles, facing, out, 0);
    return silhouette_dangling(c, indices, facing, out, n);
}

const std::vector<ConnectivityVariant> &connectivity_variants() {
    static const std::vector<ConnectivityVariant> v = {
        {"connectivity", SV_ISA_NONE, find_silhouette_connectivity},
        {"connectivity_branchless", SV_ISA_NONE, find_silhouette_connectivity_branchless},
        {"connectivity_avx2", SV_ISA_AVX2, find_silhouette_connectivity_avx2},
        {"connectivity_avx512", SV_ISA_AVX512, find_silhouette_connectivity_avx512},
    };
    return v;
}

} // namespace sv
