/*
 * `shadowvol bench --compare A.json B.json` and `shadowvol bench --report
 * FILE.json` (issue 17): results of `bench --json` (shadowvol-bench/1) and
 * `bench --scaling --json` (shadowvol-scaling/1), read back.
 *
 * --compare: per routine, variant, regime and model present in both, the
 *   medians per element of A and B, in ticks and in nanoseconds (ticks /
 *   the run's TSC rate: TSCs of different CPUs tick at different rates), and
 *   the ratio B / A of the nanoseconds, as Google Benchmark's compare.py
 *   gives the ratio of times; then the geometric mean of the ratios per
 *   variant. Rows in one file only are counted, not shown.
 * --report: the file's tables as Markdown (the script tools/docs_tables.sh
 *   writes them into the docs): a bench document's moving-light table of
 *   the first model (a row per routine, a column per variant, median ticks
 *   per element, and the best variant's speed-up over c_ref); a scaling
 *   document's table per routine (a row per mesh, a column per variant).
 *   With --regime fixed, the fixed-light table instead; with --routine R,
 *   routine R's rows only. Where the document records the plans its
 *   "planned" rows ran ("plans"), the planner's choices follow: a row per
 *   size class, a column per routine.
 * --report A.json B.json ... --routine R: routine R's moving-light row of
 *   each bench document, a row per CPU, with the best against sse2_paper.
 *
 * Copyright (C) 2026 the shadowvol authors. LGPL-2.1-or-later.
 */
#ifndef SV_BENCH_COMPARE_H
#define SV_BENCH_COMPARE_H

#include <cstdio>
#include <string>

namespace svbench {

/* Exit status: 0 done, 2 bad arguments, 3 a file that cannot be read or is
 * not a bench or scaling document. */
int compare_main(int argc, char **argv);
bool is_compare_or_report(int argc, char **argv);

} // namespace svbench

#endif
