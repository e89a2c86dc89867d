/*
 * Seed 003's classic (candidate list) and hash ("fast") silhouette finders,
 * and the SilEdge oracle they are tested against. The contracts are in
 * include/shadowvol_silhouette.h.
 *
 * Copyright (C) 2026 the shadowvol authors. LGPL-2.1-or-later.
 */
#include "shadowvol_silhouette.h"

#include <emmintrin.h>

#include <algorithm>
#include <cstring>

#include "silhouette_internal.h"

namespace sv {

SilhouetteMesh silhouette_mesh(const PreparedSurface &s) {
    SilhouetteMesh m;
    m.indices = s.indices.data();
    m.num_triangles = s.num_triangles();
    m.num_vertices = s.num_vertices();
    for (const SilEdge &e : s.sil_edges) {
        if (e.p2 == m.num_triangles) {
            m.dangling.push_back({(uint32_t)(e.v1 / 2), (uint32_t)(e.v2 / 2)});
        }
    }
    return m;
}

std::size_t silhouette_capacity(const SilhouetteMesh &m) {
    return 3 * (std::size_t)m.num_triangles + m.dangling.size();
}

std::size_t silhouette_from_sil_edges(const SilEdge *silEdges, int numSilEdges,
                                      const uint8_t *facing, DirectedEdge *out) {
    std::size_t n = 0;
    for (int i = 0; i < numSilEdges; i++) {
        const SilEdge &e = silEdges[i];
        const uint8_t f1 = facing[e.p1], f2 = facing[e.p2];
        if (f1 == f2) continue;
        const uint32_t a = (uint32_t)(e.v1 / 2), b = (uint32_t)(e.v2 / 2);
        out[n++] = f1 ? DirectedEdge{a, b} : DirectedEdge{b, a};
    }
    return n;
}

std::vector<DirectedEdge> canonical_silhouette(const DirectedEdge *edges, std::size_t n) {
    std::vector<DirectedEdge> v(edges, edges + n);
    std::sort(v.begin(), v.end());
    return v;
}

std::vector<DirectedEdge> net_silhouette(const DirectedEdge *edges, std::size_t n) {
    /* Group by undirected edge: key (min, max), then count each direction. */
    std::vector<DirectedEdge> und(n);
    for (std::size_t i = 0; i < n; i++) {
        und[i] = {std::min(edges[i].from, edges[i].to), std::max(edges[i].from, edges[i].to)};
    }
    std::vector<std::size_t> order(n);
    for (std::size_t i = 0; i < n; i++) order[i] = i;
    std::sort(order.begin(), order.end(),
              [&](std::size_t x, std::size_t y) { return und[x] < und[y]; });
    std::vector<DirectedEdge> net;
    for (std::size_t k = 0; k < n;) {
        std::size_t e = k;
        long balance = 0; /* uses min -> max minus uses max -> min */
        while (e < n && und[order[e]] == und[order[k]]) {
            balance += edges[order[e]].from < edges[order[e]].to ? 1 : -1;
            e++;
        }
        const DirectedEdge u = und[order[k]];
        for (long c = 0; c < (balance < 0 ? -balance : balance); c++) {
            net.push_back(balance > 0 ? u : DirectedEdge{u.to, u.from});
        }
        k = e;
    }
    std::sort(net.begin(), net.end());
    return net;
}

/* ---- Classic ---------------------------------------------------------------- */

ClassicFinder::ClassicFinder(const SilhouetteMesh &m) : m_(&m) {
    /* The list never holds more than every candidate at once: reserving it
     * here keeps find() free of allocations (the seed's heap churn is the
     * linked-list variant's problem, not the algorithm's). */
    list_.reserve(silhouette_capacity(m));
}

std::size_t ClassicFinder::find(const uint8_t *facing, DirectedEdge *out) {
    list_.clear();
    auto edge = [this](uint32_t a, uint32_t b) {
        const std::size_t n = list_.size();
        for (std::size_t i = 0; i < n; i++) {
            if (list_[i].from == b && list_[i].to == a) {
                list_[i] = list_.back();
                list_.pop_back();
                return;
            }
        }
        list_.push_back({a, b});
        peak_ = std::max(peak_, list_.size());
    };
    const int *idx = m_->indices;
    for (int t = 0; t < m_->num_triangles; t++) {
        if (!facing[t]) continue;
        for (int u = 3 * t; u < 3 * t + 3; u++) {
            edge((uint32_t)idx[u], (uint32_t)idx[silhouette_next_use(u)]);
        }
    }
    for (const DirectedEdge &d : m_->dangling) {
        edge(d.to, d.from); /* the virtual lit triangle across the use */
    }
    std::copy(list_.begin(), list_.end(), out);
    return list_.size();
}

/* ---- Hash ------------------------------------------------------------------- */

namespace {

constexpr std::size_t kCacheLine = 64;

template <class Index, int N, bool Simd> class HashFinder final : public HashFinderBase {
    static_assert(N == 8 || N == 16 || N == 32 || N == 64, "columns");
    static constexpr Index kEmpty = (Index) ~(Index)0;
    /* Index values per 16-byte SSE2 register; N * sizeof(Index) >= 16. */
    static constexpr int kLanes = 16 / (int)sizeof(Index);

public:
    explicit HashFinder(const SilhouetteMesh &m)
        : m_(&m), table_((std::size_t)m.num_vertices * N) {}

    std::size_t temporary_bytes() const override { return table_.size() * sizeof(Index); }

    HashStatus find(const uint8_t *facing, DirectedEdge *out, std::size_t *count) override {
        *count = 0;
        overflow_vertex_ = -1;
        Index *table = table_.data();
        std::memset(table, 0xFF, table_.size() * sizeof(Index));
        const int *idx = m_->indices;
        for (int t = 0; t < m_->num_triangles; t++) {
            if (!facing[t]) continue;
            for (int u = 3 * t; u < 3 * t + 3; u++) {
                if (!edge(table, (Index)idx[u], (Index)idx[silhouette_next_use(u)]))
                    return HashStatus::overflow;
            }
        }
        for (const DirectedEdge &d : m_->dangling) {
            if (!edge(table, (Index)d.to, (Index)d.from)) return HashStatus::overflow;
        }
        *count = scan(table, out);
        return HashStatus::ok;
    }

private:
    /* The column of V in ROW, or -1. */
    static int search(const Index *row, Index v) {
        if (Simd) {
            const __m128i key = sizeof(Index) == 2 ? _mm_set1_epi16((short)v)
                                                   : _mm_set1_epi32((int)v);
            for (int c = 0; c < N; c += kLanes) {
                const __m128i cells = _mm_load_si128((const __m128i *)(row + c));
                const __m128i eq = sizeof(Index) == 2 ? _mm_cmpeq_epi16(cells, key)
                                                      : _mm_cmpeq_epi32(cells, key);
                const unsigned mask = (unsigned)_mm_movemask_epi8(eq);
                if (mask) return c + __builtin_ctz(mask) / (int)sizeof(Index);
            }
            return -1;
        }
        for (int c = 0; c < N; c++) { /* the seed's fixed-size loop */
            if (row[c] == v) return c;
        }
        return -1;
    }

    bool edge(Index *table, Index a, Index b) {
        Index *rowB = table + (std::size_t)b * N;
        const int c = search(rowB, a);
        if (c >= 0) {
            rowB[c] = kEmpty; /* b -> a was a candidate: both are interior */
            return true;
        }
        Index *rowA = table + (std::size_t)a * N;
        const int e = search(rowA, kEmpty);
        if (e < 0) {
            overflow_vertex_ = (int)a;
            return false;
        }
        rowA[e] = b;
        return true;
    }

    std::size_t scan(const Index *table, DirectedEdge *out) const {
        std::size_t n = 0;
        const std::size_t rows = (std::size_t)m_->num_vertices;
        for (std::size_t r = 0; r < rows; r++) {
            const Index *row = table + r * N;
            if (Simd) {
                const __m128i empty = _mm_set1_epi8((char)0xFF);
                for (int c = 0; c < N; c += kLanes) {
                    const __m128i cells = _mm_load_si128((const __m128i *)(row + c));
                    const __m128i eq = sizeof(Index) == 2 ? _mm_cmpeq_epi16(cells, empty)
                                                          : _mm_cmpeq_epi32(cells, empty);
                    /* one bit per byte of a used cell; take each cell's first */
                    unsigned used = ~(unsigned)_mm_movemask_epi8(eq) & 0xFFFFu;
                    while (used) {
                        const int k = __builtin_ctz(used) / (int)sizeof(Index);
                        out[n++] = {(uint32_t)r, (uint32_t)row[c + k]};
                        used &= ~(((1u << sizeof(Index)) - 1) << (k * (int)sizeof(Index)));
                    }
                }
            } else {
                for (int c = 0; c < N; c++) {
                    if (row[c] != kEmpty) out[n++] = {(uint32_t)r, (uint32_t)row[c]};
                }
            }
        }
        return n;
    }

    const SilhouetteMesh *m_;
    AlignedVector<Index> table_;
};
static_assert(kCacheLine == AlignedAllocator<uint16_t>::kAlign, "rows on cache lines");

template <class Index, bool Simd>
std::unique_ptr<HashFinderBase> make_for_columns(const SilhouetteMesh &m, int columns) {
    switch (columns) {
    case 8: return std::make_unique<HashFinder<Index, 8, Simd>>(m);
    case 16: return std::make_unique<HashFinder<Index, 16, Simd>>(m);
    case 32: return std::make_unique<HashFinder<Index, 32, Simd>>(m);
    case 64: return std::make_unique<HashFinder<Index, 64, Simd>>(m);
    default:
        throw SilhouetteError("hash finder: columns must be 8, 16, 32 or 64, not " +
                              std::to_string(columns));
    }
}

} // namespace

std::unique_ptr<HashFinderBase> make_hash_finder(const SilhouetteMesh &m, int indexBits,
                                                 int columns, bool simd) {
    if (m.num_vertices < 0 || m.num_triangles < 0 || (m.num_triangles > 0 && !m.indices)) {
        throw SilhouetteError("hash finder: a mesh with negative counts or no indices");
    }
    if (indexBits == 16) {
        /* 0xFFFF is the empty cell: vertices 0 .. 65534 only. */
        if (m.num_vertices > 65535) {
            throw SilhouetteError("hash finder: 16-bit cells hold vertex numbers up to 65534; "
                                  "this surface has " +
                                  std::to_string(m.num_vertices) +
                                  " vertices (use the 32-bit table)");
        }
        return simd ? make_for_columns<uint16_t, true>(m, columns)
                    : make_for_columns<uint16_t, false>(m, columns);
    }
    if (indexBits == 32) {
        return simd ? make_for_columns<uint32_t, true>(m, columns)
                    : make_for_columns<uint32_t, false>(m, columns);
    }
    throw SilhouetteError("hash finder: index width must be 16 or 32 bits, not " +
                          std::to_string(indexBits));
}

int hash_columns_needed(const SilhouetteMesh &m) {
    std::vector<int> need((std::size_t)m.num_vertices, 0);
    for (int u = 0; u < 3 * m.num_triangles; u++) {
        need[(std::size_t)m.indices[u]]++;
    }
    for (const DirectedEdge &d : m.dangling) {
        need[d.to]++; /* the virtual edge d.to -> d.from goes in row d.to */
    }
    int most = 0;
    for (int n : need) most = std::max(most, n);
    return most;
}

} // namespace sv
