/*
 * What the cycle table's header says about the machine and the build: CPU
 * model and instruction-set flags (CPUID), compiler, flags, git commit.
 *
 * Copyright (C) 2026 the shadowvol authors. LGPL-2.1-or-later.
 */
#ifndef SV_BENCH_SYSINFO_H
#define SV_BENCH_SYSINFO_H

#include <string>

namespace svbench {

/* CPUID leaves 0x80000002-0x80000004, trimmed; "unknown" if absent. */
std::string cpu_model();
/* The SIMD levels CPUID reports, lowest first ("sse2 sse3 ... avx512vl").
 * For display only: the library decides what it runs with sv_cpu_isa().
 * AVX and later are listed only when the OS saves their registers (XGETBV). */
std::string cpu_isa_flags();

std::string compiler_version(); /* __VERSION__ of the bench's compiler */
std::string build_flags();      /* CMake build type and the library's C flags */
std::string git_commit();       /* short hash at configure time, or "unknown" */
std::string project_version();  /* PROJECT_VERSION */

} // namespace svbench

#endif
