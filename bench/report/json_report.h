/*
 * The cycle table for scripts: `shadowvol bench --json FILE`.
 *
 * Schema "shadowvol-bench/1". The fields below are fixed; more may be added
 * (a reader must ignore fields it does not know):
 *
 *   schema    "shadowvol-bench/1"
 *   cpu       { model: string, isa: [string] (cpuid + xgetbv: what the CPU
 *             has and the OS enables), tsc_hz: number }
 *   compiler  string        commit  string        timer  "rdtscp" | "cpuid" | "lfence"
 *   results   [ one object per row:
 *     model           the file name ("character_1344.glb") or "synthetic"
 *     triangles, edges (SilEdges), vertices: of the prepared surface
 *     routine         calculate_facing | calculate_cull_bits | count_facing |
 *                     count_facing_cull | create_sil_triangles |
 *                     create_cap_triangles | create_shadow_volume |
 *                     create_shadow_volume_cull
 *     variant         a name of the variant table (c_ref, c_branchless,
 *                     sse2_paper, ...)
 *     regime          "moving" | "fixed"
 *     elements        what per-element divides by: triangles; edges for
 *                     create_sil_triangles; vertices for calculate_cull_bits
 *     runs            timed regions (a call, or a batch of `batch` calls)
 *     ticks_min, ticks_median, ticks_per_element_min,
 *     ticks_per_element_median
 *                     TSC ticks per call, the empty region's cost
 *                     subtracted; null when the row failed its check
 *     checked         true when every call of the row matched the reference
 *   ]
 *
 * With --limits, "limits": { vector ("zmm" | "ymm" | "none"),
 * scalar_loads_per_tick, gather_lanes_per_tick, l1_load_bytes_per_tick,
 * l2_load_bytes_per_tick, l2_buffer_bytes, store_bytes_per_tick, floors: [
 * { model, routine, floor_ticks, load_port_ticks, lookup_ticks,
 * store_port_ticks } per model and routine measured with the moving light;
 * empty when vector is "none" ] } (machine_limits.h).
 *
 * Beside them: build flags, overhead, options, per model the lights'
 * actual ratios ("models"), and per row the batch, the speed-up over c_ref
 * in the same regime, whether it is below the timer's noise, the paper's
 * Pentium 4 figures (null where the paper has none) and the failure.
 * Numbers are finite; strings are valid UTF-8.
 *
 * Copyright (C) 2026 the shadowvol authors. LGPL-2.1-or-later.
 */
#ifndef SV_BENCH_JSON_REPORT_H
#define SV_BENCH_JSON_REPORT_H

#include <string>
#include <vector>

#include "bench_run.h"
#include "json_writer.h"

namespace svbench {

constexpr const char *kJsonSchema = "shadowvol-bench/1";

/* The document, ending in a newline. */
std::string bench_json(const BenchRun &run);

/* The fields every shadowvol-* benchmark document shares, written into the
 * open object J: "shadowvol_version", "cpu" {model, isa, tsc_hz,
 * tsc_step_ticks, invariant_tsc, pinned_cpu}, "compiler", "build",
 * "commit", "timer". */
void write_machine_fields(JsonWriter &j, const MachineTiming &m);

/* "isa_level" (the highest level sv_cpu_isa() reaches) and "variants" (the
 * names of VARIANTS, the ones this run measured). */
void write_isa_fields(JsonWriter &j, const std::vector<const BenchVariant *> &variants);

/* Per row, in both documents: the figure V under NAME when the row passed
 * its check, else null (a failed row has no figure). */
void write_row_figure(JsonWriter &j, const char *name, const Row &r, double v);
/* Per row, in both documents: "checked", and "failure" when it failed. */
void write_row_check(JsonWriter &j, const Row &r);

/* The plan a model's planned rows ran (nullptr: it had none). */
const sv_plan *plan_of(const std::vector<Row> &rows);
/* "plans": per model whose rows ran a plan, the plan: {model, triangles,
 * size_class, class_triangles (the mesh the class is measured on),
 * source ("measured", "wisdom", "built-in"), variants {routine: name}}.
 * `bench --report` prints them as the planner's choices. */
struct PlanUse {
    std::string model;
    int triangles;
    const sv_plan *plan;
};
void write_plans(JsonWriter &j, const std::vector<PlanUse> &uses);

} // namespace svbench

#endif
