/*
 * Which SV_ISA_* levels this CPU (and its operating system) runs, and the
 * optional limit a user sets to force a lower level.
 *
 * Detection: CPUID for the instructions, XGETBV for the OS: AVX needs the
 * OS to save the YMM state (XCR0 bits 1 and 2), AVX-512 also the opmask and
 * ZMM state (bits 5, 6, 7). A CPU that has AVX-512 under an OS that does
 * not enable it must not run AVX-512 code (it would fault), so both are
 * required.
 *
 * 32-bit x86: SSE2 is not architectural there (a Pentium III or Athlon XP
 * has none), so it is read from CPUID leaf 1 (EDX bit 26) like the rest.
 * The 32-bit build is compiled with -msse2 -mfpmath=sse (docs/PLATFORMS.md)
 * and needs SSE2 anyway; the bit still decides which SIMD variants run.
 *
 * Limit: the environment variable SV_ISA (read once, on first use) or
 * sv_set_isa_limit() caps what sv_cpu_isa() reports, so tests, benchmark
 * and dispatch can be run as on an older CPU:
 *   c       no SIMD variant (the C variants only)
 *   sse2    SV_ISA_SSE2
 *   avx2    SV_ISA_SSE2 | SV_ISA_AVX2
 *   avx512  everything (SV_ISA_AVX512 and its extras SV_ISA_AVX512_VBMI and
 *           SV_ISA_AVX512_VBMI2 included)
 *
 * Copyright (C) 2026 the shadowvol authors. LGPL-2.1-or-later.
 */
#include <stdlib.h>
#include <string.h>

#include "shadowvol.h"

#if defined(__x86_64__) || defined(__i386__)
#include <cpuid.h>

static unsigned long long xgetbv0(void) {
    unsigned eax, edx;
    __asm__ volatile("xgetbv" : "=a"(eax), "=d"(edx) : "c"(0));
    return ((unsigned long long)edx << 32) | eax;
}

static unsigned detect(void) {
#if defined(__x86_64__)
    unsigned a, b, c, d, max_leaf, isa = SV_ISA_SSE2; /* architectural on x86-64 */
    if (!__get_cpuid(0, &max_leaf, &b, &c, &d)) {
        return isa;
    }
    __cpuid(1, a, b, c, d);
#else
    /* __get_cpuid checks that CPUID exists at all (EFLAGS.ID) first. */
    unsigned a, b, c, d, max_leaf, isa = SV_ISA_NONE;
    if (!__get_cpuid(0, &max_leaf, &b, &c, &d) || max_leaf < 1) {
        return isa;
    }
    __cpuid(1, a, b, c, d);
    if (!((d >> 26) & 1)) {
        return isa;
    }
    isa = SV_ISA_SSE2;
#endif
    const unsigned osxsave = (c >> 27) & 1, avx = (c >> 28) & 1, fma = (c >> 12) & 1;
    const unsigned popcnt = (c >> 23) & 1;
    if (!osxsave || !avx || max_leaf < 7) {
        return isa;
    }
    const unsigned long long xcr0 = xgetbv0();
    const int os_ymm = (xcr0 & 0x6) == 0x6;   /* SSE + AVX state */
    const int os_zmm = (xcr0 & 0xE6) == 0xE6; /* + opmask, ZMM_Hi256, Hi16_ZMM */
    __cpuid_count(7, 0, a, b, c, d);
    const unsigned avx2 = (b >> 5) & 1, bmi1 = (b >> 3) & 1, bmi2 = (b >> 8) & 1;
    const unsigned avx512f = (b >> 16) & 1, avx512dq = (b >> 17) & 1, avx512cd = (b >> 28) & 1;
    const unsigned avx512bw = (b >> 30) & 1, avx512vl = (b >> 31) & 1;
    const unsigned vbmi = (c >> 1) & 1, vbmi2 = (c >> 6) & 1;
    /* The x86-64-v3 set: what compilers assume for -march=x86-64-v3. */
    if (os_ymm && avx2 && bmi1 && bmi2 && fma && popcnt) {
        isa |= SV_ISA_AVX2;
        /* x86-64-v4: F, BW, VL, DQ, CD. */
        if (os_zmm && avx512f && avx512bw && avx512vl && avx512dq && avx512cd) {
            isa |= SV_ISA_AVX512;
            if (vbmi) {
                isa |= SV_ISA_AVX512_VBMI;
            }
            if (vbmi2) {
                isa |= SV_ISA_AVX512_VBMI2;
            }
        }
    }
    return isa;
}
#else
static unsigned detect(void) { return SV_ISA_NONE; }
#endif

static const struct {
    const char *name;
    unsigned mask;
} levels[] = {
    {"c", SV_ISA_NONE},
    {"sse2", SV_ISA_SSE2},
    {"avx2", SV_ISA_SSE2 | SV_ISA_AVX2},
    {"avx512",
     SV_ISA_SSE2 | SV_ISA_AVX2 | SV_ISA_AVX512 | SV_ISA_AVX512_VBMI | SV_ISA_AVX512_VBMI2},
};
#define NUM_LEVELS (int)(sizeof levels / sizeof levels[0])
#define NO_LIMIT (-1)
#define UNSET (-2)

/* Detected bits + 1 (0 = not yet), and the limit's level index (UNSET =
 * SV_ISA not read yet). Relaxed atomics: every thread computes the same
 * values, so a race only repeats work. */
static unsigned detected_plus_one;
static int limit_level = UNSET;

static int level_index(const char *name) {
    int i;
    for (i = 0; name && i < NUM_LEVELS; i++) {
        if (strcmp(name, levels[i].name) == 0) {
            return i;
        }
    }
    return -1;
}

unsigned sv_cpu_isa_detected(void) {
    unsigned v = __atomic_load_n(&detected_plus_one, __ATOMIC_RELAXED);
    if (!v) {
        v = detect() + 1;
        __atomic_store_n(&detected_plus_one, v, __ATOMIC_RELAXED);
    }
    return v - 1;
}

static int current_limit(void) {
    int l = __atomic_load_n(&limit_level, __ATOMIC_RELAXED);
    if (l == UNSET) {
        const char *env = getenv("SV_ISA");
        l = (env && *env) ? level_index(env) : NO_LIMIT;
        /* An unknown SV_ISA value would silently run everything; run the
         * C variants only instead, and let sv_isa_limit_name() say so. */
        if (env && *env && l < 0) {
            l = 0;
        }
        __atomic_store_n(&limit_level, l, __ATOMIC_RELAXED);
    }
    return l;
}

unsigned sv_cpu_isa(void) {
    const int l = current_limit();
    const unsigned isa = sv_cpu_isa_detected();
    return l == NO_LIMIT ? isa : isa & levels[l].mask;
}

int sv_set_isa_limit(const char *level) {
    if (!level) {
        __atomic_store_n(&limit_level, NO_LIMIT, __ATOMIC_RELAXED);
        return 0;
    }
    const int l = level_index(level);
    if (l < 0) {
        return -1;
    }
    __atomic_store_n(&limit_level, l, __ATOMIC_RELAXED);
    return 0;
}

const char *sv_isa_limit_name(void) {
    const int l = current_limit();
    return l == NO_LIMIT ? NULL : levels[l].name;
}

const char *sv_isa_level_name(void) {
    const unsigned isa = sv_cpu_isa();
    int i;
    for (i = NUM_LEVELS - 1; i > 0; i--) {
        /* The highest level all of whose required bits are present (VBMI
         * and VBMI2 are extras, not required for "avx512"). */
        const unsigned need = levels[i].mask &
                              ~(unsigned)(SV_ISA_AVX512_VBMI | SV_ISA_AVX512_VBMI2);
        if ((isa & need) == need) {
            return levels[i].name;
        }
    }
    return levels[0].name;
}

const char *sv_isa_names(unsigned isa, char *buf, size_t size) {
    static const struct {
        unsigned bit;
        const char *name;
    } bits[] = {{SV_ISA_SSE2, "sse2"},
                {SV_ISA_AVX2, "avx2"},
                {SV_ISA_AVX512, "avx512"},
                {SV_ISA_AVX512_VBMI, "avx512vbmi"},
                {SV_ISA_AVX512_VBMI2, "avx512vbmi2"}};
    size_t used = 0, i;
    if (!buf || size == 0) {
        return "";
    }
    buf[0] = '\0';
    for (i = 0; i < sizeof bits / sizeof bits[0]; i++) {
        if (isa & bits[i].bit) {
            const size_t n = strlen(bits[i].name);
            if (used + n + (used ? 1 : 0) + 1 > size) {
                break;
            }
            if (used) {
                buf[used++] = ' ';
            }
            memcpy(buf + used, bits[i].name, n + 1);
            used += n;
        }
    }
    return buf;
}
