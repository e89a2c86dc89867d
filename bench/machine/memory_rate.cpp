/*
 * The memory rate of memory_rate.h: plain loops the compiler vectorises
 * (a sum of 64-bit words, a fill), each thread on its own buffer, warm
 * (first touched before the timed runs), wall time of the slowest thread.
 *
 * Copyright (C) 2026 the shadowvol authors. LGPL-2.1-or-later.
 */
#include "memory_rate.h"

#include <tbb/parallel_for.h>
#include <tbb/task_arena.h>

#include <algorithm>
#include <chrono>
#include <cstdint>
#include <vector>

namespace svbench {

namespace {

/* Where the sums go: the compiler must assume a volatile is read, so the
 * timed reads are not optimised away. */
volatile uint64_t g_sink = 0;

double seconds() {
    return std::chrono::duration<double>(std::chrono::steady_clock::now().time_since_epoch())
        .count();
}

} // namespace

MemoryRate measure_memory_rate(int threads, std::size_t bytes, int runs) {
    MemoryRate r;
    r.threads = std::max(threads, 1);
    r.runs = std::max(runs, 1);
    const std::size_t words = std::max<std::size_t>(bytes / 8, 1024);
    r.buffer_bytes = words * 8;
    std::vector<std::vector<uint64_t>> buffers((std::size_t)r.threads);
    tbb::task_arena arena(r.threads);
    std::vector<uint64_t> sums((std::size_t)r.threads, 0);
    auto each = [&](auto &&body) {
        arena.execute([&] {
            tbb::parallel_for(0, r.threads, [&](int t) { body(buffers[(std::size_t)t], t); });
        });
    };
    each([&](std::vector<uint64_t> &b, int) { b.assign(words, 1); });
    double best_read = 1e30, best_write = 1e30;
    for (int k = 0; k < r.runs; k++) {
        double t0 = seconds();
        each([&](std::vector<uint64_t> &b, int t) {
            uint64_t s = 0;
            for (uint64_t v : b) s += v;
            sums[(std::size_t)t] += s;
        });
        best_read = std::min(best_read, seconds() - t0);
        t0 = seconds();
        each([&](std::vector<uint64_t> &b, int) { std::fill(b.begin(), b.end(), (uint64_t)k); });
        best_write = std::min(best_write, seconds() - t0);
    }
    uint64_t total = 0;
    for (uint64_t s : sums) total += s;
    g_sink = total;
    const double moved = (double)r.buffer_bytes * r.threads;
    r.read_bytes_per_second = moved / best_read;
    r.write_bytes_per_second = moved / best_write;
    return r;
}

} // namespace svbench
