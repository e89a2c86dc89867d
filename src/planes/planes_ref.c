/*
 * The C references of include/shadowvol_planes.h (the oracle of every SIMD
 * variant), and the variant table.
 *
 * Copyright (C) 2026 the shadowvol authors. LGPL-2.1-or-later.
 */
#include <string.h>

#include "planes_internal.h"

void sv_derive_planes_c_ref(const float *positions, const int *indices, int numTriangles,
                            Plane *planes) {
    for (int t = 0; t < numTriangles; t++) planes[t] = sv_plane_one(positions, indices + 3 * t);
}

void sv_facing_from_positions_c_ref(const float *positions, const int *indices, int numTriangles,
                                    const Vec4 *light, uint8_t *facing) {
    if (numTriangles < 0) return;
    for (int t = 0; t < numTriangles; t++)
        facing[t] = sv_facing_from_positions_one(positions, indices + 3 * t, light);
    facing[numTriangles] = 1;
}

static const sv_planes_variant planes_variants[] = {
    {"c_ref", SV_ISA_NONE, sv_derive_planes_c_ref, sv_facing_from_positions_c_ref},
    {"sse2", SV_ISA_SSE2, sv_derive_planes_sse2, sv_facing_from_positions_sse2},
    {"avx2_gather", SV_ISA_SSE2 | SV_ISA_AVX2, sv_derive_planes_avx2_gather,
     sv_facing_from_positions_avx2_gather},
    {"avx2", SV_ISA_SSE2 | SV_ISA_AVX2, sv_derive_planes_avx2, sv_facing_from_positions_avx2},
    {"avx512", SV_ISA_SSE2 | SV_ISA_AVX2 | SV_ISA_AVX512, sv_derive_planes_avx512,
     sv_facing_from_positions_avx512},
};

#define NUM_PLANES_VARIANTS (sizeof planes_variants / sizeof planes_variants[0])

const sv_planes_variant *sv_planes_variants(int *count) {
    if (count) *count = (int)NUM_PLANES_VARIANTS;
    return planes_variants;
}

const sv_planes_variant *sv_planes_variant_by_name(const char *name) {
    for (size_t i = 0; name && i < NUM_PLANES_VARIANTS; i++) {
        if (strcmp(planes_variants[i].name, name) == 0) return &planes_variants[i];
    }
    return NULL;
}

const sv_planes_variant *sv_best_planes_variant(void) {
    const unsigned isa = sv_cpu_isa();
    size_t i = NUM_PLANES_VARIANTS;
    while (i-- > 1) {
        if ((planes_variants[i].isa & isa) == planes_variants[i].isa) return &planes_variants[i];
    }
    return &planes_variants[0];
}
