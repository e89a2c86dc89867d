/*
 * What the cycle table's header says about the machine and the build: CPU
 * model and instruction-set extensions (CPUID, XGETBV), compiler, flags,
 * git commit. (Which variants run is the library's sv_cpu_isa(), with its
 * ISA limit; this list is the fuller picture the reports print.)
 *
 * Copyright (C) 2026 the shadowvol authors. LGPL-2.1-or-later.
 */
#ifndef SV_BENCH_SYSINFO_H
#define SV_BENCH_SYSINFO_H

#include <string>
#include <vector>

namespace svbench {

/* CPUID leaves 0x80000002-0x80000004, trimmed; "unknown" if absent. */
std::string cpu_model();

/* The SIMD extensions this CPU has AND the OS enables, lowest first:
 * sse2 sse3 ssse3 sse4.1 sse4.2 popcnt avx avx2 fma bmi1 bmi2 f16c avx512f
 * avx512dq avx512cd avx512bw avx512vl avx512vbmi avx512vbmi2 avx512vnni
 * avx512bitalg avx512vpopcntdq avx512fp16 gfni vaes vpclmulqdq. AVX and
 * later are listed only when XGETBV says the OS saves their registers
 * (XMM|YMM for AVX, plus opmask and ZMM state for AVX-512). For reports:
 * the library decides what it runs with sv_cpu_isa(). */
const std::vector<std::string> &cpu_isa_list();
/* The list joined by spaces ("none" when empty). */
std::string cpu_isa_flags();

std::string compiler_version(); /* __VERSION__ of the bench's compiler */
std::string build_flags();      /* CMake build type and the library's C flags */
std::string git_commit();       /* short hash at configure time, or "unknown" */
std::string project_version();  /* PROJECT_VERSION */

} // namespace svbench

#endif
