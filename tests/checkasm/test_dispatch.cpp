// Runtime dispatch: what sv_cpu_isa() detects (checked against the
// compiler's own CPU detection, which also asks the OS through XGETBV), the
// ISA limit (SV_ISA / sv_set_isa_limit) and the variant sv_best_variant()
// picks. Under qemu-x86_64 with older CPU models (tests/checkasm/run_under_qemu.sh)
// the same tests prove that dispatch falls back.
//
// Copyright (C) 2026 the shadowvol authors. LGPL-2.1-or-later.
#include <gtest/gtest.h>

#include <cstdio>
#include <cstdlib>
#include <cstring>

#include "shadowvol.h"

namespace {

// Restores the limit the run started with (SV_ISA from the environment).
struct LimitGuard {
    const char *saved = sv_isa_limit_name();
    ~LimitGuard() { sv_set_isa_limit(saved); }
};

TEST(Dispatch, DetectionAgreesWithTheCompiler) {
    __builtin_cpu_init();
    const unsigned isa = sv_cpu_isa_detected();
    char names[128];
    std::printf("[ dispatch ] detected: %s; limit: %s; level: %s; best variant: %s\n",
                sv_isa_names(isa, names, sizeof names),
                sv_isa_limit_name() ? sv_isa_limit_name() : "none", sv_isa_level_name(),
                sv_best_variant()->name);
#if defined(__x86_64__)
    EXPECT_TRUE(isa & SV_ISA_SSE2) << "SSE2 is architectural on x86-64";
#else
    // 32-bit x86: read from CPUID like the rest (a Pentium III has none).
    EXPECT_EQ((isa & SV_ISA_SSE2) != 0, __builtin_cpu_supports("sse2") != 0);
#endif
    const bool v3 = __builtin_cpu_supports("avx2") && __builtin_cpu_supports("bmi") &&
                    __builtin_cpu_supports("bmi2") && __builtin_cpu_supports("fma") &&
                    __builtin_cpu_supports("popcnt");
    EXPECT_EQ((isa & SV_ISA_AVX2) != 0, v3);
    const bool v4 = v3 && __builtin_cpu_supports("avx512f") && __builtin_cpu_supports("avx512bw") &&
                    __builtin_cpu_supports("avx512vl") && __builtin_cpu_supports("avx512dq") &&
                    __builtin_cpu_supports("avx512cd");
    EXPECT_EQ((isa & SV_ISA_AVX512) != 0, v4);
    EXPECT_EQ((isa & SV_ISA_AVX512_VBMI2) != 0, v4 && __builtin_cpu_supports("avx512vbmi2"));
    EXPECT_EQ((isa & SV_ISA_AVX512_VBMI) != 0, v4 && __builtin_cpu_supports("avx512vbmi"));
    // The limited set is a subset of the detected one.
    EXPECT_EQ(sv_cpu_isa() & ~isa, 0u);
}

TEST(Dispatch, LimitCapsTheIsaAndTheBestVariant) {
    LimitGuard guard;
    const unsigned hw = sv_cpu_isa_detected();
    ASSERT_EQ(sv_set_isa_limit("c"), 0);
    EXPECT_EQ(sv_cpu_isa(), 0u);
    EXPECT_STREQ(sv_isa_level_name(), "c");
    EXPECT_EQ(sv_best_variant()->isa, 0u) << sv_best_variant()->name;
    ASSERT_EQ(sv_set_isa_limit("sse2"), 0);
    EXPECT_EQ(sv_cpu_isa(), (unsigned)SV_ISA_SSE2);
    EXPECT_STREQ(sv_isa_level_name(), "sse2");
    EXPECT_EQ(sv_best_variant()->isa & ~(unsigned)SV_ISA_SSE2, 0u) << sv_best_variant()->name;
    ASSERT_EQ(sv_set_isa_limit("avx2"), 0);
    EXPECT_EQ(sv_cpu_isa(), hw & (SV_ISA_SSE2 | SV_ISA_AVX2));
    EXPECT_EQ(sv_best_variant()->isa & (SV_ISA_AVX512 | SV_ISA_AVX512_VBMI | SV_ISA_AVX512_VBMI2),
              0u);
    ASSERT_EQ(sv_set_isa_limit("avx512"), 0);
    EXPECT_EQ(sv_cpu_isa(), hw);
    // Unknown levels are refused and change nothing.
    EXPECT_EQ(sv_set_isa_limit("avx1024"), -1);
    EXPECT_EQ(sv_cpu_isa(), hw);
    ASSERT_EQ(sv_set_isa_limit(nullptr), 0);
    EXPECT_EQ(sv_isa_limit_name(), nullptr);
    EXPECT_EQ(sv_cpu_isa(), hw);
}

// The checked entry points refuse a variant the limit excludes, as they
// refuse one the CPU lacks.
TEST(Dispatch, CheckedEntryPointsHonourTheLimit) {
#if !defined(SV_HAVE_ASM_SSE2)
    GTEST_SKIP() << "no SIMD variant in this platform's table (no asm kernels, docs/PLATFORMS.md)";
#endif
    LimitGuard guard;
    const sv_variant *paper = sv_variant_by_name("sse2_paper");
    ASSERT_NE(paper, nullptr);
    alignas(16) uint8_t facing[16] = {1, 0, 1};
    ASSERT_EQ(sv_set_isa_limit("sse2"), 0);
    EXPECT_EQ(sv_count_facing_checked(paper, facing, 16), 2);
    ASSERT_EQ(sv_set_isa_limit("c"), 0);
    EXPECT_EQ(sv_count_facing_checked(paper, facing, 16), SV_E_CPU);
    EXPECT_EQ(sv_count_facing_checked(sv_variant_by_name("c_ref"), facing, 16), 2);
}

TEST(Dispatch, BestVariantIsTheLastRunnableOne) {
    int n = 0;
    const sv_variant *all = sv_variants(&n);
    const sv_variant *want = &all[0];
    for (int i = 0; i < n; i++) {
        if ((all[i].isa & sv_cpu_isa()) == all[i].isa) want = &all[i];
    }
    EXPECT_EQ(sv_best_variant(), want);
    EXPECT_EQ((sv_best_variant()->isa & sv_cpu_isa()), sv_best_variant()->isa);
}

// SV_ISA in the environment (set by ctest's isa-limited runs) is honoured.
TEST(Dispatch, EnvironmentLimitIsHonoured) {
    const char *env = std::getenv("SV_ISA");
    if (!env || !*env) {
        // No limit: dispatch sees every bit the CPU has (the ctest runs
        // named *_isa_* set one).
        EXPECT_EQ(sv_isa_limit_name(), nullptr);
        EXPECT_EQ(sv_cpu_isa(), sv_cpu_isa_detected());
        return;
    }
    ASSERT_NE(sv_isa_limit_name(), nullptr);
    EXPECT_STREQ(sv_isa_limit_name(), env);
    char names[128];
    std::printf("[ dispatch ] SV_ISA=%s: running %s\n", env,
                sv_isa_names(sv_cpu_isa(), names, sizeof names));
}

} // namespace
