/*
 * The inner loop of the rasteriser: one row span of one triangle. The
 * triangle setup (rasterizer.cpp) hands over the three edge functions at
 * the span's first pixel and their steps per pixel, and the depth plane;
 * the kernel tests coverage pixel by pixel exactly (64-bit integers), then
 * depth, then updates depth or stencil.
 *
 * Three versions compute bit-identical buffers and counts (a test checks):
 *   c       one pixel per step;
 *   avx2    8 pixels per step: the edge functions in 4 x 64-bit lanes (two
 *           registers per edge), depth in 4 x double lanes, one 8-wide
 *           float compare; the tail of fewer than 8 pixels in C;
 *   avx512  16 pixels per step (two zmm of 8 x 64-bit per edge, 16 floats),
 *           opmasks for coverage, the test and the span's tail: no scalar
 *           tail, masked loads and stores only where the span is.
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

struct RowSpan {
    /* Edge functions at pixel x_begin, biased by the fill rule: the pixel
     * is covered when all three are >= 0. step: change per pixel in x. */
    int64_t e[3];
    int64_t step[3];
    /* Depth at pixel x: (float)(zrow + dzdx * (((double)x + 0.5) - x0)). */
    double zrow, dzdx, x0;
    int x_begin, x_end; /* pixels [x_begin, x_end) of the row */
};

/* Spans of at most this many pixels go to the C kernel from the SIMD ones:
 * a shadow volume's silhouette quads are long slivers, most of whose rows
 * are a few pixels wide, and there the vector set-up costs more than it
 * saves (measured with a sliver of 3 and of 8 pixels per row: C 44 and 105
 * ns a row, AVX2 63 and 115; from 16 pixels on AVX2 is ahead). The result
 * is the same either way: the versions are bit-identical. */
constexpr int kShortSpan = 8;

/* Bytes the SIMD kernels may READ past a row's last pixel (a whole vector
 * of depth from the span's last block; nothing outside [x_begin, x_end) is
 * ever written). Masked loads would avoid it, but on AMD cores a masked
 * load is many times slower than a plain one (measured: the AVX2 stencil
 * kernel spent two thirds of its time in vmaskmovps). FrameAllocator
 * (rasterizer.h) leaves this much after every buffer. */
constexpr int kFrameSlack = 64;

/* Row pointers (the row's pixel 0). */
struct RowBuffers {
    float *depth;
    int32_t *ids;     /* depth pass only */
    uint8_t *stencil; /* stencil passes only */
};

struct RowCounts {
    uint64_t tested = 0;  /* covered pixels (each reads one depth) */
    uint64_t written = 0; /* pixels updated */
};

/* depth:  covered and z < depth  ->  depth = z, ids = id
 * zpass:  covered and z < depth  ->  stencil += delta (mod 256)
 * zfail:  covered and !(z < depth) -> stencil += delta (mod 256)
 * The counts are ADDED to *n (a caller sums a triangle's rows there: a
 * struct returned in rax:rdx and summed into memory was stored as two
 * halves and reloaded as one vector by the compiler, a store-forwarding
 * stall on every row). */
typedef void (*row_depth_fn)(const RowSpan &s, const RowBuffers &b, int32_t id, RowCounts &n);
typedef void (*row_stencil_fn)(const RowSpan &s, const RowBuffers &b, uint8_t delta, RowCounts &n);

struct RowKernels {
    const char *name;
    unsigned isa; /* SV_ISA_* bits the CPU must have (shadowvol.h) */
    row_depth_fn depth;
    row_stencil_fn zpass;
    row_stencil_fn zfail;
};

/* c, avx2, avx512: every version compiled in (check isa against
 * sv_cpu_isa() before calling one). */
const RowKernels *const *row_kernels_all(int *count);
const RowKernels *row_kernels_by_name(const char *name);
/* The last entry that sv_cpu_isa() allows (the SV_ISA limit applies). */
const RowKernels *row_kernels_best();

/* The individual versions (row_kernels_*.cpp). */
extern const RowKernels kRowKernelsC;
extern const RowKernels kRowKernelsAvx2;
extern const RowKernels kRowKernelsAvx512;

} // namespace sv::raster

#endif
