// The check library's table and driver (routine_checks.h): which variants
// exist, which this process may run, and one routine's run over them. The
// cases themselves are in check_cases.cpp.
//
// Copyright (C) 2026 the shadowvol authors. LGPL-2.1-or-later.
#include "routine_checks.h"

#include <cstring>

#include "check_run.h"

namespace svcheck {

namespace {

const char *const kRoutineNames[kNumRoutines] = {
    "calculate_facing",
    "calculate_cull_bits",
    "calculate_facing_count",
    "count_facing",
    "count_facing_cull",
    "create_sil_triangles",
    "create_cap_triangles",
    "shadow_volume",
    "shadow_volume_cull",
    "shadow_volume_for_light",
    "create_general_sil_triangles",
    "create_general_cap_triangles",
    "derive_planes",
    "facing_from_positions",
    "skinning",
    "skin_planes",
    "extrude",
    "derive_planes_clustered",
};

// The library's own contract check decides whether bit 7 is in
// CountFacingCull's contract for these kernels (check_cull_bits in
// src/core/contracts.c), on one facing triangle whose vertex has bit 7: where
// bit 7 is in the contract, the kernel then runs on that triangle, in
// contract (a facing triangle is left as it is).
bool honours_cull_bit7(const sv_variant &k) {
    uint8_t facing[1] = {1};
    const int indices[3] = {0, 0, 0};
    const uint8_t cull[1] = {0x80};
    return sv_count_facing_cull_checked(&k, facing, 1, indices, cull, 1) != SV_E_CULL_BITS;
}

bool runs_here(unsigned isa) { return (isa & sv_cpu_isa()) == isa; }

// The deforming surfaces' choices of size class C, as sv::deform_plan_for
// makes them (src/anim/deform_plan.cpp): the planner's name where it is in
// the table and runs here, else the static choice (the widest skinning
// kernel, sv_best_planes_variant(), two passes: no one-pass kernel).
void planned_deform(int c, Kernels &k) {
    sv_deform_choice ch;
    k.skin = nullptr;
    if (sv_deform_choice_for(c, SV_DEFORM_SKINNING, &ch) == 1) {
        k.skin = sv_skin_variant_by_name(ch.variant);
    }
    if (!k.skin || !runs_here(k.skin->isa)) {
        int n = 0;
        const sv_skin_variant *sk = sv_skin_variants(&n);
        k.skin = &sk[0];
        for (int i = 0; i < n; i++) {
            if (runs_here(sk[i].isa)) k.skin = &sk[i];
        }
    }
    k.planes = nullptr;
    if (sv_deform_choice_for(c, SV_DEFORM_DERIVE_PLANES, &ch) == 1) {
        k.planes = sv_planes_variant_by_name(ch.variant);
    }
    if (!k.planes || !runs_here(k.planes->isa)) k.planes = sv_best_planes_variant();
    k.skin_planes = nullptr;
    if (sv_deform_choice_for(c, SV_DEFORM_SKIN_PLANES, &ch) == 1) {
        k.skin_planes = sv_skin_planes_variant_by_name(ch.variant);
        if (k.skin_planes && !runs_here(k.skin_planes->isa)) k.skin_planes = nullptr;
    }
    k.clustered = nullptr;
    if (sv_deform_choice_for(c, SV_DEFORM_PLANES_CLUSTERED, &ch) == 1) {
        k.clustered = sv_planes_clustered_variant_by_name(ch.variant);
        if (k.clustered && !runs_here(k.clustered->isa)) k.clustered = nullptr;
    }
}

} // namespace

const char *routine_name(Routine r) {
    const int i = (int)r;
    return i >= 0 && i < kNumRoutines ? kRoutineNames[i] : "?";
}

bool routine_by_name(const std::string &name, Routine *out) {
    for (int i = 0; i < kNumRoutines; i++) {
        if (name == kRoutineNames[i]) {
            *out = (Routine)i;
            return true;
        }
    }
    return false;
}

std::vector<Routine> all_routines() {
    std::vector<Routine> r;
    r.reserve(kNumRoutines);
    for (int i = 0; i < kNumRoutines; i++) r.push_back((Routine)i);
    return r;
}

const Kernels &Variant::for_triangles(int numTriangles) const {
    return by_class[sv_size_class(numTriangles < 0 ? 0 : numTriangles)];
}

bool Variant::has(Routine r) const {
    const Kernels &k = by_class[0];
    switch (r) {
    case Routine::calculate_facing: return k.calculate_facing != nullptr;
    case Routine::calculate_cull_bits: return k.calculate_cull_bits != nullptr;
    case Routine::calculate_facing_count: return k.calculate_facing_count != nullptr;
    case Routine::shadow_volume_for_light: return k.plan != nullptr;
    case Routine::create_general_sil_triangles:
    case Routine::create_general_cap_triangles: return k.general != nullptr;
    case Routine::derive_planes:
    case Routine::facing_from_positions: return k.planes != nullptr;
    case Routine::skinning: return k.skin != nullptr;
    case Routine::skin_planes: return k.skin_planes != nullptr;
    case Routine::extrude: return k.extrude != nullptr;
    case Routine::derive_planes_clustered: return k.clustered != nullptr;
    default: return k.kernels.count_facing != nullptr;
    }
}

Variant make_variant(const std::string &name, const sv_facing_variant *facing,
                     const sv_variant *kernels) {
    Variant v;
    v.name = name;
    Kernels k;
    if (facing) {
        v.isa |= facing->isa;
        k.calculate_facing = facing->calculate_facing;
        k.calculate_cull_bits = facing->calculate_cull_bits;
        k.calculate_facing_count = facing->calculate_facing_count;
    }
    if (kernels) {
        v.isa |= kernels->isa;
        k.kernels = *kernels;
        k.cull_bit7 = honours_cull_bit7(*kernels);
    }
    if ((k.general = sv_general_variant_by_name(name.c_str()))) v.isa |= k.general->isa;
    if ((k.planes = sv_planes_variant_by_name(name.c_str()))) v.isa |= k.planes->isa;
    if ((k.skin = sv_skin_variant_by_name(name.c_str()))) v.isa |= k.skin->isa;
    if ((k.skin_planes = sv_skin_planes_variant_by_name(name.c_str()))) {
        v.isa |= k.skin_planes->isa;
    }
    if ((k.extrude = sv_extrude_variant_by_name(name.c_str()))) v.isa |= k.extrude->isa;
    if ((k.clustered = sv_planes_clustered_variant_by_name(name.c_str()))) {
        v.isa |= k.clustered->isa;
    }
    for (Kernels &c : v.by_class) c = k;
    return v;
}

std::vector<Variant> library_variants() {
    std::vector<Variant> out;
    int nk = 0, nf = 0;
    const sv_variant *kv = sv_variants(&nk);
    const sv_facing_variant *fv = sv_facing_variants(&nf);
    out.reserve((size_t)nk + (size_t)nf);
    // The kernel table's order (reference first), each with the facing
    // routines of the same name; then facing variants with no kernels of
    // their name (sse2: the faithful kernels are sse2_paper).
    for (int i = 0; i < nk; i++) {
        out.push_back(make_variant(kv[i].name, sv_facing_variant_by_name(kv[i].name), &kv[i]));
    }
    for (int i = 0; i < nf; i++) {
        if (!sv_variant_by_name(fv[i].name))
            out.push_back(make_variant(fv[i].name, &fv[i], nullptr));
    }
    // Names only the deforming surfaces' tables have (avx2_gather,
    // avx512_avx2).
    auto add_new = [&](const char *name) {
        for (const Variant &v : out) {
            if (v.name == name) return;
        }
        out.push_back(make_variant(name, nullptr, nullptr));
    };
    int n = 0;
    const sv_planes_variant *pv = sv_planes_variants(&n);
    for (int i = 0; i < n; i++) add_new(pv[i].name);
    const sv_skin_variant *sk = sv_skin_variants(&n);
    for (int i = 0; i < n; i++) add_new(sk[i].name);
    const sv_skin_planes_variant *sp = sv_skin_planes_variants(&n);
    for (int i = 0; i < n; i++) add_new(sp[i].name);
    const sv_extrude_variant *ev = sv_extrude_variants(&n);
    for (int i = 0; i < n; i++) add_new(ev[i].name);
    // The plans this process would use now (SV_PLAN_ESTIMATE: the wisdom
    // file's or the built-in ones; nothing is measured here).
    Variant planned;
    planned.name = "planned";
    for (int c = 0; c < SV_NUM_SIZE_CLASSES; c++) {
        const sv_plan *p = sv_plan_for(sv_size_class_triangles(c), SV_PLAN_ESTIMATE);
        Kernels &k = planned.by_class[c];
        k.calculate_facing = p->calculate_facing;
        k.calculate_cull_bits = p->calculate_cull_bits;
        k.calculate_facing_count = p->calculate_facing_count;
        k.kernels = p->kernels;
        k.plan = p; // sv_plan_for's plans stay valid (shadowvol_plan.h)
        k.cull_bit7 = honours_cull_bit7(p->kernels);
        planned.isa |= p->kernels.isa;
        for (int r = SV_ROUTINE_CALCULATE_FACING; r <= SV_ROUTINE_CALCULATE_CULL_BITS; r++) {
            if (const sv_facing_variant *f = sv_facing_variant_by_name(p->variant[r])) {
                planned.isa |= f->isa;
            }
        }
        planned_deform(c, k);
        planned.isa |= k.planes->isa | k.skin->isa | (k.skin_planes ? k.skin_planes->isa : 0u) |
                       (k.clustered ? k.clustered->isa : 0u);
        // No planner choice for the extrusion: the static one, as the
        // renderer's (the widest this CPU runs).
        k.extrude = sv_best_extrude_variant();
        planned.isa |= k.extrude->isa;
    }
    out.push_back(planned);
    return out;
}

std::string skip_reason(unsigned isa) {
    if ((isa & sv_cpu_isa()) == isa) return "";
    char buf[128];
    const unsigned detected = sv_cpu_isa_detected();
    if ((isa & detected) == isa) {
        const char *limit = sv_isa_limit_name();
        return std::string("SV_ISA=") + (limit ? limit : "?") + " holds dispatch at " +
               sv_isa_level_name();
    }
    return std::string("this CPU lacks ") + sv_isa_names(isa & ~detected, buf, sizeof buf);
}

void count_case(Row &row) { row.result.cases++; }

// A case counts once however many of its checks fail (cases counts the
// case being checked already: count_case comes first).
void record_failure(Row &row, const std::string &where, const std::string &what) {
    if (row.failed_case == row.result.cases) return;
    row.failed_case = row.result.cases;
    if (row.result.failures++ == 0) row.result.detail = where + ": " + what;
    row.result.status = Result::failed;
}

void record_abi(Row &row, uint32_t failed, const std::string &where) {
#if defined(SV_HAVE_ABI_CHECKER)
    if (failed) {
        char buf[512];
        record_failure(row, where,
                       std::string("ABI broken: ") + sv_abi_failure_names(failed, buf, sizeof buf));
    }
#else
    (void)row;
    (void)failed;
    (void)where;
#endif
}

std::vector<Result> check_routine(Routine routine, const std::vector<Variant> &table,
                                  uint64_t seed) {
    std::vector<Result> results;
    std::vector<Row> rows;
    for (const Variant &v : table) {
        if (!v.has(routine)) continue;
        Result r;
        r.routine = routine;
        r.variant = v.name;
        const std::string why = skip_reason(v.isa);
        if (!why.empty()) {
            r.status = Result::skipped;
            r.detail = why;
        }
        results.push_back(r);
        if (why.empty()) {
            rows.push_back(Row{&v, r, Rng(stream_seed(seed, routine_name(routine), v.name)), -1});
        }
    }
    Rng input(stream_seed(seed, routine_name(routine)));
    switch (routine) {
    case Routine::calculate_facing: run_calculate_facing(rows, input); break;
    case Routine::calculate_cull_bits: run_calculate_cull_bits(rows, input); break;
    case Routine::calculate_facing_count: run_calculate_facing_count(rows, input); break;
    case Routine::count_facing: run_count_facing(rows, input); break;
    case Routine::count_facing_cull: run_count_facing_cull(rows, input); break;
    case Routine::create_sil_triangles: run_create_sil_triangles(rows, input); break;
    case Routine::create_cap_triangles: run_create_cap_triangles(rows, input); break;
    case Routine::shadow_volume: run_shadow_volume(rows, input, false); break;
    case Routine::shadow_volume_cull: run_shadow_volume(rows, input, true); break;
    case Routine::shadow_volume_for_light: run_shadow_volume_for_light(rows, input); break;
    case Routine::create_general_sil_triangles:
        run_create_general_sil_triangles(rows, input);
        break;
    case Routine::create_general_cap_triangles:
        run_create_general_cap_triangles(rows, input);
        break;
    case Routine::derive_planes: run_derive_planes(rows, input); break;
    case Routine::facing_from_positions: run_facing_from_positions(rows, input); break;
    case Routine::skinning: run_skinning(rows, input); break;
    case Routine::skin_planes: run_skin_planes(rows, input); break;
    case Routine::extrude: run_extrude(rows, input); break;
    case Routine::derive_planes_clustered: run_derive_planes_clustered(rows, input); break;
    }
    // Back in table order, each run row in its place.
    size_t next = 0;
    for (Result &r : results) {
        if (r.status != Result::skipped) r = rows[next++].result;
    }
    return results;
}

bool abi_checker_built() {
#if defined(SV_HAVE_ABI_CHECKER)
    return true;
#else
    return false;
#endif
}

std::string abi_checker_summary() {
#if defined(SV_HAVE_ABI_CHECKER)
    const uint32_t flags = sv_abi_detect();
    std::string saved;
    for (int i = 0; i < sv_abi_callee_saved_count(); i++) {
        saved += std::string(i ? " " : "") + sv_abi_callee_saved_name(i);
    }
    std::string s = std::string(sv_abi_name()) + ": callee-saved " + saved;
#if defined(_WIN64)
    s += ", xmm6-xmm15";
#endif
    s += ", stack pointer, direction flag, stack above the arguments, garbage upper halves of int "
         "arguments";
    s += (flags & SV_ABI_HAS_XINUSE) ? ", dirty upper YMM/ZMM state (XGETBV)"
                                     : "; upper YMM/ZMM state not checked (no XGETBV ecx=1 here)";
    return s;
#else
    return "no ABI checker on this target (outputs and guards compared only)";
#endif
}

} // namespace svcheck
