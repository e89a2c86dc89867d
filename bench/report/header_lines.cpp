/*
 * The header lines the cycle table and the scaling run share
 * (header_lines.h).
 *
 * Copyright (C) 2026 the shadowvol authors. LGPL-2.1-or-later.
 */
#include "header_lines.h"

#include "shadowvol.h"
#include "sysinfo.h"

namespace svbench {

void print_cpu_lines(FILE *out, int pinnedCpu) {
    std::fprintf(out, "cpu       %s", cpu_model().c_str());
    if (pinnedCpu >= 0) {
        std::fprintf(out, " (measuring thread pinned to cpu %d)\n", pinnedCpu);
    } else {
        std::fprintf(out, " (could not pin the measuring thread: expect noise)\n");
    }
    std::fprintf(out, "isa       %s (cpuid + xgetbv)\n", cpu_isa_flags().c_str());
}

void print_variant_lines(FILE *out, const std::vector<const BenchVariant *> &variants, bool chosen,
                         const std::string &limit, const std::vector<SkippedVariant> &skipped) {
    std::fprintf(out, "variants ");
    for (const BenchVariant *v : variants) {
        std::fprintf(out, " %s", v->name);
    }
    std::fprintf(out, " (%sISA level %s", chosen ? "--variant; " : "", sv_isa_level_name());
    if (!limit.empty()) {
        std::fprintf(out, "; limit: %s", limit.c_str());
    }
    std::fprintf(out, ")\n");
    for (const SkippedVariant &s : skipped) {
        std::fprintf(out, "skipped   variant %s: %s\n", s.name.c_str(), s.why.c_str());
    }
}

} // namespace svbench
