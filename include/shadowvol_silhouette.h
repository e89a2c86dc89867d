/*
 * shadowvol: seed 003's three silhouette finders (classic candidate list,
 * hash table, connectivity table), beside the paper's SilEdges (C++).
 *
 * WHAT EVERY FINDER RETURNS. The silhouette of a surface for given facing
 * bytes (facing[t] = 1: triangle t faces the light, "lit"), as directed
 * edges (from, to) of welded vertex numbers (NOT doubled), each in the
 * winding of the lit triangle beside it. The oracle is the paper's rule on
 * the prepared surface's SilEdges (silhouette_from_sil_edges): a SilEdge
 * is on the silhouette when facing[p1] != facing[p2], directed v1 -> v2
 * when p1 is lit, v2 -> v1 otherwise. Dangling SilEdges (p2 =
 * numTriangles, facing byte 1) are edges whose other side is a virtual,
 * always-lit triangle: that is the project's rule for boundary edges, for
 * the extra uses of non-manifold edges and for edges used twice in the same
 * direction (include/shadowvol_mesh.h), and the one every finder follows.
 *
 * The seed's classic and hash finders cancel an edge against its reverse
 * wherever they meet, so on an undirected edge they keep |#(a->b) -
 * #(b->a)| copies of the majority direction. The SilEdge rule can leave
 * both a->b and b->a on one non-manifold edge (two coincident, opposite
 * quads in the volume, which cancel in every stencil count). So:
 *   connectivity finders == silhouette_from_sil_edges, as multisets;
 *   classic and hash     == net_silhouette(silhouette_from_sil_edges),
 *                           as multisets (net: opposite pairs on one
 *                           undirected edge removed),
 * and on a surface where no undirected edge has more than two uses the
 * two are the same. tests/unit/test_silhouette_finders.cpp checks both
 * statements on every model and many lights.
 *
 * Output room: every finder writes at most silhouette_capacity(mesh) edges
 * (3 per triangle plus one per dangling use). Order differs by finder;
 * compare with sorted copies (canonical_silhouette).
 *
 * Facing bytes: facing[0 .. numTriangles - 1] each 0 or 1 and
 * facing[numTriangles] = 1, as sv_calculate_facing_* write them. The
 * gather-based connectivity kernels read 4 bytes at facing + p for every
 * neighbour p <= numTriangles, so their facing array needs numTriangles + 4
 * readable bytes (the extra 3 are ignored).
 *
 * Copyright (C) 2026 the shadowvol authors. LGPL-2.1-or-later.
 */
#ifndef SHADOWVOL_SILHOUETTE_H
#define SHADOWVOL_SILHOUETTE_H

#include <cstddef>
#include <cstdint>
#include <memory>
#include <stdexcept>
#include <string>
#include <vector>

#include "shadowvol.h"
#include "shadowvol_mesh.h"

namespace sv {

struct DirectedEdge {
    uint32_t from, to;
    bool operator==(const DirectedEdge &o) const { return from == o.from && to == o.to; }
    bool operator<(const DirectedEdge &o) const {
        return from != o.from ? from < o.from : to < o.to;
    }
};

/* Bad input to a finder's set-up (a 16-bit table for 65535 or more
 * vertices, a column count that is no power of two, ...). */
class SilhouetteError : public std::runtime_error {
public:
    using std::runtime_error::runtime_error;
};

/* What the classic and hash finders need of a surface besides its
 * indices: its vertex count and its dangling uses a -> b (from the
 * SilEdges with p2 = numTriangles), whose virtual lit neighbour contributes
 * b -> a. Empty for a closed 2-manifold. */
struct SilhouetteMesh {
    const int *indices = nullptr; /* 3 * num_triangles welded vertex numbers */
    int num_triangles = 0;
    int num_vertices = 0;
    std::vector<DirectedEdge> dangling;
};
/* The view of S (which must outlive it). */
SilhouetteMesh silhouette_mesh(const PreparedSurface &s);
/* 3 * num_triangles + dangling.size(). */
std::size_t silhouette_capacity(const SilhouetteMesh &m);

/* ---- The oracle ------------------------------------------------------------
 * The paper's rule on SilEdges (above); writes at most numSilEdges edges. */
std::size_t silhouette_from_sil_edges(const SilEdge *silEdges, int numSilEdges,
                                      const uint8_t *facing, DirectedEdge *out);
/* Sorted copy. */
std::vector<DirectedEdge> canonical_silhouette(const DirectedEdge *edges, std::size_t n);
/* Sorted, with every pair a -> b, b -> a removed (as often as it occurs). */
std::vector<DirectedEdge> net_silhouette(const DirectedEdge *edges, std::size_t n);

/* ---- Classic (seed 003): a candidate list ----------------------------------
 * For every lit triangle, for each of its edges a -> b: if b -> a is in the
 * list, remove it (swap with the last), else append a -> b; then the same
 * for the virtual edges of dangling uses. The list is an array searched
 * linearly from its start, as the seed describes: O(n * list length),
 * near-quadratic. The array is allocated once (its capacity is the
 * temporary memory); no allocation per call. */
class ClassicFinder {
public:
    explicit ClassicFinder(const SilhouetteMesh &m);
    /* Writes the silhouette to OUT (silhouette_capacity edges of room);
     * returns the count. */
    std::size_t find(const uint8_t *facing, DirectedEdge *out);
    /* The array reserved (every candidate at once: 3 per triangle plus the
     * dangling uses). */
    std::size_t temporary_bytes() const { return list_.capacity() * sizeof(DirectedEdge); }
    /* The longest the list has been in any call so far: what a list grown
     * on demand would have needed. */
    std::size_t peak_bytes() const { return peak_ * sizeof(DirectedEdge); }

private:
    const SilhouetteMesh *m_;
    std::vector<DirectedEdge> list_;
    std::size_t peak_ = 0;
};

/* ---- Hash (seed 003's "fast"): rows = vertices, N columns ------------------
 * Cell (a, k) holds b for a candidate edge a -> b, or ~0 (all ones: 0xFFFF
 * or 0xFFFFFFFF) when empty. Per edge a -> b of a lit triangle (then per
 * virtual dangling edge): search row b for a; if found, empty that cell
 * (the edge and its reverse cancel); else store b in the first empty cell
 * of row a. When row a has no empty cell the edge cannot be stored: the
 * seed's algorithm "will fail" there; find() stops and reports it (status
 * overflow, the vertex in overflow_vertex()) instead of returning a wrong
 * silhouette. Finally the table is scanned row by row and every non-empty
 * cell is an edge. Rows are N * sizeof(Index) bytes (16 .. 256), the table
 * 64-byte aligned, so a row of up to 64 bytes never straddles a cache line;
 * the table is filled with ~0 at the start of every call (memset).
 *   Index uint16_t: num_vertices <= 65535 (vertex 65535 would be ~0);
 *                   uint32_t: num_vertices < 2^32 - 1.
 *   N: 8, 16, 32 or 64.
 *   simd: rows searched with SSE2 compares (16 bytes at a time, movemask)
 *         instead of the seed's fixed-size scalar loop; the same cells
 *         chosen, so the same result and the same overflow. */
enum class HashStatus { ok, overflow };

class HashFinderBase {
public:
    virtual ~HashFinderBase() = default;
    /* OUT: silhouette_capacity edges; *count gets the edges written. On
     * overflow *count is 0 and OUT's contents are unspecified. */
    virtual HashStatus find(const uint8_t *facing, DirectedEdge *out, std::size_t *count) = 0;
    virtual std::size_t temporary_bytes() const = 0;
    /* The vertex whose row was full at the last overflow (-1: none). */
    int overflow_vertex() const { return overflow_vertex_; }

protected:
    int overflow_vertex_ = -1;
};
/* Throws SilhouetteError for an index width other than 16 or 32, N not in
 * {8, 16, 32, 64}, or too many vertices for 16 bits. */
std::unique_ptr<HashFinderBase> make_hash_finder(const SilhouetteMesh &m, int indexBits,
                                                 int columns, bool simd);

/* The largest number of distinct candidate edges a -> b any vertex a may
 * need at once in the worst case: its out-degree in the directed edge
 * uses plus its dangling in-uses. A hash with at least that many columns
 * never overflows on this surface, for any facing. */
int hash_columns_needed(const SilhouetteMesh &m);

/* ---- Connectivity table ----------------------------------------------------
 * neighbour[3t + k]: the triangle across edge k (corner k -> corner k + 1)
 * of triangle t, paired by the project's rule (opposite uses of an
 * undirected edge matched in triangle order, first with first), or
 * numTriangles when the use is dangling; dangling_uses lists those uses. */
struct ConnectivityTable {
    AlignedVector<int> neighbour;
    std::vector<int> dangling_uses;
    std::size_t permanent_bytes() const {
        return neighbour.size() * sizeof(int) + dangling_uses.size() * sizeof(int);
    }
};
/* The seed's precomputation: for each use not yet paired, scan the later
 * uses for the first unpaired reverse one. O(n^2) in the worst case (every
 * dangling use scans to the end). */
ConnectivityTable connectivity_quadratic(const int *indices, int numTriangles);
/* Ours: uses bucketed by their smaller vertex (a counting sort, O(n + V)),
 * then paired in use order inside each bucket, whose size is the vertex's
 * valence: O(n) for bounded valence. The same table as the quadratic one. */
ConnectivityTable connectivity_linear(const int *indices, int numTriangles, int numVertices);

/* Emit a -> b (use u of triangle t) when t is lit and neighbour[u] is not;
 * emit b -> a for every dangling use of an unlit triangle. */
using ConnectivityFn = std::size_t (*)(const ConnectivityTable &c, const int *indices,
                                       int numTriangles, const uint8_t *facing, DirectedEdge *out);
/* The seed's loop: per triangle, skip it when unlit, else test its three
 * neighbours (branches). */
std::size_t find_silhouette_connectivity(const ConnectivityTable &c, const int *indices,
                                         int numTriangles, const uint8_t *facing,
                                         DirectedEdge *out);
/* Branch-free: every use writes its edge at the output position, which
 * advances by (lit & !neighbour lit), the paper's trick of section 6.
 * Writes one edge past the returned count (room: silhouette_capacity). */
std::size_t find_silhouette_connectivity_branchless(const ConnectivityTable &c, const int *indices,
                                                    int numTriangles, const uint8_t *facing,
                                                    DirectedEdge *out);
/* AVX2 (x86-64-v3): eight triangles per step, the neighbours' facing bytes
 * gathered (vpgatherdd, so facing needs numTriangles + 4 bytes), the
 * triangles' own bytes spread with vpermd; the silhouette uses found from
 * the mask with tzcnt. Eight unlit triangles in a row (and each vector of
 * eight uses without a lit triangle) skip the gather: the seed's early out
 * per step. */
std::size_t find_silhouette_connectivity_avx2(const ConnectivityTable &c, const int *indices,
                                              int numTriangles, const uint8_t *facing,
                                              DirectedEdge *out);
/* AVX-512 (x86-64-v4): sixteen triangles per step, gathers, and the edges
 * of the silhouette uses written with vpcompressq. */
std::size_t find_silhouette_connectivity_avx512(const ConnectivityTable &c, const int *indices,
                                                int numTriangles, const uint8_t *facing,
                                                DirectedEdge *out);

/* The connectivity kernels by name, for tests and the benchmark. */
struct ConnectivityVariant {
    const char *name; /* "connectivity", "connectivity_branchless", ... */
    unsigned isa;     /* SV_ISA_* bits */
    ConnectivityFn fn;
};
const std::vector<ConnectivityVariant> &connectivity_variants();

} // namespace sv

#endif /* SHADOWVOL_SILHOUETTE_H */
