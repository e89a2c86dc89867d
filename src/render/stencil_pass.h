/*
 * The stencil pass (issue 12): one light's shadow volumes drawn into a
 * stencil of their own against the depth pass's depth, z-pass or z-fail
 * per volume, by the method RenderOptions::stencil names
 * (stencil_method.h). Each method is a file of its own
 * (stencil_bf.cpp, ...); this is where the frame picks one.
 *
 * Copyright (C) 2026 the shadowvol authors. LGPL-2.1-or-later.
 */
#ifndef SV_RENDER_STENCIL_PASS_H
#define SV_RENDER_STENCIL_PASS_H

#include <cstdint>
#include <memory>
#include <vector>

#include "depth_pass.h"
#include "frame.h"
#include "rasterizer.h"
#include "stencil_method.h"

namespace sv::render {

namespace detail {
class SurfaceTrianglesCache; /* surface_triangles.h */
struct TileGrid;             /* tile_depth_range.h */
struct BinnedTriangles;      /* pass_bins.h */
struct PieceSetup;           /* volume_pieces.h */
} // namespace detail

struct StencilPassInputs {
    const Scene *scene = nullptr;
    const ClipVertices *receivers = nullptr; /* the depth pass's clip vertices */
    const std::vector<Volume> *volumes = nullptr;
    Vec4 light{}; /* the volumes' light (w = 0: directional) */
    Mat4d view_proj;
    const raster::Rasterizer *rast = nullptr;
    const raster::Target *target = nullptr; /* its depth, after the depth pass */
    int tile = kDefaultStencilTile;         /* hierarchical: the tile side */
    /* Hierarchical: the depth's ranges in tiles of side TILE, computed once
     * for the frame's lights (nullptr: computed by the pass). */
    const detail::TileGrid *tile_grid = nullptr;
    /* auto: where the first light that takes hier leaves the depth's
     * ranges for the next (nullptr: each computes its own); unused when
     * TILE_GRID is given. */
    detail::TileGrid *tile_grid_for_auto = nullptr;
    StencilRule rule; /* auto: bf or hier per light */
    /* db, hier: the receivers' triangles grouped, kept across lights and
     * frames (nullptr: grouped by the pass for itself). */
    detail::SurfaceTrianglesCache *surface_triangles = nullptr;
    StencilFaults faults; /* tests only */
    /* The seed's saturating operations (seed 002, issue 31: IncrSat on
     * one pass, then DecrSat on the other) in place of additions modulo
     * 256. A saturating count depends on the order of its operations, so
     * it is the seed's order: every increment first (a pixel's count
     * min(255, I), I its increments), then every decrement (max(0, that
     * - D)). That equals max(0, min(255, I) - min(255, D)), so each
     * method keeps I and D in two counts of their own, each saturating at
     * 255 (the same bytes in any order, at any thread count), and the
     * stencil is their difference clamped at 0. Where no pixel sees more
     * than 255 of either and I >= D (closed volumes), it equals the
     * wrap-around stencil; docs/RENDERING.md says where it differs. */
    bool saturate = false;
};

/* Whether a triangle facing FRONT increments the stencil in MODE (z-pass:
 * front faces; z-fail: back faces), else it decrements it. */
inline bool stencil_increments(raster::StencilMode mode, bool front) {
    return (mode == raster::StencilMode::zpass) == front;
}

/* StencilPassInputs::saturate's two counts, target-sized, and the
 * stencil they give. */
struct SaturatingCounts {
    std::vector<uint8_t> increments, decrements;
    SaturatingCounts(int width, int height);
    /* The count a triangle facing FRONT in MODE adds 1 to. */
    uint8_t *count_for(raster::StencilMode mode, bool front) {
        return stencil_increments(mode, front) ? increments.data() : decrements.data();
    }
    /* STENCIL = max(0, increments - decrements), pixel by pixel. */
    void resolve(std::vector<uint8_t> &stencil) const;
};
/* Depth bounds that test every pixel. */
raster::DepthBounds no_depth_bounds();

struct StencilPassResult {
    std::vector<uint8_t> stencil; /* target-sized, row 0 = top */
    raster::PassCounters counters;
    /* The pass's wall time, from its stencil allocated and cleared to 0
     * (as Mesa's stencil pass is timed after its glClear; the clear is in
     * the frame's time, bench --frame's "clear, copies"). */
    uint64_t ticks = 0; /* wall TSC ticks */
    double seconds = 0;
    /* Hierarchical: (tile, volume) pairs classified, and those walked per
     * pixel (the volume's surface crosses the tile's box); tiles with at
     * least one such volume. */
    uint64_t tile_volume_pairs = 0, boundary_pairs = 0, boundary_tiles = 0, tiles = 0;
    /* Hierarchical: per tile (row-major, tiles of side `tile`), 1 where
     * some volume walked it per pixel (seed 004's boundary tiles, its
     * Figure 1); empty for the other methods. */
    std::vector<uint8_t> boundary_tile_mask;
    /* Hierarchical, for seed 004's bandwidth model (Table 1): the PSV
     * buffer's cache lines each volume touched, summed over volumes. A
     * line holds 128 tiles of one tile row (the seed's 4 bits per tile:
     * 2 bits of boundary and first, and the 8-bit count of a 2x2 group of
     * tiles sharing their sample point, section 5) in 64 bytes. */
    uint64_t psv_lines = 0;
    /* Hierarchical: the receiver's own caps in z-fail, taken by coverage
     * instead of walked (stencil_hier.cpp): their covered row spans, and
     * the pixels the running sums over them ran across. */
    uint64_t coverage_rows = 0, coverage_pixels = 0;
    /* The method that filled the stencil (auto: the one it chose), and the
     * load auto chose by (counted by auto only). */
    StencilMethod ran = StencilMethod::brute_force;
    StencilLoad load;
};

/* What every method sets up the same way. The volumes' triangles in
 * set-up chunks of submission order (kSetupChunk triangles of one volume
 * each), and each volume's double-length vertex buffer in clip space
 * through the paper's vertex program (the even vertices are the
 * receivers' own, already in IN.receivers). */
struct VolumeChunk {
    int volume, first, last; /* triangles [first, last) of volume VOLUME */
};
std::vector<VolumeChunk> volume_chunks(const std::vector<Volume> &volumes);
/* A volume's double-length vertex buffer in clip space: only the vertices
 * its drawn indices use are computed (a surface's vertices are many, and
 * a volume uses few of them: the demo terrain's 53k vertices against a
 * volume of a few thousand indices); the others are left undefined. */
using ShadowVertexBuffer = std::unique_ptr<raster::ClipVertex[]>;
std::vector<ShadowVertexBuffer> shadow_vertex_buffers(const StencilPassInputs &in);

/* Runs on the calling task arena's threads. */
StencilPassResult stencil_pass(StencilMethod method, const StencilPassInputs &in);

/* The methods (one file each). */
StencilPassResult stencil_pass_brute_force(const StencilPassInputs &in);
StencilPassResult stencil_pass_depth_bounds(const StencilPassInputs &in);
StencilPassResult stencil_pass_hierarchical(const StencilPassInputs &in);
StencilPassResult stencil_pass_automatic(const StencilPassInputs &in);

/* The stages the automatic method shares with bf and hier (RESULT's
 * stencil allocated and cleared, its timing the caller's). */
namespace detail {
/* bf's walk: BT's chunks set up, binned and given their modes. */
void brute_force_walk(const StencilPassInputs &in, const BinnedTriangles &bt,
                      StencilPassResult &result);
/* hier from the shared set-up on (its open edges, caps, classification
 * and walks). */
void hierarchical_stencil(const StencilPassInputs &in, PieceSetup &&setup,
                          StencilPassResult &result);
void check_stencil_tile(int side); /* throws std::invalid_argument */
} // namespace detail

} // namespace sv::render

#endif
