/*
 * The end of an exported AVX / AVX-512 kernel written in C intrinsics.
 *
 * GCC puts vzeroupper at the end of an AVX function only when optimising;
 * a -O0 build (the sanitizer build, tools/run.sh test) would return with
 * the upper YMM/ZMM state dirty, making the caller's SSE code pay the
 * transition, and the ABI checker (`shadowvol check`, the tests'
 * checked_call) reports it. Written out there only, at every return of the
 * exported function, so the optimised objects stay as they were.
 *
 * Copyright (C) 2026 the shadowvol authors. LGPL-2.1-or-later.
 */
#ifndef SV_CORE_SIMD_EXIT_H
#define SV_CORE_SIMD_EXIT_H

#include <immintrin.h>

#if defined(__OPTIMIZE__)
#define SV_VZEROUPPER_IF_UNOPTIMISED() ((void)0)
#else
#define SV_VZEROUPPER_IF_UNOPTIMISED() _mm256_zeroupper()
#endif

#endif
