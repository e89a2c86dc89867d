/*
 * Copyright (C) 2026 the shadowvol authors. LGPL-2.1-or-later.
 */
#include "gbench_cases.h"

#include <algorithm>
#include <cstring>

#include "cycle_table.h"
#include "timer.h"

namespace svgbench {

using namespace svbench;

namespace {

constexpr uint8_t kCanary = 0x5a;

int g_failed = 0;

size_t round_up(size_t n, size_t to) { return (n + to - 1) / to * to; }

/* The routines that write their facing input (culled triangles made
 * facing): each call needs a fresh copy. */
bool modifies_facing(Routine r) {
    return r == Routine::count_facing_cull || r == Routine::create_shadow_volume_cull;
}

/* One call of C's routine on light L: FACING is the facing array (its
 * input, or for calculate_facing its output), CULL the cull bytes
 * calculate_cull_bits writes, OUT the shadow indices. One lambda type per
 * routine, so the timed loop calls it directly. */
template <class F> void with_call(Case &c, F &&f) {
    Workload &w = c.context->workload();
    const BenchVariant &v = *c.variant;
    const sv_variant *k = v.kernels;
    switch (c.routine) {
    case Routine::calculate_facing:
        f([&w, fn = v.calculate_facing](const Light &l, uint8_t *facing, uint8_t *, int *) {
            fn(w.planes.data(), w.numTriangles, &l.position, facing);
            return 0;
        });
        break;
    case Routine::calculate_cull_bits:
        f([&w, fn = v.calculate_cull_bits](const Light &l, uint8_t *, uint8_t *cull, int *) {
            return fn(w.positions.data(), w.numVerts, &w.bounds, l.planes, cull);
        });
        break;
    case Routine::count_facing:
        f([n = w.numTriangles, fn = k->count_facing](const Light &, uint8_t *facing, uint8_t *,
                                                     int *) { return fn(facing, n); });
        break;
    case Routine::count_facing_cull:
        f([&w, fn = k->count_facing_cull](const Light &l, uint8_t *facing, uint8_t *, int *) {
            return fn(facing, w.numTriangles, w.indices.data(), l.cullBits.data());
        });
        break;
    case Routine::create_sil_triangles:
        f([&w, fn = k->create_sil_triangles](const Light &, uint8_t *facing, uint8_t *, int *out) {
            return fn(out, facing, w.silEdges.data(), w.numSilEdges);
        });
        break;
    case Routine::create_cap_triangles:
        f([&w, fn = k->create_cap_triangles](const Light &, uint8_t *facing, uint8_t *, int *out) {
            return fn(out, facing, w.indices.data(), w.numIndices);
        });
        break;
    case Routine::create_shadow_volume:
        f([&w, k](const Light &, uint8_t *facing, uint8_t *, int *out) {
            return sv_create_shadow_volume(k, out, w.indices.data(), w.numIndices,
                                           w.silEdges.data(), w.numSilEdges, facing, nullptr);
        });
        break;
    case Routine::create_shadow_volume_cull:
        f([&w, k](const Light &l, uint8_t *facing, uint8_t *, int *out) {
            return sv_create_shadow_volume(k, out, w.indices.data(), w.numIndices,
                                           w.silEdges.data(), w.numSilEdges, facing,
                                           l.cullBits.data());
        });
        break;
    case Routine::pipeline:
    case Routine::pipeline_cull: break; /* not registered (gbench_main.cpp) */
    }
}

/* The lights of C's rotation: all moving lights, or the fixed one. */
int rotation(const Case &c) { return c.moving ? c.context->workload().numMoving : 1; }
Light &light_of(Case &c, int k) {
    Workload &w = c.context->workload();
    return w.lights[(size_t)(c.moving ? k : w.fixedLight)];
}

bool canaries_intact(const uint8_t *p, size_t n) {
    return std::all_of(p, p + n, [](uint8_t b) { return b == kCanary; });
}

/* Every light of C's rotation once, into poisoned buffers with canaries
 * behind them, against the reference. Empty when all match. */
template <class Call> std::string check(Case &c, const Call &call) {
    Context &x = *c.context;
    Workload &w = x.workload();
    const std::vector<Expected> &expected = x.expected(c.routine);
    const size_t nf = (size_t)w.numTriangles + 1;
    uint8_t *facing = x.slot(0);
    uint8_t *cull = x.cull_out();
    int *out = x.out();
    for (int k = 0; k < rotation(c); k++) {
        const int li = c.moving ? k : w.fixedLight;
        const Light &l = light_of(c, k);
        initial_facing(c.routine, w, l, facing);
        std::memset(facing + nf, kCanary, kCanaryBytes);
        std::memset(cull, kPoisonByte, (size_t)w.numVerts);
        std::memset(cull + w.numVerts, kCanary, kCanaryBytes);
        std::fill_n(out, x.out_capacity(), kPoisonIndex);
        std::memset(out + x.out_capacity(), kCanary, kCanaryBytes);

        const int got = call(l, facing, cull, out);

        std::string why = compare_with_reference(c.routine, w, l, expected[(size_t)li], got, out,
                                                 facing, cull);
        if (why.empty() &&
            !(canaries_intact(facing + nf, kCanaryBytes) &&
              canaries_intact(cull + w.numVerts, kCanaryBytes) &&
              canaries_intact((const uint8_t *)(out + x.out_capacity()), kCanaryBytes))) {
            why = "wrote past the end of a buffer";
        }
        if (!why.empty()) {
            return "light " + std::to_string(li) + ": " + why;
        }
    }
    return std::string();
}

/* Fills the in-place routines' ring: slot j holds light j's facing (all
 * the fixed light's under the fixed light). */
void refill(Case &c) {
    Context &x = *c.context;
    const size_t nf = (size_t)x.workload().numTriangles + 1;
    for (int j = 0; j < x.num_slots(); j++) {
        std::memcpy(x.slot(j), light_of(c, j % rotation(c)).facing.data(), nf);
    }
}

template <class Call> void time_loop(benchmark::State &state, Case &c, const Call &call) {
    Context &x = *c.context;
    const int n = rotation(c);
    const bool inPlace = modifies_facing(c.routine);
    const bool facingOut = c.routine == Routine::calculate_facing;
    /* The ring's length is a multiple of the rotation's (numMoving or 1),
     * so slot `used` always holds the copy of light k. */
    const int ring = x.num_slots();
    if (inPlace) {
        refill(c);
    }
    int k = 0, used = 0;
    uint64_t ticks = 0;
    uint64_t t0 = TscLfence::stamp();
    for (auto _ : state) {
        if (inPlace && used == ring) {
            ticks += TscLfence::stamp() - t0;
            state.PauseTiming();
            refill(c);
            state.ResumeTiming();
            used = 0;
            t0 = TscLfence::stamp();
        }
        Light &l = light_of(c, k);
        uint8_t *facing = inPlace ? x.slot(used++) : facingOut ? x.facing_out() : l.facing.data();
        benchmark::DoNotOptimize(call(l, facing, x.cull_out(), x.out()));
        if (++k == n) {
            k = 0;
        }
    }
    ticks += TscLfence::stamp() - t0;

    const double elements = std::max(1, elements_of(c.routine, x.workload()));
    state.counters["elements_per_second"] =
        benchmark::Counter(elements * (double)state.iterations(), benchmark::Counter::kIsRate);
    state.counters["ticks_per_element"] = benchmark::Counter((double)ticks / elements,
                                                             benchmark::Counter::kAvgIterations);
    state.SetLabel(std::to_string((long)elements) + " " + element_name(element_of(c.routine)) +
                   "s");
}

} // namespace

Context::Context(Workload w) : w_(std::move(w)) {
    expected_.resize((size_t)kNumRoutines);
    const size_t nf = (size_t)w_.numTriangles + 1;
    slotBytes_ = round_up(nf + kCanaryBytes, kBufferAlignment);
    numSlots_ = std::max(1, w_.numMoving);
    slots_ = AlignedArray<uint8_t>(slotBytes_ * (size_t)numSlots_);
    facingOut_ = AlignedArray<uint8_t>(nf + kCanaryBytes);
    cullOut_ = AlignedArray<uint8_t>((size_t)w_.numVerts + kCanaryBytes);
    outCap_ = sv_shadow_volume_capacity(w_.numIndices, w_.numSilEdges);
    out_ = AlignedArray<int>(outCap_ + kCanaryBytes / sizeof(int));
}

const std::vector<Expected> &Context::expected(Routine r) {
    std::unique_ptr<std::vector<Expected>> &e = expected_[(size_t)r];
    if (!e) {
        e = std::make_unique<std::vector<Expected>>(expected_results(r, w_));
    }
    return *e;
}

std::string case_name(const Case &c) {
    return std::string(routine_name(c.routine)) + "/" + c.variant->name + "/" +
           (c.moving ? "moving" : "fixed");
}

void run_case(benchmark::State &state, Case &c) {
    with_call(c, [&](const auto &call) {
        if (!c.checked) {
            c.checked = true;
            try {
                c.failure = check(c, call);
            } catch (const std::exception &e) {
                c.failure = std::string("no reference: ") + e.what();
            }
            if (!c.failure.empty()) {
                g_failed++;
            }
        }
        if (!c.failure.empty()) {
            state.SkipWithError(("FAILED the check against the reference: " + c.failure).c_str());
            return;
        }
        time_loop(state, c, call);
    });
}

int failed_cases() { return g_failed; }

} // namespace svgbench
