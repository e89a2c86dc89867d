/*
 * Names of the ABI checker's bits, per calling convention. The order of the
 * callee-saved registers matches abi_checked_call.asm's bits 0-7.
 *
 * Copyright (C) 2026 the shadowvol authors. LGPL-2.1-or-later.
 */
#include "abi_check.h"

#include <stdio.h>
#include <string.h>

#if defined(_WIN64)
static const char *const kSaved[] = {"rbx", "rbp", "rdi", "rsi", "r12", "r13", "r14", "r15"};
static const char kAbi[] = "Windows x64";
#elif defined(__x86_64__)
static const char *const kSaved[] = {"rbx", "rbp", "r12", "r13", "r14", "r15"};
static const char kAbi[] = "System V x86-64";
#elif defined(__i386__)
static const char *const kSaved[] = {"ebx", "esi", "edi", "ebp"};
static const char kAbi[] = "x86-32 cdecl";
#else
#error "the ABI checker knows x86-64 (System V, Windows) and x86-32 only"
#endif

const char *sv_abi_name(void) { return kAbi; }

/* On x86-32 the dirty-upper check is off. The 32-bit build holds C and
 * SSE2 code only (no routine there can leave the upper state dirty), and
 * in 32-bit mode XINUSE's YMM bit is not reliable: vzeroupper reaches
 * ymm0-7 only, and on an AMD Zen 4 (family 25 model 17, Linux) a process
 * that had once left the upper state dirty (the checker's own self-test)
 * then read as dirty after hundreds of calls of plain C routines (the
 * state apparently restored as in use by the kernel). The tests that need
 * the check skip there and say why. */
uint32_t sv_abi_detect(void) {
    uint32_t flags = sv_abi_detect_cpu();
#if defined(__i386__)
    flags &= ~SV_ABI_HAS_XINUSE;
    sv_abi_flags = flags;
#endif
    return flags;
}

int sv_abi_callee_saved_count(void) { return (int)(sizeof kSaved / sizeof kSaved[0]); }

const char *sv_abi_callee_saved_name(int i) {
    return i >= 0 && i < sv_abi_callee_saved_count() ? kSaved[i] : "?";
}

static void append(char *buf, size_t size, size_t *len, const char *s) {
    int n = snprintf(buf + *len, size - *len, "%s%s", *len ? ", " : "", s);
    if (n > 0) *len = *len + (size_t)n < size ? *len + (size_t)n : size - 1;
}

const char *sv_abi_failure_names(uint32_t mask, char *buf, size_t size) {
    size_t len = 0;
    if (size == 0) return buf;
    buf[0] = 0;
    for (int i = 0; i < sv_abi_callee_saved_count(); i++)
        if (mask & SV_ABI_FAIL_GPR(i)) append(buf, size, &len, kSaved[i]);
    if (mask & SV_ABI_FAIL_SP) append(buf, size, &len, "stack pointer");
    if (mask & SV_ABI_FAIL_DF) append(buf, size, &len, "direction flag");
    if (mask & SV_ABI_FAIL_YMM_UPPER)
        append(buf, size, &len, "upper YMM state dirty (missing vzeroupper)");
    if (mask & SV_ABI_FAIL_ZMM_UPPER)
        append(buf, size, &len, "upper ZMM state dirty (missing vzeroupper)");
    if (mask & SV_ABI_FAIL_STACK_CANARY)
        append(buf, size, &len, "stack written above the arguments");
    for (int x = 6; x <= 15; x++) {
        if (mask & SV_ABI_FAIL_XMM(x)) {
            char name[8];
            snprintf(name, sizeof name, "xmm%d", x);
            append(buf, size, &len, name);
        }
    }
    return buf;
}
