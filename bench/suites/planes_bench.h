/*
 * `shadowvol bench --planes` (planes_bench.cpp): per-frame plane derivation
 * against facing from positions. Takes the options of the seed benchmarks
 * (seed_bench.h); exit status as theirs.
 *
 * Copyright (C) 2026 the shadowvol authors. LGPL-2.1-or-later.
 */
#ifndef SV_BENCH_PLANES_BENCH_H
#define SV_BENCH_PLANES_BENCH_H

#include "seed_bench.h"

namespace svbench {

int run_planes_bench(const SeedCommand &cmd);

} // namespace svbench

#endif
