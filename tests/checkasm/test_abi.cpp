// The ABI checker checks itself: a deliberately broken routine for every
// promise it claims to check (tests/checkasm/abi_selfcheck.asm) must be reported
// with exactly its bit, and the correct twins must pass, or the
// differential tests' "ABI ok" means nothing.
//
// Copyright (C) 2026 the shadowvol authors. LGPL-2.1-or-later.
#include "test_support.h"

using namespace svtest;

extern "C" {
extern const uint32_t sv_abi_selftest_clobber_count;
extern int (*const sv_abi_selftest_clobbers[])(void);
int sv_abi_selftest_leave_df_set(void);
int sv_abi_selftest_shift_sp(void);
int sv_abi_selftest_dirty_ymm(void);
int sv_abi_selftest_clean_ymm(void);
int sv_abi_selftest_write_canary(void);
int sv_abi_selftest_write_own_args(void);
#if UINTPTR_MAX > 0xFFFFFFFFu
int64_t sv_abi_selftest_return_arg1(int);
int64_t sv_abi_selftest_return_arg1_as_64bit(int);
int64_t sv_abi_selftest_return_arg2_as_64bit(const void *, int);
#endif
}

namespace {

// The failure mask of one checked call of a (void) routine.
template <class Fn> uint32_t mask_of(Rng &rng, Fn fn) {
    uint32_t failed = 0;
    svcheck::checked_call(rng, &failed, fn);
    return failed;
}

} // namespace

TEST(AbiChecker, CatchesEachClobberedCalleeSavedRegister) {
    Rng rng = rng_for("AbiChecker.Clobber");
    ASSERT_EQ((int)sv_abi_selftest_clobber_count, sv_abi_callee_saved_count()) << sv_abi_name();
    for (int i = 0; i < sv_abi_callee_saved_count(); i++) {
        const uint32_t m = mask_of(rng, sv_abi_selftest_clobbers[i]);
        EXPECT_EQ(m, SV_ABI_FAIL_GPR(i)) << sv_abi_callee_saved_name(i) << ": " << abi_failures(m);
        EXPECT_EQ(abi_failures(m), sv_abi_callee_saved_name(i));
    }
}

TEST(AbiChecker, CatchesDirectionFlagLeftSet) {
    Rng rng = rng_for("AbiChecker.DF");
    EXPECT_EQ(mask_of(rng, sv_abi_selftest_leave_df_set), SV_ABI_FAIL_DF);
}

TEST(AbiChecker, CatchesAShiftedStackPointer) {
    Rng rng = rng_for("AbiChecker.SP");
    EXPECT_EQ(mask_of(rng, sv_abi_selftest_shift_sp), SV_ABI_FAIL_SP);
}

TEST(AbiChecker, CatchesAWriteAboveTheStackArguments) {
    Rng rng = rng_for("AbiChecker.Canary");
    const uint32_t m = mask_of(rng, sv_abi_selftest_write_canary);
    EXPECT_EQ(m, SV_ABI_FAIL_STACK_CANARY) << abi_failures(m);
    // Its own stack arguments (and the shadow space on Windows) are the
    // routine's to write: no report.
    EXPECT_EQ(mask_of(rng, sv_abi_selftest_write_own_args), 0u);
}

TEST(AbiChecker, CatchesDirtyUpperYmmState) {
    svcheck::detect_once();
    if (!(sv_abi_flags & SV_ABI_HAS_AVX))
        GTEST_SKIP() << "this CPU (or OS) has no AVX: no upper state to leave dirty";
    if (!(sv_abi_flags & SV_ABI_HAS_XINUSE))
        GTEST_SKIP() << "the dirty-upper check is off: this CPU has no XGETBV ecx=1 "
                        "(CPUID.(0Dh,1):EAX bit 2), or this is the x86-32 build (C and SSE2 "
                        "only; src/check/abi_check.c says why)";
    Rng rng = rng_for("AbiChecker.Ymm");
    const uint32_t m = mask_of(rng, sv_abi_selftest_dirty_ymm);
    EXPECT_EQ(m, SV_ABI_FAIL_YMM_UPPER) << abi_failures(m) << " xinuse " << sv_abi_xinuse_after;
    EXPECT_EQ(mask_of(rng, sv_abi_selftest_clean_ymm), 0u)
        << "vzeroupper before ret must pass; xinuse " << sv_abi_xinuse_after;
    // The checker starts every call clean: a clean routine after the dirty
    // one passes (the state does not leak from one call to the next).
    EXPECT_EQ(mask_of(rng, sv_abi_selftest_leave_df_set), SV_ABI_FAIL_DF);
}

// x86-64 only: on x86-32 an int argument is a whole 32-bit stack word (no
// upper half to garble; abi_selfcheck.asm has no such routines there).
#if UINTPTR_MAX > 0xFFFFFFFFu
TEST(AbiChecker, EveryIntArgumentCarriesGarbageInTheUpperHalf) {
    Rng rng = rng_for("AbiChecker.Upper");
    for (int v : {0, 1, -1, 600, INT32_MIN, INT32_MAX}) {
        EXPECT_EQ(checked_call(rng, sv_abi_selftest_return_arg1, v), (int64_t)v);
        // Read as 64 bits, the int argument is wrong, in first or second
        // place: the template garbled every int parameter by itself.
        EXPECT_NE(checked_call(rng, sv_abi_selftest_return_arg1_as_64bit, v), (int64_t)v);
        EXPECT_NE(checked_call(rng, sv_abi_selftest_return_arg2_as_64bit, nullptr, v), (int64_t)v);
        // Pointers travel unchanged.
        const void *p = &v;
        EXPECT_EQ((uintptr_t)svcheck::arg_word<const void *>(p, rng.next()), (uintptr_t)p);
    }
}
#endif

TEST(AbiChecker, NamesEveryBit) {
    EXPECT_EQ(abi_failures(SV_ABI_FAIL_SP | SV_ABI_FAIL_DF), "stack pointer, direction flag");
    EXPECT_NE(abi_failures(SV_ABI_FAIL_YMM_UPPER).find("vzeroupper"), std::string::npos);
    EXPECT_EQ(abi_failures(SV_ABI_FAIL_STACK_CANARY), "stack written above the arguments");
    EXPECT_EQ(abi_failures(SV_ABI_FAIL_XMM(6) | SV_ABI_FAIL_XMM(15)), "xmm6, xmm15");
}
