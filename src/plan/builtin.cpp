/*
 * The built-in plans: what a CPU that was never tuned gets. The static
 * choice (the highest instruction set the CPU runs, as sv_best_variant and
 * sv_best_facing_variant), except where this project measured a CPU
 * family on which another variant is faster. Each exception names its
 * measurement; `shadowvol tune` replaces all of this with this CPU's own.
 *
 * Copyright (C) 2026 the shadowvol authors. LGPL-2.1-or-later.
 */
#include <cpuid.h>

#include <cstdio>
#include <cstring>

#include "plan_internal.h"

namespace {

struct CpuId {
    char vendor[13] = {};
    unsigned family = 0, model = 0, stepping = 0;
    bool avx512fp16 = false;
    char brand[49] = {};
};

CpuId read_cpuid() {
    CpuId c;
    unsigned a = 0, b = 0, cx = 0, d = 0, max_leaf = 0;
    if (!__get_cpuid(0, &max_leaf, &b, &cx, &d)) return c;
    std::memcpy(c.vendor, &b, 4);
    std::memcpy(c.vendor + 4, &d, 4);
    std::memcpy(c.vendor + 8, &cx, 4);
    __cpuid(1, a, b, cx, d);
    const unsigned base_family = (a >> 8) & 0xF, base_model = (a >> 4) & 0xF;
    c.family = base_family == 0xF ? base_family + ((a >> 20) & 0xFF) : base_family;
    c.model = base_family == 0x6 || base_family == 0xF ? (((a >> 16) & 0xF) << 4) | base_model
                                                       : base_model;
    c.stepping = a & 0xF;
    if (max_leaf >= 7) {
        __cpuid_count(7, 0, a, b, cx, d);
        c.avx512fp16 = (d >> 23) & 1;
    }
    unsigned ext = 0;
    __cpuid(0x80000000u, ext, b, cx, d);
    if (ext >= 0x80000004u) {
        unsigned *w = reinterpret_cast<unsigned *>(c.brand);
        for (unsigned leaf = 0; leaf < 3; leaf++) {
            __cpuid(0x80000002u + leaf, w[4 * leaf], w[4 * leaf + 1], w[4 * leaf + 2],
                    w[4 * leaf + 3]);
        }
    }
    /* Trim the brand string's padding. */
    char *p = c.brand;
    while (*p == ' ') p++;
    std::memmove(c.brand, p, std::strlen(p) + 1);
    for (size_t n = std::strlen(c.brand); n > 0 && c.brand[n - 1] == ' '; n--) c.brand[n - 1] = 0;
    return c;
}

/* One measured exception to the static choice. */
struct Exception {
    bool (*applies)(const CpuId &);
    int first_class, last_class;
    sv_routine routine;
    const char *variant;
};

/* Intel server cores with AVX512-FP16 (Sapphire Rapids and later),
 * measured on a Sapphire Rapids KVM guest at commit 8454378
 * (../shared/results/, issue 15): the AVX2 CreateCapTriangles beats the
 * AVX-512 one on the character (1050 against 1148 ticks), and from about
 * 100k triangles on the AVX2 volume beats the AVX-512 one (108k: 4.09
 * against 4.62 ticks per triangle; 980k: 5.09 against 5.75). */
bool intel_avx512fp16(const CpuId &c) {
    return std::strcmp(c.vendor, "GenuineIntel") == 0 && c.avx512fp16;
}

const Exception kExceptions[] = {
    {intel_avx512fp16, 0, SV_NUM_SIZE_CLASSES - 1, SV_ROUTINE_CREATE_CAP_TRIANGLES, "avx2"},
    {intel_avx512fp16, 2, SV_NUM_SIZE_CLASSES - 1, SV_ROUTINE_COUNT_FACING, "avx2"},
    {intel_avx512fp16, 2, SV_NUM_SIZE_CLASSES - 1, SV_ROUTINE_CREATE_SIL_TRIANGLES, "avx2"},
};

const CpuId &cpu() {
    static const CpuId c = read_cpuid();
    return c;
}

} // namespace

namespace svplan {

sv_plan builtin_plan(int sizeClass) {
    const char *names[SV_NUM_ROUTINES];
    const char *f = sv_best_facing_variant()->name, *v = sv_best_variant()->name;
    names[SV_ROUTINE_CALCULATE_FACING] = names[SV_ROUTINE_CALCULATE_CULL_BITS] = f;
    for (int r = SV_ROUTINE_COUNT_FACING; r < SV_NUM_ROUTINES; r++) names[r] = v;
    for (const Exception &e : kExceptions) {
        if (sizeClass >= e.first_class && sizeClass <= e.last_class && e.applies(cpu()) &&
            variant_runs_routine(e.variant, e.routine)) {
            names[e.routine] = e.variant;
        }
    }
    return make_plan(sizeClass, "built-in", names, nullptr);
}

} // namespace svplan

extern "C" const char *sv_cpu_model_key(char *buf, size_t size) {
    if (!buf || size == 0) return buf;
    const CpuId &c = cpu();
    std::snprintf(buf, size, "%s %u/%u/%u %s %s", c.vendor[0] ? c.vendor : "unknown", c.family,
                  c.model, c.stepping, sv_isa_level_name(), c.brand[0] ? c.brand : "-");
    return buf;
}
