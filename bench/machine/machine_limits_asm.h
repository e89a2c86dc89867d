/*
 * The throughput primitives of bench/machine/machine_limits.asm (`shadowvol bench
 * --limits`), declared once for the benchmark and its test
 * (tests/checkasm/test_machine_limits.cpp, which calls them through the ABI
 * checker with argument words built from these prototypes).
 *
 * The counts are int64_t, not long: the asm reads whole 64-bit registers,
 * and long is 32 bits on Windows x64, where the checker's garbage upper
 * half made the primitives loop for ever under wine.
 *
 * Copyright (C) 2026 the shadowvol authors. LGPL-2.1-or-later.
 */
#ifndef SV_BENCH_MACHINE_LIMITS_ASM_H
#define SV_BENCH_MACHINE_LIMITS_ASM_H

#include <stdint.h>

#ifdef __cplusplus
extern "C" {
#endif

void svb_scalar_loads(const uint8_t *buf, int64_t iters);
void svb_dependent_adds(int64_t iters);
void svb_vector_loads_zmm(const uint8_t *buf, int64_t iters, int64_t bytes);
void svb_vector_loads_ymm(const uint8_t *buf, int64_t iters, int64_t bytes);
void svb_vector_stores_zmm(uint8_t *buf, int64_t iters);
void svb_vector_stores_ymm(uint8_t *buf, int64_t iters);
void svb_gather_lanes_zmm(const uint8_t *buf, int64_t iters);
void svb_gather_lanes_ymm(const uint8_t *buf, int64_t iters);

#ifdef __cplusplus
}
#endif

#endif
