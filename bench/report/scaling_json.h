/*
 * The scaling run for scripts: `shadowvol bench --scaling --json FILE`.
 *
 * Schema "shadowvol-scaling/1". The fields below are fixed; more may be
 * added (a reader must ignore fields it does not know):
 *
 *   schema    "shadowvol-scaling/1"
 *   cpu       { model: string, isa: [string], tsc_hz: number }
 *   caches    { l1d_bytes, l2_bytes, l3_bytes: number, or null when
 *             unknown; sources: { l1d, l2, l3: "sysconf" | "sysfs" | null } }
 *   compiler  string        commit  string        timer  "rdtscp" | "cpuid" | "lfence"
 *   working_set [ per routine: { routine, bytes_per_triangle (at the
 *             paper's ratios), formula: string } ]
 *   models    [ per mesh, smallest first: { model, generated: bool,
 *             subdivision: n or null, triangles, edges, vertices, lights,
 *             runs, facing_ratio, silhouette_ratio (means over the lights),
 *             working_set_bytes (create_shadow_volume's, from the mesh's
 *             counts), seconds (building, lighting, measuring) } ]
 *   results   [ per mesh x routine x variant:
 *     model, triangles   as in models
 *     routine, variant   as in shadowvol-bench/1
 *     regime             "moving"
 *     elements, element  what per element divides by ("triangle",
 *                        "SilEdge", "vertex")
 *     runs               timed regions of the row
 *     ticks_per_element_min, ticks_per_element_median
 *                        TSC ticks, the empty region's cost subtracted;
 *                        null when the row failed its check
 *     below_noise        the median call is mostly timer noise
 *                        (cycle_table.h, kNoiseFactor)
 *     working_set_bytes  the routine's, on this mesh
 *     fits               "L1D" | "L2" | "L3" | "DRAM" | "?": the smallest
 *                        cache at least working_set_bytes large
 *     checked            true when every call matched c_ref
 *     failure            why not, when it did not
 *   ]
 *
 * Numbers are finite; strings are valid UTF-8.
 *
 * Copyright (C) 2026 the shadowvol authors. LGPL-2.1-or-later.
 */
#ifndef SV_BENCH_SCALING_JSON_H
#define SV_BENCH_SCALING_JSON_H

#include <string>

#include "scaling.h"

namespace svbench {

constexpr const char *kScalingJsonSchema = "shadowvol-scaling/1";

/* The document, ending in a newline. */
std::string scaling_json(const ScalingRun &run);

} // namespace svbench

#endif
