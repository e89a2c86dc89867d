/*
 * One Google Benchmark case of shadowvol_gbench: a routine of one variant
 * under the moving or the fixed light, on the workload `shadowvol bench`
 * times (bench/harness/workload.h), checked against c_ref before it is timed.
 *
 * How a case is timed, and how that differs from the cycle table:
 *   - Google Benchmark's loop: back-to-back calls, its own clock over the
 *     whole loop, as many iterations as its --benchmark_min_time asks.
 *     The cycle table times each call alone between serialising fences;
 *     here the figure is a throughput, the fences' cost is not in it, and
 *     calls overlap a little in the pipeline.
 *   - Iteration i uses light i mod L (the moving light: L = the workload's
 *     moving lights; the fixed light: always the same one), as the cycle
 *     table's rows do.
 *   - Input: the routines that leave their facing bytes alone read the
 *     light's own array. The two that modify them in place
 *     (count_facing_cull, create_shadow_volume_cull: culled triangles made
 *     facing) get a fresh copy each call from a ring of one slot per moving
 *     light, refilled with the timer paused after each pass through it, so
 *     both kinds rotate through the same number of facing arrays (about 86
 *     KB on the 1344-triangle character: L2, not L1, unlike the cycle
 *     table's copy made just before each call).
 *   - Counters: elements_per_second (benchmark::Counter::kIsRate: elements
 *     x iterations over the time) and ticks_per_element (the TSC read
 *     around the loop, cheap lfence-fenced reads outside the timer's
 *     pauses, over iterations x elements). Elements as in the cycle table:
 *     triangles; SilEdges for create_sil_triangles; vertices for
 *     calculate_cull_bits.
 *
 * Check: the first time a case runs, every light of its rotation is
 * called once into a poisoned buffer with canaries behind it and compared
 * with the reference (bench/harness/expected.h). A case that fails is reported by
 * state.SkipWithError on every run, and failed_cases() counts it.
 *
 * Copyright (C) 2026 the shadowvol authors. LGPL-2.1-or-later.
 */
#ifndef SV_BENCH_GBENCH_CASES_H
#define SV_BENCH_GBENCH_CASES_H

#include <memory>
#include <string>
#include <vector>

#include <benchmark/benchmark.h>

#include "expected.h"
#include "routines.h"
#include "workload.h"

namespace svgbench {

/* What the cases of one workload share: the workload, the reference
 * results per routine (computed when a routine's first case runs) and the
 * buffers (the cases run one at a time, on one thread). */
class Context {
public:
    explicit Context(svbench::Workload w);
    svbench::Workload &workload() { return w_; }
    const std::vector<svbench::Expected> &expected(svbench::Routine r);

    /* Buffers; each is followed by kCanaryBytes of canary room. */
    uint8_t *slot(int i) { return slots_.data() + (size_t)i * slotBytes_; }
    int num_slots() const { return numSlots_; }
    uint8_t *facing_out() { return facingOut_.data(); }
    uint8_t *cull_out() { return cullOut_.data(); }
    int *out() { return out_.data(); }
    size_t out_capacity() const { return outCap_; }

private:
    svbench::Workload w_;
    std::vector<std::unique_ptr<std::vector<svbench::Expected>>> expected_;
    size_t slotBytes_ = 0, outCap_ = 0;
    int numSlots_ = 0;
    svbench::AlignedArray<uint8_t> slots_, facingOut_, cullOut_;
    svbench::AlignedArray<int> out_;
};

constexpr int kCanaryBytes = 64;

struct Case {
    Context *context = nullptr;
    svbench::Routine routine = svbench::Routine::count_facing;
    const svbench::BenchVariant *variant = nullptr;
    bool moving = true;
    bool checked = false;
    std::string failure; /* empty: the check passed */
};

/* "create_shadow_volume/sse2_paper/moving". */
std::string case_name(const Case &c);

/* The benchmark body. */
void run_case(benchmark::State &state, Case &c);

/* Cases whose check failed so far. */
int failed_cases();

} // namespace svgbench

#endif
