/*
 * The C reference of include/shadowvol_extrude.h (the oracle of every SIMD
 * variant), and the variant table.
 *
 * Copyright (C) 2026 the shadowvol authors. LGPL-2.1-or-later.
 */
#include <string.h>

#include "extrude_internal.h"

void sv_extrude_c_ref(const float *stream, int numVertices, const sv_extrude_light *light,
                      Vec4 *out) {
    const Vec4 l = light->position;
    const float range = light->range;
    const int finite = sv_extrude_finite(&l, range);
    for (int i = 0; i < numVertices; i++)
        out[i] = sv_extrude_one(stream + SV_EXTRUDE_STREAM_FLOATS * (ptrdiff_t)i, &l, range,
                                finite);
}

static const sv_extrude_variant extrude_variants[] = {
    {"c_ref", SV_ISA_NONE, sv_extrude_c_ref},
    {"avx2", SV_ISA_SSE2 | SV_ISA_AVX2, sv_extrude_avx2},
    {"avx512", SV_ISA_SSE2 | SV_ISA_AVX2 | SV_ISA_AVX512, sv_extrude_avx512},
};
#define NUM_EXTRUDE_VARIANTS (sizeof extrude_variants / sizeof extrude_variants[0])

const sv_extrude_variant *sv_extrude_variants(int *count) {
    if (count) *count = (int)NUM_EXTRUDE_VARIANTS;
    return extrude_variants;
}

const sv_extrude_variant *sv_extrude_variant_by_name(const char *name) {
    for (size_t i = 0; name && i < NUM_EXTRUDE_VARIANTS; i++)
        if (strcmp(extrude_variants[i].name, name) == 0) return &extrude_variants[i];
    return NULL;
}

const sv_extrude_variant *sv_best_extrude_variant(void) {
    const unsigned isa = sv_cpu_isa();
    for (size_t i = NUM_EXTRUDE_VARIANTS; i-- > 0;)
        if ((extrude_variants[i].isa & isa) == extrude_variants[i].isa) return &extrude_variants[i];
    return &extrude_variants[0];
}
