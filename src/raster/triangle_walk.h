/*
 * The triangle walks of row_kernels.h, one set per instruction set:
 * triangle_walk_c.cpp (the reference: row_walk.h's spans through the C
 * rows), triangle_walk_avx2.cpp and triangle_walk_avx512.cpp. Each
 * version's RowKernels table (row_kernels_*.cpp) points at its walks.
 *
 * Copyright (C) 2026 the shadowvol authors. LGPL-2.1-or-later.
 */
#ifndef SV_RASTER_TRIANGLE_WALK_H
#define SV_RASTER_TRIANGLE_WALK_H

#include "row_kernels.h"

namespace sv::raster {

void walk_depth_c(const SetupTriangle &tri, const RowBand &band, const WalkBuffers &b,
                  RowCounts &n);
void walk_zpass_c(const SetupTriangle &tri, const RowBand &band, const WalkBuffers &b,
                  uint8_t delta, RowCounts &n);
void walk_zfail_c(const SetupTriangle &tri, const RowBand &band, const WalkBuffers &b,
                  uint8_t delta, RowCounts &n);

void walk_depth_avx2(const SetupTriangle &tri, const RowBand &band, const WalkBuffers &b,
                     RowCounts &n);
void walk_zpass_avx2(const SetupTriangle &tri, const RowBand &band, const WalkBuffers &b,
                     uint8_t delta, RowCounts &n);
void walk_zfail_avx2(const SetupTriangle &tri, const RowBand &band, const WalkBuffers &b,
                     uint8_t delta, RowCounts &n);

void walk_depth_avx512(const SetupTriangle &tri, const RowBand &band, const WalkBuffers &b,
                       RowCounts &n);
void walk_zpass_avx512(const SetupTriangle &tri, const RowBand &band, const WalkBuffers &b,
                       uint8_t delta, RowCounts &n);
void walk_zfail_avx512(const SetupTriangle &tri, const RowBand &band, const WalkBuffers &b,
                       uint8_t delta, RowCounts &n);

} // namespace sv::raster

#endif
