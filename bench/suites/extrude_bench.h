/*
 * `shadowvol bench --extrude` (extrude_bench.cpp, issue 31): seed 002's
 * vertex program emulated on the CPU, every variant, beside the paper's
 * pipeline on the same meshes and lights. Takes the options of the seed
 * benchmarks (seed_bench.h); exit status as theirs.
 *
 * Copyright (C) 2026 the shadowvol authors. LGPL-2.1-or-later.
 */
#ifndef SV_BENCH_EXTRUDE_BENCH_H
#define SV_BENCH_EXTRUDE_BENCH_H

#include "seed_bench.h"

namespace svbench {

int run_extrude_bench(const SeedCommand &cmd);

} // namespace svbench

#endif
