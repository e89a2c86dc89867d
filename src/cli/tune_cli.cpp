/*
 * shadowvol tune: per size class, every runnable variant of each routine
 * timed on the planner's generated mesh (every call checked against
 * c_ref), a table of the timings with the winner and the static choice
 * marked, then the winners saved as this CPU's section of the wisdom file.
 *
 * Exit status: 0 done; 1 a variant disagreed with c_ref (nothing saved);
 * 2 bad arguments; 3 the wisdom file could not be written (or read, when
 * it exists and is not a wisdom file).
 *
 * Copyright (C) 2026 the shadowvol authors. LGPL-2.1-or-later.
 */
#include "tune_cli.h"

#include <algorithm>
#include <cstdio>
#include <map>
#include <string>
#include <vector>

#include "cli_args.h"
#include "shadowvol_plan.h"

namespace svcli {

void tune_usage(FILE *out) {
    std::fprintf(out,
                 "usage: shadowvol tune [--class N]... [--wisdom FILE] [--dry-run]\n"
                 "  Times every variant of every routine this CPU runs on a generated mesh of\n"
                 "  each size class (0: under 4096 triangles, 1: under 65536, 2: under 524288,\n"
                 "  3: larger; measured at 2048, 24576, 196608 and 1048576 triangles), checks\n"
                 "  every call against c_ref, and saves the fastest per routine and class as\n"
                 "  this CPU's plans (sv_plan_for reads them; see docs/benchmark.md).\n"
                 "  --class N       measure class N only (repeatable; default: all four)\n"
                 "  --wisdom FILE   the wisdom file (default: $SV_WISDOM, else\n"
                 "                  $XDG_CACHE_HOME/shadowvol/wisdom, else ~/.cache/shadowvol/wisdom)\n"
                 "  --dry-run       measure and print, save nothing\n"
                 "exit status: 0 done, 1 a variant disagreed with c_ref, 2 bad arguments,\n"
                 "3 the wisdom file could not be written\n");
}

int tune_main(int argc, char **argv) {
    std::vector<int> classes;
    std::string path;
    bool dry = false;
    try {
        ArgReader a(argc, argv);
        while (a.next()) {
            if (a.is_flag("--help") || a.is_flag("-h")) {
                tune_usage(stdout);
                return 0;
            } else if (a.is("--class")) {
                classes.push_back((int)a.integer(0, SV_NUM_SIZE_CLASSES - 1));
            } else if (a.is("--wisdom")) {
                path = a.value();
                if (path.empty()) usage_error("--wisdom needs a file name");
            } else if (a.is_flag("--dry-run")) {
                dry = true;
            } else {
                usage_error("unknown argument '" + quoted(a.arg()) + "'");
            }
        }
    } catch (const UsageError &e) {
        std::fprintf(stderr, "shadowvol tune: %s\nTry 'shadowvol tune --help'.\n", e.message.c_str());
        return 2;
    }
    if (classes.empty()) {
        for (int c = 0; c < SV_NUM_SIZE_CLASSES; c++) classes.push_back(c);
    }
    char buf[1024];
    if (path.empty()) path = sv_wisdom_default_path(buf, sizeof buf);
    if (path.empty() && !dry) {
        std::fprintf(stderr, "shadowvol tune: no wisdom file (set SV_WISDOM or HOME, or give --wisdom)\n");
        return 3;
    }
    char key[256];
    std::printf("cpu       %s\n", sv_cpu_model_key(key, sizeof key));
    std::printf("unit      median TSC ticks per call, 8 moving lights, each call checked against c_ref\n");
    for (int c : classes) {
        std::vector<sv_plan_timing> t(256);
        const int n = sv_plan_measure(c, t.data(), (int)t.size());
        if (n < 0) {
            std::fprintf(stderr, "shadowvol tune: class %d: a variant's result differed from c_ref's; "
                                 "nothing saved (a bug: please report it)\n", c);
            return 1;
        }
        t.resize((size_t)std::min(n, (int)t.size()));
        const sv_plan *p = sv_plan_for(sv_size_class_triangles(c), SV_PLAN_ESTIMATE);
        std::printf("\nclass %d (%d triangles)\n", c, sv_size_class_triangles(c));
        std::printf("%-22s %-14s %12s %10s  %s\n", "routine", "variant", "ticks", "vs static", "");
        for (int r = 0; r < SV_NUM_ROUTINES; r++) {
            const char *stat = sv_static_variant_name((sv_routine)r);
            double stat_ticks = 0;
            for (const sv_plan_timing &x : t) {
                if (x.routine == r && std::string(x.variant) == stat) stat_ticks = x.ticks;
            }
            for (const sv_plan_timing &x : t) {
                if (x.routine != r) continue;
                const bool chosen = std::string(x.variant) == p->variant[r];
                const bool is_static = std::string(x.variant) == stat;
                std::printf("%-22s %-14s %12.0f %9.2fx  %s%s\n", sv_routine_name((sv_routine)r),
                            x.variant, x.ticks, x.ticks > 0 ? stat_ticks / x.ticks : 0.0,
                            chosen ? "<- planned" : "", is_static ? (chosen ? ", static" : "(static)") : "");
            }
        }
    }
    if (dry) {
        std::printf("\n--dry-run: nothing saved\n");
        return 0;
    }
    if (sv_wisdom_save(path.c_str()) != 0) {
        std::fprintf(stderr, "shadowvol tune: cannot write the wisdom file %s\n",
                     quoted(path).c_str());
        return 3;
    }
    std::printf("\nsaved     %s (this CPU's section; other CPUs' kept)\n", path.c_str());
    return 0;
}

} // namespace svcli
