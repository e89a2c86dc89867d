// What one ctest entry of a test program covers, so that a test that cannot
// run shows as skipped in ctest's own summary instead of passing.
//
// ctest runs a whole test program as one entry, so a GTEST_SKIP or a
// printed NOTE inside one used to count as a passed entry. Each condition a
// test may lack is therefore its own entry (tests/CMakeLists.txt,
// sv_add_gtest), chosen by the environment:
//
//   SV_TEST_ISA=avx2|avx512|avx512vbmi   the variants of that ISA tier;
//                         unset: the baseline tier (c and sse2 variants),
//                         which every x86-64 CPU runs, and every test that
//                         names no variant
//   SV_TEST_SHARED_MODELS=1   the tests whose suite or name has SharedModels (the real
//                         characters of ../shared/models); unset: every
//                         other test
//
// The program's main (tests/support/test_main.cpp) exits 77 (ctest's
// SKIP_RETURN_CODE) before running anything when the entry's condition is
// not met here (the CPU lacks the tier, the folder is missing), and after
// running when any test skipped or a variant of the entry's tier could not
// run. It narrows gtest's filter to the entry: a test of one variant (a
// parameterised test named .../VARIANT) runs only in its tier's entry, a
// *SharedModels* test only in the shared-models entry.
//
// Copyright (C) 2026 the shadowvol authors. LGPL-2.1-or-later.
#pragma once

#include <gtest/gtest.h>

#include <string>
#include <vector>

namespace svtest {

// The ISA tier of a variant with ISA bits ISA (SV_ISA_*): "" for the
// baseline (C, SSE2), else "avx2", "avx512" or "avx512vbmi".
const char *isa_tier(unsigned isa);

// Why a variant with ISA bits ISA cannot run here: "" when it can, "held
// down by the ISA limit (SV_ISA=...)", or "this CPU lacks its instruction
// set".
std::string isa_missing(unsigned isa);

// This entry's tier (SV_TEST_ISA), "" for the baseline.
const char *tier_of_this_run();

// Whether a test that loops over a routine's variants checks the variant
// NAME with ISA bits ISA in this entry: its tier is the baseline or the
// entry's, and dispatch may run it (a variant held down by SV_ISA is out of
// the entry's scope). A variant of the entry's tier that this CPU lacks is
// recorded, and the program exits 77 naming it: never a silent pass.
bool in_this_run(unsigned isa, const char *name);

// Registers a test that loops over a routine's variants (SV_TIERED_TEST);
// returns true, for a static initializer.
bool declare_tiered(const char *suite_dot_name);

// The two model sets a test of the real characters is instantiated over:
// "bundled" (the bundled character) and "SharedModels" (../shared/models;
// that instance runs in the shared-models entry).
inline std::vector<std::string> model_sets() { return {"bundled", "SharedModels"}; }

// Whether this entry is the shared-models one (SV_TEST_SHARED_MODELS=1).
bool shared_models_run();

// The folder of the real characters. Only for tests named *SharedModels*:
// any other test that calls it fails (the name is what puts a test in the
// shared-models entry).
std::string shared_models_dir();

} // namespace svtest

// A test that loops over a routine's variants (it calls in_this_run, or a
// helper that does) is declared with these instead of TEST / TEST_P: a tier's
// entry runs them, over the baseline and that tier's variants, and the
// tier's parameterised tests, and nothing else (the other tests ran in the
// baseline entry). A test that calls in_this_run undeclared fails, so none
// is left out of the tier entries unnoticed.
#define SV_TIERED_TEST(suite, name)                                                                \
    static const bool sv_tiered_##suite##_##name = ::svtest::declare_tiered(#suite "." #name);     \
    TEST(suite, name)
#define SV_TIERED_TEST_P(suite, name)                                                              \
    static const bool sv_tiered_##suite##_##name = ::svtest::declare_tiered(#suite "." #name);     \
    TEST_P(suite, name)
