/*
 * Copyright (C) 2026 the shadowvol authors. LGPL-2.1-or-later.
 */
#include "table_report.h"

#include <algorithm>
#include <cstring>
#include <string>

#include "paper_results.h"
#include "header_lines.h"
#include "sysinfo.h"

namespace svbench {

namespace {

std::string pct(double ratio) {
    char s[32];
    std::snprintf(s, sizeof s, "%.1f%%", 100.0 * ratio);
    return s;
}

/* A ratio over the moving lights: "49.0% (46.9..51.3)", mean (lowest ..
 * highest), or one figure when they all agree. */
std::string stats(const Workload &w, Ratio which) {
    const RatioStats s = ratio_stats(w, which);
    char buf[64];
    if (s.min == s.max) {
        std::snprintf(buf, sizeof buf, "%.1f%%", 100.0 * s.mean);
    } else {
        std::snprintf(buf, sizeof buf, "%.1f%% (%.1f..%.1f)", 100.0 * s.mean, 100.0 * s.min,
                      100.0 * s.max);
    }
    return buf;
}

/* The paper's character: 1344 triangles, 2016 SilEdges. Its totals are
 * printed beside a mesh of that size only. */
bool paper_sized(const Workload &w) {
    return w.numTriangles == kPaperTriangles && w.numSilEdges == kPaperSilEdges;
}

void print_mesh(FILE *out, const Workload &w) {
    std::fprintf(out, "\nmodel     %s: %s\n", w.name.c_str(), w.source.c_str());
    std::fprintf(out,
                 "mesh      %d surface%s, welded: %d vertices, %d triangles, %d SilEdges (%d "
                 "dangling), %s",
                 w.surfaces, w.surfaces == 1 ? "" : "s merged", w.numVerts, w.numTriangles,
                 w.numSilEdges, w.numDangling, w.closed ? "closed" : "not closed");
    if (w.degenerateDropped) {
        std::fprintf(out, ",\n          %d degenerate triangle%s dropped", w.degenerateDropped,
                     w.degenerateDropped == 1 ? "" : "s");
    }
    std::fprintf(out, "\n");
}

void print_lights(FILE *out, const Workload &w) {
    const LightOrigin &o = w.origin;
    const Light &f = w.lights[(size_t)w.fixedLight];
    if (o.lit) {
        std::fprintf(out,
                     "lights    %d point lights, those nearest to facing %s and silhouette %s of "
                     "%d placed at random\n          1 to 16 bounding radii from the centre "
                     "(seed %llu); mean (lowest..highest):\n          facing %s, silhouette "
                     "%s\n",
                     w.numMoving, pct(o.targetFacing).c_str(), pct(o.targetSilhouette).c_str(),
                     o.candidates, (unsigned long long)o.seed, stats(w, Ratio::facing).c_str(),
                     stats(w, Ratio::silhouette).c_str());
        std::fprintf(out,
                     "fixed     %s at (%.6g, %.6g, %.6g, %g):\n          facing %s, silhouette "
                     "%s, culled %s\n",
                     o.fixedGiven ? "--light" : "the nearest of them,", f.position.x, f.position.y,
                     f.position.z, f.position.w, pct(light_ratio(w, f, Ratio::facing)).c_str(),
                     pct(light_ratio(w, f, Ratio::silhouette)).c_str(),
                     pct(light_ratio(w, f, Ratio::culled)).c_str());
        std::fprintf(out,
                     "cull      a cube around each light: %s of the triangles outside (target "
                     "%s);\n          the culling routines turn %s of the non-facing triangles "
                     "facing\n",
                     stats(w, Ratio::culled).c_str(), pct(o.targetCulled).c_str(),
                     stats(w, Ratio::turned).c_str());
    } else {
        std::fprintf(out,
                     "lights    %d facing patterns generated, not lit (seed %llu), each: facing "
                     "%s (%d),\n          silhouette %s (%d) (on a closed mesh the silhouette "
                     "count has the parity\n          of the facing count)\n",
                     w.numMoving, (unsigned long long)o.seed,
                     pct(light_ratio(w, f, Ratio::facing)).c_str(), f.numFacing,
                     pct(light_ratio(w, f, Ratio::silhouette)).c_str(), f.numSilhouette);
        std::fprintf(out, "fixed     pattern %d%s\n", w.fixedLight,
                     o.fixedGiven ? " (--light does not apply: the patterns are not lit)" : "");
        std::fprintf(out,
                     "cull      one fixed light box: %s of the triangles outside; the culling "
                     "routines turn\n          %s of the non-facing triangles facing\n",
                     stats(w, Ratio::culled).c_str(), stats(w, Ratio::turned).c_str());
    }
}

void print_runs(FILE *out, const BenchRun &run, const ModelRun &m) {
    const ModelTable &t = m.table;
    std::fprintf(out,
                 "runs      %d timed regions per row in %d round%s over all rows, each after %d "
                 "warm-up calls; a row\n          keeps its lowest min and its lowest round median",
                 t.runs, t.rounds, t.rounds == 1 ? "" : "s", t.warmup);
    if (t.runs != run.options.runs) {
        std::fprintf(out, "\n          (--runs %d scaled down to this mesh's size)",
                     run.options.runs);
    }
    uint64_t lo = UINT64_MAX, hi = 0;
    for (const Row &r : t.rows) {
        if (r.ok) {
            lo = std::min(lo, r.emptyMedian);
            hi = std::max(hi, r.emptyMedian);
        }
    }
    if (hi) {
        std::fprintf(out, ";\n          the rows' empty-region medians ranged %llu..%llu ticks",
                     (unsigned long long)lo, (unsigned long long)hi);
    }
    std::fprintf(out, "\n");
    for (Routine r : t.skippedRoutines) {
        std::fprintf(out, "skipped   %s: the facing patterns have no light\n", routine_name(r));
    }
}

void print_table(FILE *out, bool moving, const ModelRun &m, uint64_t step) {
    const Workload &w = m.workload;
    const std::vector<Row> &rows = m.table.rows;
    std::fprintf(out, "\n");
    if (moving) {
        std::fprintf(out, "regime: moving light (%d %s, a different one every call)\n", w.numMoving,
                     w.origin.lit ? "lights" : "facing patterns");
    } else {
        std::fprintf(out,
                     "regime: fixed light (the same %s every call: the paper's "
                     "hot-cache setup)\n",
                     w.origin.lit ? "light" : "facing pattern");
    }
    std::fprintf(out, "%-26s %-13s %10s %10s %9s %9s %8s | %8s %5s | %8s %5s | %s\n", "routine",
                 "variant", "ticks min", "ticks med", "/elem min", "/elem med", "vs c_ref",
                 "P4-130nm", "/elem", "P4-90nm", "/elem", "checked");
    for (const Row &r : rows) {
        if (r.moving != moving) {
            continue;
        }
        const char *rn = routine_name(r.routine);
        std::fprintf(out, "%-26s %-13s ", rn, r.variant->name);
        if (!r.ok) {
            std::fprintf(out, "%10s %10s %9s %9s %8s | %8s %5s | %8s %5s | %s\n", "FAILED", "-",
                         "-", "-", "-", "-", "-", "-", "-", "FAILED");
            continue;
        }
        const double el = std::max(1, elements_of(r.routine, w));
        /* A batched row: "xN" before its min, ticks per call to a tenth. */
        char mark[16] = "", mn[32], md[32];
        const bool batched = r.batch > 1;
        if (batched) {
            std::snprintf(mark, sizeof mark, "x%d", r.batch);
        }
        std::snprintf(mn, sizeof mn, batched ? "%.1f" : "%.0f", r.min);
        std::snprintf(md, sizeof md, batched ? "%.1f" : "%.0f", r.median);
        const int pad = std::max(batched ? 1 : 0,
                                 10 - (int)std::strlen(mark) - (int)std::strlen(mn));
        std::fprintf(out, "%s%*s%s %10s %9.2f %9.2f ", mark, pad, "", mn, md, r.min / el,
                     r.median / el);
        const Row *ref = reference_row(rows, r);
        if (ref && r.median > 0) {
            const bool noisy = below_noise(r, step) || below_noise(*ref, step);
            std::fprintf(out, "%s%6.2fx | ", noisy ? "~" : " ", ref->median / r.median);
        } else {
            std::fprintf(out, "%8s | ", "-");
        }
        const PaperFigures *pf = paper_figures(rn, r.variant->name);
        if (pf && paper_sized(w)) {
            std::fprintf(out, "%8ld %5s | %8ld %5s | ", pf->p4_130nm_total,
                         pf->p4_130nm_per_element, pf->p4_90nm_total, pf->p4_90nm_per_element);
        } else if (pf) { /* totals of another mesh size: per element only */
            std::fprintf(out, "%8s %5s | %8s %5s | ", "-", pf->p4_130nm_per_element, "-",
                         pf->p4_90nm_per_element);
        } else {
            std::fprintf(out, "%8s %5s | %8s %5s | ", "-", "-", "-", "-");
        }
        std::fprintf(out, "ok\n");
    }
}

} // namespace

void print_run_header(FILE *out, const BenchRun &run) {
    const MachineTiming &m = run.machine;
    const TableOptions &o = run.options;
    std::fprintf(out,
                 "shadowvol %s bench: the cycle table of J.M.P. van Waveren, \"Shadow Volume "
                 "Construction\" (Id Software, 2005), section 8\n",
                 project_version().c_str());
    print_cpu_lines(out, m.cpu);
    print_variant_lines(out, o.variants, run.variantsChosen, run.isaLimit, run.skipped);
    std::fprintf(out,
                 "tsc       %.3f GHz (rdtsc against CLOCK_MONOTONIC over %.0f ms), steps of %llu "
                 "ticks, invariant-TSC bit %s;\n          unit: ticks, not core cycles\n",
                 m.tscHz * 1e-9, m.tscSeconds * 1e3, (unsigned long long)m.step,
                 cpu_has_invariant_tsc() ? "set" : "not set");
    std::fprintf(out, "timer     %s%s: %s\n", timer_name(m.timer),
                 m.timerAuto
                     ? (cpu_has_rdtscp() ? " (auto: CPU has RDTSCP)" : " (auto: CPU lacks RDTSCP)")
                     : "",
                 timer_sequence(m.timer));
    std::fprintf(out,
                 "overhead  empty region at start: min %llu, median %llu, p90 %llu ticks (%d "
                 "tries); each row times one\n          before every timed region and subtracts "
                 "their min from the calls' min, their median from\n          the calls' median\n",
                 (unsigned long long)m.overhead.min, (unsigned long long)m.overhead.median,
                 (unsigned long long)m.overhead.p90, m.overhead.tries);
    std::fprintf(out,
                 "checks    every call, outside the timed region: its count, facing bytes, cull "
                 "bits, indices and the\n          canaries past its buffers against c_ref "
                 "(calculate_*: against a second computation)\n");
    if (o.batch == 0) {
        std::fprintf(out,
                     "batch     a region times one call, or, in a row of a routine that writes no "
                     "indices whose warm-up\n          calls' median is below %llu ticks (%llu x "
                     "the larger of the TSC step and the IQR of %d empty\n          regions less "
                     "one step: %llu - %llu), a batch of back-to-back calls after an untimed\n"
                     "          one, each on its own input, as many as fit in 2/3 of the %zu KiB "
                     "L1D: rows marked xN\n",
                     (unsigned long long)m.batchThreshold, (unsigned long long)kBatchSteps,
                     m.overhead.tries, (unsigned long long)m.emptyIqr, (unsigned long long)m.step,
                     m.l1dBytes / 1024);
    } else if (o.batch == 1) {
        std::fprintf(out, "batch     one call per timed region (--batch 1)\n");
    } else {
        std::fprintf(out,
                     "batch     %d back-to-back calls per timed region in every row (--batch "
                     "%d), each on its own input\n",
                     o.batch, o.batch);
    }
    std::fprintf(out, "build     %s, %s, commit %s\n", compiler_version().c_str(),
                 build_flags().c_str(), git_commit().c_str());
    std::fprintf(out, "models    %s\n", run.realModels.c_str());
}

void print_model(FILE *out, const BenchRun &run, const ModelRun &m) {
    print_mesh(out, m.workload);
    print_lights(out, m.workload);
    print_runs(out, run, m);
    for (int regime = 0; regime < 2; regime++) {
        const bool moving = regime == 0;
        if ((moving && run.options.moving) || (!moving && run.options.fixed)) {
            print_table(out, moving, m, run.machine.step);
        }
    }
    std::fflush(out);
}

void print_notes(FILE *out, const BenchRun &run) {
    std::fprintf(out,
                 "\n/elem: per triangle; create_sil_triangles per SilEdge, as in the paper; "
                 "calculate_cull_bits per vertex.\nvs c_ref: c_ref's median over this row's "
                 "median; ~: this row's or c_ref's median is below %llu x\n  the TSC step or "
                 "the spread (IQR) of the row's empty regions: mostly timer noise.\n",
                 (unsigned long long)kNoiseFactor);
    bool anyBatched = false;
    for (const ModelRun &m : run.models) {
        for (const Row &r : m.table.rows) {
            anyBatched = anyBatched || (r.ok && r.batch > 1);
        }
    }
    if (anyBatched) {
        std::fprintf(out, "xN: N back-to-back calls per timed region, each on a fresh copy of its "
                          "input (moving light: the\n  next light each) and each checked; "
                          "figures per call: (batch - empty region) / N, the min and\n  median "
                          "over the batches; ~ then compares the whole batch with the noise.\n");
    }
    std::fprintf(out, "P4 columns: the paper's \"Hot Cache Clock Cycle Counts\" (core cycles) on "
                      "the row of its C (c_ref) and of its\n  SSE2 listing (sse2_paper); "
                      "create_shadow_volume = \"CreateShadowVolume, no culling\",\n"
                      "  create_shadow_volume_cull = \"with culling\". Its character had 1344 "
                      "triangles and 2016 SilEdges:\n  beside a mesh of another size only its "
                      "per-element figures are shown. It times no calculate_*\n  routine.\n");
    /* How far the rounds of a row disagreed: the noise left after taking
     * the lowest round median. */
    const Row *worst = nullptr;
    const ModelRun *worstModel = nullptr;
    double worstSpread = 0;
    for (const ModelRun &m : run.models) {
        for (const Row &r : m.table.rows) {
            if (r.ok && r.rounds > 1 && r.median > 0 && !below_noise(r, run.machine.step)) {
                const double spread = (r.medianWorst - std::min(r.medianWorst, r.median)) /
                                      r.median;
                if (!worst || spread > worstSpread) {
                    worst = &r;
                    worstModel = &m;
                    worstSpread = spread;
                }
            }
        }
    }
    if (worst) {
        std::fprintf(out,
                     "Rounds: the highest round median of a row was at most %.0f%% above the "
                     "row's median (%s %s %s, %s\n  light; rows marked ~ left out).\n",
                     100.0 * worstSpread, worstModel->workload.name.c_str(),
                     routine_name(worst->routine), worst->variant->name,
                     worst->moving ? "moving" : "fixed");
    }
    bool first = true;
    for (const ModelRun &m : run.models) {
        for (const Row &r : m.table.rows) {
            if (!r.ok) {
                std::fprintf(out, "%sFAILED %s %s %s (%s light): %s\n", first ? "\n" : "",
                             m.workload.name.c_str(), routine_name(r.routine), r.variant->name,
                             r.moving ? "moving" : "fixed", r.failure.c_str());
                first = false;
            }
        }
    }
    std::fflush(out);
}

} // namespace svbench
