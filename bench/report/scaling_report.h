/*
 * The scaling run as a person reads it: a header on the machine, its
 * caches and how the run was made; one line per mesh as soon as it is
 * measured (its size, lights, working set and the cache that holds it);
 * then per routine a table of ticks per element (min / median) with a
 * column per variant and a row per mesh, smallest first; then the notes
 * and every failed check.
 *
 * Copyright (C) 2026 the shadowvol authors. LGPL-2.1-or-later.
 */
#ifndef SV_BENCH_SCALING_REPORT_H
#define SV_BENCH_SCALING_REPORT_H

#include <cstdio>
#include <string>

#include "cache_info.h"
#include "scaling.h"

namespace svbench {

void print_scaling_header(FILE *out, const ScalingRun &run);
/* The line of one mesh (with the column heads before the first). */
void print_scaling_mesh(FILE *out, const ScalingMesh &m, bool first);
/* The per-routine tables, the notes and the FAILED lines. */
void print_scaling_tables(FILE *out, const ScalingRun &run);

/* "L1D", "L2", "L3" for the smallest cache of C at least BYTES large;
 * "DRAM" above them all; "?" when no level is known. */
const char *smallest_cache_holding(const CacheSizes &c, double bytes);

} // namespace svbench

#endif
