/*
 * `shadowvol bench --limits`: what this core can move per TSC tick at best
 * (machine_limits.asm's primitives), and from it a floor for each routine
 * on the workload: the ticks its unavoidable memory traffic needs. Printed
 * after the model's table, beside the best variant measured in the same
 * run and the goals (twice sse2_paper's speed per routine; eight
 * times c_ref's for the whole volume).
 *
 * The floor's model, per call, with the moving lights' mean ratios
 * (N triangles, E SilEdges, nf = non-facing triangles, sE = silhouette
 * edges; "lookup" = one load, or one gather lane where gathers are the
 * faster):
 *   count_facing          N facing bytes read                  / L1 bandwidth
 *   count_facing_cull     N facing bytes + min(all 12 N index bytes by
 *                         vector, one load per non-facing triangle) + 3 nf
 *                         cull-byte lookups
 *   create_sil_triangles  16 E bytes of SilEdges / L1 bandwidth + 2 E
 *                         facing lookups + 24 sE bytes stored
 *   create_cap_triangles  13 N bytes (facing, indices) / L1 bandwidth + 24 nf
 *                         bytes stored (6 ints per casting triangle)
 *   create_shadow_volume  count_facing + create_sil + create_cap
 *   ..._cull              count_facing_cull + create_sil + create_cap, with
 *                         the caps of the triangles culling left
 * Every term assumes its data in L1 and the best rate measured. Loads and
 * lookups share the load ports, so their times add; stores go through
 * their own port and may overlap them: the floor is the larger of the
 * two. A kernel that keeps its lookup table in registers (the avx512
 * silhouette kernel's 2048-bit window) replaces lookups by vector
 * instructions and is not bound by the lookup term. Approximations, both
 * small: ..._cull takes the silhouette share measured before culling
 * (the routine runs on the culled facing bytes), and CountFacingCull's
 * one-byte facing stores are not counted on the store port.
 *
 * Copyright (C) 2026 the shadowvol authors. LGPL-2.1-or-later.
 */
#ifndef SV_BENCH_MACHINE_LIMITS_H
#define SV_BENCH_MACHINE_LIMITS_H

#include <cstddef>
#include <cstdio>

#include "cycle_table.h"
#include "workload.h"

namespace svbench {

struct MachineLimits {
    const char *vector = "none"; /* "zmm", "ymm", or "none" (no AVX2: the
                                    vector rates are 0, not measured) */
    double scalarLoads = 0;      /* byte loads per tick, independent, L1 */
    double gatherLanes = 0;      /* vpgatherdd lanes per tick, L1 */
    double l1LoadBytes = 0;      /* vector load bytes per tick, a 16 KiB buffer */
    double l2LoadBytes = 0;      /* the same over l2Buffer bytes */
    size_t l2Buffer = 0;         /* half the L2 (256 KiB when unknown) */
    double storeBytes = 0;       /* vector store bytes per tick, L1 */
    /* Core cycles per TSC tick (a chain of dependent adds, one cycle
     * each): the clock the core ran at, over the TSC's. A row's ticks
     * times it are core cycles, which is what instruction counts per
     * element (tools/instruction_counts.sh) divide into: instructions per
     * cycle, against the core's issue width. Turbo makes it a snapshot. */
    double coreCyclesPerTick = 0;
};

/* Each primitive timed 25 times (one call of 2^20 loads, stores or gather
 * instructions each, the fences' cost subtracted); the fastest call
 * counts. The vector forms are the widest the CPU runs within the ISA
 * limit (sv_cpu_isa(): --isa, SV_ISA): zmm, ymm, or none without AVX2. */
MachineLimits measure_machine_limits();

/* This core's rate of streaming reads from memory, in bytes per TSC tick:
 * 16-byte loads over a BYTES buffer (a multiple of 64; several times any
 * L3 a core of this kind has, 256 MiB by default), the best of three
 * passes. The bound of a mesh whose working set no cache holds (the
 * scaling run's large-mesh check). 0 when the buffer cannot be had. */
double measure_memory_load_rate(size_t bytes = (size_t)256 << 20);

struct RoutineFloor {
    Routine routine;
    double loadPorts = 0; /* loads + lookups: they share the load ports */
    double lookups = 0;   /* of which lookups */
    double storePort = 0; /* stores */
    double ticks = 0;     /* the floor: the larger of the two, per call */
    /* The streaming floor (issue 15): only the bytes the call must read and
     * write, at the best load and store rates, without the lookup term, so
     * that a kernel holding its tables in registers (which escapes the
     * lookups) still has a floor that means something. */
    double streaming = 0;
};
/* One per routine the table measured (moving light), in its order; none
 * when the machine's vector rates were not measured. */
std::vector<RoutineFloor> routine_floors(const MachineLimits &l, const Workload &w,
                                         const ModelTable &t);

/* The primitives, then per routine: its floor, the best variant's median
 * in T (moving light), and the goals' figures from the same rows. */
void print_limits(FILE *out, const MachineLimits &l, const Workload &w, const ModelTable &t);

} // namespace svbench

#endif
