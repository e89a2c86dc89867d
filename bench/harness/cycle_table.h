/*
 * The cycle table's measurements (DESIGN.md section 5; the paper's section
 * 8): every routine of every variant selected, timed call by call with the
 * serialised TSC on one workload (routines too short for the TSC's
 * resolution in batches of back-to-back calls, reported per call), in two
 * regimes, each call checked outside the timed region (expected.h).
 *
 *   moving light  a different light every call, rotating through the
 *                 workload's moving lights: the branch predictor cannot
 *                 learn the input. The headline.
 *   fixed light   the workload's fixed light every call: the paper's
 *                 hot-cache setup, where a modern predictor memorises the
 *                 branches of the paper's C.
 *
 * Printing is table_report.h's job, JSON json_report.h's.
 *
 * Copyright (C) 2026 the shadowvol authors. LGPL-2.1-or-later.
 */
#ifndef SV_BENCH_CYCLE_TABLE_H
#define SV_BENCH_CYCLE_TABLE_H

#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

#include "routines.h"
#include "timer.h"
#include "workload.h"

namespace svbench {

/* The largest batch: calls per timed region. */
constexpr int kMaxBatch = 64;
/* A row is batched when its single call lasts under this many TSC steps
 * (or jitters of the empty region; see cycle_table.cpp). */
constexpr uint64_t kBatchSteps = 50;
/* A timed region whose median is below kNoiseFactor times the larger of
 * the TSC's step and the spread (IQR) of the row's empty regions is mostly
 * timer noise: its speed-up is marked "~". */
constexpr uint64_t kNoiseFactor = 5;

/* The timer and what it costs on this machine, measured once per run. */
struct MachineTiming {
    TimerKind timer = TimerKind::cpuid;
    bool timerAuto = true;       /* auto chose it (the header says why) */
    double tscHz = 0;            /* rdtsc against CLOCK_MONOTONIC */
    double tscSeconds = 0;       /* over how long */
    Overhead overhead{};         /* of an empty timed region */
    uint64_t step = 0;           /* the smallest TSC increment seen */
    uint64_t emptyIqr = 0;       /* IQR of the empty regions */
    uint64_t batchThreshold = 0; /* ticks: a shorter call is batched */
    size_t l1dBytes = 0;
    int cpu = -1; /* the CPU the thread is pinned to; -1 not pinned */
};
MachineTiming measure_machine(TimerKind timer, bool timerAuto, int overheadTries,
                              double tscSeconds);

struct TableOptions {
    int runs = 0;       /* timed regions per row (a call or a batch of calls) */
    int rounds = 4;     /* the runs of a row are split over this many passes
                          over all rows */
    int warmup = 0;     /* untimed (but checked) calls before each round */
    int batch = 0;      /* calls per timed region: 0 chooses per row, 1 never
                          batches, N > 1 forces N on every row */
    bool moving = true; /* regimes to run */
    bool fixed = true;
    std::vector<Routine> routines;              /* in table order */
    std::vector<const BenchVariant *> variants; /* in table order */
    bool progress = true;                       /* a \r-updated line on stderr when it is a TTY */
};

/* One row of the table. */
struct Row {
    Routine routine = Routine::count_facing;
    const BenchVariant *variant = nullptr;
    bool moving = true;
    bool ok = true;
    std::string failure;
    int rounds = 0;                         /* rounds measured so far */
    int batch = 0;                          /* calls per timed region; 0: not decided yet */
    long calls = 0;                         /* calls made: the moving light's next light */
    double min = 0, median = 0;             /* ticks per call, the fences' cost subtracted */
    uint64_t emptyMedian = 0, emptyIqr = 0; /* empty regions of the round kept */
    double medianWorst = 0;                 /* the highest of the rounds' medians */
};

/* Elements a row's per-element figures divide by. */
int elements_of(Routine r, const Workload &w);
/* The row's median is mostly timer noise (kNoiseFactor). */
bool below_noise(const Row &r, uint64_t step);
/* The c_ref row of the same routine and regime, when it was measured and
 * passed its check. */
const Row *reference_row(const std::vector<Row> &rows, const Row &r);

struct ModelTable {
    std::vector<Row> rows; /* moving regime first, then routines, then variants */
    int runs = 0, warmup = 0, rounds = 0;
    std::vector<Routine> skippedRoutines; /* need a light; the workload has none */
};

/* Measures every row on W. Throws std::logic_error if the workload breaks
 * an invariant. */
ModelTable run_cycle_table(const TableOptions &o, const MachineTiming &m, const Workload &w);

} // namespace svbench

#endif
