/*
 * What the seed benchmarks (`shadowvol bench --silhouette`, seed 003's
 * finders; `shadowvol bench --backface`, seed 001's culling) share: timing
 * one kind of call over a rotation of inputs with the serialised TSC, each
 * call's output checked outside the timed region, for a time budget; the
 * meshes (generated at chosen sizes, and the real characters); the header.
 *
 * Unlike the cycle table these routines run from microseconds to seconds
 * (the classic finder is quadratic), so a row is not a fixed number of
 * calls: it runs for a time budget, at least kMinCalls calls and at most
 * kMaxCalls, and reports the minimum and the median.
 *
 * Copyright (C) 2026 the shadowvol authors. LGPL-2.1-or-later.
 */
#ifndef SV_BENCH_SEED_BENCH_H
#define SV_BENCH_SEED_BENCH_H

#include <cstdint>
#include <cstdio>
#include <functional>
#include <memory>
#include <string>
#include <vector>

#include "timer.h"
#include "workload.h"

namespace svbench {

/* `shadowvol bench --silhouette` / `--backface`, as bench_cli.cpp parsed
 * them. */
struct SeedCommand {
    bool quick = false;
    std::string json; /* --json FILE: "" none, "-" standard output */
    TimerKind timer = TimerKind::rdtscp;
    long maxTriangles = 0;           /* --max-triangles: leave out larger meshes (0: none) */
    uint64_t seed = 1;               /* the lights' jitter */
    std::string sharedModels;        /* the real characters' folder */
    std::string casterRule = "auto"; /* --caster-rule of --scene (shadowvol_casters.h) */
    /* --preset and --size of --scene: the table of passes for that scene
     * only ("" and 0: the demo scene's tables, then its table of passes). */
    std::string scenePreset;
    int sceneWidth = 0, sceneHeight = 0;
};
/* Exit status as bench_main's: 0 done, 1 a row failed its check (or the
 * document could not be written), 2 --json names a file that cannot be
 * written, 3 a model could not be loaded. */
int run_silhouette_bench(const SeedCommand &cmd);
int run_backface_bench(const SeedCommand &cmd);
/* `shadowvol bench --casters` (casters_bench.cpp, issue 27). */
int run_casters_bench(const SeedCommand &cmd);

/* The frame both commands share: the --json file opened before anything
 * runs, BODY printing its tables to OUT (stdout; stderr when the JSON goes
 * to stdout) and returning how many rows failed their check, with the JSON
 * document in *DOC; then the document written and the exit status
 * (run_silhouette_bench's). WHAT names the rows in the failure line. */
int run_seed_frame(const SeedCommand &cmd, const char *what,
                   const std::function<int(FILE *out, std::string *doc)> &body);

class ScenePreset; /* scene_presets.h */
/* make_scene_preset for preset NAME with the bench's folders (the bundled
 * models, CMD's shared models, the demo scene), a frame of ASPECT; what
 * does not load throws WorkloadError naming --preset NAME (exit 3, as a
 * model that cannot be loaded). */
std::unique_ptr<ScenePreset> open_bench_preset(const SeedCommand &cmd, const std::string &name,
                                               double aspect);

struct SeedTiming {
    bool ok = true;
    std::string failure;        /* the first check that failed */
    int calls = 0;              /* timed calls (each checked) */
    double min = 0, median = 0; /* ticks per call, the fences' cost subtracted */
};

class JsonWriter;

struct SeedTimer {
    TimerKind kind = TimerKind::rdtscp;
    uint64_t overhead = 0; /* min of an empty region */
    double tscHz = 0;
    double budget = 0.2; /* seconds per row */
    int minCalls = 3, maxCalls = 2000;
};
/* Measures the timer (kind's overhead, the TSC rate). */
SeedTimer make_seed_timer(TimerKind kind, bool quick);

/* Calls RUN(i) for i = 0, 1, ... (one untimed warm-up call first), each
 * timed; after each, CHECK(i) returns "" or what is wrong, and the row
 * stops at the first failure. */
SeedTiming time_seed_row(const SeedTimer &t, const std::function<void(int)> &run,
                         const std::function<std::string(int)> &check);

/* The members every JSON row of the seed benchmarks starts with: routine,
 * variant, calls, median_ticks, min_ticks (in the open object). */
void seed_json_row(JsonWriter &j, const char *routine, const std::string &variant,
                   const SeedTiming &t);

/* A mesh of the seed tables. */
struct SeedMesh {
    std::string name; /* "character_33600 (Dino size)", "spot.glb", ... */
    std::string source;
    Workload w; /* the mesh arrays (no lights) */
};
/* The generated character subdivided n x n (1344 n^2 triangles). */
SeedMesh generated_seed_mesh(int n, const std::string &note);
/* PATH, all surfaces merged (load_model_surface); throws WorkloadError. */
SeedMesh loaded_seed_mesh(const std::string &path);

/* The cpu and timer lines, and the runs line: how each row is measured,
 * RUNS where the suite does not time calls against the timer's budget
 * (default: the budget's line). */
void print_seed_header(FILE *out, const char *title, const SeedTimer &t, int pinnedCpu,
                       const char *runs = nullptr);
/* The same facts as JSON members of the open object. */
void seed_json_header(JsonWriter &j, const char *schema, const SeedTimer &t);

} // namespace svbench

#endif
