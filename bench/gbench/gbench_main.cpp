/*
 * shadowvol_gbench: the routines of `shadowvol bench` as Google Benchmark
 * cases, for users who want that tool's console and JSON output
 * (--benchmark_format=json), filters and repetitions.
 *
 * Cases: routine/variant/regime, for every routine of the paper's
 * pipeline and every variant that implements it and this CPU runs
 * (sv_cpu_isa(), so SV_ISA=sse2 holds them down as it does the library's
 * dispatch), under the moving light and the fixed one:
 *   create_shadow_volume/sse2_paper/moving
 * on the workload of the cycle table: the bundled 1344-triangle character
 * lit by 64 searched lights (bench/harness/lights.h), or --model FILE. How a case
 * is timed, and checked against c_ref first: gbench_cases.h.
 *
 * Exit status: 0 done; 1 a case failed its check (its row says ERROR
 * OCCURRED and why); 2 bad arguments; 3 the model could not be loaded.
 *
 * Copyright (C) 2026 the shadowvol authors. LGPL-2.1-or-later.
 */
#include <cerrno>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <deque>
#include <string>

#include <benchmark/benchmark.h>

#include "gbench_cases.h"
#include "lights.h"
#include "model_workload.h"
#include "routines.h"
#include "sysinfo.h"
#include "timer.h"

/* Set by bench/gbench/CMakeLists.txt. */
#ifndef SV_MODELS_DIR
#define SV_MODELS_DIR "models"
#endif

namespace {

constexpr int kLights = 64; /* as `shadowvol bench` */
constexpr int kExitFailed = 1;
constexpr int kExitUsage = 2;
constexpr int kExitBadModel = 3;

const char *const kBundledModel = SV_MODELS_DIR "/character_1344.glb";

void usage() {
    std::printf("usage: shadowvol_gbench [--model FILE] [--seed N] [Google Benchmark options]\n"
                "\n"
                "The routines of `shadowvol bench` (routine/variant/regime) as Google Benchmark\n"
                "cases, on the same workload: the bundled 1344-triangle character lit by %d\n"
                "searched lights (about 50%% of the triangles facing, 20%% of the SilEdges on\n"
                "the silhouette). Every case is checked against c_ref before it is timed.\n"
                "Counters: elements_per_second; ticks_per_element (TSC ticks, not core cycles).\n"
                "\n"
                "  --model FILE     time another glTF model (all its surfaces merged)\n"
                "  --seed N         seed of the light search (default 1)\n"
                "  SV_ISA=LEVEL     (environment) only the variants within c, sse2, avx2 or\n"
                "                   avx512\n"
                "\n"
                "e.g. --benchmark_filter=/moving --benchmark_min_time=0.1 --benchmark_format=json\n"
                "\n"
                "Google Benchmark's options:\n",
                kLights);
    benchmark::PrintDefaultHelp();
}

struct Args {
    std::string model = kBundledModel;
    uint64_t seed = 1;
};

/* Takes our options out of ARGV (Google Benchmark has taken its own);
 * returns false, with a message, on a bad one. */
bool parse_args(int *argc, char **argv, Args *a) {
    int kept = 1;
    for (int i = 1; i < *argc; i++) {
        std::string arg = argv[i], value;
        const size_t eq = arg.find('=');
        std::string opt = arg.substr(0, eq);
        const bool inline_ = eq != std::string::npos;
        if (opt != "--model" && opt != "--seed") {
            argv[kept++] = argv[i];
            continue;
        }
        if (inline_) {
            value = arg.substr(eq + 1);
        } else if (i + 1 < *argc) {
            value = argv[++i];
        } else {
            std::fprintf(stderr, "shadowvol_gbench: %s needs a value\n", opt.c_str());
            return false;
        }
        if (opt == "--model") {
            if (value.empty()) {
                std::fprintf(stderr, "shadowvol_gbench: --model needs a file\n");
                return false;
            }
            a->model = value;
        } else {
            errno = 0;
            char *end = nullptr;
            a->seed = std::strtoull(value.c_str(), &end, 10);
            if (value.empty() || value.find_first_not_of("0123456789") != std::string::npos ||
                errno == ERANGE) {
                std::fprintf(stderr, "shadowvol_gbench: --seed needs a whole number, not '%s'\n",
                             value.c_str());
                return false;
            }
        }
    }
    *argc = kept;
    argv[kept] = nullptr;
    return true;
}

} // namespace

int main(int argc, char **argv) {
    benchmark::Initialize(&argc, argv, usage);
    Args args;
    if (!parse_args(&argc, argv, &args)) {
        return kExitUsage;
    }
    if (benchmark::ReportUnrecognizedArguments(argc, argv)) {
        return kExitUsage;
    }

    svbench::Workload w;
    try {
        w = svbench::make_model_workload(args.model, svbench::LightTargets{}, kLights, args.seed,
                                         nullptr);
    } catch (const svbench::WorkloadError &e) {
        std::fprintf(stderr, "shadowvol_gbench: %s\n", e.what());
        return kExitBadModel;
    }
    /* One CPU for the whole run, as the cycle table: no migration between
     * caches in the middle of a case. */
    const int cpu = svbench::pin_to_current_cpu();

    char ratios[128];
    std::snprintf(ratios, sizeof ratios, "%d moving lights: facing %.1f%%, silhouette %.1f%%",
                  w.numMoving, 100 * svbench::ratio_stats(w, svbench::Ratio::facing).mean,
                  100 * svbench::ratio_stats(w, svbench::Ratio::silhouette).mean);
    benchmark::AddCustomContext("shadowvol_model", w.source);
    benchmark::AddCustomContext("shadowvol_mesh", std::to_string(w.numTriangles) + " triangles, " +
                                                      std::to_string(w.numSilEdges) +
                                                      " SilEdges, " + std::to_string(w.numVerts) +
                                                      " vertices");
    benchmark::AddCustomContext("shadowvol_lights", ratios);
    benchmark::AddCustomContext("shadowvol_cpu", svbench::cpu_model());
    benchmark::AddCustomContext("shadowvol_isa_level", sv_isa_level_name());
    char hz[64];
    std::snprintf(hz, sizeof hz, "%.0f", svbench::estimate_tsc_hz(0.05));
    benchmark::AddCustomContext("shadowvol_tsc_hz", hz);
    benchmark::AddCustomContext("shadowvol_pinned_cpu", std::to_string(cpu));
    benchmark::AddCustomContext("shadowvol_commit", svbench::git_commit());

    svgbench::Context context(std::move(w));
    std::deque<svgbench::Case> cases; /* stable addresses for the lambdas */
    for (svbench::Routine r : svbench::kAllRoutines) {
        for (const svbench::BenchVariant &v : svbench::bench_variants()) {
            /* The pipelines and the planner's choice are the cycle table's
             * (shadowvol bench); this twin times the paper's routines. */
            if (v.planned || r == svbench::Routine::pipeline ||
                r == svbench::Routine::pipeline_cull) {
                continue;
            }
            if (!svbench::implements(v, r) || (v.isa & sv_cpu_isa()) != v.isa) {
                continue;
            }
            for (bool moving : {true, false}) {
                svgbench::Case c;
                c.context = &context;
                c.routine = r;
                c.variant = &v;
                c.moving = moving;
                cases.push_back(c);
                svgbench::Case *p = &cases.back();
                benchmark::RegisterBenchmark(svgbench::case_name(*p).c_str(),
                                             [p](benchmark::State &s) {
                                                 svgbench::run_case(s, *p);
                                             });
            }
        }
    }

    benchmark::RunSpecifiedBenchmarks();
    benchmark::Shutdown();
    if (const int failed = svgbench::failed_cases()) {
        std::fprintf(stderr, "shadowvol_gbench: %d case%s FAILED the check against c_ref\n", failed,
                     failed == 1 ? "" : "s");
        return kExitFailed;
    }
    return 0;
}
