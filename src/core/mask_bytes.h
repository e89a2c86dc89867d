/*
 * Eight mask bits (a movemask of 8 lanes) as eight 0/1 bytes, by table:
 * kMaskBytes[m] has byte k = bit k of m. The SIMD facing and cull-bit
 * kernels store their results this way instead of with BMI2's
 * pdep(m, 0x0101010101010101): pdep is microcoded on AMD before Zen 3
 * (18 or more cycles per set bit of the mask), where it made the AVX2
 * CalculateFacing slower than the C reference; a 2 KiB table in L1 costs
 * one load on every CPU.
 *
 * Copyright (C) 2026 the shadowvol authors. LGPL-2.1-or-later.
 */
#ifndef SV_MASK_BYTES_H
#define SV_MASK_BYTES_H

#include <stdint.h>

#define SV_MB1(m)                                                                                  \
    ((uint64_t)((m)&1) | (uint64_t)((m) >> 1 & 1) << 8 | (uint64_t)((m) >> 2 & 1) << 16 |          \
     (uint64_t)((m) >> 3 & 1) << 24 | (uint64_t)((m) >> 4 & 1) << 32 |                             \
     (uint64_t)((m) >> 5 & 1) << 40 | (uint64_t)((m) >> 6 & 1) << 48 |                             \
     (uint64_t)((m) >> 7 & 1) << 56)
#define SV_MB4(m) SV_MB1(m), SV_MB1((m) + 1), SV_MB1((m) + 2), SV_MB1((m) + 3)
#define SV_MB16(m) SV_MB4(m), SV_MB4((m) + 4), SV_MB4((m) + 8), SV_MB4((m) + 12)
#define SV_MB64(m) SV_MB16(m), SV_MB16((m) + 16), SV_MB16((m) + 32), SV_MB16((m) + 48)

static const uint64_t kMaskBytes[256] = {SV_MB64(0), SV_MB64(64), SV_MB64(128), SV_MB64(192)};

#undef SV_MB64
#undef SV_MB16
#undef SV_MB4
#undef SV_MB1

#endif
