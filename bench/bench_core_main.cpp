/*
 * `shadowvol bench` for the core-only builds (SV_CORE_ONLY, 32-bit x86;
 * docs/platforms.md): the cycle table of the bundled character, printed as
 * the full program prints it (table_report.h), from the same measurement
 * code (cycle_table.h). The full CLI's other commands (render, scene,
 * accuracy, --scaling, --json) need libraries that the core build leaves
 * out (TBB, OSMesa), so this program has the table only.
 *
 *   shadowvol bench [--quick] [--runs N] [--seed S] [--model FILE.glb]
 *
 * --limits is refused with a clear message: its probes are System V
 * x86-64 asm (bench/machine_limits.asm), not built here.
 *
 * Copyright (C) 2026 the shadowvol authors. LGPL-2.1-or-later.
 */
#include <algorithm>
#include <cerrno>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <string>

#include "bench_run.h"
#include "model_workload.h"
#include "routines.h"
#include "table_report.h"
#include "timer.h"

namespace {

using namespace svbench;

/* The full program's defaults (bench/bench_cli.cpp). */
constexpr int kDefaultRuns = 4000;
constexpr int kQuickRuns = 256;
constexpr int kMaxRuns = 1000000;
constexpr int kLights = 64;
constexpr int kExitCheckFailed = 1;
constexpr int kExitUsage = 2;
constexpr int kExitBadModel = 3;

void usage(FILE *out) {
    std::fprintf(out,
                 "usage: shadowvol bench [--quick] [--runs N] [--seed S] [--model FILE.glb]\n"
                 "\n"
                 "The cycle table (every routine of every variant this CPU runs, moving and\n"
                 "fixed light) on the bundled character, or on FILE.glb. This build is the\n"
                 "core-only one (docs/platforms.md): the full program's other commands and\n"
                 "options are not in it.\n");
}

bool parse_long(const char *s, long lo, long hi, long &out) {
    char *end = nullptr;
    errno = 0;
    const long v = std::strtol(s, &end, 10);
    if (errno || end == s || *end || v < lo || v > hi) return false;
    out = v;
    return true;
}

int bench(int argc, char **argv) {
    bool quick = false;
    long runs = 0, seed = 1;
    std::string model = SV_MODELS_DIR "/character_1344.glb";
    for (int i = 0; i < argc; i++) {
        const std::string a = argv[i];
        auto value = [&](const char *name) -> const char * {
            if (i + 1 >= argc) {
                std::fprintf(stderr, "shadowvol bench: %s needs a value\n", name);
                std::exit(kExitUsage);
            }
            return argv[++i];
        };
        if (a == "--help" || a == "-h") {
            usage(stdout);
            return 0;
        } else if (a == "--quick") {
            quick = true;
        } else if (a == "--runs") {
            if (!parse_long(value("--runs"), 1, kMaxRuns, runs)) {
                std::fprintf(stderr, "shadowvol bench: --runs takes 1 to %d\n", kMaxRuns);
                return kExitUsage;
            }
        } else if (a == "--seed") {
            if (!parse_long(value("--seed"), 0, 0x7fffffffL, seed)) {
                std::fprintf(stderr, "shadowvol bench: --seed takes 0 to 2147483647\n");
                return kExitUsage;
            }
        } else if (a == "--model") {
            model = value("--model");
        } else if (a == "--limits") {
            std::fprintf(stderr,
                         "shadowvol bench: --limits is not available on this platform: its "
                         "probes (bench/machine_limits.asm) are System V x86-64 code\n");
            return kExitUsage;
        } else {
            std::fprintf(stderr,
                         "shadowvol bench: unknown option '%s' (this core-only build has the "
                         "cycle table only)\nTry 'shadowvol bench --help'.\n",
                         a.c_str());
            return kExitUsage;
        }
    }

    BenchRun run;
    run.seed = (uint64_t)seed;
    if (sv_isa_limit_name()) {
        run.isaLimit = std::string(sv_isa_limit_name()) + " (SV_ISA)";
    }
    run.options.runs = runs ? (int)runs : quick ? kQuickRuns : kDefaultRuns;
    run.options.routines.assign(kAllRoutines, kAllRoutines + kNumRoutines);
    std::sort(run.options.routines.begin(), run.options.routines.end());
    for (const BenchVariant &v : bench_variants()) {
        if ((v.isa & sv_cpu_isa_detected()) != v.isa) {
            run.skipped.push_back({v.name, "this CPU lacks its instruction set"});
        } else if ((v.isa & sv_cpu_isa()) != v.isa) {
            run.skipped.push_back({v.name, "above the ISA limit " + run.isaLimit});
        } else {
            run.options.variants.push_back(&v);
        }
    }
    run.realModels = "not run (the core-only build times one model)";

    try {
        ModelRun mr;
        mr.workload = make_model_workload(model, LightTargets{}, kLights, run.seed, nullptr);
        run.models.push_back(std::move(mr));
    } catch (const WorkloadError &e) {
        std::fprintf(stderr, "shadowvol bench: %s\n", e.what());
        return kExitBadModel;
    }

    try {
        run.machine = measure_machine(timer_auto(), true, quick ? 1000 : 5000, 0.05);
        print_run_header(stdout, run);
        for (ModelRun &m : run.models) {
            TableOptions o = run.options;
            const int perRound = (o.runs + o.rounds - 1) / o.rounds;
            o.warmup = std::min(m.workload.numMoving, perRound);
            m.table = run_cycle_table(o, run.machine, m.workload);
            print_model(stdout, run, m);
        }
        print_notes(stdout, run);
    } catch (const std::exception &e) {
        std::fprintf(stderr, "shadowvol bench: internal error: %s\n", e.what());
        return kExitCheckFailed;
    }
    const int failed = failed_rows(run);
    if (failed) {
        std::fprintf(stderr, "shadowvol bench: %d row%s failed the check against the reference\n",
                     failed, failed == 1 ? "" : "s");
        return kExitCheckFailed;
    }
    return 0;
}

} // namespace

int main(int argc, char **argv) {
    if (argc >= 2 && std::strcmp(argv[1], "bench") == 0) {
        return bench(argc - 2, argv + 2);
    }
    if (argc >= 2 && (std::strcmp(argv[1], "--help") == 0 || std::strcmp(argv[1], "help") == 0)) {
        usage(stdout);
        return 0;
    }
    std::fprintf(stderr, "shadowvol (core-only build): the one command is 'bench'\n");
    usage(stderr);
    return kExitUsage;
}
