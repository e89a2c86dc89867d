/*
 * The inner loops of the rasteriser, one set per instruction set: the
 * triangle walks, each a whole set-up triangle's rows inside a band in
 * one call. Set-up (rasterizer.cpp) hands over the three edge functions
 * (64-bit integers, exact), their steps per pixel and per row, the depth
 * plane and the pixel bounds; a walk finds each row's span (row_walk.h),
 * tests coverage pixel by pixel exactly, then depth, then updates depth
 * or stencil.
 *
 * Three versions compute bit-identical buffers and counts (tests check):
 *   c       row_walk.h's spans through the C rows of row_kernels_c.h, one
 *           pixel per step (triangle_walk_c.cpp; the reference);
 *   avx2    the span bounds of the three edges in one vector, blocks of 8
 *           pixels from the span's first (triangle_walk_avx2.cpp);
 *   avx512  the same spans, blocks of 8 or 16 pixels under opmasks
 *           (triangle_walk_avx512.cpp).
 * A shadow volume's silhouette quads are slivers, a few pixels by hundreds
 * of rows: what a row costs around its pixels (a call, the span, a scalar
 * loop) is what the SIMD walks take away.
 * Depth is computed identically in all three: dx = ((double)x + 0.5) - x0;
 * z = (float)(zrow + dzdx * dx), no FMA (the files are compiled with
 * -ffp-contract=off, and the SIMD code uses separate mul and add).
 *
 * Copyright (C) 2026 the shadowvol authors. LGPL-2.1-or-later.
 */
#ifndef SV_RASTER_ROW_KERNELS_H
#define SV_RASTER_ROW_KERNELS_H

#include <cstdint>

namespace sv::raster {

/* One row's span of a triangle, for the C rows (row_kernels_c.h). */
struct RowSpan {
    /* Edge functions at pixel x_begin, biased by the fill rule: the pixel
     * is covered when all three are >= 0. step: change per pixel in x. */
    int64_t e[3];
    int64_t step[3];
    /* Depth at pixel x: (float)(zrow + dzdx * (((double)x + 0.5) - x0)). */
    double zrow, dzdx, x0;
    int x_begin, x_end; /* pixels [x_begin, x_end) of the row */
};

/* Bytes the SIMD walks may READ past a row's last pixel (a whole vector
 * of depth from a span's last block; nothing outside a span is ever
 * written). Masked loads would avoid it, but on AMD cores a masked load is
 * many times slower than a plain one (measured: an AVX2 stencil kernel
 * spent two thirds of its time in vmaskmovps). FrameAllocator
 * (rasterizer.h) leaves this much after every buffer. */
constexpr int kFrameSlack = 64;

/* Row pointers (the row's pixel 0), for the C rows. */
struct RowBuffers {
    float *depth;
    int32_t *ids;     /* depth pass only */
    uint8_t *stencil; /* stencil passes only */
};

struct RowCounts {
    uint64_t tested = 0;  /* covered pixels (each reads one depth) */
    uint64_t written = 0; /* pixels updated */
    uint64_t rows = 0;    /* rows walked: rows whose span (row_walk.h) is not empty */
};

struct SetupTriangle; /* rasterizer.h */
struct RowBand;       /* rasterizer.h */

/* A target's buffers for a triangle walk: WIDTH x HEIGHT pixels each,
 * depth with kFrameSlack readable bytes after it (ids and stencil need
 * none). */
struct WalkBuffers {
    float *depth;
    int32_t *ids;     /* depth pass only */
    uint8_t *stencil; /* stencil passes only */
    int width, height;
};

/* The rows of TRI inside BAND, each pixel:
 *   depth:  covered and z < depth  ->  depth = z, ids = tri.id
 *   zpass:  covered and z < depth  ->  stencil += delta (mod 256)
 *   zfail:  covered and !(z < depth) -> stencil += delta (mod 256)
 * The counts are ADDED to N. A walk writes nothing outside its spans, and
 * reads and rewrites unchanged bytes only within the triangle's pixel
 * bounds [x_first, x_last] of the rows it walks: a caller that clamps a
 * triangle to the pixels it owns (as the hierarchical stencil does per
 * tile) keeps the walk's writes there. */
typedef void (*walk_depth_fn)(const SetupTriangle &tri, const RowBand &band, const WalkBuffers &b,
                              RowCounts &n);
typedef void (*walk_stencil_fn)(const SetupTriangle &tri, const RowBand &band, const WalkBuffers &b,
                                uint8_t delta, RowCounts &n);

struct RowKernels {
    const char *name;
    unsigned isa; /* SV_ISA_* bits the CPU must have (shadowvol.h) */
    walk_depth_fn walk_depth;
    walk_stencil_fn walk_zpass;
    walk_stencil_fn walk_zfail;
};

/* c, avx2, avx512: every version compiled in (check isa against
 * sv_cpu_isa() before calling one). */
const RowKernels *const *row_kernels_all(int *count);
const RowKernels *row_kernels_by_name(const char *name);
/* The last entry that sv_cpu_isa() allows (the SV_ISA limit applies). */
const RowKernels *row_kernels_best();

/* The individual versions (triangle_walk_*.cpp). */
extern const RowKernels kRowKernelsC;
extern const RowKernels kRowKernelsAvx2;
extern const RowKernels kRowKernelsAvx512;

} // namespace sv::raster

#endif
