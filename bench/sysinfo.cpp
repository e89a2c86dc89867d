/*
 * Copyright (C) 2026 the shadowvol authors. LGPL-2.1-or-later.
 */
#include "sysinfo.h"

#include <cstring>

#include <cpuid.h>

/* Set by bench/CMakeLists.txt on this file only. */
#ifndef SV_GIT_COMMIT
#define SV_GIT_COMMIT "unknown"
#endif
#ifndef SV_BUILD_TYPE
#define SV_BUILD_TYPE "unknown"
#endif
#ifndef SV_C_FLAGS
#define SV_C_FLAGS ""
#endif
#ifndef SV_PROJECT_VERSION
#define SV_PROJECT_VERSION "unknown"
#endif

namespace svbench {

std::string cpu_model() {
    unsigned r[12];
    if ((unsigned)__get_cpuid_max(0x80000000u, nullptr) < 0x80000004u) {
        return "unknown";
    }
    for (unsigned i = 0; i < 3; i++) {
        __get_cpuid(0x80000002u + i, &r[4 * i], &r[4 * i + 1], &r[4 * i + 2], &r[4 * i + 3]);
    }
    char s[49];
    std::memcpy(s, r, 48);
    s[48] = 0;
    std::string m(s);
    size_t b = m.find_first_not_of(' ');
    size_t e = m.find_last_not_of(' ');
    if (b == std::string::npos) {
        return "unknown";
    }
    return m.substr(b, e - b + 1);
}

static unsigned long long xgetbv0() {
    unsigned lo, hi;
    __asm__ __volatile__("xgetbv" : "=a"(lo), "=d"(hi) : "c"(0u));
    return (unsigned long long)hi << 32 | lo;
}

std::string cpu_isa_flags() {
    unsigned a, b, c, d;
    std::string s;
    auto add = [&s](bool has, const char *name) {
        if (has) {
            if (!s.empty()) {
                s += ' ';
            }
            s += name;
        }
    };
    if (!__get_cpuid(1, &a, &b, &c, &d)) {
        return "unknown";
    }
    const unsigned c1 = c, d1 = d;
    bool os_avx = false, os_avx512 = false;
    if ((c1 >> 27) & 1u) { /* OSXSAVE */
        unsigned long long x = xgetbv0();
        os_avx = (x & 0x6u) == 0x6u;      /* XMM and YMM state */
        os_avx512 = (x & 0xe6u) == 0xe6u; /* plus opmask, ZMM_Hi256, Hi16_ZMM */
    }
    unsigned b7 = 0, c7 = 0;
    if ((unsigned)__get_cpuid_max(0, nullptr) >= 7) {
        __cpuid_count(7, 0, a, b, c, d);
        b7 = b;
        c7 = c;
    }
    add((d1 >> 26) & 1u, "sse2");
    add(c1 & 1u, "sse3");
    add((c1 >> 9) & 1u, "ssse3");
    add((c1 >> 19) & 1u, "sse4.1");
    add((c1 >> 20) & 1u, "sse4.2");
    add((c1 >> 23) & 1u, "popcnt");
    add(os_avx && ((c1 >> 28) & 1u), "avx");
    add(os_avx && ((b7 >> 5) & 1u), "avx2");
    add(os_avx && ((c1 >> 12) & 1u), "fma");
    add((b7 >> 8) & 1u, "bmi2");
    add(os_avx512 && ((b7 >> 16) & 1u), "avx512f");
    add(os_avx512 && ((b7 >> 17) & 1u), "avx512dq");
    add(os_avx512 && ((b7 >> 28) & 1u), "avx512cd");
    add(os_avx512 && ((b7 >> 30) & 1u), "avx512bw");
    add(os_avx512 && ((b7 >> 31) & 1u), "avx512vl");
    add(os_avx512 && ((c7 >> 1) & 1u), "avx512vbmi");
    add(os_avx512 && ((c7 >> 14) & 1u), "avx512vpopcntdq");
    return s.empty() ? "none" : s;
}

std::string compiler_version() {
#ifdef __clang__
    return std::string("clang ") + __clang_version__;
#elif defined(__GNUC__)
    return std::string("gcc ") + __VERSION__;
#else
    return "unknown";
#endif
}

std::string build_flags() {
    std::string f = SV_C_FLAGS;
    size_t b = f.find_first_not_of(' ');
    f = b == std::string::npos ? "" : f.substr(b);
    return std::string(SV_BUILD_TYPE) + (f.empty() ? "" : ", C flags: " + f);
}

std::string git_commit() {
    return SV_GIT_COMMIT;
}

std::string project_version() {
    return SV_PROJECT_VERSION;
}

} // namespace svbench
