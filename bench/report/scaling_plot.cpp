/*
 * Copyright (C) 2026 the shadowvol authors. LGPL-2.1-or-later.
 */
#include "scaling_plot.h"

#include <algorithm>
#include <cstdio>

#include "cache_info.h"
#include "svg_plot.h"
#include "sysinfo.h"
#include "timer.h"
#include "working_set.h"

namespace svbench {

namespace {

svplot::Panel panel(const ScalingRun &run, Routine routine) {
    svplot::Panel p;
    const char *element = element_name(element_of(routine));
    p.id = routine_name(routine);
    p.title = std::string(routine_name(routine)) + ": ticks per " + element +
              " (median), moving light";
    p.xLabel = "triangles (log scale)";
    p.yLabel = std::string("ticks per ") + element;

    bool anyFailed = false;
    for (size_t k = 0; k < run.options.variants.size(); k++) {
        const BenchVariant *v = run.options.variants[k];
        svplot::Series s;
        s.name = v->name;
        s.style = (int)k; /* a variant looks the same in every panel */
        bool any = false;
        for (const ScalingMesh &m : run.meshes) {
            const Row *r = scaling_row(m, routine, v);
            if (!r) {
                continue;
            }
            any = true;
            if (!r->ok) {
                anyFailed = true;
                continue;
            }
            const Workload &w = m.workload;
            svplot::Point pt;
            pt.x = w.numTriangles;
            pt.y = r->median / std::max(1, elements_of(routine, w));
            pt.label = m.spec.name;
            (m.spec.generated ? s.line : s.loose).push_back(pt);
        }
        if (any) {
            p.series.push_back(std::move(s));
        }
    }

    const WorkingSet ws = working_set(routine, paper_shape());
    std::string where;
    for (const CacheLevel &c : cache_sizes()) {
        if (!c.bytes) {
            continue;
        }
        const std::string label = std::string(c.name) + " " + format_bytes((double)c.bytes);
        const double x = (double)c.bytes / ws.total;
        p.markers.push_back(svplot::VMarker{label, x});
        where += (where.empty() ? "" : ", ") + label + " at " + svplot::si(x);
    }
    p.caption.push_back("Working set of one call: " + working_set_formula(ws) +
                        " (bench/machine/working_set.h),");
    p.caption.push_back("at the paper's ratios (50% facing, 20% of the SilEdges on the "
                        "silhouette) on a closed mesh (1.5 SilEdges, 0.5 vertices per "
                        "triangle).");
    p.caption.push_back("Dashed lines: the triangle count whose working set fills the cache" +
                        (where.empty() ? std::string(" (cache sizes unknown: none drawn)")
                                       : ": " + where + " triangles") +
                        ".");
    if (anyFailed) {
        p.caption.push_back("Rows that FAILED their check against c_ref are left out.");
    }
    return p;
}

} // namespace

std::string scaling_svg(const ScalingRun &run) {
    svplot::Document d;
    d.title = "shadowvol bench --scaling: cost per element as the mesh grows (" + cpu_model() + ")";
    char tsc[160];
    std::snprintf(tsc, sizeof tsc,
                  "TSC %.3f GHz, unit: ticks, not core cycles; timer %s; every call checked "
                  "against c_ref outside the timed region.",
                  run.machine.tscHz * 1e-9, timer_name(run.machine.timer));
    d.notes.push_back(tsc);
    d.notes.push_back("Caches: " + cache_summary(cache_sizes()) + ". Build: " + compiler_version() +
                      ", " + build_flags() + ", commit " + git_commit() + ".");
    d.notes.push_back("Lines: the generated character subdivided n x n (1344 n^2 triangles); "
                      "hollow markers: the real characters. y: the median call (the lowest of " +
                      std::to_string(run.options.rounds) + " rounds' medians).");
    d.lineKey = "generated character";
    for (const ScalingMesh &m : run.meshes) {
        if (!m.spec.generated) {
            d.looseKey = "real characters";
        }
    }
    for (Routine r : run.options.routines) {
        d.panels.push_back(panel(run, r));
    }
    return svplot::render(d);
}

} // namespace svbench
