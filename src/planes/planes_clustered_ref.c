/*
 * The clustered planes' definition and table (include/shadowvol_planes.h,
 * "Planes by clusters"): sv_derive_planes_c_ref's expression, per
 * triangle of each cluster, on the cluster's vertex numbers.
 *
 * Copyright (C) 2026 the shadowvol authors. LGPL-2.1-or-later.
 */
#include <string.h>

#include "planes_internal.h"

void sv_derive_planes_clustered_c_ref(const float *positions, const sv_plane_clusters *clusters,
                                      Plane *planes) {
    for (int c = 0; c < clusters->num_clusters; c++) {
        const uint32_t *vertices = clusters->vertex_offsets + clusters->vertex_begin[c];
        for (int g = clusters->group_begin[c]; g < clusters->group_begin[c + 1]; g++) {
            const uint8_t *corners = clusters->corners + 48 * (size_t)g;
            for (int i = 0; i < 16; i++) {
                const int tri[3] = {(int)(vertices[corners[i]] / 12),
                                    (int)(vertices[corners[16 + i]] / 12),
                                    (int)(vertices[corners[32 + i]] / 12)};
                planes[clusters->plane_offsets[16 * (size_t)g + (size_t)i] / 16] =
                    sv_plane_one(positions, tri);
            }
        }
    }
}

static const sv_planes_clustered_variant clustered_variants[] = {
    {"c_ref", SV_ISA_NONE, sv_derive_planes_clustered_c_ref},
    {"avx512", SV_ISA_SSE2 | SV_ISA_AVX2 | SV_ISA_AVX512, sv_derive_planes_clustered_avx512},
};

#define NUM_CLUSTERED_VARIANTS (sizeof clustered_variants / sizeof clustered_variants[0])

const sv_planes_clustered_variant *sv_planes_clustered_variants(int *count) {
    if (count) *count = (int)NUM_CLUSTERED_VARIANTS;
    return clustered_variants;
}

const sv_planes_clustered_variant *sv_planes_clustered_variant_by_name(const char *name) {
    for (size_t i = 0; name && i < NUM_CLUSTERED_VARIANTS; i++) {
        if (strcmp(clustered_variants[i].name, name) == 0) return &clustered_variants[i];
    }
    return NULL;
}
