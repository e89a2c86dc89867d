/*
 * `shadowvol bench --figure1`: seed 004's Figure 1 for a frame of a scene
 * preset (figure1.cpp).
 *
 * Copyright (C) 2026 the shadowvol authors. LGPL-2.1-or-later.
 */
#ifndef SV_BENCH_FIGURE1_H
#define SV_BENCH_FIGURE1_H

#include <string>

#include "seed_bench.h"

namespace svbench {

/* Writes OUT_DIR/PRESET_{correct,lowres,boundary,composed}.png for the
 * first frame of cmd.scenePreset (default knights) at cmd.sceneWidth x
 * cmd.sceneHeight (default 640x400), its first light, hier at tile
 * TILE. Exit status: 0 written; 1 the composed shadow differs from the
 * correct one, or hier's stencil from bf's; 2 an unwritable folder; 3 a
 * preset that cannot be loaded. */
int run_figure1(const SeedCommand &cmd, const std::string &out_dir, int tile);

} // namespace svbench

#endif
