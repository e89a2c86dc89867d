/*
 * shadowvol bench --frame (issue 29): see frame_bench.cpp.
 *
 * Copyright (C) 2026 the shadowvol authors. LGPL-2.1-or-later.
 */
#ifndef SV_BENCH_FRAME_BENCH_H
#define SV_BENCH_FRAME_BENCH_H

#include <cstdint>
#include <cstdio>
#include <string>
#include <vector>

#include "frame_vs_mesa.h"
#include "divider_rate.h"
#include "memory_rate.h"
#include "seed_bench.h"
#include "stencil_method.h"

namespace svbench {

struct FrameBenchOptions {
    std::string preset; /* simple, knights, demo or a glTF file (scene_presets.h); "" demo */
    int width = 1280, height = 720;
    int threads = 0; /* 0: every core */
    int frames = 8;
    int runs = 3;        /* drawings per frame on each side, the minimum kept */
    bool mesa = true;    /* Mesa's same frame beside ours */
    std::string out_dir; /* "" none; else the last frame's PNGs, ours and Mesa's */
    /* Our stencil pass: its method (stencil_method.h), hier's tile side
     * and auto's threshold, and where they came from. The CLI fills them
     * as render does where --stencil is not given (the planner's choice:
     * the wisdom file's, else auto at its offline threshold; source
     * "wisdom", "measured" or "default"; "option" for --stencil). */
    std::string stencil = "auto";
    int stencil_tile = sv::render::kDefaultStencilTile;
    double hier_from_area_per_piece = sv::render::kDefaultHierFromAreaPerPiece;
    std::string stencil_source = "default";
};

/* The table of a run: a row per pass (ms; floor and Mesa's ms where they
 * apply, else -1), and the checks of the same run. */
struct FrameTable {
    std::string preset, scene; /* the name given, and what the scene holds */
    int width = 0, height = 0, threads = 0, frames = 0, runs = 0;
    int moving_light = -1;
    std::string stencil;        /* our stencil method */
    std::string stencil_source; /* FrameBenchOptions::stencil_source */
    int stencil_tile = 0;
    double hier_from_area_per_piece = 0;
    MemoryRate rate;
    struct Row {
        const char *name;
        double ours, floor, mesa;
    };
    std::vector<Row> rows;
    /* What each pass works through, a frame's mean (the last drawing of
     * each frame): what bounds it, beside its time. */
    struct Work {
        double depth_triangles = 0, depth_rows = 0, depth_pixels = 0;
        double stencil_triangles = 0, stencil_rows = 0, stencil_pixels = 0;
        double pixels = 0, lights = 0;
        double visible_pixels = 0; /* pixels showing a triangle (the camera ray's divide) */
        double divider_lanes = 0;  /* lanes through a light's square root and divides */
    } work;
    DividerRate divider;
    double hz = 0; /* TSC ticks a second */
    double first_drawing_wall_ms = 0;
    int same_runs = 0; /* frames whose drawings were the same bytes */
    bool mesa_wanted = false;
    std::string mesa_note, mesa_renderer;
    int lp_num_threads = 0;
    std::vector<sv::render::MesaFrameComparison> mesa; /* one per frame */
    uint64_t compared = 0, equal = 0, on_edge = 0, other = 0, stencil_other = 0;
    std::vector<uint8_t> last_rgb, last_mesa_rgb; /* the last frame's pictures */
    int failed() const { return (same_runs != frames) + (other != 0 || stencil_other != 0); }
};

/* Measures the table (HZ: the TSC rate). Throws WorkloadError when the
 * preset cannot be loaded. */
FrameTable measure_frame_table(const SeedCommand &cmd, const FrameBenchOptions &fo, double hz);
void print_frame_table(FILE *out, const FrameTable &t);
class JsonWriter;
void frame_table_json(JsonWriter &j, const FrameTable &t);

int run_frame_bench(const SeedCommand &cmd, const FrameBenchOptions &fo);

} // namespace svbench

#endif
