/*
 * The rate at which this machine streams memory, measured in the run that
 * uses it (issue 29's floors: a pass that must touch B bytes cannot take
 * less than B / rate).
 *
 * Copyright (C) 2026 the shadowvol authors. LGPL-2.1-or-later.
 */
#ifndef SV_BENCH_MEMORY_RATE_H
#define SV_BENCH_MEMORY_RATE_H

#include <cstddef>

namespace svbench {

struct MemoryRate {
    double read_bytes_per_second = 0;  /* a sum over the buffer */
    double write_bytes_per_second = 0; /* a fill of the buffer */
    std::size_t buffer_bytes = 0;      /* per thread, larger than the last-level cache share */
    int threads = 1, runs = 0;         /* the best of RUNS, each on THREADS threads */
};

/* Streams a buffer of BYTES per thread on THREADS threads (oneTBB, one
 * block per thread), RUNS times each way, the best kept. */
MemoryRate measure_memory_rate(int threads, std::size_t bytes, int runs);

} // namespace svbench

#endif
