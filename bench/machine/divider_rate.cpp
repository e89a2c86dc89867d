/*
 * measure_divider_rate (divider_rate.h): eight independent chains of
 * divides (or square roots) per loop, enough to keep a pipelined divider
 * full, in the widest vector this CPU has; ticks per lane, the best of the
 * runs. The divisor is just above 1, so the values stay normal numbers.
 *
 * Copyright (C) 2026 the shadowvol authors. LGPL-2.1-or-later.
 */
/* GCC 12's own AVX-512 headers pass an undefined register to the masked
 * builtins behind _mm512_sqrt_pd and then warn about it (a known false
 * positive of -Wmaybe-uninitialized and -Wuninitialized). */
#pragma GCC diagnostic ignored "-Wmaybe-uninitialized"
#pragma GCC diagnostic ignored "-Wuninitialized"
#include "divider_rate.h"

#include <immintrin.h>
#include <x86intrin.h>

#include <algorithm>
#include <cstdint>

#include "shadowvol.h"

namespace svbench {
namespace {

constexpr int kChains = 8, kSteps = 4096;

/* The timed loop, stamped out per vector type inside a function of that
 * ISA's target (an intrinsic must be inlined into a function of its
 * target; a call per operation would be timed too). Sets BEST to the
 * fewest ticks of RUNS loops of kSteps x kChains operations OP. */
#define SV_DIVIDER_LOOP(V, SET, ADD, OP, KEEP, BEST)                                               \
    do {                                                                                           \
        V a[kChains];                                                                              \
        for (int i = 0; i < kChains; i++) a[i] = SET(1.0 + 0.125 * i);                             \
        const V b = SET(1.0000001);                                                                \
        (void)b;                                                                                   \
        for (int r = 0; r < runs; r++) {                                                           \
            const uint64_t t0 = __rdtsc();                                                         \
            for (int k = 0; k < kSteps; k++) {                                                     \
                for (int i = 0; i < kChains; i++) a[i] = OP;                                       \
            }                                                                                      \
            (BEST) = std::min<uint64_t>((BEST), __rdtsc() - t0);                                   \
        }                                                                                          \
        (KEEP) = a[0];                                                                             \
        for (int i = 1; i < kChains; i++) (KEEP) = ADD((KEEP), a[i]);                              \
    } while (0)

#define SV_TARGET_AVX512 __attribute__((target("avx512f")))
#define SV_TARGET_AVX2 __attribute__((target("avx2")))

/* Ticks per lane from the best loop's ticks. */
double per_lane(uint64_t best, int lanes) {
    return (double)best / ((double)kSteps * kChains * lanes);
}

SV_TARGET_AVX512 DividerRate measure_avx512(int runs) {
    uint64_t d = UINT64_MAX, q = UINT64_MAX;
    __m512d keep_d, keep_q;
    SV_DIVIDER_LOOP(__m512d, _mm512_set1_pd, _mm512_add_pd, _mm512_div_pd(a[i], b), keep_d, d);
    SV_DIVIDER_LOOP(__m512d, _mm512_set1_pd, _mm512_add_pd, _mm512_sqrt_pd(a[i]), keep_q, q);
    if (_mm512_reduce_add_pd(_mm512_add_pd(keep_d, keep_q)) == -1) d++;
    return {per_lane(d, 8), per_lane(q, 8), 8, runs};
}

SV_TARGET_AVX2 DividerRate measure_avx2(int runs) {
    uint64_t d = UINT64_MAX, q = UINT64_MAX;
    __m256d keep_d, keep_q;
    SV_DIVIDER_LOOP(__m256d, _mm256_set1_pd, _mm256_add_pd, _mm256_div_pd(a[i], b), keep_d, d);
    SV_DIVIDER_LOOP(__m256d, _mm256_set1_pd, _mm256_add_pd, _mm256_sqrt_pd(a[i]), keep_q, q);
    if (_mm256_cvtsd_f64(_mm256_add_pd(keep_d, keep_q)) == -1) d++;
    return {per_lane(d, 4), per_lane(q, 4), 4, runs};
}

DividerRate measure_sse2(int runs) {
    uint64_t d = UINT64_MAX, q = UINT64_MAX;
    __m128d keep_d, keep_q;
    SV_DIVIDER_LOOP(__m128d, _mm_set1_pd, _mm_add_pd, _mm_div_pd(a[i], b), keep_d, d);
    SV_DIVIDER_LOOP(__m128d, _mm_set1_pd, _mm_add_pd, _mm_sqrt_pd(a[i]), keep_q, q);
    if (_mm_cvtsd_f64(_mm_add_pd(keep_d, keep_q)) == -1) d++;
    return {per_lane(d, 2), per_lane(q, 2), 2, runs};
}

} // namespace

DividerRate measure_divider_rate(int runs) {
    runs = std::max(runs, 1);
    const unsigned isa = sv_cpu_isa();
    if (isa & SV_ISA_AVX512) return measure_avx512(runs);
    if (isa & SV_ISA_AVX2) return measure_avx2(runs);
    return measure_sse2(runs);
}

} // namespace svbench
