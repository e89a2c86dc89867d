// The self-test of `shadowvol check` (checkasm's way: dav1d, FFmpeg): for
// each routine and each variant of a table, seeded random inputs over every
// tail length, the offsets the variant's alignment contract allows, and the
// edge cases each contract admits; every call through the ABI checker
// (src/check/checked_call.h, where the target has it); results compared
// with the paper's C (the sv_*_c_ref functions, called directly, never
// through the table: a broken table cannot break the oracle), output byte
// for byte and the guard zones past the documented write bound.
//
// The table is a parameter, so a test can hand it deliberately broken
// variants (tests/checkasm/test_routine_checks.cpp) and see each reported.
//
// Copyright (C) 2026 the shadowvol authors. LGPL-2.1-or-later.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "shadowvol.h"
#include "shadowvol_extrude.h"
#include "shadowvol_plan.h"
#include "shadowvol_planes.h"
#include "shadowvol_skin.h"

namespace svcheck {

// Appendices A and B, A fused with C, C-F by the benchmark's names; the
// whole volume (sv_create_shadow_volume) without and with cull bits; and
// the one call per light (sv_shadow_volume_for_light, with a plan).
enum class Routine {
    calculate_facing,
    calculate_cull_bits,
    calculate_facing_count,
    count_facing,
    count_facing_cull,
    create_sil_triangles,
    create_cap_triangles,
    shadow_volume,
    shadow_volume_cull,
    shadow_volume_for_light,
    create_general_sil_triangles, /* the general rule (issue 27) */
    create_general_cap_triangles,
    derive_planes, /* deforming surfaces (shadowvol_planes.h, shadowvol_skin.h) */
    facing_from_positions,
    skinning,
    skin_planes,
    extrude,                 /* seed 002's vertex program (shadowvol_extrude.h, issue 31) */
    derive_planes_clustered, /* planes by clusters (shadowvol_planes.h, issue 32) */
};
constexpr int kNumRoutines = 18;
const char *routine_name(Routine r);
// false when NAME is none of routine_name()'s.
bool routine_by_name(const std::string &name, Routine *out);
std::vector<Routine> all_routines();

// What one variant runs for meshes of one size class. A null pointer means
// the variant has no such routine (c_branchless has no CalculateFacing;
// the facing table's sse2 has no C-F): no line is printed for it.
struct Kernels {
    sv_calculate_facing_fn calculate_facing = nullptr;
    sv_calculate_cull_bits_fn calculate_cull_bits = nullptr;
    sv_calculate_facing_count_fn calculate_facing_count = nullptr;
    sv_variant kernels{}; // C-F with their alignment needs; count_facing null: none
    // The plan sv_shadow_volume_for_light runs ("planned" only; null: none).
    const sv_plan *plan = nullptr;
    // The general rule's kernels of the variant's name (null: none).
    const sv_general_variant *general = nullptr;
    // The deforming surfaces' kernels of the variant's name (null: none):
    // derive_planes and facing_from_positions, skinning, skin_planes.
    const sv_planes_variant *planes = nullptr;
    const sv_skin_variant *skin = nullptr;
    const sv_skin_planes_variant *skin_planes = nullptr;
    // Seed 002's vertex program of the variant's name (null: none).
    const sv_extrude_variant *extrude = nullptr;
    // The clustered planes kernel of the variant's name (null: none;
    // planned: the planner's choice, none when it keeps the planes variant).
    const sv_planes_clustered_variant *clustered = nullptr;
    // Whether the contract lets CountFacingCull see cull bit 7
    // (sse2_paper's does not, erratum D-5): asked of the library's own
    // contract check (sv_count_facing_cull_checked), not known by name.
    bool cull_bit7 = true;
};

struct Variant {
    std::string name;
    unsigned isa = 0; // SV_ISA_* bits the CPU must run
    // One set per size class (sv_size_class): the same four for a plain
    // variant; the class's plan for "planned", whose choice may differ by
    // mesh size.
    Kernels by_class[SV_NUM_SIZE_CLASSES];
    const Kernels &for_triangles(int numTriangles) const;
    bool has(Routine r) const;
};

// The library's variants: the union of sv_variants() and
// sv_facing_variants() by name (avx2's facing and its kernels are one
// row), with the planes, skinning and one-pass kernels of the same name
// and the extrusion of the same name (and rows of their own for names only
// they have), then "planned"
// (sv_plan_for, SV_PLAN_ESTIMATE, per size class, and the deform choices:
// sv_deform_choice_for, else the static ones; the extrusion: the widest,
// sv_best_extrude_variant, which the renderer runs).
std::vector<Variant> library_variants();
// A plain variant from the library's tables; FACING or KERNELS may be null.
Variant make_variant(const std::string &name, const sv_facing_variant *facing,
                     const sv_variant *kernels);

// "" when this process may run a variant needing ISA, else why not: "this
// CPU lacks avx512 avx512vbmi" or "SV_ISA=avx2 holds dispatch at avx2".
std::string skip_reason(unsigned isa);

struct Result {
    enum Status { ok, failed, skipped };
    Routine routine;
    std::string variant;
    Status status = ok;
    int cases = 0;      // calls compared
    int failures = 0;   // of them, how many differed or broke a rule
    std::string detail; // skipped: the reason; failed: the first failing case
};

// Runs ROUTINE for every variant of TABLE that has it, on the inputs that
// SEED gives (the same inputs for every variant of the table). Variants the
// CPU cannot run come back skipped.
std::vector<Result> check_routine(Routine routine, const std::vector<Variant> &table,
                                  uint64_t seed);

// Whether checked calls go through the ABI checker on this target, and a
// line saying what it checks ("System V x86-64: callee-saved rbx ...").
bool abi_checker_built();
std::string abi_checker_summary();

} // namespace svcheck
