/*
 * Which SV_ISA_* levels this CPU runs. SSE2 is architectural on x86-64;
 * later issues add AVX2 / AVX-512 with CPUID + XGETBV here.
 *
 * Copyright (C) 2026 the shadowvol authors. LGPL-2.1-or-later.
 */
#include "shadowvol.h"

unsigned sv_cpu_isa(void) {
#if defined(__x86_64__) || defined(_M_X64)
    return SV_ISA_SSE2;
#else
    return SV_ISA_NONE;
#endif
}
