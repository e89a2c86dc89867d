/*
 * The cycle table (DESIGN.md section 5; the paper's section 8): every
 * routine of every variant the CPU runs, timed call by call with the
 * serialised TSC on the synthetic workload (routines too short for the
 * TSC's resolution in batches of back-to-back calls, reported per call), in
 * two regimes, each call checked against the paper's C, printed beside the
 * paper's Pentium 4 figures.
 *
 *   moving light  a different facing pattern every call, rotating through
 *                 the workload's patterns: the branch predictor cannot learn
 *                 the input. The headline.
 *   fixed light   pattern 0 every call: the paper's hot-cache setup, where a
 *                 modern predictor memorises the branches of the paper's C.
 *
 * Copyright (C) 2026 the shadowvol authors. LGPL-2.1-or-later.
 */
#ifndef SV_BENCH_CYCLE_TABLE_H
#define SV_BENCH_CYCLE_TABLE_H

#include <cstdint>
#include <cstdio>
#include <string>
#include <vector>

#include "shadowvol.h"
#include "timer.h"

namespace svbench {

enum class Routine {
    count_facing,
    count_facing_cull,
    create_sil_triangles,
    create_cap_triangles,
    create_shadow_volume,      /* sv_create_shadow_volume, cullBits NULL */
    create_shadow_volume_cull, /* sv_create_shadow_volume with cull bits */
};
constexpr int kNumRoutines = 6;

/* The largest batch: calls per timed region. */
constexpr int kMaxBatch = 64;

const char *routine_name(Routine r);
/* False when NAME is none of the names above. */
bool routine_by_name(const std::string &name, Routine *r);

struct TableOptions {
    int runs = 0;       /* timed regions per row (a call or a batch of calls) */
    int rounds = 4;     /* the runs of a row are split over this many passes
                           over all rows */
    int warmup = 0;     /* untimed (but checked) calls before each round */
    int batch = 0;      /* calls per timed region: 0 chooses per row (see
                           cycle_table.cpp), 1 never batches, N > 1 forces N
                           on every row; at most kMaxBatch */
    int patterns = 64;  /* facing patterns of the moving light */
    uint64_t seed = 1;  /* workload seed */
    bool moving = true; /* regimes to run */
    bool fixed = true;
    std::vector<Routine> routines;            /* empty: all */
    std::vector<const sv_variant *> variants; /* empty: all the CPU runs */
    TimerKind timer = TimerKind::cpuid;
    bool timerAuto = true; /* say in the header that auto chose it */
    int overheadTries = 5000;
    double tscSeconds = 0.05;
    bool progress = true; /* a \r-updated line on stderr when it is a TTY */
};

/* Builds the workload, measures, prints the header and one table per
 * regime to OUT. Returns 0 when every row's check passed, 1 otherwise.
 * Throws std::logic_error if the workload breaks an invariant. */
int run_cycle_table(const TableOptions &options, FILE *out);

} // namespace svbench

#endif
