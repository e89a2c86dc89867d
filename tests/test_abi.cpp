// The ABI checker checks itself: deliberately broken routines must be
// caught, and a correct one must pass, or the differential tests' "ABI ok"
// means nothing.
//
// Copyright (C) 2026 the shadowvol authors. LGPL-2.1-or-later.
#include "test_support.h"

using namespace svtest;

extern "C" {
int sv_abi_selftest_clobber_rbx_r13(void);
int sv_abi_selftest_leave_df_set(void);
int64_t sv_abi_selftest_return_arg1(int);
int64_t sv_abi_selftest_return_arg1_as_64bit(int);
}

TEST(AbiChecker, CatchesClobberedCalleeSavedRegisters) {
    Rng rng = rng_for("AbiChecker.Clobber");
    abi_scramble(rng);
    sv_abi_failed = 0;
    sv_abi_checked_call((const void *)sv_abi_selftest_clobber_rbx_r13, 0, 0, 0, 0, 0);
    EXPECT_EQ(sv_abi_failed, (1u << 0) | (1u << 3)) << abi_failures(sv_abi_failed);
    EXPECT_EQ(abi_failures(sv_abi_failed), "rbx, r13");
}

TEST(AbiChecker, CatchesDirectionFlagLeftSet) {
    Rng rng = rng_for("AbiChecker.DF");
    abi_scramble(rng);
    sv_abi_failed = 0;
    sv_abi_checked_call((const void *)sv_abi_selftest_leave_df_set, 0, 0, 0, 0, 0);
    EXPECT_EQ(sv_abi_failed, 1u << 7);
}

TEST(AbiChecker, IntArgumentsCarryGarbageInTheUpperHalf) {
    Rng rng = rng_for("AbiChecker.Upper");
    for (int v : {0, 1, -1, 600, INT32_MIN, INT32_MAX}) {
        uint64_t a = int_arg(v, rng);
        abi_scramble(rng);
        sv_abi_failed = 0;
        int64_t good = (int64_t)sv_abi_checked_call((const void *)sv_abi_selftest_return_arg1,
                                                    a, 0, 0, 0, 0);
        EXPECT_EQ(good, (int64_t)v);
        EXPECT_EQ(sv_abi_failed, 0u);
        int64_t bad = (int64_t)sv_abi_checked_call(
            (const void *)sv_abi_selftest_return_arg1_as_64bit, a, 0, 0, 0, 0);
        EXPECT_NE(bad, (int64_t)v) << "a routine reading the whole 64-bit register is caught";
    }
}
