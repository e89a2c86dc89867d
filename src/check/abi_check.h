/*
 * The ABI checker's C interface (src/check/abi_checked_call.asm): the call
 * trampoline, its state, and the names of the bits it reports. Plain C so
 * that the test suite and `shadowvol check` share it; the C++ template that
 * builds the argument words from a prototype is in checked_call.h.
 *
 * Copyright (C) 2026 the shadowvol authors. LGPL-2.1-or-later.
 */
#ifndef SV_ABI_CHECK_H
#define SV_ABI_CHECK_H

#include <stddef.h>
#include <stdint.h>

#ifdef __cplusplus
extern "C" {
#endif

/* sv_abi_failed bits (abi_checked_call.asm's header explains each). Bits
 * 0-7 are the callee-saved GPRs in sv_abi_callee_saved_name() order. */
#define SV_ABI_FAIL_GPR(i) (1u << (i))
#define SV_ABI_FAIL_SP (1u << 8)
#define SV_ABI_FAIL_DF (1u << 9)
#define SV_ABI_FAIL_YMM_UPPER (1u << 10)
#define SV_ABI_FAIL_ZMM_UPPER (1u << 11)
#define SV_ABI_FAIL_STACK_CANARY (1u << 12)
#define SV_ABI_FAIL_XMM(n) (1u << (16 + (n)-6)) /* win64: xmm6..xmm15 */

/* sv_abi_flags bits, from sv_abi_detect(). */
#define SV_ABI_HAS_AVX 1u    /* vzeroupper runs before the call */
#define SV_ABI_HAS_XINUSE 2u /* XGETBV ecx=1: the dirty-upper checks run */
#define SV_ABI_HAS_SSE2 4u   /* the xmm garbage is loaded */

#define SV_ABI_ARGS 8           /* argument words sv_abi_checked_call passes */
#define SV_ABI_STACK_CANARIES 4 /* words above the stack arguments */

/* Calls fn(args[0..7]) with the platform's convention and hostile register
 * contents; sets sv_abi_failed. Returns rax (eax on x86-32). Not reentrant. */
uintptr_t sv_abi_checked_call(const void *fn, const uintptr_t *args);
/* Fills sv_abi_flags from CPUID / XGETBV (sv_abi_detect_cpu, the
 * assembly) and returns it; on x86-32 without SV_ABI_HAS_XINUSE: the
 * dirty-upper check is off there (abi_check.c says why). */
uint32_t sv_abi_detect(void);
uint32_t sv_abi_detect_cpu(void);

extern uintptr_t sv_abi_canary[8]; /* callee-saved GPR values */
extern uintptr_t sv_abi_stack_canary[SV_ABI_STACK_CANARIES];
extern uint8_t sv_abi_xmm_garbage[256]; /* xmm0-15 (xmm0-7 on x86-32) */
extern uint32_t sv_abi_failed;
extern uint32_t sv_abi_flags;
extern uint32_t sv_abi_xinuse_after; /* XINUSE after the last call */

/* "System V x86-64", "Windows x64" or "x86-32 cdecl". */
const char *sv_abi_name(void);
/* Number of callee-saved GPRs checked (6, 8, 4) and the name of number i. */
int sv_abi_callee_saved_count(void);
const char *sv_abi_callee_saved_name(int i);
/* The broken promises in MASK, comma-separated, in BUF; returns BUF. */
const char *sv_abi_failure_names(uint32_t mask, char *buf, size_t size);

#ifdef __cplusplus
}
#endif

#endif
