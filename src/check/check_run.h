// Internal to the check library: one routine's run over the variants of a
// table (the rows), the checked call, and how a row records a failure.
// routine_checks.cpp drives it; check_cases.cpp writes the cases.
//
// Copyright (C) 2026 the shadowvol authors. LGPL-2.1-or-later.
#pragma once

#include <cstdint>
#include <cstring>
#include <string>
#include <vector>

#include "check_inputs.h"
#include "routine_checks.h"
#if defined(SV_HAVE_ABI_CHECKER)
#include "checked_call.h"
#endif

namespace svcheck {

// One variant's line: its result so far and its own stream of ABI garbage
// (seeded by routine and variant, so the other rows do not shift it).
struct Row {
    const Variant *variant;
    Result result;
    Rng abi;
    int failed_case; // the case whose failure was counted last (-1: none)
};

// Calls FN(ARGS...) through the ABI checker where the target has one
// (*FAILED: the broken promises, sv_abi_failed bits), directly elsewhere
// (*FAILED = 0: results and guards are still compared).
template <class Fn, class... A> auto abi_call(Rng &abi, uint32_t *failed, Fn fn, A... args) {
#if defined(SV_HAVE_ABI_CHECKER)
    return checked_call(abi, failed, fn, args...);
#else
    (void)abi;
    *failed = 0;
    return fn(args...);
#endif
}

// A row's bookkeeping for one call: a case counted, and the first failure
// kept as the line's detail (WHERE names the case, WHAT what broke).
void count_case(Row &row);
void record_failure(Row &row, const std::string &where, const std::string &what);
// The ABI part of one call: a failure when FAILED has bits set.
void record_abi(Row &row, uint32_t failed, const std::string &where);

// "" when N elements of GOT equal WANT's, else the first difference:
// "facing[12] = 0, c_ref 1".
template <class T>
std::string first_difference(const T *got, const T *want, size_t n, const char *what) {
    for (size_t i = 0; i < n; i++) {
        if (std::memcmp(&got[i], &want[i], sizeof(T)) != 0) {
            return std::string(what) + "[" + std::to_string(i) +
                   "] = " + std::to_string((long long)got[i]) + ", c_ref " +
                   std::to_string((long long)want[i]);
        }
    }
    return "";
}

// The cases of one routine, over ROWS (every row runnable here); RNG is
// the routine's input stream, the same for every row.
void run_calculate_facing(std::vector<Row> &rows, Rng &rng);
void run_calculate_cull_bits(std::vector<Row> &rows, Rng &rng);
void run_calculate_facing_count(std::vector<Row> &rows, Rng &rng);
void run_count_facing(std::vector<Row> &rows, Rng &rng);
void run_count_facing_cull(std::vector<Row> &rows, Rng &rng);
void run_create_sil_triangles(std::vector<Row> &rows, Rng &rng);
void run_create_cap_triangles(std::vector<Row> &rows, Rng &rng);
void run_shadow_volume(std::vector<Row> &rows, Rng &rng, bool cull);
void run_shadow_volume_for_light(std::vector<Row> &rows, Rng &rng);
void run_create_general_sil_triangles(std::vector<Row> &rows, Rng &rng);
void run_create_general_cap_triangles(std::vector<Row> &rows, Rng &rng);
void run_derive_planes(std::vector<Row> &rows, Rng &rng);
void run_derive_planes_clustered(std::vector<Row> &rows, Rng &rng);
void run_facing_from_positions(std::vector<Row> &rows, Rng &rng);
void run_skinning(std::vector<Row> &rows, Rng &rng);
void run_skin_planes(std::vector<Row> &rows, Rng &rng);
void run_extrude(std::vector<Row> &rows, Rng &rng);

} // namespace svcheck
