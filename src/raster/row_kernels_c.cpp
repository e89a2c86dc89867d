/*
 * The table of the rasteriser's kernels (row_kernels.h), and the C
 * version's entry.
 *
 * Copyright (C) 2026 the shadowvol authors. LGPL-2.1-or-later.
 */
#include "row_kernels.h"
#include "triangle_walk.h"

#include "shadowvol.h"

namespace sv::raster {
namespace {

const RowKernels *const kAll[] = {&kRowKernelsC, &kRowKernelsAvx2, &kRowKernelsAvx512};

} // namespace

const RowKernels kRowKernelsC = {"c", SV_ISA_NONE, walk_depth_c, walk_zpass_c, walk_zfail_c};

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
