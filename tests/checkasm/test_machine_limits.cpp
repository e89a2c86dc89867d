// bench/machine/machine_limits.asm, the throughput primitives of `shadowvol bench
// --limits`, as routines: through the ABI-checking trampoline (callee-saved
// registers kept, int/long arguments with garbage upper halves where they
// are ints), at iteration counts 0, negative and small, each store
// primitive writing exactly its documented bytes (guards around them), and
// the wrap of the load walk at the buffer's size. No timing is asserted.
//
// Copyright (C) 2026 the shadowvol authors. LGPL-2.1-or-later.
#include <gtest/gtest.h>
#include <algorithm>
#include <x86intrin.h>

#include <cstdint>
#include <cstring>
#include <vector>

#include "machine_limits_asm.h"
#include "shadowvol.h"
#include "test_support.h"

using namespace svtest;

namespace {

constexpr size_t kGuard = 256;
constexpr size_t kBuffer = 16 * 1024;

// The primitives' own prototypes (machine_limits_asm.h), so that
// checked_call builds the argument words from them.
struct Form {
    const char *name;
    unsigned isa;
    void (*loads)(const uint8_t *, int64_t, int64_t);
    void (*stores)(uint8_t *, int64_t);
    void (*gather)(const uint8_t *, int64_t);
    size_t storeBytes; // what one call of the store primitive writes
};

const Form kForms[] = {
    {"ymm", SV_ISA_AVX2, svb_vector_loads_ymm, svb_vector_stores_ymm, svb_gather_lanes_ymm, 256},
    {"zmm", SV_ISA_AVX512, svb_vector_loads_zmm, svb_vector_stores_zmm, svb_gather_lanes_zmm, 512},
};

const Form *form_named(const std::string &name) {
    for (const Form &f : kForms)
        if (name == f.name) return &f;
    return nullptr;
}

// A 64-byte aligned buffer of kBuffer bytes between two guards of kGuard.
struct Guarded {
    std::vector<uint8_t> raw = std::vector<uint8_t>(kBuffer + 2 * kGuard + 64, 0xA5);
    uint8_t *data() {
        uintptr_t p = (uintptr_t)raw.data() + kGuard;
        return (uint8_t *)((p + 63) & ~(uintptr_t)63);
    }
    // Bytes [from, to) of the data that are not 0xA5, and the guards.
    size_t changed(size_t from, size_t to) {
        size_t n = 0;
        for (size_t i = from; i < to; i++) n += data()[i] != 0xA5;
        return n;
    }
    bool guards_intact() {
        const uint8_t *d = data();
        for (const uint8_t *q = raw.data(); q < d; q++)
            if (*q != 0xA5) return false;
        for (const uint8_t *q = d + kBuffer; q < raw.data() + raw.size(); q++)
            if (*q != 0xA5) return false;
        return true;
    }
};

} // namespace

TEST(MachineLimits, ScalarLoadsKeepTheAbiAndWriteNothing) {
    SCOPED_TRACE(seed_trace());
    Rng rng = rng_for("MachineLimits.Scalar");
    Guarded g;
    for (int64_t iters : {0L, -1L, 1L, 3L}) {
        checked_call(rng, svb_scalar_loads, g.data(), iters);
        EXPECT_EQ(g.changed(0, kBuffer), 0u) << iters;
        EXPECT_TRUE(g.guards_intact()) << iters;
    }
}

// The core-clock chain: it takes only a count (no memory), keeps the ABI
// for every count, the non-positive ones included, and does its work: the
// chain of 32 adds per iteration costs measurably more for more
// iterations (a loop that skipped it would time the same for any count).
TEST(MachineLimits, DependentAddsKeepTheAbi) {
    SCOPED_TRACE(seed_trace());
    Rng rng = rng_for("MachineLimits.DependentAdds");
    for (int64_t iters : {0L, -1L, 1L, 3L, 1000L}) checked_call(rng, svb_dependent_adds, iters);
    uint64_t shortest[2] = {UINT64_MAX, UINT64_MAX};
    for (int round = 0; round < 20; round++) {
        for (int k = 0; k < 2; k++) {
            const uint64_t t0 = __rdtsc();
            svb_dependent_adds(k ? 200000 : 1000);
            shortest[k] = std::min<uint64_t>(shortest[k], __rdtsc() - t0);
        }
    }
    EXPECT_GT(shortest[1], 10 * shortest[0]) << "the chain did not run its iterations";
}

// One instance per vector form (ymm, zmm), skipped where the CPU (or
// SV_ISA) lacks it: Forms/MachineLimits.VectorPrimitivesKeepTheAbiAndTheirBytes/zmm.
class MachineLimitsForm : public ::testing::TestWithParam<std::string> {};

// Named by tier (avx2_ymm, avx512_zmm), so each runs in its tier's ctest
// entry (tests/support/test_conditions.h).
INSTANTIATE_TEST_SUITE_P(Forms, MachineLimitsForm, ::testing::Values("ymm", "zmm"),
                         [](const ::testing::TestParamInfo<std::string> &i) {
                             return std::string(i.param == "ymm" ? "avx2_" : "avx512_") + i.param;
                         });

TEST_P(MachineLimitsForm, VectorPrimitivesKeepTheAbiAndTheirBytes) {
    SCOPED_TRACE(seed_trace());
    const Form *fp = form_named(GetParam());
    ASSERT_NE(fp, nullptr);
    const Form &f = *fp;
    const std::string why = isa_missing(f.isa);
    if (!why.empty()) GTEST_SKIP() << f.name << " forms: " << why;
    Rng rng = rng_for(("MachineLimits.Vector/" + GetParam()).c_str());
    for (int64_t iters : {0L, -2L, 1L, 5L}) {
        Guarded g;
        // loads over 512 bytes (one iteration wraps at once) and the whole buffer
        for (int64_t bytes : {512L, (long)kBuffer}) {
            checked_call(rng, f.loads, g.data(), iters, bytes);
        }
        checked_call(rng, f.gather, g.data(), iters);
        EXPECT_EQ(g.changed(0, kBuffer), 0u) << f.name << " loads wrote, iters " << iters;
        checked_call(rng, f.stores, g.data(), iters);
        // zeros in exactly the first storeBytes when it ran, nothing otherwise
        EXPECT_EQ(g.changed(0, f.storeBytes), iters > 0 ? f.storeBytes : 0u)
            << f.name << " iters " << iters;
        EXPECT_EQ(g.changed(f.storeBytes, kBuffer), 0u) << f.name << " iters " << iters;
        EXPECT_TRUE(g.guards_intact()) << f.name << " iters " << iters;
    }
}
