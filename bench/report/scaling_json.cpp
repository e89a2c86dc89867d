/*
 * Copyright (C) 2026 the shadowvol authors. LGPL-2.1-or-later.
 */
#include "scaling_json.h"

#include "json_report.h"

#include <algorithm>
#include <cmath>

#include "cache_info.h"
#include "json_writer.h"
#include "scaling_report.h"
#include "sysinfo.h"
#include "timer.h"
#include "working_set.h"

namespace svbench {

namespace {

void caches(JsonWriter &j) {
    const CacheSizes &c = cache_sizes();
    const char *const keys[] = {"l1d_bytes", "l2_bytes", "l3_bytes"};
    const char *const sources[] = {"l1d", "l2", "l3"};
    j.key("caches");
    j.begin_object();
    int i = 0;
    for (const CacheLevel &l : c) {
        j.key(keys[i++]);
        if (l.bytes) {
            j.value((unsigned long long)l.bytes);
        } else {
            j.null();
        }
    }
    j.key("sources");
    j.begin_object(true);
    i = 0;
    for (const CacheLevel &l : c) {
        j.key(sources[i++]);
        if (l.bytes) {
            j.value(l.source);
        } else {
            j.null();
        }
    }
    j.end_object();
    j.end_object();
}

void model(JsonWriter &j, const ScalingMesh &m) {
    const Workload &w = m.workload;
    j.begin_object(true);
    j.key("model");
    j.value(m.spec.name);
    j.key("generated");
    j.value(m.spec.generated);
    j.key("subdivision");
    if (m.spec.generated) {
        j.value(m.spec.subdivision);
    } else {
        j.null();
    }
    j.key("triangles");
    j.value(w.numTriangles);
    j.key("edges");
    j.value(w.numSilEdges);
    j.key("vertices");
    j.value(w.numVerts);
    j.key("lights");
    j.value(w.numMoving);
    j.key("runs");
    j.value(m.runs);
    j.key("facing_ratio");
    j.value(ratio_stats(w, Ratio::facing).mean);
    j.key("silhouette_ratio");
    j.value(ratio_stats(w, Ratio::silhouette).mean);
    j.key("working_set_bytes");
    j.value(std::round(working_set_bytes(Routine::create_shadow_volume, w)));
    j.key("seconds");
    j.value(m.seconds);
    j.end_object();
}

void result(JsonWriter &j, const ScalingMesh &m, const Row &r, uint64_t step) {
    const Workload &w = m.workload;
    const double el = std::max(1, elements_of(r.routine, w));
    const double ws = working_set_bytes(r.routine, w);
    j.begin_object(true);
    j.key("model");
    j.value(m.spec.name);
    j.key("triangles");
    j.value(w.numTriangles);
    j.key("routine");
    j.value(routine_name(r.routine));
    j.key("variant");
    j.value(r.variant->name);
    j.key("regime");
    j.value("moving");
    j.key("elements");
    j.value(elements_of(r.routine, w));
    j.key("element");
    j.value(element_name(element_of(r.routine)));
    j.key("runs");
    j.value(m.table.runs);
    write_row_figure(j, "ticks_per_element_min", r, r.min / el);
    write_row_figure(j, "ticks_per_element_median", r, r.median / el);
    j.key("below_noise");
    j.value(r.ok && below_noise(r, step));
    j.key("working_set_bytes"); /* an estimate: whole bytes */
    j.value(std::round(ws));
    j.key("fits");
    j.value(smallest_cache_holding(cache_sizes(), ws));
    write_row_check(j, r);
    j.end_object();
}

} // namespace

std::string scaling_json(const ScalingRun &run) {
    const MachineTiming &m = run.machine;
    JsonWriter j;
    j.begin_object();
    j.key("schema");
    j.value(kScalingJsonSchema);
    write_machine_fields(j, m);
    caches(j);

    j.key("options");
    j.begin_object(true);
    j.key("quick");
    j.value(run.options.quick);
    j.key("runs");
    j.value(scaling_runs(run.options, kScalingReferenceTriangles));
    j.key("rounds");
    j.value(run.options.rounds);
    j.key("max_triangles");
    if (run.options.maxTriangles) {
        j.value(run.options.maxTriangles);
    } else {
        j.null();
    }
    j.key("seed");
    j.value((unsigned long long)run.options.seed);
    j.key("isa_limit");
    if (const char *limit = sv_isa_limit_name()) {
        j.value(limit);
    } else {
        j.null();
    }
    j.end_object();
    write_isa_fields(j, run.options.variants);

    j.key("working_set");
    j.begin_array();
    for (Routine r : run.options.routines) {
        const WorkingSet ws = working_set(r, paper_shape());
        j.begin_object(true);
        j.key("routine");
        j.value(routine_name(r));
        j.key("bytes_per_triangle");
        j.value(ws.total);
        j.key("formula");
        j.value(working_set_formula(ws));
        j.end_object();
    }
    j.end_array();

    j.key("models");
    j.begin_array();
    for (const ScalingMesh &sm : run.meshes) {
        model(j, sm);
    }
    j.end_array();

    j.key("results");
    j.begin_array();
    for (const ScalingMesh &sm : run.meshes) {
        for (const Row &r : sm.table.rows) {
            result(j, sm, r, m.step);
        }
    }
    j.end_array();
    std::vector<PlanUse> uses;
    for (const ScalingMesh &sm : run.meshes) {
        if (const sv_plan *p = plan_of(sm.table.rows)) {
            uses.push_back({sm.spec.name, sm.workload.numTriangles, p});
        }
    }
    write_plans(j, uses);
    j.end_object();
    return j.str();
}

} // namespace svbench
