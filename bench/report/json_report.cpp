/*
 * Copyright (C) 2026 the shadowvol authors. LGPL-2.1-or-later.
 */
#include "json_report.h"

#include "shadowvol_plan.h"

#include <cstdlib>

#include "json_writer.h"
#include "paper_results.h"
#include "sysinfo.h"

namespace svbench {

namespace {

void ratio(JsonWriter &j, const char *name, const Workload &w, Ratio which, double target) {
    const RatioStats s = ratio_stats(w, which);
    j.key(name);
    j.begin_object(true);
    if (target >= 0) {
        j.key("target");
        j.value(target);
    }
    j.key("mean");
    j.value(s.mean);
    j.key("min");
    j.value(s.min);
    j.key("max");
    j.value(s.max);
    j.end_object();
}

void model(JsonWriter &j, const ModelRun &m) {
    const Workload &w = m.workload;
    const LightOrigin &o = w.origin;
    j.begin_object();
    j.key("model");
    j.value(w.name);
    j.key("source");
    j.value(w.source);
    j.key("surfaces");
    j.value(w.surfaces);
    j.key("vertices");
    j.value(w.numVerts);
    j.key("triangles");
    j.value(w.numTriangles);
    j.key("edges");
    j.value(w.numSilEdges);
    j.key("dangling_edges");
    j.value(w.numDangling);
    j.key("closed");
    j.value(w.closed);
    j.key("lit");
    j.value(o.lit);
    j.key("lights");
    j.value(w.numMoving);
    if (o.lit) {
        j.key("light_candidates");
        j.value(o.candidates);
    }
    j.key("seed");
    j.value((unsigned long long)o.seed);
    j.key("runs");
    j.value(m.table.runs);
    j.key("warmup");
    j.value(m.table.warmup);
    ratio(j, "facing_ratio", w, Ratio::facing, o.targetFacing);
    ratio(j, "silhouette_ratio", w, Ratio::silhouette, o.targetSilhouette);
    ratio(j, "culled_ratio", w, Ratio::culled, o.targetCulled);
    ratio(j, "turned_ratio", w, Ratio::turned, -1);
    const Light &f = w.lights[(size_t)w.fixedLight];
    j.key("fixed_light");
    j.begin_object(true);
    j.key("given");
    j.value(o.fixedGiven && o.lit);
    if (o.lit) {
        j.key("position");
        j.begin_array();
        for (float c : {f.position.x, f.position.y, f.position.z, f.position.w}) {
            j.value(c);
        }
        j.end_array();
    }
    j.key("facing_ratio");
    j.value(light_ratio(w, f, Ratio::facing));
    j.key("silhouette_ratio");
    j.value(light_ratio(w, f, Ratio::silhouette));
    j.key("culled_ratio");
    j.value(light_ratio(w, f, Ratio::culled));
    j.end_object();
    j.end_object();
}

void paper(JsonWriter &j, const Row &r) {
    const PaperFigures *pf = paper_figures(routine_name(r.routine), r.variant->name);
    j.key("paper");
    if (!pf) {
        j.null();
        return;
    }
    j.begin_object();
    j.key("row");
    j.value(pf->paperRow);
    j.key("triangles");
    j.value(kPaperTriangles);
    j.key("edges");
    j.value(kPaperSilEdges);
    j.key("p4_130nm");
    j.begin_object();
    j.key("cycles");
    j.value(pf->p4_130nm_total);
    j.key("per_element");
    j.value(std::strtod(pf->p4_130nm_per_element, nullptr));
    j.end_object();
    j.key("p4_90nm");
    j.begin_object();
    j.key("cycles");
    j.value(pf->p4_90nm_total);
    j.key("per_element");
    j.value(std::strtod(pf->p4_90nm_per_element, nullptr));
    j.end_object();
    j.end_object();
}

void result(JsonWriter &j, const ModelRun &m, const Row &r, uint64_t step) {
    const Workload &w = m.workload;
    const double el = std::max(1, elements_of(r.routine, w));
    j.begin_object(true);
    j.key("model");
    j.value(w.name);
    j.key("triangles");
    j.value(w.numTriangles);
    j.key("edges");
    j.value(w.numSilEdges);
    j.key("vertices");
    j.value(w.numVerts);
    j.key("routine");
    j.value(routine_name(r.routine));
    j.key("variant");
    j.value(r.variant->name);
    j.key("regime");
    j.value(r.moving ? "moving" : "fixed");
    j.key("elements");
    j.value(elements_of(r.routine, w));
    j.key("element");
    j.value(element_name(element_of(r.routine)));
    j.key("runs");
    j.value(m.table.runs);
    j.key("batch");
    j.value(std::max(1, r.batch));
    write_row_figure(j, "ticks_min", r, r.min);
    write_row_figure(j, "ticks_median", r, r.median);
    write_row_figure(j, "ticks_per_element_min", r, r.min / el);
    write_row_figure(j, "ticks_per_element_median", r, r.median / el);
    const Row *ref = reference_row(m.table.rows, r);
    j.key("speedup_vs_c_ref");
    if (r.ok && ref && r.median > 0) {
        j.value(ref->median / r.median);
    } else {
        j.null();
    }
    j.key("below_noise");
    j.value(r.ok && (below_noise(r, step) || (ref && below_noise(*ref, step))));
    write_row_check(j, r);
    paper(j, r);
    j.end_object();
}

/* "limits" (--limits): the machine's rates and, per model, each routine's
 * floor (machine_limits.h). */
void limits(JsonWriter &j, const BenchRun &run) {
    const MachineLimits &l = run.limits;
    j.key("limits");
    j.begin_object();
    j.key("vector");
    j.value(l.vector);
    j.key("scalar_loads_per_tick");
    j.value(l.scalarLoads);
    j.key("core_cycles_per_tick");
    j.value(l.coreCyclesPerTick);
    j.key("gather_lanes_per_tick");
    j.value(l.gatherLanes);
    j.key("l1_load_bytes_per_tick");
    j.value(l.l1LoadBytes);
    j.key("l2_load_bytes_per_tick");
    j.value(l.l2LoadBytes);
    j.key("l2_buffer_bytes");
    j.value((unsigned long long)l.l2Buffer);
    j.key("store_bytes_per_tick");
    j.value(l.storeBytes);
    j.key("floors");
    j.begin_array();
    for (const ModelRun &mr : run.models) {
        for (const RoutineFloor &f : routine_floors(l, mr.workload, mr.table)) {
            j.begin_object(true);
            j.key("model");
            j.value(mr.workload.name);
            j.key("routine");
            j.value(routine_name(f.routine));
            j.key("floor_ticks");
            j.value(f.ticks);
            j.key("load_port_ticks");
            j.value(f.loadPorts);
            j.key("lookup_ticks");
            j.value(f.lookups);
            j.key("store_port_ticks");
            j.value(f.storePort);
            j.key("streaming_floor_ticks");
            j.value(f.streaming);
            j.end_object();
        }
    }
    j.end_array();
    j.end_object();
}

} // namespace

void write_machine_fields(JsonWriter &j, const MachineTiming &m) {
    j.key("shadowvol_version");
    j.value(project_version());
    j.key("cpu");
    j.begin_object();
    j.key("model");
    j.value(cpu_model());
    j.key("isa");
    j.begin_array(true);
    for (const std::string &f : cpu_isa_list()) {
        j.value(f);
    }
    j.end_array();
    j.key("tsc_hz");
    j.value(m.tscHz);
    j.key("tsc_step_ticks");
    j.value((unsigned long long)m.step);
    j.key("invariant_tsc");
    j.value(cpu_has_invariant_tsc());
    j.key("pinned_cpu");
    j.value(m.cpu);
    /* The brand string alone does not tell one CPU generation from
     * another ("AMD EPYC" on Zen 1, 3 and 5 guests): the wisdom file's
     * key has the family, model and stepping. */
    char key[256];
    j.key("model_key");
    j.value(sv_cpu_model_key(key, sizeof key));
    j.end_object();
    j.key("compiler");
    j.value(compiler_version());
    j.key("build");
    j.value(build_flags());
    j.key("commit");
    j.value(git_commit());
    j.key("timer");
    j.value(timer_name(m.timer));
}

void write_row_figure(JsonWriter &j, const char *name, const Row &r, double v) {
    j.key(name);
    if (r.ok) {
        j.value(v);
    } else {
        j.null();
    }
}

void write_row_check(JsonWriter &j, const Row &r) {
    j.key("checked");
    j.value(r.ok);
    if (!r.ok) {
        j.key("failure");
        j.value(r.failure);
    }
}

void write_isa_fields(JsonWriter &j, const std::vector<const BenchVariant *> &variants) {
    j.key("isa_level");
    j.value(sv_isa_level_name());
    j.key("variants");
    j.begin_array(true);
    for (const BenchVariant *v : variants) {
        j.value(v->name);
    }
    j.end_array();
}

std::string bench_json(const BenchRun &run) {
    const MachineTiming &m = run.machine;
    JsonWriter j;
    j.begin_object();
    j.key("schema");
    j.value(kJsonSchema);
    write_machine_fields(j, m);
    j.key("timer_sequence");
    j.value(timer_sequence(m.timer));
    j.key("overhead_ticks");
    j.begin_object(true);
    j.key("min");
    j.value((unsigned long long)m.overhead.min);
    j.key("median");
    j.value((unsigned long long)m.overhead.median);
    j.key("p90");
    j.value((unsigned long long)m.overhead.p90);
    j.key("tries");
    j.value(m.overhead.tries);
    j.end_object();
    j.key("batch_threshold_ticks");
    j.value((unsigned long long)m.batchThreshold);

    j.key("options");
    j.begin_object(true);
    j.key("runs");
    j.value(run.options.runs);
    j.key("rounds");
    j.value(run.options.rounds);
    j.key("batch");
    if (run.options.batch == 0) {
        j.value("auto");
    } else {
        j.value(run.options.batch);
    }
    j.key("seed");
    j.value((unsigned long long)run.seed);
    j.key("isa_limit");
    if (const char *limit = sv_isa_limit_name()) {
        j.value(limit);
    } else {
        j.null();
    }
    j.end_object();

    write_isa_fields(j, run.options.variants);
    j.key("skipped_variants");
    j.begin_array();
    for (const SkippedVariant &s : run.skipped) {
        j.begin_object(true);
        j.key("variant");
        j.value(s.name);
        j.key("why");
        j.value(s.why);
        j.end_object();
    }
    j.end_array();

    j.key("models");
    j.begin_array();
    for (const ModelRun &mr : run.models) {
        model(j, mr);
    }
    j.end_array();

    j.key("results");
    j.begin_array();
    for (const ModelRun &mr : run.models) {
        for (const Row &r : mr.table.rows) {
            result(j, mr, r, m.step);
        }
    }
    j.end_array();
    std::vector<PlanUse> uses;
    for (const ModelRun &mr : run.models) {
        if (const sv_plan *p = plan_of(mr.table.rows)) {
            uses.push_back({mr.workload.name, mr.workload.numTriangles, p});
        }
    }
    write_plans(j, uses);
    if (run.limitsMeasured) {
        limits(j, run);
    }
    j.end_object();
    return j.str();
}

const sv_plan *plan_of(const std::vector<Row> &rows) {
    for (const Row &r : rows) {
        if (r.variant && r.variant->plan) return r.variant->plan;
    }
    return nullptr;
}

void write_plans(JsonWriter &j, const std::vector<PlanUse> &uses) {
    j.key("plans");
    j.begin_array();
    for (const PlanUse &u : uses) {
        j.begin_object(true);
        j.key("model");
        j.value(u.model);
        j.key("triangles");
        j.value(u.triangles);
        j.key("size_class");
        j.value(u.plan->size_class);
        j.key("class_triangles");
        j.value(sv_size_class_triangles(u.plan->size_class));
        j.key("source");
        j.value(u.plan->source);
        j.key("variants");
        j.begin_object(true);
        for (int r = 0; r < SV_NUM_ROUTINES; r++) {
            j.key(sv_routine_name((sv_routine)r));
            j.value(u.plan->variant[r]);
        }
        j.end_object();
        j.end_object();
    }
    j.end_array();
}

} // namespace svbench
