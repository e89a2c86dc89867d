/*
 * `shadowvol bench --scene`'s table of passes (issue 28): a preset's
 * frames rendered by every stencil method at one thread and every core,
 * a row per pass, method and thread count, with the check of the same
 * run. Only the stencil pass has rows yet; a pass is a PassTiming entry
 * (scene_pass_table.cpp) and a row per method follows.
 *
 * Copyright (C) 2026 the shadowvol authors. LGPL-2.1-or-later.
 */
#ifndef SV_BENCH_SCENE_PASS_TABLE_H
#define SV_BENCH_SCENE_PASS_TABLE_H

#include <cstdint>
#include <cstdio>
#include <string>
#include <vector>

#include "scene_presets.h"

namespace svbench {

class JsonWriter;

struct PassTableOptions {
    int width = 640, height = 512;
    int frames = 4; /* 1/8 s apart */
    int runs = 3;   /* renders per frame, method and thread count: the minimum is kept */
    int threads_all = 1;
    int stencil_tile = 0;  /* hier's tile side; 0: the frame's default */
    bool tile_rows = true; /* hier at the other tile sides too (1 thread) */
};

struct PassRow {
    std::string pass;   /* "stencil" */
    std::string method; /* bf, db, hier */
    int tile = 0;       /* hier's tile side (0: not hier) */
    int threads = 1;
    double ms_per_frame = 0;       /* mean over frames of the minimum over runs */
    uint64_t pixels_per_frame = 0; /* pixels tested (hier: its per-pixel stage only) */
    uint64_t volume_triangles = 0; /* per frame: drawn volume triangles, all lights */
    int frames_equal = 0;          /* frames whose every light's stencil equals bf's */
    int frames = 0, runs = 0;
    /* Seed 004's Table 1 accounting, bytes per frame, all lights
     * (bandwidth_model in scene_pass_table.cpp): stencil and Z in the
     * shadow pass, stencil in the lighting pass, the PSV buffer through
     * its cache, the delay stream. */
    double bw_stencil_shadow = 0, bw_z_shadow = 0, bw_stencil_lighting = 0, bw_psv = 0,
           bw_delay = 0;
    double bw_total() const {
        return bw_stencil_shadow + bw_z_shadow + bw_stencil_lighting + bw_psv + bw_delay;
    }
};

struct PassTable {
    std::string scene;
    int width = 0, height = 0, lights = 0;
    std::vector<PassRow> rows;
    int failed() const; /* rows with a frame that differs from bf's */
};

PassTable run_pass_table(ScenePreset &preset, const PassTableOptions &o);
void print_pass_table(FILE *out, const PassTable &t);
/* The bandwidth rows (1-thread rows: the model does not depend on the
 * thread count). */
void print_bandwidth_table(FILE *out, const PassTable &t);
/* The table as the JSON value of key "passes" (an object). */
void pass_table_json(JsonWriter &j, const PassTable &t);

} // namespace svbench

#endif
