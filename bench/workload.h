/*
 * The cycle table's synthetic workload, with the paper's sizes and ratios
 * (section 8): a closed 2-manifold of 1344 triangles and 2016 SilEdges,
 * facing patterns with 50% of the triangles facing the light and 20% of
 * the SilEdges on the silhouette, and cull bits from a light box that cuts
 * away a quarter of the triangles.
 *
 * The mesh is a torus grid of 24 x 28 quads, each split into two triangles
 * wound counter-clockwise seen from outside. A point light on a smooth torus
 * gives far fewer silhouette edges than a character does, so the facing
 * patterns are not lit but generated to the paper's ratios directly: a
 * random half of the triangles, then random swaps of one facing and one
 * non-facing triangle, each kept when it does not take the silhouette count
 * further from its target, until the count is on it.
 *
 * Silhouette target: on a closed mesh the number of silhouette edges is
 * 3F - 2 * (edges between two facing triangles), so it has the parity of F,
 * the number of facing triangles. With F = 672 the 403 of round(0.2 * 2016)
 * cannot be reached; the target is the even count nearest 0.2 * 2016, 404.
 *
 * Every buffer is allocated 64-byte aligned (above every variant's align_*
 * need) with 64 bytes of padding past its end.
 *
 * Copyright (C) 2026 the shadowvol authors. LGPL-2.1-or-later.
 */
#ifndef SV_BENCH_WORKLOAD_H
#define SV_BENCH_WORKLOAD_H

#include <cstddef>
#include <cstdint>
#include <cstdlib>
#include <cstring>
#include <memory>
#include <new>
#include <vector>

#include "shadowvol.h"

namespace svbench {

constexpr size_t kBufferAlignment = 64;

/* A zero-initialised array of N trivially copyable T, kBufferAlignment-
 * aligned, with kBufferAlignment bytes of padding after element N - 1. */
template <class T> class AlignedArray {
public:
    AlignedArray() = default;
    explicit AlignedArray(size_t n) : n_(n) {
        size_t bytes =
            (n * sizeof(T) + 2 * kBufferAlignment - 1) / kBufferAlignment * kBufferAlignment;
        void *p = std::aligned_alloc(kBufferAlignment, bytes);
        if (!p) {
            throw std::bad_alloc();
        }
        std::memset(p, 0, bytes);
        p_.reset(static_cast<T *>(p));
    }
    T *data() { return p_.get(); }
    const T *data() const { return p_.get(); }
    size_t size() const { return n_; }
    T &operator[](size_t i) { return p_.get()[i]; }
    const T &operator[](size_t i) const { return p_.get()[i]; }

private:
    struct Free {
        void operator()(T *p) const { std::free(p); }
    };
    std::unique_ptr<T, Free> p_;
    size_t n_ = 0;
};

/* One light: numTriangles + 1 facing bytes (the last = 1, for dangling
 * edges; this mesh has none). */
struct FacingPattern {
    AlignedArray<uint8_t> facing;
    int numFacing = 0;
    int numSilhouette = 0; /* SilEdges whose two triangles differ */
    long swaps = 0;        /* swap attempts the generator needed */
};

/* The light box of the cull bits: bit 0 x < xmin, 1 x > xmax, 2 y < ymin,
 * 3 y > ymax, 4 z < zmin, 5 z > zmax. Bits 6 and 7 are never set (the
 * sse2_paper CountFacingCull compares the AND of the cull bytes signed;
 * see include/shadowvol.h). */
struct LightBox {
    float xmin, xmax, ymin, ymax, zmin, zmax;
};

struct Workload {
    int gridU = 0, gridV = 0; /* quads around the ring and around the tube */
    int numVerts = 0, numTriangles = 0, numIndices = 0, numSilEdges = 0;
    std::vector<float> xyz;         /* 3 floats per vertex */
    AlignedArray<int> indices;      /* 3 per triangle, counter-clockwise */
    AlignedArray<SilEdge> silEdges; /* doubled vertex numbers */
    LightBox box{};
    AlignedArray<uint8_t> cullBits; /* one byte per vertex */
    int numCulled = 0;              /* triangles whose 3 vertices share a cull bit */
    uint64_t seed = 0;
    int targetFacing = 0;
    int targetSilhouette = 0;
    std::vector<FacingPattern> patterns;
};

/* Builds the mesh, cull bits and NUM_PATTERNS facing patterns from SEED,
 * and checks every invariant the table relies on (each edge shared by
 * exactly two triangles, 2016 edges, outward winding, the ratios).
 * Throws std::logic_error when one does not hold. */
Workload make_workload(uint64_t seed, int numPatterns);

} // namespace svbench

#endif
