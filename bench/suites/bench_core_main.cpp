/*
 * `shadowvol bench` for the core-only builds (SV_CORE_ONLY, 32-bit x86;
 * docs/PLATFORMS.md): the cycle table of the project's character, printed
 * as the full program prints it (table_report.h), from the same
 * measurement code (cycle_table.h). The full CLI's other commands (render,
 * scene, accuracy, --scaling, --json) need libraries that the core build
 * leaves out (TBB, OSMesa), so this program has the table only.
 *
 * The character is built in memory by the model generator
 * (tools/generate_models, svgen::build_character(1)): the mesh that
 * models/character_1344.glb holds byte for byte (the generated_models test
 * proves it), without the glTF loader, whose tinygltf build alone would
 * double this program's build time.
 *
 *   shadowvol bench [--quick] [--runs N] [--seed S]
 *
 * --limits is refused with a clear message: its probes are System V
 * x86-64 asm (bench/machine/machine_limits.asm), which only the full x86-64 Linux
 * build links.
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
#include "lights.h"
#include "model_gen.h"
#include "shadowvol_mesh.h"
#include "routines.h"
#include "table_report.h"
#include "timer.h"

namespace {

using namespace svbench;

/* The full program's defaults (src/cli/bench_cli.cpp). */
constexpr int kDefaultRuns = 4000;
constexpr int kQuickRuns = 256;
constexpr int kMaxRuns = 1000000;
constexpr int kLights = 64;
constexpr int kExitCheckFailed = 1;
constexpr int kExitUsage = 2;
constexpr int kExitBadModel = 3;

void usage(FILE *out) {
    std::fprintf(out, "usage: shadowvol bench [--quick] [--runs N] [--seed S]\n"
                      "\n"
                      "The cycle table (every routine of every variant this CPU runs, moving and\n"
                      "fixed light) on the generated character (1344 triangles, the mesh of\n"
                      "models/character_1344.glb). This build is the core-only one\n"
                      "(docs/PLATFORMS.md): the full program's other commands and options are\n"
                      "not in it.\n");
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
        } else if (a == "--limits") {
            std::fprintf(stderr,
                         "shadowvol bench: --limits is not in this build: its probes "
                         "(bench/machine/machine_limits.asm) are System V x86-64 asm, built by the "
                         "full x86-64 Linux build only\n");
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
    run.realModels = "the generated character only (the core-only build has no glTF loader)";

    try {
        ModelRun mr;
        const svgen::TriMesh mesh = svgen::build_character(1);
        const sv::PreparedSurface prepared = sv::prepare_surface(mesh.positions.data(),
                                                                 mesh.num_vertices(),
                                                                 mesh.indices.data(),
                                                                 mesh.indices.size());
        mr.workload =
            workload_from_surface(prepared, "character_1344",
                                  "the generated character (tools/generate_models), the mesh of "
                                  "models/character_1344.glb");
        mr.workload.surfaces = 1;
        place_lights(mr.workload, LightTargets{}, kLights, run.seed, nullptr);
        run.models.push_back(std::move(mr));
    } catch (const sv::PrepareError &e) {
        std::fprintf(stderr, "shadowvol bench: the generated character: %s\n", e.what());
        return kExitBadModel;
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
    return check_failed_status(run);
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
