/*
 * A light's shadow volumes set up once for the stencil methods that skip
 * pixels (depth bounds, hierarchical; internal to src/render): every drawn
 * triangle through the paper's vertex program and the rasteriser's set-up,
 * each piece kept with its extent, its volume, its stencil delta and
 * whether the argument that lets a method skip pixels holds for it
 * (open_edges.h; a triangle cut by the near plane is open there too).
 *
 * Copyright (C) 2026 the shadowvol authors. LGPL-2.1-or-later.
 */
#ifndef SV_RENDER_VOLUME_PIECES_H
#define SV_RENDER_VOLUME_PIECES_H

#include <cstdint>
#include <vector>

#include "rasterizer.h"
#include "stencil_pass.h"

namespace sv::render::detail {

constexpr uint8_t kOpenWhole = 8;

/* The set-up's records of the pieces, left where the set-up wrote them
 * (PieceSetup::ChunkOut, kept by VolumePieces) and reached through a
 * pointer each: gathering them in one array copied 224 bytes a piece, and
 * faulted in fresh pages for them, on every pass. */
template <class T> class PieceRecords {
public:
    const T &operator[](std::size_t q) const { return *at_[q]; }
    std::size_t size() const { return at_.size(); }
    void reserve(std::size_t n) { at_.reserve(n); }
    void push_back(const T &record) { at_.push_back(&record); }

private:
    std::vector<const T *> at_;
};

struct VolumePieces {
    VolumePieces() = default;
    VolumePieces(VolumePieces &&) = default;
    VolumePieces &operator=(VolumePieces &&) = default;
    /* A copy's records would point into the original's chunks. */
    VolumePieces(const VolumePieces &) = delete;
    VolumePieces &operator=(const VolumePieces &) = delete;
    /* In submission order (volume by volume, triangle by triangle), pieces
     * that cover no pixel centre included (empty pixel bounds). */
    PieceRecords<raster::SetupTriangle> pieces;
    PieceRecords<raster::PieceExtent> extents;
    std::vector<int> volume;    /* per piece */
    std::vector<uint8_t> delta; /* per piece: 1 or 255, by facing and the volume's mode */
    /* Per piece: 1 where its triangle has an open edge or the near plane
     * cut it (the cut is an edge of no other piece); the visible parts of
     * those edges, as the view clips them, in window pixels (y down):
     * segments [open_first[q], open_first[q + 1]); kOpenWhole where one
     * could not be projected (the piece as a whole is open). */
    std::vector<uint8_t> open;
    struct Segment {
        double x0, y0, x1, y1;
    };
    std::vector<Segment> open_segments;
    std::vector<int> open_first; /* per piece, and one past the last */
    /* Per piece: 1 where its triangle is one of the receiver's own (a cap
     * made of the surface's vertices, as the depth pass drew them, in
     * either order): its depth at every pixel it covers is the depth pass's
     * value for that triangle, never less than the stored depth, so its
     * test fails there, whatever the tile. The edges where such triangles
     * do not close among themselves (the silhouette, where the sides
     * attach), visible parts as above: [cap_first[q], cap_first[q + 1]). */
    std::vector<uint8_t> receiver;
    std::vector<Segment> cap_segments;
    std::vector<int> cap_first;
    std::vector<int> first_piece; /* per volume, and one past the last */
    /* Per volume: no open piece, so its count is 0 wherever every one of
     * its triangles passes the depth test, and wherever every one fails. */
    std::vector<uint8_t> closed;
    std::vector<uint8_t> zfail; /* per volume */
    /* Per volume: z-fail, and every triangle of the receiver's own among
     * its pieces is flagged in RECEIVER (none lost its flag to an edge
     * that could not be projected), so the edges between those pieces and
     * the others are all in CAP_SEGMENTS: a method may then take the
     * receiver's pieces out of the volume and add their counts by
     * coverage alone (stencil_hier.cpp). */
    std::vector<uint8_t> caps_by_coverage;
    raster::PassCounters counters; /* triangle counts of the set-up */
    /* Where PIECES and EXTENTS point: the set-up's chunks, moved here. */
    std::vector<std::vector<raster::SetupTriangle>> piece_chunks;
    std::vector<std::vector<raster::PieceExtent>> extent_chunks;
};

/* The first half of the set-up, what brute force's set-up does too (so
 * the automatic method can choose after it, stencil_auto.cpp): the
 * volumes' triangles set up in chunks (volume_chunks), each chunk's
 * pieces, their extents and the triangle each came from; per volume and
 * triangle whether it drew nothing and whether the near plane cut it. */
struct PieceSetup {
    std::vector<VolumeChunk> chunks;
    std::vector<ShadowVertexBuffer> sv_clip; /* per volume (shadow_vertex_buffers) */
    struct ChunkOut {
        std::vector<raster::SetupTriangle> pieces;
        std::vector<raster::PieceExtent> extents;
        std::vector<int> triangle;
        raster::PassCounters counters;
    };
    std::vector<ChunkOut> chunk_out; /* per chunk */
    std::vector<std::vector<uint8_t>> degenerate, near_cut;
};

/* Each runs on the calling task arena's threads; the same result at
 * every thread count. */
PieceSetup set_up_pieces(const StencilPassInputs &in);
/* The second half: per volume its open edges and the receiver's caps,
 * the pieces in submission order. */
VolumePieces finish_volume_pieces(const StencilPassInputs &in, PieceSetup &&ps);
/* Both halves. */
VolumePieces set_up_volume_pieces(const StencilPassInputs &in);

} // namespace sv::render::detail

#endif
