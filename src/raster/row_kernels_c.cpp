/*
 * The row kernels in plain C++ (one pixel per step): the reference the
 * SIMD versions must match bit for bit, and the table of all versions.
 *
 * Copyright (C) 2026 the shadowvol authors. LGPL-2.1-or-later.
 */
#include "row_kernels.h"

#include "shadowvol.h"

namespace sv::raster {
namespace {

/* The depth of pixel x, in the operation order every version uses. */
inline float depth_at(const RowSpan &s, int x) {
    const double dx = ((double)x + 0.5) - s.x0;
    return (float)(s.zrow + s.dzdx * dx);
}

void depth_c(const RowSpan &s, const RowBuffers &b, int32_t id, RowCounts &n) {
    /* Local counts: a stencil byte store may alias *n, a local cannot. */
    uint64_t tested = 0, written = 0;
    int64_t e0 = s.e[0], e1 = s.e[1], e2 = s.e[2];
    for (int x = s.x_begin; x < s.x_end; x++) {
        if ((e0 | e1 | e2) >= 0) {
            tested++;
            const float z = depth_at(s, x);
            if (z < b.depth[x]) {
                b.depth[x] = z;
                b.ids[x] = id;
                written++;
            }
        }
        e0 += s.step[0], e1 += s.step[1], e2 += s.step[2];
    }
    n.tested += tested;
    n.written += written;
}

template <bool kFail> void stencil_c(const RowSpan &s, const RowBuffers &b, uint8_t delta, RowCounts &n) {
    /* Local counts: a stencil byte store may alias *n, a local cannot. */
    uint64_t tested = 0, written = 0;
    int64_t e0 = s.e[0], e1 = s.e[1], e2 = s.e[2];
    for (int x = s.x_begin; x < s.x_end; x++) {
        if ((e0 | e1 | e2) >= 0) {
            tested++;
            const bool less = depth_at(s, x) < b.depth[x];
            if (less != kFail) {
                b.stencil[x] = (uint8_t)(b.stencil[x] + delta);
                written++;
            }
        }
        e0 += s.step[0], e1 += s.step[1], e2 += s.step[2];
    }
    n.tested += tested;
    n.written += written;
}

const RowKernels *const kAll[] = {&kRowKernelsC, &kRowKernelsAvx2, &kRowKernelsAvx512};

} // namespace

const RowKernels kRowKernelsC = {"c", SV_ISA_NONE, depth_c, stencil_c<false>, stencil_c<true>};

const RowKernels *const *row_kernels_all(int *count) {
    *count = (int)(sizeof kAll / sizeof kAll[0]);
    return kAll;
}

const RowKernels *row_kernels_by_name(const char *name) {
    for (const RowKernels *k : kAll) {
        const char *a = k->name, *b = name;
        while (*a && *a == *b) a++, b++;
        if (*a == 0 && *b == 0) return k;
    }
    return nullptr;
}

const RowKernels *row_kernels_best() {
    const unsigned isa = sv_cpu_isa();
    const RowKernels *best = &kRowKernelsC;
    for (const RowKernels *k : kAll) {
        if ((k->isa & isa) == k->isa) best = k;
    }
    return best;
}

} // namespace sv::raster
