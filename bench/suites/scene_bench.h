/*
 * shadowvol bench --scene (issue 13): see scene_bench.cpp.
 *
 * Copyright (C) 2026 the shadowvol authors. LGPL-2.1-or-later.
 */
#ifndef SV_BENCH_SCENE_BENCH_H
#define SV_BENCH_SCENE_BENCH_H

#include "seed_bench.h"

namespace svbench {

int run_scene_bench(const SeedCommand &cmd);

} // namespace svbench

#endif
