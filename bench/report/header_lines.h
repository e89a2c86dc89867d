/*
 * The header lines `shadowvol bench` and `shadowvol bench --scaling` both
 * print: the CPU (and whether the measuring thread is pinned), its ISA
 * flags, and the variants measured with those left out and why.
 *
 * Copyright (C) 2026 the shadowvol authors. LGPL-2.1-or-later.
 */
#ifndef SV_BENCH_HEADER_LINES_H
#define SV_BENCH_HEADER_LINES_H

#include <cstdio>
#include <string>
#include <vector>

#include "bench_run.h"

namespace svbench {

/* "cpu" (PINNED_CPU: the CPU the thread is pinned to, -1 if not) and "isa". */
void print_cpu_lines(FILE *out, int pinnedCpu);

/* "variants" (with the ISA level, "--variant" when CHOSEN narrowed them,
 * and the ISA LIMIT when set) and a "skipped" line per SKIPPED variant. */
void print_variant_lines(FILE *out, const std::vector<const BenchVariant *> &variants, bool chosen,
                         const std::string &limit, const std::vector<SkippedVariant> &skipped);

} // namespace svbench

#endif
