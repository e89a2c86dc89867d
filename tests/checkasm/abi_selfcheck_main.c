/* Standalone self-check of the ABI checker for the ABIs the main build does
 * not produce (win64 under wine, elf32 natively or under qemu-i386): each
 * broken routine of abi_selfcheck.asm must be reported with exactly its bit.
 * Build: nasm -f elf32 (or win64) both .asm files, link with this file.
 * Prints one line per check; exits 1 on any mismatch.
 * Copyright (C) 2026 the shadowvol authors. LGPL-2.1-or-later. */
#include <stdio.h>
#include <string.h>

#include "abi_check.h"

extern const uint32_t sv_abi_selftest_clobber_count;
extern int (*const sv_abi_selftest_clobbers[])(void);
int sv_abi_selftest_leave_df_set(void);
int sv_abi_selftest_shift_sp(void);
int sv_abi_selftest_dirty_ymm(void);
int sv_abi_selftest_clean_ymm(void);
int sv_abi_selftest_write_canary(void);
int sv_abi_selftest_write_own_args(void);
#ifdef _WIN64
int sv_abi_selftest_clobber_xmm6(void);
int sv_abi_selftest_clobber_xmm15(void);
#endif

static uint64_t state = 0x9E3779B97F4A7C15ull;
static uint64_t next(void) {
    state ^= state << 13, state ^= state >> 7, state ^= state << 17;
    return state;
}

static int failures;
static void expect(const char *what, const void *fn, uint32_t want) {
    uintptr_t args[SV_ABI_ARGS];
    for (int i = 0; i < SV_ABI_ARGS; i++) args[i] = (uintptr_t)next();
    for (int i = 0; i < 8; i++) sv_abi_canary[i] = (uintptr_t)next();
    for (int i = 0; i < SV_ABI_STACK_CANARIES; i++) sv_abi_stack_canary[i] = (uintptr_t)next();
    for (int i = 0; i < 256; i++) sv_abi_xmm_garbage[i] = (uint8_t)next();
    sv_abi_checked_call(fn, args);
    char buf[256];
    int ok = sv_abi_failed == want;
    printf("%-28s %s (%s)\n", what, ok ? "ok" : "FAILED",
           sv_abi_failure_names(sv_abi_failed, buf, sizeof buf));
    failures += !ok;
}

int main(void) {
    uint32_t flags = sv_abi_detect();
    printf("ABI %s, flags %u\n", sv_abi_name(), (unsigned)flags);
    for (int i = 0; i < (int)sv_abi_selftest_clobber_count; i++)
        expect(sv_abi_callee_saved_name(i), (const void *)sv_abi_selftest_clobbers[i],
               SV_ABI_FAIL_GPR(i));
    expect("direction flag", (const void *)sv_abi_selftest_leave_df_set, SV_ABI_FAIL_DF);
    expect("stack pointer", (const void *)sv_abi_selftest_shift_sp, SV_ABI_FAIL_SP);
    expect("canary", (const void *)sv_abi_selftest_write_canary, SV_ABI_FAIL_STACK_CANARY);
    expect("own stack arguments", (const void *)sv_abi_selftest_write_own_args, 0);
#ifdef _WIN64
    expect("xmm6", (const void *)sv_abi_selftest_clobber_xmm6, SV_ABI_FAIL_XMM(6));
    expect("xmm15", (const void *)sv_abi_selftest_clobber_xmm15, SV_ABI_FAIL_XMM(15));
#endif
    if ((flags & SV_ABI_HAS_AVX) && (flags & SV_ABI_HAS_XINUSE)) {
        expect("dirty ymm", (const void *)sv_abi_selftest_dirty_ymm, SV_ABI_FAIL_YMM_UPPER);
        expect("clean ymm", (const void *)sv_abi_selftest_clean_ymm, 0);
    } else {
        printf("dirty ymm                    skipped: no AVX, no XGETBV ecx=1, or x86-32 "
               "(abi_check.c)\n");
    }
    return failures ? 1 : 0;
}
