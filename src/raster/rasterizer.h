/*
 * The project's own triangle rasteriser for depth and stencil (issue 12):
 * deterministic, watertight, and counting what it touches.
 *
 * Pipeline per triangle, given its three vertices in clip space (double):
 *  1. Homogeneous clipping against the near plane (z >= -w) and the four
 *     side planes (|x|, |y| <= w). There is no far plane: with the
 *     infinite projection of shadowvol_scene.h, vertices at w = 0 (the
 *     extruded ones) land at depth 1 - 2^-21. An edge is always cut from
 *     its inside end towards its outside end, so the two triangles sharing
 *     an edge get bit-identical new vertices (watertight after clipping).
 *  2. Window coordinates, y down (row 0 = the image's top), snapped to
 *     1/256 pixel (8 sub-pixel bits), round to nearest.
 *  3. Fixed-point edge functions in 64-bit integers, sampled at pixel
 *     centres (x + 1/2, y + 1/2), with the fill rule below: every pixel
 *     centre on an edge shared by two triangles is covered by exactly one.
 *  4. Depth: window depth (z_ndc + 1) / 2 as an affine function of the
 *     snapped window position, from a canonical choice of three polygon
 *     vertices, so the same triangle drawn with its corners in any order
 *     (a near cap is the triangle reversed) gets bit-identical depths.
 *     Evaluated in double, rounded to float, compared with LESS.
 *
 * Fill rule: see fill_rule.h (the one place that decides it).
 *
 * Front faces are counter-clockwise in GL window space (y up), as in
 * OpenGL's default, so the same index list has the same facing here and in
 * Mesa.
 *
 * Copyright (C) 2026 the shadowvol authors. LGPL-2.1-or-later.
 */
#ifndef SV_RASTER_RASTERIZER_H
#define SV_RASTER_RASTERIZER_H

#include <cstddef>
#include <cstdint>
#include <new>
#include <string>
#include <utility>
#include <vector>

#include "row_kernels.h"

namespace sv::raster {

/* The largest target side the fixed-point edge functions are proved for
 * (row_walk.h, walk_rows: 1/256-pixel coordinates below 2^21 + 2^8):
 * Target::resize and Rasterizer::setup refuse larger ones
 * (std::invalid_argument). */
constexpr int kMaxTargetSide = 8192;

/* A clip-space vertex (x, y, z, w). */
struct ClipVertex {
    double x, y, z, w;
};

/* What a pass touched. "Tested": covered pixel centres whose depth was
 * compared; "written": pixels whose depth (depth pass) or stencil
 * (stencil pass) changed hands. Bytes count one read per test and one
 * write per written pixel, per buffer. */
struct PassCounters {
    uint64_t triangles = 0;            /* submitted */
    uint64_t triangles_clipped = 0;    /* crossed a clip plane and were cut */
    uint64_t triangles_outside = 0;    /* wholly outside the view volume */
    uint64_t triangles_degenerate = 0; /* zero area after snapping */
    uint64_t pixels_tested = 0;
    uint64_t pixels_written = 0;
    uint64_t rows = 0; /* row spans walked (a sliver's cost is per row as much as per pixel) */
    uint64_t depth_bytes_read = 0;
    uint64_t depth_bytes_written = 0;
    uint64_t stencil_bytes_read = 0;
    uint64_t stencil_bytes_written = 0;
    void add(const PassCounters &o);
};

/* An allocator for frame buffers: 2 MiB aligned, and asks the kernel for
 * transparent huge pages (madvise). A shadow volume's slivers are tall and
 * thin: with 4 KiB pages every row of a 1280-pixel depth buffer is a page
 * of its own, and the stencil pass was bound by TLB misses, one per row. */
template <class T> struct FrameAllocator {
    using value_type = T;
    FrameAllocator() noexcept = default;
    template <class U> FrameAllocator(const FrameAllocator<U> &) noexcept {}
    T *allocate(std::size_t n);
    void deallocate(T *p, std::size_t n) noexcept;
    /* resize(n) leaves new elements uninitialised (they are numbers): a
     * frame's buffers are filled right after, band by band in parallel
     * (Target::clear_rows), not zeroed first on one thread. */
    template <class U> void construct(U *p) noexcept { ::new (static_cast<void *>(p)) U; }
    template <class U, class... A> void construct(U *p, A &&...a) {
        ::new (static_cast<void *>(p)) U(std::forward<A>(a)...);
    }
    template <class U> bool operator==(const FrameAllocator<U> &) const noexcept { return true; }
    template <class U> bool operator!=(const FrameAllocator<U> &) const noexcept { return false; }
};
/* At least kFrameSlack bytes after the end of every frame buffer are
 * allocated and readable (never written). */
void *allocate_frame_bytes(std::size_t bytes);
void free_frame_bytes(void *p) noexcept;
template <class T> T *FrameAllocator<T>::allocate(std::size_t n) {
    if (n > std::size_t(-1) / sizeof(T)) throw std::bad_array_new_length();
    return static_cast<T *>(allocate_frame_bytes(n * sizeof(T)));
}
template <class T> void FrameAllocator<T>::deallocate(T *p, std::size_t) noexcept {
    free_frame_bytes(p);
}
template <class T> using FrameBuffer = std::vector<T, FrameAllocator<T>>;

/* The buffers of one frame. Depth is window depth in [0, 1]; ids name the
 * triangle that wrote the depth (-1: none). */
struct Target {
    int width = 0, height = 0;
    FrameBuffer<float> depth;
    FrameBuffer<int32_t> ids;
    FrameBuffer<uint8_t> stencil;
    /* Bytes a WIDTH x HEIGHT target takes (depth, ids, stencil). */
    static uint64_t bytes_for(int width, int height);
    /* Throws std::invalid_argument unless 1 <= WIDTH, HEIGHT <=
     * kMaxTargetSide. */
    void resize(int width, int height);
    /* resize() without the fill: the buffers' contents are undefined until
     * clear_rows() has run over every row (for a fill spread over threads). */
    void allocate(int width, int height);
    /* Rows [ROW_BEGIN, ROW_END): depth 1, ids -1, stencil 0. */
    void clear_rows(int row_begin, int row_end);
    void clear_depth();   /* depth 1, ids -1 */
    void clear_stencil(); /* 0 */
};

enum class StencilMode { zpass, zfail };

/* One triangle (a piece of a clipped polygon's fan) after set-up: what the
 * row walk needs, so that set-up runs once per triangle while the rows are
 * walked band by band (screen bands in parallel, each band in submission
 * order: the same buffers at every band count). */
struct SetupTriangle {
    int64_t e_origin[3]; /* edge functions at pixel (0, 0)'s centre, biased */
    int64_t step_x[3], step_y[3];
    double x0, y0, z0, a, b;              /* depth plane (pixels) */
    int x_first, x_last, y_first, y_last; /* pixel bounds, inclusive */
    int32_t id;                           /* depth pass: the id to write */
    bool front;
};

/* A piece as snapped, in 1/256 pixel (y down), before its pixel bounds
 * are clamped to the frame: what a tile classifier needs to know where the
 * piece lies between pixel centres too (a sliver that covers no centre of
 * a tile can still cross the tile's box). */
struct PieceExtent {
    int64_t min_x, max_x, min_y, max_y;
    int64_t X[3], Y[3]; /* its corners */
    /* How far the polygon's corners (snapped, with their own depth) are
     * from the depth plane (chosen through three of them): 0 for a
     * triangle, a little for a clipped polygon. */
    double off_plane;
};

/* Depth bounds for a stencil walk (the depth-bounds test): a pixel whose
 * stored depth d has !(d > skip_at_or_below) or d > skip_above is not
 * tested at all. */
struct DepthBounds {
    float skip_at_or_below, skip_above;
};

/* A vertex's window position as set-up snaps it, and the clip planes it
 * lies outside of: worked out once per vertex of a mesh whose triangles
 * share their corners (the depth pass), so that a triangle inside every
 * plane skips clipping and snapping (Rasterizer::setup_shared). */
struct WindowVertex {
    int64_t X = 0, Y = 0;  /* 1/256 pixel, y down */
    double z = 0;          /* window depth */
    uint8_t outside = 0;   /* bit P: outside clip plane P (near, left, right, bottom, top) */
    bool drawable = false; /* w > 0 and finite: set-up can snap it */
};
WindowVertex window_vertex(const ClipVertex &v, int width, int height);

/* A band of rows [row_begin, row_end) of a target. */
struct RowBand {
    int row_begin, row_end;
};

class Rasterizer {
public:
    /* KERNELS: the row kernels to use (row_kernels_by_name / best). */
    explicit Rasterizer(const RowKernels *kernels);
    const RowKernels &kernels() const { return *kernels_; }

    /* Depth pass: where the triangle is nearer (LESS), write its depth and
     * ID. Both faces are drawn (no culling). */
    void draw_depth(Target &t, const ClipVertex v[3], int32_t id, PassCounters &c) const;

    /* Stencil pass, depth read only. zpass: front faces +1, back faces -1
     * (mod 256) where the depth test passes; zfail: back faces +1, front
     * faces -1 where it fails. */
    void draw_stencil(Target &t, const ClipVertex v[3], StencilMode mode, PassCounters &c) const;

    /* Set-up of one input triangle: clipping, snapping, edge functions and
     * the depth plane; appends 0 to 6 pieces to OUT (none when it is
     * outside, degenerate or covers no pixel centre's box). Counts the
     * triangle in C (triangles, clipped, outside, degenerate). With
     * EXTENTS, pieces that cover no pixel centre are kept too (empty pixel
     * bounds) and each piece's extent is appended there, one per piece. */
    void setup(const ClipVertex v[3], int width, int height, int32_t id, PassCounters &c,
               std::vector<SetupTriangle> &out, std::vector<PieceExtent> *extents = nullptr) const;
    /* setup() of a triangle whose corners' window_vertex() are W: the same
     * pieces and counts, without clipping or snapping again when all three
     * lie inside every plane. */
    void setup_shared(const ClipVertex v[3], const WindowVertex w[3], int width, int height,
                      int32_t id, PassCounters &c, std::vector<SetupTriangle> &out) const;
    /* The rows of T inside BAND: depth pass into T's depth and ids. */
    void walk_depth(const SetupTriangle &tri, Target &t, RowBand band, RowCounts &r) const;
    /* The rows of TRI inside BAND: stencil pass against DEPTH into
     * STENCIL (both WIDTH pixels per row; DEPTH with kFrameSlack after it:
     * row_kernels.h's WalkBuffers). */
    void walk_stencil(const SetupTriangle &tri, const float *depth, uint8_t *stencil, int width,
                      int height, RowBand band, StencilMode mode, RowCounts &r) const;
    /* walk_stencil with the depth-bounds test BOUNDS first (the C rows:
     * the same bits for the pixels it tests). */
    void walk_stencil_bounded(const SetupTriangle &tri, const float *depth, uint8_t *stencil,
                              int width, RowBand band, StencilMode mode, DepthBounds bounds,
                              RowCounts &r) const;
    /* The seed's saturating stencil operation (IncrSat; seed 002, issue
     * 31): where TRI passes MODE's test (and BOUNDS, as
     * walk_stencil_bounded's; infinite bounds test every pixel), COUNT =
     * min(255, COUNT + 1), whichever way TRI faces. A saturating stencil
     * keeps its increments and decrements in two such counts
     * (stencil_pass.h). The C rows: the same pixels as walk_stencil's. */
    void walk_stencil_saturating(const SetupTriangle &tri, const float *depth, uint8_t *count,
                                 int width, RowBand band, StencilMode mode, DepthBounds bounds,
                                 RowCounts &r) const;
    /* Pixel centres [x_begin, x_end) of row y. */
    struct CoveredSpan {
        int y, x_begin, x_end;
    };
    /* The pixel centres of TRI in BAND's rows, by the fill rule alone (no
     * depth, nothing counted): one span per row that has any, appended to
     * OUT. They are the pixels every walk tests (the same edge functions,
     * the same padded span shrunk to the covered centres; a triangle's
     * centres on a row are one run). For a triangle whose depth test is
     * known to fail at every pixel (stencil_hier.cpp: the receiver's own
     * caps in z-fail), its stencil count is its delta on exactly these. */
    static void covered_spans(const SetupTriangle &tri, RowBand band,
                              std::vector<CoveredSpan> &out);
    /* Adds a pass's pixel counts R to C (bytes as the draw_* functions
     * count them). */
    static void add_depth_counts(const RowCounts &r, PassCounters &c);
    static void add_stencil_counts(const RowCounts &r, PassCounters &c);

    /* For tests and the GL comparison: the triangle's pieces after
     * clipping, as window-space triangles in pixels (x, y down, depth),
     * the coordinates the coverage test uses (snapped). */
    struct WindowTriangle {
        double x[3], y[3], z[3];
        bool front;
    };
    std::vector<WindowTriangle> window_triangles(const ClipVertex v[3], int width,
                                                 int height) const;

    /* The depth plane the rasteriser uses for the triangle (after
     * clipping), as depth = z0 + a (x - x0) + b (y - y0) in pixels: for
     * tests that it does not depend on the corners' order (coefficients
     * that differ in the last bit of a double rarely change a float depth,
     * so comparing depth buffers alone would hardly notice). ok = false
     * when nothing is left to draw. */
    struct PlaneCoefficients {
        double x0, y0, z0, a, b;
        bool ok;
    };
    PlaneCoefficients depth_plane(const ClipVertex v[3], int width, int height) const;

private:
    const RowKernels *kernels_;
};

} // namespace sv::raster

#endif
