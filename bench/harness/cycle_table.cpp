/*
 * Copyright (C) 2026 the shadowvol authors. LGPL-2.1-or-later.
 */
#include "cycle_table.h"

#include <algorithm>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <stdexcept>
#include <string>
#include <vector>

#include <unistd.h>

#include "cache_info.h"
#include "expected.h"

namespace svbench {

namespace {

constexpr int kCanaryInts = 16;
constexpr int kCanaryBytes = 16;
constexpr int kCanaryValue = 0x5a5a5a5a;

/* One call's work buffers, each followed by canaries: the facing bytes
 * (numTriangles + 1), the cull bytes (numVerts; CalculateCullBits writes
 * them) and, for the index routines, the shadow indices (capacity of
 * sv_shadow_volume_capacity). Filled before each call by prepare_slot. */
struct Slot {
    AlignedArray<uint8_t> facing;
    AlignedArray<uint8_t> cull;
    AlignedArray<int> out; /* allocated when a row of an index routine needs it */
};

/* A timed region holds one call, or a batch of calls each with a slot of
 * its own (below). Slots are added as a row first needs them. */
struct Buffers {
    std::vector<Slot> slots;
    size_t facingBytes = 0, cullBytes = 0, outCap = 0;
    /* At least N slots (with index buffers when OUT), the canaries after
     * each (re-)armed: a row that broke them failed alone. */
    void arm(size_t n, bool out) {
        while (slots.size() < n) {
            Slot s;
            s.facing = AlignedArray<uint8_t>(facingBytes + kCanaryBytes);
            s.cull = AlignedArray<uint8_t>(cullBytes + kCanaryBytes);
            slots.push_back(std::move(s));
        }
        for (size_t i = 0; i < n && out; i++) {
            if (!slots[i].out.data()) {
                slots[i].out = AlignedArray<int>(outCap + kCanaryInts);
            }
        }
        for (Slot &s : slots) {
            std::fill_n(s.facing.data() + facingBytes, kCanaryBytes, (uint8_t)kCanaryValue);
            std::fill_n(s.cull.data() + cullBytes, kCanaryBytes, (uint8_t)kCanaryValue);
            if (s.out.data()) {
                std::fill_n(s.out.data() + outCap, kCanaryInts, kCanaryValue);
            }
        }
    }
};

/* What one call reads and writes, set up before the timed region so that
 * the region holds nothing but the fences and the call. */
struct CallArgs {
    uint8_t *facing;          /* the slot's facing bytes */
    uint8_t *cull;            /* the slot's cull bytes (App. B's output) */
    int *out;                 /* the slot's shadow indices */
    const uint8_t *cullBits;  /* the light's cull bits (input) */
    const Vec4 *light;        /* the light's position */
    const Plane *lightPlanes; /* the light box's planes */
};

/* The calls, one functor per routine. */
struct CalculateFacingCall {
    CalculateFacingFn f;
    const Plane *planes;
    int numTriangles;
    int operator()(const CallArgs &a) const {
        f(planes, numTriangles, a.light, a.facing);
        return 0;
    }
};
struct CalculateCullBitsCall {
    CalculateCullBitsFn f;
    const Vec4 *positions;
    int numVerts;
    const Bounds *bounds;
    int operator()(const CallArgs &a) const {
        return f(positions, numVerts, bounds, a.lightPlanes, a.cull);
    }
};
struct CountFacingCall {
    sv_count_facing_fn f;
    int n;
    int operator()(const CallArgs &a) const { return f(a.facing, n); }
};
struct CountFacingCullCall {
    sv_count_facing_cull_fn f;
    int n;
    const int *indices;
    int operator()(const CallArgs &a) const { return f(a.facing, n, indices, a.cullBits); }
};
struct SilCall {
    sv_create_sil_triangles_fn f;
    const SilEdge *edges;
    int numEdges;
    int operator()(const CallArgs &a) const { return f(a.out, a.facing, edges, numEdges); }
};
struct CapCall {
    sv_create_cap_triangles_fn f;
    const int *indices;
    int numIndices;
    int operator()(const CallArgs &a) const { return f(a.out, a.facing, indices, numIndices); }
};
template <bool kCull> struct VolumeCall {
    const sv_variant *v;
    const int *indices;
    int numIndices;
    const SilEdge *edges;
    int numEdges;
    int operator()(const CallArgs &a) const {
        return sv_create_shadow_volume(v, a.out, indices, numIndices, edges, numEdges, a.facing,
                                       kCull ? a.cullBits : nullptr);
    }
};

/* One light's whole job (issue 15): A, then the volume; or A, B and the
 * volume with the culling decision (no cull bits when B finds the surface
 * inside the light volume, as sv_calculate_cull_bits_c_ref's contract
 * says). */
template <bool kCull> struct PipelineCall {
    const BenchVariant *bv;
    const Workload *w;
    int operator()(const CallArgs &a) const {
        if (bv->plan && !bv->unfused) { /* the planned row: the public one-call entry point */
            const sv_surface s{w->planes.data(),   w->indices.data(), w->numIndices,
                               w->silEdges.data(), w->numSilEdges,    w->positions.data(),
                               w->numVerts,        w->bounds};
            return sv_shadow_volume_for_light(
                bv->plan, &s, a.light, kCull ? a.lightPlanes : nullptr, a.out,
                sv_shadow_volume_capacity(w->numIndices, w->numSilEdges), a.facing, a.cull);
        }
        bv->pipeline_facing(w->planes.data(), w->numTriangles, a.light, a.facing);
        const uint8_t *cull = nullptr;
        if (kCull && bv->pipeline_cull_bits(w->positions.data(), w->numVerts, &w->bounds,
                                            a.lightPlanes, a.cull) == 0) {
            cull = a.cull;
        }
        return sv_create_shadow_volume(bv->kernels, a.out, w->indices.data(), w->numIndices,
                                       w->silEdges.data(), w->numSilEdges, a.facing, cull);
    }
};

struct Context {
    const Workload *w;
    const std::vector<Expected> *expected; /* per light, for this routine */
    Buffers *buf;
    int runs, warmup;
    int round;
    int forcedBatch;         /* --batch; 0: choose per row */
    int autoBatch;           /* the batch of this routine's rows that need one */
    uint64_t batchThreshold; /* ticks: a row whose call is shorter needs one */
};

/* The light of the row's K-th call. */
int light_of(const Row &row, const Workload &w, long k) {
    return row.moving ? (int)(k % w.numMoving) : w.fixedLight;
}

/* The cost of the fences themselves, subtracted from the calls. It is not
 * one constant: where a hypervisor traps cpuid, its cost drifts by 20% in
 * phases of a fraction of a second to seconds (12.6k to 15.4k ticks on one
 * VM), so a minimum taken once at start-up would add the drift to every
 * figure. Each row therefore times an empty region right before every timed
 * region (one call or a batch), and compares like with like over the same
 * stretch of time:
 *   min    = min of the regions    - min of the empty regions
 *   median = median of the regions - median of the empty regions
 * (clamped at 0). Where the timer is steady (rdtscp, lfence on bare metal)
 * this is the classic "minus the empty region's minimum". */
template <class Timer> inline uint64_t empty_region() {
    const uint64_t t0 = Timer::begin();
    const uint64_t t1 = Timer::end();
    return t1 - t0;
}

uint64_t saturating_sub(uint64_t a, uint64_t b) { return a > b ? a - b : 0; }

/* Batching, as checkasm does for functions shorter than its timer can
 * resolve. Where one call lasts only a few TSC steps (sse2_paper
 * count_facing: about one 21-tick step on the reference VM), a timed region
 * holds a batch of B calls back to back, and the row reports ticks per
 * call: (min over the batches - min of the empty regions) / B and (median
 * over the batches - median of the empty regions) / B.
 *
 * Which rows, decided once per row in the warm-up of its first round: the
 * warm-up's single calls are timed like measured ones, and a row is batched
 * when their median (the warm-up's empty-region median subtracted) is below
 * the threshold (batch_threshold): kBatchSteps x the larger of the TSC
 * step and the jitter of the empty regions timed at start-up, their IQR
 * less one step. Less one step, because the difference of two stamps of a
 * counter that moves in steps spreads a region of constant length over two
 * neighbouring values, so the IQR of the readings exceeds the jitter of the
 * regions by up to a step (here 21 ticks, and 42 in some runs while the
 * timer is quiet, which alone would double the threshold). The IQR of
 * thousands of regions, one for all rows, rather than each row's 64
 * warm-up regions: on the reference VM about one window of 64 in 30 has an
 * IQR of 2 or 3 steps while the timer is quiet, which would batch a
 * count_facing_cull row (1200 to 3000 ticks, over 50 steps) in one run and
 * not in the next. Where the hypervisor's cpuid cost is noisy (IQRs of
 * 1000 ticks and more), the threshold rises and those rows are batched
 * too, for the whole run; the header prints the threshold.
 *
 * Which B: one size per routine, the same for all its variants (so the
 * speed-up column compares like with like), the largest whose per-call
 * buffers stay in L1 beside the input all calls share (batch_size), not
 * the smallest that would reach the threshold. The figure per call moves a
 * little with B, since a batch pays the fences' entry and exit once
 * (reference VM: sse2_paper count_facing 26.2 ticks per call in batches of
 * 12, 28.3 to 30.1 in batches of 23, about 30 in batches of 64; c_ref 357
 * alone, 329 in batches of 3, 316 to 326 in batches of 23 or 64). A B that
 * followed the timer's noise would move the figures from run to run.
 *
 * Inputs and outputs: every call of a batch has its own slot, so each call
 * gets a fresh copy of its input, made before the batch (count_facing_cull
 * modifies facing in place); the moving light gives each call the next
 * light (a batch never replays one input), the fixed light gives all of
 * them the same, as it does a single call; every call's count, facing,
 * cull bytes, output and canaries are checked after the batch, outside the
 * timed region.
 *
 * Working set, and why not the index routines: a single call reads a copy
 * of its facing array made just before it, hot in L1. The B slots of a
 * batch and the input they share (the indices of CountFacingCull, the
 * planes of CalculateFacing, the positions of CalculateCullBits) are kept
 * to 2/3 of the L1 data cache (the copies' sources stream through it too):
 * 23 facing copies of 1408 bytes in a 48 KiB L1 for CountFacing. In a loop
 * without fences, sse2_paper count_facing takes 28.7 ticks per call
 * rotating over up to 32 such copies, 31.6 over 48 or 64 (out of L1). The
 * index routines write 9.7 to 26 KB of output per call: B output buffers
 * would take the row's working set out of L1 at B = 2 or 3, so they run one
 * call per region unless --batch forces a size. They take over 70 TSC
 * steps a call here, which a single call resolves. */
constexpr size_t kDefaultL1Bytes = 32 * 1024; /* when neither sysconf nor sysfs knows */

size_t cache_lines(size_t bytes) { return (bytes + 63) / 64 * 64; }

size_t l1d_bytes() {
    const size_t l1 = cache_sizes().l1d.bytes;
    return l1 ? l1 : kDefaultL1Bytes;
}

bool may_batch(Routine r) { return !writes_indices(r); }

/* The batch of R's batched rows (see above): at least 2, at most
 * kMaxBatch. */
int batch_size(Routine r, const Workload &w, size_t l1d) {
    const size_t facing = cache_lines((size_t)w.numTriangles + 1 + kCanaryBytes);
    const size_t cull = cache_lines((size_t)w.numVerts + kCanaryBytes);
    size_t perCall = facing, shared = 0;
    switch (r) {
    case Routine::calculate_facing: shared = sizeof(Plane) * (size_t)w.numTriangles; break;
    case Routine::calculate_cull_bits:
        perCall = cull;
        shared = sizeof(Vec4) * (size_t)w.numVerts;
        break;
    case Routine::count_facing_cull: /* each call reads its light's cull bits */
        perCall = facing + cache_lines((size_t)w.numVerts);
        shared = sizeof(int) * (size_t)w.numIndices;
        break;
    default: break;
    }
    const size_t budget = l1d * 2 / 3;
    const size_t fit = budget > shared ? (budget - shared) / perCall : 0;
    return (int)std::clamp<size_t>(fit, 2, kMaxBatch);
}

uint64_t median_of(std::vector<uint64_t> v) {
    std::sort(v.begin(), v.end());
    return v[(v.size() - 1) / 2];
}

/* The IQR of TRIES empty regions, after a short warm-up. */
template <class Timer> uint64_t empty_iqr_with(int tries) {
    std::vector<uint64_t> e((size_t)std::max(tries, 4));
    for (int i = 0; i < 64; i++) {
        (void)empty_region<Timer>();
    }
    for (uint64_t &x : e) {
        x = empty_region<Timer>();
    }
    std::sort(e.begin(), e.end());
    return e[e.size() * 3 / 4] - e[e.size() / 4];
}
uint64_t empty_iqr(TimerKind k, int tries) {
    switch (k) {
    case TimerKind::rdtscp: return empty_iqr_with<TscRdtscp>(tries);
    case TimerKind::cpuid: return empty_iqr_with<TscCpuid>(tries);
    case TimerKind::lfence: return empty_iqr_with<TscLfence>(tries);
    }
    return 0;
}

/* Ticks below which a row is batched (see above). */
uint64_t batch_threshold(uint64_t step, uint64_t iqr) {
    return kBatchSteps * std::max(step, saturating_sub(iqr, step));
}

/* The row's batch from its timed warm-up calls (see above). */
int choose_batch(const Context &c, Routine r, const std::vector<uint64_t> &calls,
                 const std::vector<uint64_t> &empties) {
    if (c.forcedBatch) {
        return c.forcedBatch;
    }
    if (!may_batch(r) || calls.empty()) {
        return 1;
    }
    const uint64_t single = saturating_sub(median_of(calls), median_of(empties));
    return single < c.batchThreshold ? c.autoBatch : 1;
}

/* The parts of a row's measurement around the timed regions, out of line so
 * that the template below holds little more than the loops, the fences and
 * the calls. */

/* Fresh input and poisoned outputs in slot S for a call of R on light LI;
 * returns the call's arguments. */
CallArgs prepare_slot(const Context &c, Routine r, size_t s, int li) {
    const Workload &w = *c.w;
    const Light &l = w.lights[(size_t)li];
    Slot &sl = c.buf->slots[s];
    initial_facing(r, w, l, sl.facing.data());
    if (r == Routine::calculate_cull_bits || r == Routine::pipeline_cull) {
        std::fill_n(sl.cull.data(), w.numVerts, kPoisonByte);
    }
    if (writes_indices(r)) {
        std::fill_n(sl.out.data(), (*c.expected)[(size_t)li].count, kPoisonIndex);
    }
    return CallArgs{sl.facing.data(),  sl.cull.data(), sl.out.data(),
                    l.cullBits.data(), &l.position,    l.planes};
}

/* Empty when the canaries past slot SL's buffers are intact. */
std::string check_canaries(const Buffers &buf, const Slot &sl) {
    for (int i = 0; i < kCanaryBytes; i++) {
        if (sl.facing[buf.facingBytes + (size_t)i] != (uint8_t)kCanaryValue) {
            return "wrote past the facing array";
        }
        if (sl.cull[buf.cullBytes + (size_t)i] != (uint8_t)kCanaryValue) {
            return "wrote past the cull bits";
        }
    }
    for (int i = 0; sl.out.data() && i < kCanaryInts; i++) {
        if (sl.out[buf.outCap + (size_t)i] != kCanaryValue) {
            return "wrote past the output capacity";
        }
    }
    return std::string();
}

/* Checks the call on light LI that returned GOT in slot S; on a mismatch
 * marks the row failed, saying where: WHAT (a warm-up or timed call or
 * batch) number N, and in a batch of B > 1 which call I. */
bool check_slot(const Context &c, Row &row, int got, size_t s, int li, const char *what, int n,
                int i, int b) {
    const Slot &sl = c.buf->slots[s];
    std::string why = compare_with_reference(row.routine, *c.w, c.w->lights[(size_t)li],
                                             (*c.expected)[(size_t)li], got, sl.out.data(),
                                             sl.facing.data(), sl.cull.data());
    if (why.empty()) {
        why = check_canaries(*c.buf, sl);
    }
    if (why.empty()) {
        return true;
    }
    char where[160];
    if (b > 1) {
        std::snprintf(where, sizeof where, "light %d, round %d, %s %d, call %d of %d: ", li,
                      c.round + 1, what, n, i + 1, b);
    } else {
        std::snprintf(where, sizeof where, "light %d, round %d, %s %d: ", li, c.round + 1, what, n);
    }
    row.failure = where + why;
    row.ok = false;
    return false;
}

/* Folds one round's timed regions of B calls into the row. */
void record_round(Row &row, std::vector<uint64_t> &calls, std::vector<uint64_t> &empties, int b) {
    std::sort(calls.begin(), calls.end());
    std::sort(empties.begin(), empties.end());
    const size_t n = calls.size(), mid = (n - 1) / 2;
    const double min = (double)saturating_sub(calls[0], empties[0]) / b;
    const double median = (double)saturating_sub(calls[mid], empties[mid]) / b;
    if (row.rounds == 0 || min < row.min) {
        row.min = min;
    }
    if (row.rounds == 0 || median < row.median) {
        row.median = median;
        row.emptyMedian = empties[mid];
        row.emptyIqr = empties[n * 3 / 4] - empties[n / 4];
    }
    row.medianWorst = std::max(row.medianWorst, median);
    row.rounds++;
}

template <class Timer, class Call> void measure_row(const Call &call, const Context &c, Row &row) {
    Buffers &buf = *c.buf;
    const Workload &w = *c.w;
    const bool out = writes_indices(row.routine);
    buf.arm((size_t)std::max(1, row.batch), out);

    /* Warm-up: single calls, checked, and timed like the measured ones: in
     * the first round their median decides the row's batch. */
    std::vector<uint64_t> wcalls((size_t)c.warmup), wempties((size_t)c.warmup);
    for (int r = 0; r < c.warmup; r++) {
        const int li = light_of(row, w, row.calls++);
        const CallArgs a = prepare_slot(c, row.routine, 0, li);
        const uint64_t empty = empty_region<Timer>();

        const uint64_t t0 = Timer::begin();
        const int got = call(a);
        const uint64_t t1 = Timer::end();

        if (!check_slot(c, row, got, 0, li, "warm-up call", r + 1, 0, 1)) {
            return;
        }
        wcalls[(size_t)r] = t1 - t0;
        wempties[(size_t)r] = empty;
    }
    if (row.batch == 0) {
        row.batch = choose_batch(c, row.routine, wcalls, wempties);
        buf.arm((size_t)row.batch, out);
    }
    const int B = row.batch;

    std::vector<uint64_t> calls((size_t)c.runs), empties((size_t)c.runs);
    if (B == 1) {
        for (int r = 0; r < c.runs; r++) {
            const int li = light_of(row, w, row.calls++);
            const CallArgs a = prepare_slot(c, row.routine, 0, li);
            const uint64_t empty = empty_region<Timer>();

            const uint64_t t0 = Timer::begin();
            const int got = call(a);
            const uint64_t t1 = Timer::end();

            if (!check_slot(c, row, got, 0, li, "timed call", r + 1, 0, 1)) {
                return;
            }
            calls[(size_t)r] = t1 - t0;
            empties[(size_t)r] = empty;
        }
    } else {
        CallArgs args[kMaxBatch];
        int got[kMaxBatch];
        int lights[kMaxBatch];
        /* r = -1: one untimed batch after the warm-up's single calls. */
        for (int r = -1; r < c.runs; r++) {
            for (int i = 0; i < B; i++) {
                lights[i] = light_of(row, w, row.calls++);
                args[i] = prepare_slot(c, row.routine, (size_t)i, lights[i]);
            }
            const uint64_t empty = empty_region<Timer>();

            const uint64_t t0 = Timer::begin();
            for (int i = 0; i < B; i++) {
                got[i] = call(args[i]);
            }
            const uint64_t t1 = Timer::end();

            for (int i = 0; i < B; i++) {
                if (!check_slot(c, row, got[i], (size_t)i, lights[i],
                                r < 0 ? "warm-up batch" : "timed batch", r < 0 ? 1 : r + 1, i, B)) {
                    return;
                }
            }
            if (r >= 0) {
                calls[(size_t)r] = t1 - t0;
                empties[(size_t)r] = empty;
            }
        }
    }
    record_round(row, calls, empties, B);
}

template <class Call> void measure_with(TimerKind k, const Call &call, const Context &c, Row &row) {
    switch (k) {
    case TimerKind::rdtscp: measure_row<TscRdtscp>(call, c, row); break;
    case TimerKind::cpuid: measure_row<TscCpuid>(call, c, row); break;
    case TimerKind::lfence: measure_row<TscLfence>(call, c, row); break;
    }
}

void measure(TimerKind k, const Context &c, Row &row) {
    const Workload &w = *c.w;
    const BenchVariant &bv = *row.variant;
    const sv_variant *v = bv.kernels;
    switch (row.routine) {
    case Routine::calculate_facing:
        measure_with(k, CalculateFacingCall{bv.calculate_facing, w.planes.data(), w.numTriangles},
                     c, row);
        break;
    case Routine::calculate_cull_bits:
        measure_with(k,
                     CalculateCullBitsCall{bv.calculate_cull_bits, w.positions.data(), w.numVerts,
                                           &w.bounds},
                     c, row);
        break;
    case Routine::count_facing:
        measure_with(k, CountFacingCall{v->count_facing, w.numTriangles}, c, row);
        break;
    case Routine::count_facing_cull:
        measure_with(k, CountFacingCullCall{v->count_facing_cull, w.numTriangles, w.indices.data()},
                     c, row);
        break;
    case Routine::create_sil_triangles:
        measure_with(k, SilCall{v->create_sil_triangles, w.silEdges.data(), w.numSilEdges}, c, row);
        break;
    case Routine::create_cap_triangles:
        measure_with(k, CapCall{v->create_cap_triangles, w.indices.data(), w.numIndices}, c, row);
        break;
    case Routine::create_shadow_volume:
        measure_with(k,
                     VolumeCall<false>{v, w.indices.data(), w.numIndices, w.silEdges.data(),
                                       w.numSilEdges},
                     c, row);
        break;
    case Routine::create_shadow_volume_cull:
        measure_with(k,
                     VolumeCall<true>{v, w.indices.data(), w.numIndices, w.silEdges.data(),
                                      w.numSilEdges},
                     c, row);
        break;
    case Routine::pipeline: measure_with(k, PipelineCall<false>{&bv, &w}, c, row); break;
    case Routine::pipeline_cull: measure_with(k, PipelineCall<true>{&bv, &w}, c, row); break;
    }
}

/* A \r-updated line on stderr once a run has taken a second. */
class Progress {
public:
    Progress(bool enabled, const std::string &model, int rounds, int rows)
        : enabled_(enabled && isatty(STDERR_FILENO)), model_(model), rounds_(rounds), rows_(rows),
          t0_(monotonic_seconds()) {}
    void update(int round, int i, const Row &row) {
        if (!enabled_ || monotonic_seconds() - t0_ < 1.0) {
            return;
        }
        std::fprintf(stderr, "\rshadowvol bench: %.24s round %d/%d, row %2d/%d  %-6s %-26s %-13s",
                     model_.c_str(), round + 1, rounds_, i + 1, rows_,
                     row.moving ? "moving" : "fixed", routine_name(row.routine), row.variant->name);
        std::fflush(stderr);
        shown_ = true;
    }
    void finish() {
        if (shown_) {
            std::fprintf(stderr, "\r%-118s\r", "");
            std::fflush(stderr);
        }
    }

private:
    bool enabled_;
    std::string model_;
    int rounds_, rows_;
    double t0_;
    bool shown_ = false;
};

} // namespace

MachineTiming measure_machine(TimerKind timer, bool timerAuto, int overheadTries,
                              double tscSeconds) {
    MachineTiming m;
    m.cpu = pin_to_current_cpu();
    m.timer = timer;
    m.timerAuto = timerAuto;
    m.tscSeconds = tscSeconds;
    m.tscHz = estimate_tsc_hz(tscSeconds);
    m.overhead = measure_overhead(timer, overheadTries);
    m.step = tsc_step();
    m.emptyIqr = empty_iqr(timer, overheadTries);
    m.batchThreshold = batch_threshold(m.step, m.emptyIqr);
    m.l1dBytes = l1d_bytes();
    return m;
}

int elements_of(Routine r, const Workload &w) {
    switch (element_of(r)) {
    case Element::triangle: return w.numTriangles;
    case Element::sil_edge: return w.numSilEdges;
    case Element::vertex: return w.numVerts;
    }
    return 0;
}

bool below_noise(const Row &r, uint64_t step) {
    return r.median * std::max(1, r.batch) < (double)(kNoiseFactor * std::max(step, r.emptyIqr));
}

const Row *reference_row(const std::vector<Row> &rows, const Row &r) {
    for (const Row &x : rows) {
        if (x.moving == r.moving && x.routine == r.routine &&
            std::strcmp(x.variant->name, reference_variant().name) == 0) {
            return x.ok ? &x : nullptr;
        }
    }
    return nullptr;
}

ModelTable run_cycle_table(const TableOptions &o, const MachineTiming &m, const Workload &w) {
    ModelTable t;
    if (w.numMoving < 1 || w.fixedLight < 0 || (size_t)w.fixedLight >= w.lights.size()) {
        throw std::logic_error("workload " + w.name + " has no lights");
    }
    /* Every buffer is allocated more aligned than any variant asks. */
    /* The planned variant becomes the plan for this workload's size. */
    std::vector<const BenchVariant *> variants;
    for (const BenchVariant *bv : o.variants)
        variants.push_back(resolve_planned(bv, w.numTriangles));
    for (const BenchVariant *bv : variants) {
        const sv_variant *v = bv->kernels;
        if (v && (kBufferAlignment % v->align_facing || kBufferAlignment % v->align_indices ||
                  kBufferAlignment % v->align_shadow_indices)) {
            throw std::logic_error(std::string("variant ") + v->name +
                                   " needs more alignment than the bench allocates");
        }
    }

    /* Rows: regimes x routines x variants, moving first. */
    std::vector<Routine> routines;
    for (Routine r : o.routines) {
        if (needs_light(r) && !w.origin.lit) {
            t.skippedRoutines.push_back(r);
        } else {
            routines.push_back(r);
        }
    }
    for (int regime = 0; regime < 2; regime++) {
        const bool moving = regime == 0;
        if ((moving && !o.moving) || (!moving && !o.fixed)) {
            continue;
        }
        for (Routine r : routines) {
            for (const BenchVariant *v : variants) {
                if (implements(*v, r)) {
                    Row row;
                    row.routine = r;
                    row.variant = v;
                    row.moving = moving;
                    t.rows.push_back(row);
                }
            }
        }
    }

    Buffers buf;
    buf.facingBytes = (size_t)w.numTriangles + 1;
    buf.cullBytes = (size_t)w.numVerts;
    buf.outCap = sv_shadow_volume_capacity(w.numIndices, w.numSilEdges);

    std::vector<std::vector<Expected>> expected((size_t)kNumRoutines);
    std::vector<int> autoBatch((size_t)kNumRoutines, 1);
    for (Routine r : routines) {
        expected[(size_t)r] = expected_results(r, w);
        autoBatch[(size_t)r] = batch_size(r, w, m.l1dBytes);
    }

    /* Rounds: every row measured once per round, a share of its runs each
     * time. A disturbance of the machine lasting a fraction of a second
     * (another tenant, a frequency change) then lands in one round of a row,
     * not in all of its runs; the row keeps its lowest min and its lowest
     * round median. */
    t.runs = o.runs;
    t.warmup = o.warmup;
    t.rounds = std::max(1, std::min(o.rounds, o.runs));
    Progress progress(o.progress, w.name, t.rounds, (int)t.rows.size());
    for (int round = 0; round < t.rounds; round++) {
        const int runs = o.runs / t.rounds + (round < o.runs % t.rounds ? 1 : 0);
        for (size_t i = 0; i < t.rows.size(); i++) {
            Row &row = t.rows[i];
            if (!row.ok) {
                continue;
            }
            progress.update(round, (int)i, row);
            Context c;
            c.w = &w;
            c.expected = &expected[(size_t)row.routine];
            c.buf = &buf;
            c.runs = runs;
            c.warmup = o.warmup;
            c.round = round;
            c.forcedBatch = o.batch;
            c.autoBatch = autoBatch[(size_t)row.routine];
            c.batchThreshold = m.batchThreshold;
            measure(m.timer, c, row);
        }
    }
    for (Row &row : t.rows) {
        /* Estimated apart, the two can cross when the call is shorter than
         * the timer's jitter; the median is then shown equal to the min. */
        row.median = std::max(row.median, row.min);
    }
    progress.finish();
    return t;
}

} // namespace svbench
