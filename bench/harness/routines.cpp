/*
 * Copyright (C) 2026 the shadowvol authors. LGPL-2.1-or-later.
 */
#include "routines.h"

#include "shadowvol_plan.h"

#include <cstring>
#include <deque>
#include <mutex>
#include <stdexcept>

namespace svbench {

const Routine kAllRoutines[kNumRoutines] = {
    Routine::calculate_facing,
    Routine::calculate_cull_bits,
    Routine::count_facing,
    Routine::count_facing_cull,
    Routine::create_sil_triangles,
    Routine::create_cap_triangles,
    Routine::create_shadow_volume,
    Routine::create_shadow_volume_cull,
    Routine::pipeline,
    Routine::pipeline_cull,
};

namespace {

const char *const kRoutineNames[kNumRoutines] = {
    "calculate_facing",     "calculate_cull_bits",       "count_facing",
    "count_facing_cull",    "create_sil_triangles",      "create_cap_triangles",
    "create_shadow_volume", "create_shadow_volume_cull", "pipeline",
    "pipeline_cull",
};

/* Implementations of appendices A and B come from the library's own table
 * (sv_facing_variants: c_ref, sse2, avx2, avx512); each joins the kernel
 * variant of the same name, or gets a row of its own. */
std::vector<BenchVariant> make_bench_variants() {
    std::vector<BenchVariant> all;
    int n = 0;
    const sv_variant *v = sv_variants(&n);
    all.reserve((size_t)n);
    for (int i = 0; i < n; i++) {
        all.push_back(BenchVariant{v[i].name, v[i].isa, &v[i], nullptr, nullptr});
    }
    int nf = 0;
    const sv_facing_variant *fv = sv_facing_variants(&nf);
    for (int k = 0; k < nf; k++) {
        const sv_facing_variant &c = fv[k];
        BenchVariant *same = nullptr;
        for (BenchVariant &b : all) {
            if (std::strcmp(b.name, c.name) == 0) {
                same = &b;
            }
        }
        if (!same) { /* A and B only, under a name of their own */
            all.push_back(BenchVariant{c.name, c.isa, nullptr, nullptr, nullptr});
            same = &all.back();
        } else {
            /* A row runs only where both its kernels and its A/B run. */
            same->isa |= c.isa;
        }
        same->calculate_facing = c.calculate_facing;
        same->calculate_cull_bits = c.calculate_cull_bits;
    }
    /* The planner's choice: resolved per workload (resolve_planned). */
    BenchVariant planned{"planned", 0, nullptr, nullptr, nullptr};
    planned.planned = true;
    all.push_back(planned);
    BenchVariant planned_kernels{"planned_kernels", 0, nullptr, nullptr, nullptr};
    planned_kernels.planned = true;
    planned_kernels.unfused = true;
    all.push_back(planned_kernels);
    for (BenchVariant &b : all) {
        if (!b.kernels) continue;
        const sv_facing_variant *pick = nullptr;
        for (int k = 0; k < nf; k++) {
            if (std::strcmp(fv[k].name, b.name) == 0) {
                pick = &fv[k];
                break;
            }
            if ((fv[k].isa & b.kernels->isa) == fv[k].isa) pick = &fv[k]; /* the table ascends */
        }
        if (pick) {
            b.pipeline_facing = pick->calculate_facing;
            b.pipeline_cull_bits = pick->calculate_cull_bits;
            b.pipeline_facing_name = pick->name;
        }
    }
    return all;
}

} // namespace

const char *routine_name(Routine r) { return kRoutineNames[(int)r]; }

bool routine_by_name(const std::string &name, Routine *r) {
    for (int i = 0; i < kNumRoutines; i++) {
        if (name == kRoutineNames[i]) {
            *r = kAllRoutines[i];
            return true;
        }
    }
    return false;
}

std::string routine_list() {
    std::string s;
    for (int i = 0; i < kNumRoutines; i++) {
        s += (i ? ", " : "");
        s += kRoutineNames[i];
    }
    return s;
}

Element element_of(Routine r) {
    switch (r) {
    case Routine::create_sil_triangles: return Element::sil_edge;
    case Routine::calculate_cull_bits: return Element::vertex;
    default: return Element::triangle;
    }
}

const char *element_name(Element e) {
    switch (e) {
    case Element::triangle: return "triangle";
    case Element::sil_edge: return "SilEdge";
    case Element::vertex: return "vertex";
    }
    return "?";
}

bool needs_light(Routine r) {
    return r == Routine::calculate_facing || r == Routine::calculate_cull_bits ||
           r == Routine::pipeline || r == Routine::pipeline_cull;
}

bool writes_indices(Routine r) {
    return r == Routine::create_sil_triangles || r == Routine::create_cap_triangles ||
           r == Routine::create_shadow_volume || r == Routine::create_shadow_volume_cull ||
           r == Routine::pipeline || r == Routine::pipeline_cull;
}

const std::vector<BenchVariant> &bench_variants() {
    static const std::vector<BenchVariant> all = make_bench_variants();
    return all;
}

const BenchVariant *bench_variant_by_name(const std::string &name) {
    for (const BenchVariant &v : bench_variants()) {
        if (name == v.name) {
            return &v;
        }
    }
    return nullptr;
}

std::string variant_list() {
    std::string s;
    for (const BenchVariant &v : bench_variants()) {
        s += (s.empty() ? "" : ", ");
        s += v.name;
    }
    return s;
}

const BenchVariant *resolve_planned(const BenchVariant *v, int numTriangles) {
    if (!v->planned) return v;
    static std::mutex lock;
    static std::deque<BenchVariant> resolved;
    static bool wisdom_read = false;
    std::lock_guard<std::mutex> g(lock);
    if (!wisdom_read) {
        char path[1024];
        sv_wisdom_load(sv_wisdom_default_path(path, sizeof path));
        wisdom_read = true;
    }
    const sv_plan *p = sv_plan_for(numTriangles, SV_PLAN_MEASURE);
    BenchVariant b = *v;
    b.origin = v;
    b.plan = p;
    b.kernels = &p->kernels;
    b.calculate_facing = b.pipeline_facing = p->calculate_facing;
    b.calculate_cull_bits = b.pipeline_cull_bits = p->calculate_cull_bits;
    b.pipeline_facing_name = p->variant[SV_ROUTINE_CALCULATE_FACING];
    resolved.push_back(b);
    return &resolved.back();
}

bool implements(const BenchVariant &v, Routine r) {
    if (v.planned) { /* every routine, once resolved; the unfused form the pipelines only */
        return !v.unfused || r == Routine::pipeline || r == Routine::pipeline_cull;
    }
    switch (r) {
    case Routine::calculate_facing: return v.calculate_facing != nullptr;
    case Routine::calculate_cull_bits: return v.calculate_cull_bits != nullptr;
    case Routine::pipeline:
    case Routine::pipeline_cull: return v.kernels != nullptr && v.pipeline_facing != nullptr;
    default: return v.kernels != nullptr;
    }
}

const BenchVariant &reference_variant() {
    const BenchVariant *ref = bench_variant_by_name("c_ref");
    if (!ref || !ref->kernels || !ref->calculate_facing || !ref->calculate_cull_bits) {
        throw std::logic_error("the variant table has no complete c_ref");
    }
    return *ref;
}

} // namespace svbench
