/*
 * `shadowvol bench --scaling`, once bench_cli.cpp has parsed its options:
 * the meshes loaded or built in turn, each measured (scaling.h) and
 * printed as it completes, then the tables, the JSON document and the
 * plot.
 *
 * Copyright (C) 2026 the shadowvol authors. LGPL-2.1-or-later.
 */
#ifndef SV_BENCH_SCALING_CLI_H
#define SV_BENCH_SCALING_CLI_H

#include <string>
#include <vector>

#include "bench_run.h"
#include "scaling.h"
#include "timer.h"

namespace svbench {

struct ScalingCommand {
    ScalingOptions options; /* variants and routines chosen */
    std::string json;       /* --json FILE: "" none, "-" standard output */
    std::string plot;       /* --plot FILE: the same */
    TimerKind timer = TimerKind::rdtscp;
    bool timerAuto = true;
    std::string isaLimit; /* as BenchRun's */
    bool variantsChosen = false;
    std::vector<SkippedVariant> skipped;
};

/* The exit status, as bench_main's: 0 done, 1 a row failed its check (or
 * an internal error, or a document could not be written), 2 a file named
 * by --json or --plot cannot be written, 3 a real character could not be
 * loaded. */
int run_scaling(const ScalingCommand &cmd);

} // namespace svbench

#endif
