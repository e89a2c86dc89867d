/*
 * The workloads' random numbers: SplitMix64 (Steele, Lea, Flood 2014),
 * small, seedable with any value, the same sequence on every compiler and
 * library (std::uniform_*_distribution are not), so a seed names the same
 * workload everywhere.
 *
 * Copyright (C) 2026 the shadowvol authors. LGPL-2.1-or-later.
 */
#ifndef SV_BENCH_RNG_H
#define SV_BENCH_RNG_H

#include <cstdint>

namespace svbench {

struct Rng {
    uint64_t s;
    uint64_t next() {
        uint64_t z = (s += 0x9e3779b97f4a7c15ull);
        z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ull;
        z = (z ^ (z >> 27)) * 0x94d049bb133111ebull;
        return z ^ (z >> 31);
    }
    /* Uniform in [0, n) for n < 2^32 (multiply-shift; the bias is below
     * 2^-32 and the same everywhere). */
    uint32_t below(uint32_t n) { return (uint32_t)(((next() >> 32) * n) >> 32); }
    /* Uniform in [0, 1), 53 bits. */
    double unit() { return (double)(next() >> 11) * 0x1.0p-53; }
};

} // namespace svbench

#endif
