/*
 * Copyright (C) 2026 the shadowvol authors. LGPL-2.1-or-later.
 */
#include "routines.h"

#include <cstring>
#include <stdexcept>

namespace svbench {

const Routine kAllRoutines[kNumRoutines] = {
    Routine::calculate_facing,     Routine::calculate_cull_bits,
    Routine::count_facing,         Routine::count_facing_cull,
    Routine::create_sil_triangles, Routine::create_cap_triangles,
    Routine::create_shadow_volume, Routine::create_shadow_volume_cull,
};

namespace {

const char *const kRoutineNames[kNumRoutines] = {
    "calculate_facing",     "calculate_cull_bits",  "count_facing",
    "count_facing_cull",    "create_sil_triangles", "create_cap_triangles",
    "create_shadow_volume", "create_shadow_volume_cull",
};

/* Implementations of appendices A and B come from the library's own table
 * (sv_facing_variants: c_ref, sse2, avx2, avx512); each joins the kernel
 * variant of the same name, or gets a row of its own. */
std::vector<BenchVariant> make_bench_variants() {
    std::vector<BenchVariant> all;
    int n = 0;
    const sv_variant *v = sv_variants(&n);
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
    return all;
}

} // namespace

const char *routine_name(Routine r) {
    return kRoutineNames[(int)r];
}

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
    return r == Routine::calculate_facing || r == Routine::calculate_cull_bits;
}

bool writes_indices(Routine r) {
    return r == Routine::create_sil_triangles || r == Routine::create_cap_triangles ||
           r == Routine::create_shadow_volume || r == Routine::create_shadow_volume_cull;
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

bool implements(const BenchVariant &v, Routine r) {
    switch (r) {
    case Routine::calculate_facing: return v.calculate_facing != nullptr;
    case Routine::calculate_cull_bits: return v.calculate_cull_bits != nullptr;
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
