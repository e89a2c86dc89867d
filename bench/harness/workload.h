/*
 * What the cycle table runs on: one prepared surface and the lights that
 * give its facing patterns and cull bits (the paper's section 8 workload).
 *
 * Two kinds of workload fill the same struct:
 *   - a glTF model (model_workload.h): lit by point lights chosen so that
 *     about 50% of the triangles face the light and about 20% of the
 *     SilEdges are on the silhouette (lights.h); facing from
 *     sv_calculate_facing_c_ref, cull bits from sv_calculate_cull_bits_c_ref;
 *   - the synthetic torus (synthetic_workload.h): facing patterns generated
 *     to the paper's ratios exactly, with no light behind them.
 *
 * Every array is 64-byte aligned (above every variant's align_* need) with
 * 64 bytes of padding past its end.
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
#include <stdexcept>
#include <string>
#include <vector>

#include "shadowvol.h"

namespace sv {
struct PreparedSurface;
}

namespace svbench {

constexpr size_t kBufferAlignment = 64;

/* A zero-initialised array of N trivially copyable T, kBufferAlignment-
 * aligned, with kBufferAlignment bytes of padding after element N - 1. */
template <class T> class AlignedArray {
public:
    AlignedArray() = default;
    explicit AlignedArray(size_t n) : n_(n) {
        size_t bytes = (n * sizeof(T) + 2 * kBufferAlignment - 1) / kBufferAlignment *
                       kBufferAlignment;
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

/* An axis-aligned light volume. Its planes (light_box_planes) point into
 * the box, so cull bit i of a vertex means: bit 0 x < xmin, 1 x > xmax,
 * 2 y < ymin, 3 y > ymax, 4 z < zmin, 5 z > zmax. Bits 6 and 7 are never
 * set (sse2_paper's CountFacingCull compares the AND of the cull bytes
 * signed; see include/shadowvol.h). */
struct LightBox {
    float xmin, xmax, ymin, ymax, zmin, zmax;
};
void light_box_planes(const LightBox &box, Plane planes[SV_NUM_LIGHT_PLANES]);

/* One light: the input of one call. */
struct Light {
    Vec4 position{};                     /* (x,y,z,1) point, (x,y,z,0) directional */
    LightBox box{};                      /* its light volume */
    Plane planes[SV_NUM_LIGHT_PLANES]{}; /* the box's planes, for App. B */
    AlignedArray<uint8_t> facing;        /* numTriangles + 1 bytes, the last 1 */
    AlignedArray<uint8_t> cullBits;      /* one byte per vertex */
    bool cullInside = false;             /* App. B returned 1: the surface is inside the box
                                and cullBits (all 0 here) were not written */
    int numFacing = 0;                   /* facing bytes set, the last one not counted */
    int numSilhouette = 0;               /* SilEdges whose two facing bytes differ */
    int numCulled = 0;                   /* triangles whose 3 cull bytes share a bit */
    int numTurned = 0;                   /* culled triangles that were not facing */
    double score = 0;                    /* how far from the targets (lights.h) */
};

/* How the lights were made, for the header. */
struct LightOrigin {
    bool lit = false;        /* positions and planes: App. A and B rows run */
    double targetFacing = 0; /* the ratios aimed at */
    double targetSilhouette = 0;
    double targetCulled = 0;
    uint64_t seed = 0;
    int candidates = 0;      /* light positions tried (glTF) */
    bool fixedGiven = false; /* --light chose the fixed light */
};

struct Workload {
    std::string name;   /* "character_1344.glb", "synthetic", ... (JSON "model") */
    std::string source; /* the file, or how the mesh was made */
    int surfaces = 0;   /* glTF mesh instances merged into the one surface */
    int numVerts = 0, numTriangles = 0, numIndices = 0, numSilEdges = 0;
    int numDangling = 0;          /* SilEdges with p2 = numTriangles */
    int degenerateDropped = 0;    /* triangles preparation dropped */
    bool closed = false;          /* every edge used twice, in opposite directions */
    AlignedArray<Vec4> positions; /* welded vertices, w = 1 (App. B's input) */
    AlignedArray<Plane> planes;   /* one per triangle (App. A's input) */
    Bounds bounds{};              /* sv::surface_bounds */
    AlignedArray<int> indices;    /* 3 per triangle, counter-clockwise */
    AlignedArray<SilEdge> silEdges;

    /* The moving light rotates over lights[0 .. numMoving); the fixed light
     * is lights[fixedLight] (the best of them, or the one --light gave,
     * appended after them). */
    std::vector<Light> lights;
    int numMoving = 0;
    int fixedLight = 0;
    LightOrigin origin;
};

/* The mesh arrays of a workload from a prepared surface (no lights yet). */
Workload workload_from_surface(const sv::PreparedSurface &s, const std::string &name,
                               const std::string &source);

/* Fills L's counts (numFacing .. numTurned) from its facing and cull bits. */
void count_light(const Workload &w, Light &l);

/* Mean, lowest and highest of a ratio over the moving lights. */
struct RatioStats {
    double mean = 0, min = 0, max = 0;
};
enum class Ratio { facing, silhouette, culled, turned };
RatioStats ratio_stats(const Workload &w, Ratio which);
/* The ratio for one light: facing and culled per triangle, silhouette per
 * SilEdge, turned per non-facing triangle. */
double light_ratio(const Workload &w, const Light &l, Ratio which);

/* Input that cannot make a workload (an unloadable model, ratios the
 * synthetic patterns cannot reach): a message for the user. */
class WorkloadError : public std::runtime_error {
public:
    using std::runtime_error::runtime_error;
};

} // namespace svbench

#endif
