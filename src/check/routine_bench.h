// `shadowvol check --bench`: checkasm's cycle counts, a quick look rather
// than the benchmark (`shadowvol bench` is the measurement). Each routine
// on one character-sized input (1344 triangles, as the bundled character
// models/character_1344.glb: 2016 edges, about half the triangles facing),
// median TSC ticks per call over a few hundred timed regions, the fences'
// own cost subtracted.
//
// Copyright (C) 2026 the shadowvol authors. LGPL-2.1-or-later.
#pragma once

#include <cstdint>
#include <memory>

#include "routine_checks.h"

namespace svcheck {

class BenchWorkload {
public:
    static constexpr int kTriangles = 1344;
    explicit BenchWorkload(uint64_t seed);
    ~BenchWorkload();
    BenchWorkload(const BenchWorkload &) = delete;
    BenchWorkload &operator=(const BenchWorkload &) = delete;
    // Median ticks per call of ROUTINE as K runs it (K's alignment needs
    // are met: every array starts on a 64-byte boundary). Call only for a
    // routine the variant has and the CPU runs; shadow_volume_for_light
    // without a plan times the paper's pipeline of K's kernels instead
    // (A, B, the volume: the reference of the one call).
    double ticks(Routine routine, const Kernels &k);

private:
    struct Data;
    std::unique_ptr<Data> d_;
};

} // namespace svcheck
