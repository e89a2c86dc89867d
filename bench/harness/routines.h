/*
 * What the cycle table times: the routines of the paper's pipeline, and the
 * implementations ("variants") of each, by name.
 *
 * The library's variant table (sv_variants) carries the kernels of
 * appendices C-F, from which sv_create_shadow_volume is glued. Appendices A
 * (CalculateFacing) and B (CalculateCullBits) exist only as the reference C
 * so far, outside that table. A BenchVariant joins the two: one name, the
 * ISA it needs, and whichever routines it implements. A row of the table
 * exists for every (routine, variant) pair the variant implements, so a SIMD
 * CalculateFacing added later is one more entry in sv_facing_variants() (or, once
 * sv_variant carries A and B, a field read in routines.cpp) and shows up in
 * every table and JSON document without other changes.
 *
 * Copyright (C) 2026 the shadowvol authors. LGPL-2.1-or-later.
 */
#ifndef SV_BENCH_ROUTINES_H
#define SV_BENCH_ROUTINES_H

#include <cstdint>
#include <string>
#include <vector>

#include "shadowvol.h"
#include "shadowvol_plan.h"

namespace svbench {

/* In pipeline order: appendix A, B, then C-F and the volume. */
enum class Routine {
    calculate_facing,          /* App. A: facing bytes from the triangle planes */
    calculate_cull_bits,       /* App. B: cull bits from the light box */
    count_facing,              /* App. C */
    count_facing_cull,         /* App. D */
    create_sil_triangles,      /* App. E */
    create_cap_triangles,      /* App. F */
    create_shadow_volume,      /* sv_create_shadow_volume, cullBits NULL */
    create_shadow_volume_cull, /* sv_create_shadow_volume with cull bits */
    /* One light's whole job as a user calls it (issue 15): A, then the
     * volume (C, E, F); and A, B, then the volume with the culling
     * decision (D, E, F; no culling when B says the surface is inside
     * the light volume). */
    pipeline,
    pipeline_cull,
};
constexpr int kNumRoutines = 10;
extern const Routine kAllRoutines[kNumRoutines];

/* The names of the table and of the JSON document. */
const char *routine_name(Routine r);
/* False when NAME is none of them. */
bool routine_by_name(const std::string &name, Routine *r);
/* ", "-separated, in pipeline order. */
std::string routine_list();

/* What a row's "per element" divides by: the paper counts CountFacing ..
 * CreateCapTriangles and the volume per triangle, CreateSilTriangles per
 * SilEdge; CalculateCullBits runs over vertices. */
enum class Element { triangle, sil_edge, vertex };
Element element_of(Routine r);
const char *element_name(Element e); /* "triangle", "SilEdge", "vertex" */

/* Appendices A and B (and the pipelines, which start with them) need a
 * light with a position and planes: a workload whose facing patterns are
 * generated rather than lit has no rows for them. */
bool needs_light(Routine r);
/* The routine writes shadow indices (the output buffer). */
bool writes_indices(Routine r);

using CalculateFacingFn = void (*)(const Plane *planes, int numTriangles, const Vec4 *light,
                                   uint8_t *facing);
using CalculateCullBitsFn = int (*)(const Vec4 *positions, int numVerts,
                                    const Bounds *surfaceBounds, const Plane *lightPlanes,
                                    uint8_t *cullBits);

struct BenchVariant {
    const char *name;
    unsigned isa;                            /* SV_ISA_* bits it needs */
    const sv_variant *kernels;               /* C-F and the volume; nullptr: none */
    CalculateFacingFn calculate_facing;      /* A; nullptr: none */
    CalculateCullBitsFn calculate_cull_bits; /* B; nullptr: none */
    /* What the pipeline rows run for A and B: the variant's own, else (a
     * kernel variant without them: c_branchless, sse2_paper, avx512vbmi)
     * the facing variant of the highest ISA the variant itself needs
     * (sse2_paper's pipeline is the paper's: the SSE2 A and B, then its
     * listings). */
    CalculateFacingFn pipeline_facing = nullptr;
    CalculateCullBitsFn pipeline_cull_bits = nullptr;
    const char *pipeline_facing_name = nullptr;
    /* "planned": the planner's choice (include/shadowvol_plan.h) for the
     * workload's size, resolved per workload by resolve_planned(). */
    bool planned = false;
    /* "planned_kernels": the same plan's kernels called one after the
     * other (A, then sv_create_shadow_volume), not the fused one-call
     * entry. It has pipeline rows only (elsewhere it is "planned"), so
     * that the planner's choice of kernels is compared with the fixed
     * variants like with like, and the fused entry's own gain shows as
     * the difference between the two rows. */
    bool unfused = false;
    /* A resolved planned variant: the table's entry it was made from, and
     * the plan (its pipeline rows call sv_shadow_volume_for_light with it:
     * the fused facing and count, what a user of the one-call entry gets). */
    const BenchVariant *origin = nullptr;
    const sv_plan *plan = nullptr;
};

/* For the planned variant: a variant with the kernels and A/B of the plan
 * for a mesh of NUMTRIANGLES (sv_plan_for with SV_PLAN_MEASURE: the wisdom
 * file's plan when it has this CPU, else measured now). Other variants come
 * back unchanged. The result lives as long as the program. */
const BenchVariant *resolve_planned(const BenchVariant *v, int numTriangles);

/* Every variant compiled in, the reference (c_ref) first, in the library's
 * order; those whose ISA this CPU lacks included. */
const std::vector<BenchVariant> &bench_variants();
/* The variant called NAME, or nullptr. */
const BenchVariant *bench_variant_by_name(const std::string &name);
/* ", "-separated names. */
std::string variant_list();
/* The variant implements routine R. */
bool implements(const BenchVariant &v, Routine r);
/* The oracle of the C-F kernels and of the volume: c_ref. */
const BenchVariant &reference_variant();

} // namespace svbench

#endif
