/*
 * Copyright (C) 2026 the shadowvol authors. LGPL-2.1-or-later.
 */
#include "sysinfo.h"

#include <algorithm>
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

namespace {

unsigned long long xgetbv0() {
    unsigned lo, hi;
    __asm__ __volatile__("xgetbv" : "=a"(lo), "=d"(hi) : "c"(0u));
    return (unsigned long long)hi << 32 | lo;
}

bool bit(unsigned reg, int n) { return (reg >> n) & 1u; }

std::vector<std::string> detect_isa() {
    std::vector<std::string> isa;
    unsigned a, b, c, d;
    if (!__get_cpuid(1, &a, &b, &c, &d)) {
        return isa;
    }
    const unsigned c1 = c, d1 = d;
    /* XCR0: which register states the OS saves on a context switch. */
    bool osAvx = false, osAvx512 = false;
    if (bit(c1, 27)) { /* OSXSAVE */
        const unsigned long long x = xgetbv0();
        osAvx = (x & 0x6u) == 0x6u;      /* XMM and YMM */
        osAvx512 = (x & 0xe6u) == 0xe6u; /* plus opmask, ZMM_Hi256, Hi16_ZMM */
    }
    unsigned b7 = 0, c7 = 0, d7 = 0;
    if ((unsigned)__get_cpuid_max(0, nullptr) >= 7) {
        __cpuid_count(7, 0, a, b, c, d);
        b7 = b;
        c7 = c;
        d7 = d;
    }
    const struct {
        bool has;
        const char *name;
    } flags[] = {
        {bit(d1, 26), "sse2"},
        {bit(c1, 0), "sse3"},
        {bit(c1, 9), "ssse3"},
        {bit(c1, 19), "sse4.1"},
        {bit(c1, 20), "sse4.2"},
        {bit(c1, 23), "popcnt"},
        {osAvx && bit(c1, 28), "avx"},
        {osAvx && bit(b7, 5), "avx2"},
        {osAvx && bit(c1, 12), "fma"},
        {bit(b7, 3), "bmi1"},
        {bit(b7, 8), "bmi2"},
        {osAvx && bit(c1, 29), "f16c"},
        {osAvx512 && bit(b7, 16), "avx512f"},
        {osAvx512 && bit(b7, 17), "avx512dq"},
        {osAvx512 && bit(b7, 28), "avx512cd"},
        {osAvx512 && bit(b7, 30), "avx512bw"},
        {osAvx512 && bit(b7, 31), "avx512vl"},
        {osAvx512 && bit(c7, 1), "avx512vbmi"},
        {osAvx512 && bit(c7, 6), "avx512vbmi2"},
        {osAvx512 && bit(c7, 11), "avx512vnni"},
        {osAvx512 && bit(c7, 12), "avx512bitalg"},
        {osAvx512 && bit(c7, 14), "avx512vpopcntdq"},
        {osAvx512 && bit(d7, 23), "avx512fp16"},
        {bit(c7, 8), "gfni"},
        {osAvx && bit(c7, 9), "vaes"},
        {osAvx && bit(c7, 10), "vpclmulqdq"},
    };
    for (const auto &f : flags) {
        if (f.has) {
            isa.push_back(f.name);
        }
    }
    return isa;
}

} // namespace

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
    const size_t b = m.find_first_not_of(' ');
    const size_t e = m.find_last_not_of(' ');
    if (b == std::string::npos) {
        return "unknown";
    }
    return m.substr(b, e - b + 1);
}

const std::vector<std::string> &cpu_isa_list() {
    static const std::vector<std::string> isa = detect_isa();
    return isa;
}

std::string cpu_isa_flags() {
    std::string s;
    for (const std::string &f : cpu_isa_list()) {
        s += (s.empty() ? "" : " ") + f;
    }
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
    const size_t b = f.find_first_not_of(' ');
    f = b == std::string::npos ? "" : f.substr(b);
    return std::string(SV_BUILD_TYPE) + (f.empty() ? "" : ", C flags: " + f);
}

std::string git_commit() { return SV_GIT_COMMIT; }

std::string project_version() { return SV_PROJECT_VERSION; }

} // namespace svbench
