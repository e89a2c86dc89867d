/*
 * `shadowvol bench --scaling`: the cost per element as the mesh grows
 * (DESIGN.md section 5, "beyond one character"), under the moving light,
 * for every variant this CPU runs.
 *
 * Meshes:
 *   generated  the project's character (tools/generate_models) with each
 *              quad subdivided n x n: 1344 n^2 triangles, n = 1, 2, 3, 5,
 *              9, 14, 27 (1344 to 979776); closed and 2-manifold at every
 *              size, so the family differs in size alone. n = 1 is the
 *              bundled models/character_1344.glb.
 *   real       every glTF file in the real characters' folder
 *              (SV_SHARED_MODELS_DIR) when it exists: other shapes, vertex
 *              orders and silhouette ratios, plotted as loose points.
 *
 * Each mesh is one cycle table (cycle_table.h), moving light only: every
 * call timed alone with the serialised TSC and checked against c_ref
 * outside the timed region. What changes with the size:
 *   lights  64 up to kFullLightTriangles triangles, then 64 x
 *           kFullLightTriangles / T, at least kMinScalingLights: the light
 *           search and the reference results cost per light and per
 *           triangle, and a branch predictor cannot learn one pattern of
 *           tens of thousands of branches, let alone eight.
 *   runs    as given for a 1344-triangle mesh, then in proportion to
 *           1344 / T, at least kMinScalingRuns (a long call is steadier).
 * Meshes are built (or loaded) in turn and their arrays freed once
 * measured: the run peaks at about 150 MB, on the 1M-triangle mesh.
 *
 * Copyright (C) 2026 the shadowvol authors. LGPL-2.1-or-later.
 */
#ifndef SV_BENCH_SCALING_H
#define SV_BENCH_SCALING_H

#include <cstdint>
#include <string>
#include <vector>

#include "bench_run.h"
#include "cache_info.h"
#include "cycle_table.h"
#include "lights.h"
#include "routines.h"
#include "workload.h"

namespace svbench {

/* The generated sizes: 1344 n^2 triangles. */
constexpr int kScalingSubdivisions[] = {1, 2, 3, 5, 9, 14, 27};
/* --quick: up to about 100k triangles. */
constexpr int kQuickScalingSubdivisions[] = {1, 3, 9};

constexpr int kScalingLights = 64;
constexpr int kFullLightTriangles = 16384;
constexpr int kMinScalingLights = 8;
constexpr int kScalingReferenceTriangles = 1344;
constexpr int kDefaultScalingRuns = 1000;
constexpr int kQuickScalingRuns = 128;
constexpr int kMinScalingRuns = 32;
constexpr int kMinQuickScalingRuns = 8;
constexpr long kWarmupTriangles = 16L * kFullLightTriangles;
constexpr int kMinScalingWarmup = 2;

/* The routines a scaling run times unless --routine narrows them: the
 * volume first (the headline; the plot's first panel), then appendix A
 * and the four kernels it is made of. */
const std::vector<Routine> &default_scaling_routines();

struct ScalingOptions {
    bool quick = false;
    int runs = 0;          /* per row on a 1344-triangle mesh; 0: the default */
    int rounds = 4;        /* as the cycle table's --rounds */
    long maxTriangles = 0; /* larger meshes are left out; 0: no limit */
    uint64_t seed = 1;
    LightTargets targets;
    int batch = 0;                              /* as the cycle table's --batch */
    std::vector<Routine> routines;              /* in table order */
    std::vector<const BenchVariant *> variants; /* in table order */
    bool progress = true;
    std::string sharedModels; /* the real characters' folder */
    /* --model FILE or DIR (repeatable): the user's own meshes, measured
     * beside the generated ones and the real characters (each loaded with
     * every surface merged into one, as the real characters are). */
    std::vector<std::string> models;
};

/* One mesh to measure. */
struct MeshSpec {
    std::string name; /* "character_5376", or the file name */
    bool generated = false;
    int subdivision = 0; /* n, for a generated mesh */
    std::string path;    /* a real model's file */
};

/* The generated character of S (S.subdivision), prepared, as a workload
 * without lights (also the seed benchmarks' meshes). Throws WorkloadError. */
Workload generated_surface(const MeshSpec &s);

/* One measured mesh: its workload (arrays freed once measured, counts and
 * lights' ratios kept) and its table. */
struct ScalingMesh {
    MeshSpec spec;
    long triangles = 0; /* known before the mesh is built */
    Workload workload;
    ModelTable table;
    int runs = 0;
    double seconds = 0; /* building, lighting and measuring it */
};

struct ScalingRun {
    MachineTiming machine;
    ScalingOptions options;
    std::string isaLimit; /* as BenchRun's */
    bool variantsChosen = false;
    std::vector<SkippedVariant> skipped;
    std::string realModels;           /* where the real characters are, whether they run */
    std::vector<std::string> leftOut; /* meshes above --max-triangles, with their sizes */
    std::vector<ScalingMesh> meshes;  /* in order of triangles */
    /* Streaming reads from memory, bytes per tick (measure_memory_load_rate),
     * measured when the largest mesh's pipeline working set is beyond 32
     * MiB; 0 otherwise. */
    double memoryLoadBytes = 0;
};

/* Lights and runs for a mesh of TRIANGLES (see above). */
int scaling_lights(long triangles);
int scaling_runs(const ScalingOptions &o, long triangles);
/* Untimed (checked) calls before each round of a row: as the cycle table,
 * up to a turn of the lights and a round's runs, and on a large mesh no
 * more than kWarmupTriangles / T (at least kMinScalingWarmup): one call
 * of a million triangles warms what it can, and the warm-up calls of the
 * largest mesh would otherwise take half the run. */
int scaling_warmup(int runs, int rounds, const Workload &w);

/* The generated meshes of the run (--quick: fewer), and the real
 * characters of O.sharedModels (a note on them in *NOTE). Throws
 * ModelListError for a folder without glTF files. */
std::vector<MeshSpec> scaling_meshes(const ScalingOptions &o, std::string *note);

/* The mesh of S, no lights yet: the generated character built and
 * prepared, or the model loaded with every surface merged into one (as the
 * cycle table does). Throws WorkloadError. */
Workload scaling_surface(const MeshSpec &s);

/* Places scaling_lights() lights on W (O's targets and seed). */
void light_scaling_workload(Workload &w, const ScalingOptions &o);

/* Measures M (whose workload is built) with RUN's machine and options,
 * then frees the workload's arrays. */
void measure_scaling_mesh(const ScalingRun &run, ScalingMesh &m);

/* Rows that failed their check, over all meshes. */
int failed_scaling_rows(const ScalingRun &run);

/* The row of ROUTINE x VARIANT in M, or nullptr. */
const Row *scaling_row(const ScalingMesh &m, Routine routine, const BenchVariant *variant);

} // namespace svbench

#endif
