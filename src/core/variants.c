/*
 * The table of variants: every implementation of the four kernels, by name,
 * so tests and benchmarks iterate over all of them (checkasm-style). Ordered
 * from the reference to the fastest: sv_best_variant() takes the last one
 * the CPU runs.
 *
 * Which asm variants exist depends on the platform (CMake's SV_ASM_KERNELS:
 * SV_HAVE_ASM_SSE2 / _AVX2 / _AVX512, docs/PLATFORMS.md): the table lists
 * only what was built, so every consumer (tests, benchmark, dispatch)
 * iterates over what exists and names no missing symbol.
 *
 * Copyright (C) 2026 the shadowvol authors. LGPL-2.1-or-later.
 */
#include <string.h>

#include "shadowvol.h"

static const sv_variant variants[] = {
    {"c_ref", SV_ISA_NONE, sv_count_facing_c_ref, sv_count_facing_cull_c_ref,
     sv_create_sil_triangles_c_ref, sv_create_cap_triangles_c_ref, 1, 1, 1},
    {"c_branchless", SV_ISA_NONE, sv_count_facing_c_branchless, sv_count_facing_cull_c_branchless,
     sv_create_sil_triangles_c_branchless, sv_create_cap_triangles_c_branchless, 1, 1, 1},
#if defined(SV_HAVE_ASM_SSE2)
    /* Alignments from the listings: movdqa on facing (App. C) and on
     * indices (App. F); the output pointer kept as ptr / 8 (App. E, F). */
    {"sse2_paper", SV_ISA_SSE2, sv_count_facing_sse2_paper, sv_count_facing_cull_sse2_paper,
     sv_create_sil_triangles_sse2_paper, sv_create_cap_triangles_sse2_paper, 16, 16, 8},
#endif
#if defined(SV_HAVE_ASM_AVX2)
    /* x86-64-v3, no alignment: unaligned 32-byte loads, left-packing by
     * table and popcnt (asm/..._avx2.asm). */
    {"avx2", SV_ISA_AVX2, sv_count_facing_avx2, sv_count_facing_cull_avx2,
     sv_create_sil_triangles_avx2, sv_create_cap_triangles_avx2, 1, 1, 1},
#endif
#if defined(SV_HAVE_ASM_AVX512)
    /* x86-64-v4 (asm/..._avx512.asm): vpcompressd left-packing, facing
     * bits looked up in registers (sil), a list of the non-facing
     * triangles (cull), masked tails; no alignment needed anywhere. */
    {"avx512", SV_ISA_AVX512 | SV_ISA_AVX2 | SV_ISA_SSE2, sv_count_facing_avx512,
     sv_count_facing_cull_avx512, sv_create_sil_triangles_avx512, sv_create_cap_triangles_avx512, 1,
     1, 1},
    /* The AVX-512 kernels, with CountFacingCull looking the cull bytes up
     * in registers by vpermi2b (AVX512_VBMI: Ice Lake, Zen 4 and later). */
    {"avx512vbmi", SV_ISA_AVX512_VBMI | SV_ISA_AVX512 | SV_ISA_AVX2 | SV_ISA_SSE2,
     sv_count_facing_avx512, sv_count_facing_cull_avx512vbmi, sv_create_sil_triangles_avx512,
     sv_create_cap_triangles_avx512, 1, 1, 1},
#endif
};

const sv_variant *sv_variants(int *count) {
    if (count) {
        *count = (int)(sizeof variants / sizeof variants[0]);
    }
    return variants;
}

const sv_variant *sv_variant_by_name(const char *name) {
    size_t i;
    if (!name) {
        return NULL;
    }
    for (i = 0; i < sizeof variants / sizeof variants[0]; i++) {
        if (strcmp(variants[i].name, name) == 0) {
            return &variants[i];
        }
    }
    return NULL;
}

const sv_variant *sv_best_variant(void) {
    const unsigned isa = sv_cpu_isa();
    size_t i = sizeof variants / sizeof variants[0];
    while (i-- > 1) {
        if ((variants[i].isa & isa) == variants[i].isa) {
            return &variants[i];
        }
    }
    return &variants[0];
}

/* The general rule's kernels (issue 27), from the reference to the
 * fastest, as the table above. */
static const sv_general_variant general_variants[] = {
    {"c_ref", SV_ISA_NONE, sv_create_general_sil_triangles_c_ref,
     sv_create_general_cap_triangles_c_ref},
#if defined(SV_HAVE_ASM_AVX2)
    /* src/core/x86/general_simd.c: gathers and left-packing by a
     * permutation; the paper's class by the AVX2 asm kernel. */
    {"avx2", SV_ISA_AVX2, sv_create_general_sil_triangles_avx2,
     sv_create_general_cap_triangles_avx2},
#endif
#if defined(SV_HAVE_ASM_AVX512)
    /* vpcompressd lists and caps; the paper's class by the AVX-512 asm. */
    {"avx512", SV_ISA_AVX512 | SV_ISA_AVX2 | SV_ISA_SSE2, sv_create_general_sil_triangles_avx512,
     sv_create_general_cap_triangles_avx512},
#endif
};

const sv_general_variant *sv_general_variants(int *count) {
    if (count) {
        *count = (int)(sizeof general_variants / sizeof general_variants[0]);
    }
    return general_variants;
}

const sv_general_variant *sv_general_variant_by_name(const char *name) {
    size_t i;
    if (!name) {
        return NULL;
    }
    for (i = 0; i < sizeof general_variants / sizeof general_variants[0]; i++) {
        if (strcmp(general_variants[i].name, name) == 0) {
            return &general_variants[i];
        }
    }
    return NULL;
}

const sv_general_variant *sv_general_variant_for_isa(unsigned isa) {
    size_t i = sizeof general_variants / sizeof general_variants[0];
    while (i-- > 1) {
        if ((general_variants[i].isa & isa) == general_variants[i].isa) {
            return &general_variants[i];
        }
    }
    return &general_variants[0];
}

const sv_general_variant *sv_best_general_variant(void) {
    return sv_general_variant_for_isa(sv_cpu_isa());
}
