/*
 * One `shadowvol bench` run as the reports see it: the machine, the
 * options, and per model its workload and measured rows. The human table
 * (table_report.h) and the JSON document (json_report.h) both print this.
 *
 * Copyright (C) 2026 the shadowvol authors. LGPL-2.1-or-later.
 */
#ifndef SV_BENCH_BENCH_RUN_H
#define SV_BENCH_BENCH_RUN_H

#include <cstdio>
#include <cstdint>
#include <string>
#include <vector>

#include "cycle_table.h"
#include "machine_limits.h"
#include "workload.h"

namespace svbench {

struct ModelRun {
    Workload workload;
    ModelTable table;
};

struct SkippedVariant {
    std::string name;
    std::string why;
};

struct BenchRun {
    MachineTiming machine;
    TableOptions options; /* runs as asked (models above 1344 triangles get
                               fewer: their ModelTable says how many) */
    uint64_t seed = 1;
    std::string isaLimit;        /* "c (--isa)", "sse2 (SV_ISA)"; "" when none */
    bool variantsChosen = false; /* --variant narrowed them */
    std::vector<SkippedVariant> skipped;
    std::string realModels; /* where the real characters are, and whether they run */
    std::vector<ModelRun> models;
    bool limitsMeasured = false; /* --limits */
    MachineLimits limits;
};

/* Rows that failed their check, over all models. */
inline int failed_rows(const BenchRun &run) {
    int n = 0;
    for (const ModelRun &m : run.models) {
        for (const Row &r : m.table.rows) {
            n += !r.ok;
        }
    }
    return n;
}

/* The run's exit status after its table: 1 with a message on stderr when a
 * row failed its check, else 0 (shadowvol bench, and the 32-bit bench). */
inline int check_failed_status(const BenchRun &run) {
    const int failed = failed_rows(run);
    if (failed) {
        std::fprintf(stderr, "shadowvol bench: %d row%s failed the check against the reference\n",
                     failed, failed == 1 ? "" : "s");
        return 1;
    }
    return 0;
}

} // namespace svbench

#endif
