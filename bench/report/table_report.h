/*
 * The cycle table as a person reads it: a header on the machine and the
 * build, then per model its workload (sizes, the lights' actual ratios)
 * and one table per regime beside the paper's Pentium 4 figures, then the
 * notes that explain the columns and every failed check.
 *
 * Copyright (C) 2026 the shadowvol authors. LGPL-2.1-or-later.
 */
#ifndef SV_BENCH_TABLE_REPORT_H
#define SV_BENCH_TABLE_REPORT_H

#include <cstdio>

#include "bench_run.h"

namespace svbench {

/* The machine, timer, build and options: printed before any model. */
void print_run_header(FILE *out, const BenchRun &run);
/* One model's workload and tables, printed as soon as it is measured. */
void print_model(FILE *out, const BenchRun &run, const ModelRun &model);
/* The notes under all tables, and a FAILED line per failed row. */
void print_notes(FILE *out, const BenchRun &run);

} // namespace svbench

#endif
