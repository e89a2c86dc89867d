/*
 * The paper's measurements, printed beside ours.
 *
 * Source: J.M.P. van Waveren, "Shadow Volume Construction", Id Software,
 * 2005, section 8 "Results", table "Hot Cache Clock Cycle Counts": an Intel
 * Pentium 4 on 130nm and one on 90nm, a player character of 1344 triangles
 * and 2016 SilEdges, 50% of the triangles facing the light, 20% of the
 * SilEdges on the silhouette (../shared/seeds/000_eca603d06c761598.txt).
 *
 * The figures are core clock cycles (the Pentium 4's TSC counted at the core
 * clock), per call, with a hot cache and, as far as the paper says, the same
 * input every call: compare them with the fixed-light table first. "Per
 * element" is per triangle, except for CreateSilTriangles, per SilEdge
 * (32314 / 2016 = 16); the per-element figures are kept as the paper
 * rounded them.
 *
 * Rows: "(C)" is the paper's C (variant c_ref), "(SSE)" its SSE2 listing
 * (variant sse2_paper). "CreateShadowVolume, no culling" is the routine
 * create_shadow_volume, "with culling" create_shadow_volume_cull. The
 * table has no row for CalculateFacing or CalculateCullBits (appendices A
 * and B): calculate_facing and calculate_cull_bits have no figures.
 *
 * Copyright (C) 2026 the shadowvol authors. LGPL-2.1-or-later.
 */
#ifndef SV_BENCH_PAPER_RESULTS_H
#define SV_BENCH_PAPER_RESULTS_H

#include <cstring>

namespace svbench {

/* The paper's character. */
constexpr int kPaperTriangles = 1344;
constexpr int kPaperSilEdges = 2016;

struct PaperFigures {
    const char *routine;  /* this project's routine name */
    const char *paperRow; /* the row as the paper names it */
    bool sse;             /* false: "(C)", true: "(SSE)" */
    long p4_130nm_total;
    const char *p4_130nm_per_element;
    long p4_90nm_total;
    const char *p4_90nm_per_element;
};

inline constexpr PaperFigures kPaperFigures[] = {
    {"count_facing", "CountFacing (C)", false, 22548, "17", 22688, "17"},
    {"count_facing", "CountFacing (SSE)", true, 348, "0.3", 383, "0.3"},
    {"count_facing_cull", "CountFacingCull (C)", false, 24124, "18", 29835, "22"},
    {"count_facing_cull", "CountFacingCull (SSE)", true, 10848, "8", 13883, "10"},
    {"create_sil_triangles", "CreateSilTriangles (C)", false, 32314, "16", 44983, "22"},
    {"create_sil_triangles", "CreateSilTriangles (SSE)", true, 32292, "16", 36901, "18"},
    {"create_cap_triangles", "CreateCapTriangles (C)", false, 23780, "18", 33848, "25"},
    {"create_cap_triangles", "CreateCapTriangles (SSE)", true, 12080, "9", 14205, "11"},
    {"create_shadow_volume", "CreateShadowVolume, no culling (C)", false, 79042, "59", 112443,
     "83"},
    {"create_shadow_volume", "CreateShadowVolume, no culling (SSE)", true, 44924, "33", 51503,
     "38"},
    {"create_shadow_volume_cull", "CreateShadowVolume, with culling (C)", false, 80625, "60",
     119590, "89"},
    {"create_shadow_volume_cull", "CreateShadowVolume, with culling (SSE)", true, 55648, "41",
     66660, "50"},
};

/* The paper's figures for ROUTINE measured with variant VARIANT: c_ref
 * shows "(C)", sse2_paper "(SSE)"; any other variant has none (nullptr). */
inline const PaperFigures *paper_figures(const char *routine, const char *variant) {
    bool sse;
    if (std::strcmp(variant, "c_ref") == 0) {
        sse = false;
    } else if (std::strcmp(variant, "sse2_paper") == 0) {
        sse = true;
    } else {
        return nullptr;
    }
    for (const PaperFigures &f : kPaperFigures) {
        if (f.sse == sse && std::strcmp(f.routine, routine) == 0) {
            return &f;
        }
    }
    return nullptr;
}

} // namespace svbench

#endif
