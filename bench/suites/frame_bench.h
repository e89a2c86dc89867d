/*
 * shadowvol bench --frame (issue 29): see frame_bench.cpp.
 *
 * Copyright (C) 2026 the shadowvol authors. LGPL-2.1-or-later.
 */
#ifndef SV_BENCH_FRAME_BENCH_H
#define SV_BENCH_FRAME_BENCH_H

#include <string>

#include "seed_bench.h"

namespace svbench {

struct FrameBenchOptions {
    std::string preset; /* simple, knights, demo or a glTF file (scene_presets.h); "" demo */
    int width = 1280, height = 720;
    int threads = 0; /* 0: every core */
    int frames = 8;
    int runs = 3;        /* drawings per frame on each side, the minimum kept */
    bool mesa = true;    /* Mesa's same frame beside ours */
    std::string out_dir; /* "" none; else the last frame's PNGs, ours and Mesa's */
};

int run_frame_bench(const SeedCommand &cmd, const FrameBenchOptions &fo);

} // namespace svbench

#endif
