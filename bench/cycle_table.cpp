/*
 * Copyright (C) 2026 the shadowvol authors. LGPL-2.1-or-later.
 */
#include "cycle_table.h"

#include <algorithm>
#include <cstdint>
#include <cstring>
#include <stdexcept>
#include <string>
#include <vector>

#include <unistd.h>

#include "paper_results.h"
#include "sysinfo.h"
#include "workload.h"

namespace svbench {

namespace {

const char *const kRoutineNames[kNumRoutines] = {
    "count_facing",         "count_facing_cull",    "create_sil_triangles",
    "create_cap_triangles", "create_shadow_volume", "create_shadow_volume_cull",
};

constexpr Routine kAllRoutines[kNumRoutines] = {
    Routine::count_facing,         Routine::count_facing_cull,
    Routine::create_sil_triangles, Routine::create_cap_triangles,
    Routine::create_shadow_volume, Routine::create_shadow_volume_cull,
};

constexpr int kCanaryInts = 16;
constexpr int kCanaryBytes = 16;
constexpr int kCanaryValue = 0x5a5a5a5a;
constexpr int kPoison = -1; /* never a valid shadow index */

/* What the paper's C computes for one routine and one facing pattern. */
struct Expected {
    int count = 0;
    std::vector<int> out;        /* output[0 .. count) for the index routines */
    std::vector<uint8_t> facing; /* numTriangles + 1 bytes after the call */
};

/* One row of the table. */
struct Row {
    Routine routine = Routine::count_facing;
    const sv_variant *variant = nullptr;
    bool moving = true;
    bool ok = true;
    std::string failure;
    int rounds = 0;                         /* rounds measured so far */
    int batch = 0;                          /* calls per timed region; 0: not decided yet */
    double min = 0, median = 0;             /* ticks per call, the fences' cost subtracted */
    uint64_t emptyMedian = 0, emptyIqr = 0; /* empty regions of the round kept */
    double medianWorst = 0;                 /* the highest of the rounds' medians */
};

/* A timed region whose median (the empty regions' subtracted) is below
 * kNoiseFactor times the larger of the TSC's step and the interquartile
 * range of the row's empty regions is mostly timer noise: its speed-up is
 * printed with a "~". For a batched row the region is the whole batch. */
constexpr uint64_t kNoiseFactor = 5;

bool below_noise(const Row &r, uint64_t step) {
    return r.median * std::max(1, r.batch) < (double)(kNoiseFactor * std::max(step, r.emptyIqr));
}

bool is_index_routine(Routine r) {
    return r != Routine::count_facing && r != Routine::count_facing_cull;
}

int elements_of(Routine r, const Workload &w) {
    return r == Routine::create_sil_triangles ? w.numSilEdges : w.numTriangles;
}

/* One call's work buffers: facing (copied from the pattern before the call,
 * canary bytes after its numTriangles + 1 bytes) and the output (capacity of
 * sv_shadow_volume_capacity, canary ints after it; poisoned before the
 * call). */
struct Slot {
    AlignedArray<uint8_t> facing;
    AlignedArray<int> out;
};

/* A timed region holds one call, or a batch of calls each with a slot of
 * its own (below). Slots are added as a row first needs them. */
struct Buffers {
    std::vector<Slot> slots;
    size_t facingBytes = 0;
    size_t outCap = 0;
    /* At least N slots, the canaries after each (re-)armed: a row that broke
     * them failed alone. */
    void arm(size_t n) {
        while (slots.size() < n) {
            Slot s;
            s.facing = AlignedArray<uint8_t>(facingBytes + kCanaryBytes);
            s.out = AlignedArray<int>(outCap + kCanaryInts);
            slots.push_back(std::move(s));
        }
        for (Slot &s : slots) {
            std::fill_n(s.facing.data() + facingBytes, kCanaryBytes, (uint8_t)kCanaryValue);
            std::fill_n(s.out.data() + outCap, kCanaryInts, kCanaryValue);
        }
    }
};

struct Context {
    const Workload *w;
    const std::vector<Expected> *expected; /* per pattern, for this routine */
    Buffers *buf;
    int runs, warmup, patterns;
    int round;
    int forcedBatch;         /* --batch; 0: choose per row */
    int autoBatch;           /* the batch of a row that needs one */
    uint64_t batchThreshold; /* ticks: a row whose call is shorter needs one */
};

/* The calls, one functor per routine, so the timed region holds nothing but
 * the fences and the call through the variant's pointer. */
struct CountFacingCall {
    sv_count_facing_fn f;
    int n;
    int operator()(uint8_t *facing, int *) const { return f(facing, n); }
};
struct CountFacingCullCall {
    sv_count_facing_cull_fn f;
    int n;
    const int *indices;
    const uint8_t *cullBits;
    int operator()(uint8_t *facing, int *) const { return f(facing, n, indices, cullBits); }
};
struct SilCall {
    sv_create_sil_triangles_fn f;
    const SilEdge *edges;
    int numEdges;
    int operator()(uint8_t *facing, int *out) const { return f(out, facing, edges, numEdges); }
};
struct CapCall {
    sv_create_cap_triangles_fn f;
    const int *indices;
    int numIndices;
    int operator()(uint8_t *facing, int *out) const { return f(out, facing, indices, numIndices); }
};
struct VolumeCall {
    const sv_variant *v;
    const int *indices;
    int numIndices;
    const SilEdge *edges;
    int numEdges;
    const uint8_t *cullBits; /* nullptr: no culling */
    int operator()(uint8_t *facing, int *out) const {
        return sv_create_shadow_volume(v, out, indices, numIndices, edges, numEdges, facing,
                                       cullBits);
    }
};

/* Compares one call's result in slot SL with the paper's C, outside the
 * timed region: the count, output[0 .. count), the whole facing array (cull
 * routines modify it; the others must not), and the canaries past both
 * buffers.
 * Returns an empty string when all agree, else what differed first. */
std::string check_call(const Expected &e, int got, const Buffers &buf, const Slot &sl) {
    char msg[160];
    if (got != e.count) {
        std::snprintf(msg, sizeof msg, "returned %d, c_ref %d", got, e.count);
        return msg;
    }
    if (!e.out.empty() && std::memcmp(sl.out.data(), e.out.data(), e.out.size() * sizeof(int))) {
        size_t i = 0;
        while (sl.out[i] == e.out[i]) {
            i++;
        }
        std::snprintf(msg, sizeof msg, "output[%zu] = %d, c_ref %d", i, sl.out[i], e.out[i]);
        return msg;
    }
    if (std::memcmp(sl.facing.data(), e.facing.data(), e.facing.size())) {
        size_t i = 0;
        while (sl.facing[i] == e.facing[i]) {
            i++;
        }
        std::snprintf(msg, sizeof msg, "facing[%zu] = %d after the call, c_ref %d", i, sl.facing[i],
                      e.facing[i]);
        return msg;
    }
    for (int i = 0; i < kCanaryBytes; i++) {
        if (sl.facing[buf.facingBytes + (size_t)i] != (uint8_t)kCanaryValue) {
            return "wrote past the facing array";
        }
    }
    for (int i = 0; i < kCanaryInts; i++) {
        if (sl.out[buf.outCap + (size_t)i] != kCanaryValue) {
            return "wrote past the output capacity";
        }
    }
    return std::string();
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

uint64_t saturating_sub(uint64_t a, uint64_t b) {
    return a > b ? a - b : 0;
}

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
 * Which B: one size for every batched row, the largest whose input copies
 * stay in L1 (batch_size), not the smallest that would reach the
 * threshold. The figure per call moves a little with B, since a batch pays
 * the fences' entry and exit once (reference VM: sse2_paper count_facing
 * 26.2 ticks per call in batches of 12, 28.3 to 30.1 in batches of 23,
 * about 30 in batches of 64; c_ref 357 alone, 329 in batches of 3, 316 to
 * 326 in batches of 23 or 64). A B that followed the timer's noise would
 * move the figures from run to run; one B makes batched rows compare like
 * with like.
 *
 * Inputs and outputs: every call of a batch has its own slot, so each call
 * gets a fresh copy of its input, made before the batch (count_facing_cull
 * modifies facing in place); the moving light gives each call the next
 * pattern (a batch never replays one input), the fixed light gives all of
 * them pattern 0, as it does a single call; every call's count, facing,
 * output and canaries are checked after the batch, outside the timed
 * region.
 *
 * Working set, and why only the count routines: a single call reads a copy
 * of its facing array made just before it, hot in L1. The B copies of a
 * batch are kept to 2/3 of the L1 data cache (their sources stream through
 * it too): 23 copies of 1408 bytes in a 48 KiB L1. In a loop without
 * fences, sse2_paper count_facing takes 28.7 ticks per call rotating over up
 * to 32 such copies, 31.6 over 48 or 64 (out of L1). The index routines
 * write 9.7 to 26 KB of output per call: B output buffers would take the
 * row's working set out of L1 at B = 2 or 3, so they run one call per
 * region unless --batch forces a size. They take over 70 TSC steps a call
 * here, which a single call resolves. */
constexpr uint64_t kBatchSteps = 50;
constexpr size_t kDefaultL1Bytes = 32 * 1024; /* when sysconf does not know */

/* Bytes of one call's slot as a count routine uses it: the facing array
 * and its canaries, in whole cache lines. */
size_t slot_bytes(size_t facingBytes) {
    return (facingBytes + kCanaryBytes + 63) / 64 * 64;
}

/* The L1 data cache's size, and the batch of the batched rows: as many
 * slots as fit in 2/3 of it, at least 2, at most kMaxBatch. */
size_t l1d_bytes() {
    const long l1 = sysconf(_SC_LEVEL1_DCACHE_SIZE);
    return l1 > 0 ? (size_t)l1 : kDefaultL1Bytes;
}
int batch_size(size_t facingBytes) {
    const size_t fit = l1d_bytes() * 2 / 3 / slot_bytes(facingBytes);
    return (int)std::max<size_t>(2, std::min<size_t>(kMaxBatch, fit));
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
    if (is_index_routine(r) || calls.empty()) {
        return 1;
    }
    const uint64_t single = saturating_sub(median_of(calls), median_of(empties));
    return single < c.batchThreshold ? c.autoBatch : 1;
}

/* The parts of a row's measurement around the timed regions, out of line so
 * that the template below holds little more than the loops, the fences and
 * the calls. */

/* Fresh input and poisoned output in slot S for a call on pattern P. */
void prepare_slot(Buffers &buf, const Workload &w, const Expected &e, size_t s, int p) {
    Slot &sl = buf.slots[s];
    std::memcpy(sl.facing.data(), w.patterns[(size_t)p].facing.data(), buf.facingBytes);
    std::fill_n(sl.out.data(), e.out.size(), kPoison);
}

/* Checks the call on pattern P that returned GOT in slot S; on a mismatch
 * marks the row failed, saying where: WHAT (a warm-up or timed call or
 * batch) number N, and in a batch of B > 1 which call I. */
bool check_slot(const Context &c, Row &row, int got, size_t s, int p, const char *what, int n,
                int i, int b) {
    const std::string why = check_call((*c.expected)[(size_t)p], got, *c.buf, c.buf->slots[s]);
    if (why.empty()) {
        return true;
    }
    char where[160];
    if (b > 1) {
        std::snprintf(where, sizeof where, "pattern %d, round %d, %s %d, call %d of %d: ", p,
                      c.round + 1, what, n, i + 1, b);
    } else {
        std::snprintf(where, sizeof where, "pattern %d, round %d, %s %d: ", p, c.round + 1, what,
                      n);
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
    const std::vector<Expected> &ex = *c.expected;
    /* The k-th call of this round (warm-up first) gets pattern k mod the
     * pattern count with the light moving, pattern 0 with it fixed. */
    auto pattern = [&](long k) { return row.moving ? (int)(k % c.patterns) : 0; };
    buf.arm((size_t)std::max(1, row.batch));

    /* Warm-up: single calls, checked, and timed like the measured ones: in
     * the first round their median decides the row's batch. */
    std::vector<uint64_t> wcalls((size_t)c.warmup), wempties((size_t)c.warmup);
    for (int r = 0; r < c.warmup; r++) {
        const int p = pattern(r);
        prepare_slot(buf, w, ex[(size_t)p], 0, p);
        const uint64_t empty = empty_region<Timer>();

        const uint64_t t0 = Timer::begin();
        const int got = call(buf.slots[0].facing.data(), buf.slots[0].out.data());
        const uint64_t t1 = Timer::end();

        if (!check_slot(c, row, got, 0, p, "warm-up call", r + 1, 0, 1)) {
            return;
        }
        wcalls[(size_t)r] = t1 - t0;
        wempties[(size_t)r] = empty;
    }
    if (row.batch == 0) {
        row.batch = choose_batch(c, row.routine, wcalls, wempties);
        buf.arm((size_t)row.batch);
    }
    const int B = row.batch;

    std::vector<uint64_t> calls((size_t)c.runs), empties((size_t)c.runs);
    long next = c.warmup; /* the number of this round's next call */
    if (B == 1) {
        uint8_t *const facing = buf.slots[0].facing.data();
        int *const out = buf.slots[0].out.data();
        for (int r = 0; r < c.runs; r++) {
            const int p = pattern(next++);
            prepare_slot(buf, w, ex[(size_t)p], 0, p);
            const uint64_t empty = empty_region<Timer>();

            const uint64_t t0 = Timer::begin();
            const int got = call(facing, out);
            const uint64_t t1 = Timer::end();

            if (!check_slot(c, row, got, 0, p, "timed call", r + 1, 0, 1)) {
                return;
            }
            calls[(size_t)r] = t1 - t0;
            empties[(size_t)r] = empty;
        }
    } else {
        uint8_t *facing[kMaxBatch];
        int *out[kMaxBatch];
        int got[kMaxBatch];
        int pat[kMaxBatch];
        for (int i = 0; i < B; i++) {
            facing[i] = buf.slots[(size_t)i].facing.data();
            out[i] = buf.slots[(size_t)i].out.data();
        }
        /* r = -1: one untimed batch after the warm-up's single calls. */
        for (int r = -1; r < c.runs; r++) {
            for (int i = 0; i < B; i++) {
                pat[i] = pattern(next++);
                prepare_slot(buf, w, ex[(size_t)pat[i]], (size_t)i, pat[i]);
            }
            const uint64_t empty = empty_region<Timer>();

            const uint64_t t0 = Timer::begin();
            for (int i = 0; i < B; i++) {
                got[i] = call(facing[i], out[i]);
            }
            const uint64_t t1 = Timer::end();

            for (int i = 0; i < B; i++) {
                if (!check_slot(c, row, got[i], (size_t)i, pat[i],
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
    const sv_variant *v = row.variant;
    switch (row.routine) {
    case Routine::count_facing:
        measure_with(k, CountFacingCall{v->count_facing, w.numTriangles}, c, row);
        break;
    case Routine::count_facing_cull:
        measure_with(k,
                     CountFacingCullCall{v->count_facing_cull, w.numTriangles, w.indices.data(),
                                         w.cullBits.data()},
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
                     VolumeCall{v, w.indices.data(), w.numIndices, w.silEdges.data(), w.numSilEdges,
                                nullptr},
                     c, row);
        break;
    case Routine::create_shadow_volume_cull:
        measure_with(k,
                     VolumeCall{v, w.indices.data(), w.numIndices, w.silEdges.data(), w.numSilEdges,
                                w.cullBits.data()},
                     c, row);
        break;
    }
}

/* The oracle: the paper's C (variant c_ref), called directly, untimed. */
std::vector<Expected> expected_results(Routine r, const Workload &w) {
    const sv_variant *ref = sv_variant_by_name("c_ref");
    std::vector<Expected> all;
    const size_t cap = sv_shadow_volume_capacity(w.numIndices, w.numSilEdges);
    std::vector<int> out(cap);
    for (const FacingPattern &p : w.patterns) {
        Expected e;
        e.facing.assign(p.facing.data(), p.facing.data() + w.numTriangles + 1);
        uint8_t *f = e.facing.data();
        switch (r) {
        case Routine::count_facing: e.count = ref->count_facing(f, w.numTriangles); break;
        case Routine::count_facing_cull:
            e.count =
                ref->count_facing_cull(f, w.numTriangles, w.indices.data(), w.cullBits.data());
            break;
        case Routine::create_sil_triangles:
            e.count = ref->create_sil_triangles(out.data(), f, w.silEdges.data(), w.numSilEdges);
            break;
        case Routine::create_cap_triangles:
            e.count = ref->create_cap_triangles(out.data(), f, w.indices.data(), w.numIndices);
            break;
        case Routine::create_shadow_volume:
        case Routine::create_shadow_volume_cull:
            e.count = sv_create_shadow_volume(
                ref, out.data(), w.indices.data(), w.numIndices, w.silEdges.data(), w.numSilEdges,
                f, r == Routine::create_shadow_volume_cull ? w.cullBits.data() : nullptr);
            break;
        }
        if (is_index_routine(r)) {
            e.out.assign(out.begin(), out.begin() + e.count);
        }
        all.push_back(std::move(e));
    }
    return all;
}

/* What the workload's ratios promise, so that a broken reference or
 * workload cannot pass silently as "ok". */
void sanity_check_expected(Routine r, const Workload &w, const std::vector<Expected> &ex) {
    for (size_t p = 0; p < ex.size(); p++) {
        const FacingPattern &pat = w.patterns[p];
        int want = -1;
        switch (r) {
        case Routine::count_facing: want = pat.numFacing; break;
        case Routine::create_sil_triangles: want = 6 * pat.numSilhouette; break;
        case Routine::create_cap_triangles: want = 6 * (w.numTriangles - pat.numFacing); break;
        case Routine::create_shadow_volume:
            want = 6 * pat.numSilhouette + 6 * (w.numTriangles - pat.numFacing);
            break;
        default: break;
        }
        if (want >= 0 && ex[p].count != want) {
            throw std::logic_error(std::string("c_ref ") + routine_name(r) + " returned " +
                                   std::to_string(ex[p].count) + " on pattern " +
                                   std::to_string(p) + ", the workload implies " +
                                   std::to_string(want));
        }
    }
}

/* A \r-updated line on stderr once a run has taken a second. */
class Progress {
public:
    Progress(bool enabled, int rounds, int rows)
        : enabled_(enabled && isatty(STDERR_FILENO)), rounds_(rounds), rows_(rows),
          t0_(monotonic_seconds()) {}
    void update(int round, int i, const Row &row) {
        if (!enabled_ || monotonic_seconds() - t0_ < 1.0) {
            return;
        }
        std::fprintf(stderr, "\rshadowvol bench: round %d/%d, row %2d/%d  %-6s %-26s %-13s",
                     round + 1, rounds_, i + 1, rows_, row.moving ? "moving" : "fixed",
                     routine_name(row.routine), row.variant->name);
        std::fflush(stderr);
        shown_ = true;
    }
    void finish() {
        if (shown_) {
            std::fprintf(stderr, "\r%-90s\r", "");
            std::fflush(stderr);
        }
    }

private:
    bool enabled_;
    int rounds_, rows_;
    double t0_;
    bool shown_ = false;
};

std::string pct(int part, int whole) {
    char s[32];
    std::snprintf(s, sizeof s, "%.1f%%", 100.0 * part / whole);
    return s;
}

void print_header(FILE *out, const TableOptions &o, const Workload &w, int cpu, double tscHz,
                  const Overhead &ovh, uint64_t step, int autoBatch, uint64_t iqr,
                  uint64_t threshold, const std::vector<Row> &rows,
                  const std::vector<const sv_variant *> &skipped) {
    std::fprintf(out,
                 "shadowvol %s bench: the cycle table of J.M.P. van Waveren, \"Shadow Volume "
                 "Construction\" (Id Software, 2005), section 8\n",
                 project_version().c_str());
    std::fprintf(out, "cpu       %s", cpu_model().c_str());
    if (cpu >= 0) {
        std::fprintf(out, " (measuring thread pinned to cpu %d)\n", cpu);
    } else {
        std::fprintf(out, " (could not pin the measuring thread: expect noise)\n");
    }
    std::fprintf(out, "isa       %s (cpuid; display only: variants run on sv_cpu_isa())\n",
                 cpu_isa_flags().c_str());
    std::fprintf(out,
                 "tsc       %.3f GHz (rdtsc against CLOCK_MONOTONIC over %.0f ms), steps of %llu "
                 "ticks, invariant-TSC bit %s;\n          unit: ticks, not core cycles\n",
                 tscHz * 1e-9, o.tscSeconds * 1e3, (unsigned long long)step,
                 cpu_has_invariant_tsc() ? "set" : "not set");
    std::fprintf(out, "timer     %s%s: %s\n", timer_name(o.timer),
                 o.timerAuto
                     ? (cpu_has_rdtscp() ? " (auto: CPU has RDTSCP)" : " (auto: CPU lacks RDTSCP)")
                     : "",
                 timer_sequence(o.timer));
    uint64_t lo = UINT64_MAX, hi = 0;
    for (const Row &r : rows) {
        if (r.ok) {
            lo = std::min(lo, r.emptyMedian);
            hi = std::max(hi, r.emptyMedian);
        }
    }
    std::fprintf(out,
                 "overhead  empty region at start: min %llu, median %llu, p90 %llu ticks (%d "
                 "tries); each row times one\n"
                 "          before every timed region and subtracts their min from the calls' min, "
                 "their median from the calls'\n"
                 "          median (the rows' empty-region medians ranged %llu..%llu ticks)\n",
                 (unsigned long long)ovh.min, (unsigned long long)ovh.median,
                 (unsigned long long)ovh.p90, ovh.tries, (unsigned long long)(hi ? lo : 0),
                 (unsigned long long)hi);
    const int rounds = std::max(1, std::min(o.rounds, o.runs));
    std::fprintf(out,
                 "runs      %d timed regions per row in %d round%s over all rows, each after "
                 "%d warm-up calls; every call\n          checked against c_ref. A row keeps "
                 "its lowest min and its lowest round median\n",
                 o.runs, rounds, rounds == 1 ? "" : "s", o.warmup);
    if (o.batch == 0) {
        std::fprintf(out,
                     "batch     a region times one call, or, in a count routine's row whose "
                     "warm-up calls' median is\n          below %llu ticks (%llu x the larger of "
                     "the TSC step and the IQR of %d empty regions\n          less one step: "
                     "%llu - %llu), a batch of %d back-to-back calls after an untimed one,\n"
                     "          each on its own input, whose copies fill 2/3 of the %zu KiB L1D: "
                     "rows marked x%d\n",
                     (unsigned long long)threshold, (unsigned long long)kBatchSteps,
                     o.overheadTries, (unsigned long long)iqr, (unsigned long long)step, autoBatch,
                     l1d_bytes() / 1024, autoBatch);
    } else if (o.batch == 1) {
        std::fprintf(out, "batch     one call per timed region (--batch 1)\n");
    } else {
        std::fprintf(out,
                     "batch     %d back-to-back calls per timed region in every row (--batch "
                     "%d), each on its own input\n",
                     o.batch, o.batch);
    }
    std::fprintf(out, "build     %s, %s, commit %s\n", compiler_version().c_str(),
                 build_flags().c_str(), git_commit().c_str());
    std::fprintf(out,
                 "mesh      synthetic torus, %d x %d quads: %d vertices, %d triangles, %d "
                 "SilEdges (closed 2-manifold)\n",
                 w.gridU, w.gridV, w.numVerts, w.numTriangles, w.numSilEdges);
    const FacingPattern &p0 = w.patterns[0];
    std::fprintf(out,
                 "light     %d facing patterns (seed %llu), each: facing %s of triangles (%d), "
                 "silhouette %s of SilEdges (%d);\n          paper: 50%%, 20%% (on a closed "
                 "mesh the silhouette count has the parity of the facing count)\n",
                 (int)w.patterns.size(), (unsigned long long)w.seed,
                 pct(p0.numFacing, w.numTriangles).c_str(), p0.numFacing,
                 pct(p0.numSilhouette, w.numSilEdges).c_str(), p0.numSilhouette);
    /* Non-facing triangles the cull routines turn facing, over the patterns. */
    long turned = 0;
    for (const FacingPattern &p : w.patterns) {
        for (int t = 0; t < w.numTriangles; t++) {
            const int *i = &w.indices[(size_t)(3 * t)];
            if (!p.facing[(size_t)t] &&
                (w.cullBits[(size_t)i[0]] & w.cullBits[(size_t)i[1]] & w.cullBits[(size_t)i[2]])) {
                turned++;
            }
        }
    }
    std::fprintf(out,
                 "cull      %s of triangles outside the light box (%d; cull bits 0-5); "
                 "%.1f%% of the non-facing ones become facing\n",
                 pct(w.numCulled, w.numTriangles).c_str(), w.numCulled,
                 100.0 * (double)turned /
                     ((double)w.patterns.size() * (w.numTriangles - p0.numFacing)));
    for (const sv_variant *v : skipped) {
        std::fprintf(out, "skipped   variant %s: this CPU lacks its instruction set\n", v->name);
    }
}

void print_table(FILE *out, bool moving, const std::vector<Row> &rows, const Workload &w,
                 int patterns, uint64_t step) {
    std::fprintf(out, "\n");
    if (moving) {
        std::fprintf(out, "regime: moving light (%d facing patterns, a different one every call)\n",
                     patterns);
    } else {
        std::fprintf(out, "regime: fixed light (the same facing pattern every call: the paper's "
                          "hot-cache setup)\n");
    }
    std::fprintf(out, "%-26s %-13s %10s %10s %9s %9s %8s | %8s %5s | %8s %5s | %s\n", "routine",
                 "variant", "ticks min", "ticks med", "/elem min", "/elem med", "vs c_ref",
                 "P4-130nm", "/elem", "P4-90nm", "/elem", "checked");
    for (const Row &r : rows) {
        if (r.moving != moving) {
            continue;
        }
        const char *rn = routine_name(r.routine);
        std::fprintf(out, "%-26s %-13s ", rn, r.variant->name);
        if (!r.ok) {
            std::fprintf(out, "%10s %10s %9s %9s %8s | %8s %5s | %8s %5s | %s\n", "FAILED", "-",
                         "-", "-", "-", "-", "-", "-", "-", "FAILED");
            continue;
        }
        const double el = elements_of(r.routine, w);
        /* A batched row: "xN" before its min, ticks per call to a tenth. */
        char mark[16] = "", mn[32], md[32];
        const bool batched = r.batch > 1;
        if (batched) {
            std::snprintf(mark, sizeof mark, "x%d", r.batch);
        }
        std::snprintf(mn, sizeof mn, batched ? "%.1f" : "%.0f", r.min);
        std::snprintf(md, sizeof md, batched ? "%.1f" : "%.0f", r.median);
        const int pad =
            std::max(batched ? 1 : 0, 10 - (int)std::strlen(mark) - (int)std::strlen(mn));
        std::fprintf(out, "%s%*s%s %10s %9.2f %9.2f ", mark, pad, "", mn, md, r.min / el,
                     r.median / el);
        const Row *ref = nullptr;
        for (const Row &x : rows) {
            if (x.moving == moving && x.routine == r.routine &&
                std::strcmp(x.variant->name, "c_ref") == 0 && x.ok) {
                ref = &x;
            }
        }
        if (ref && r.median > 0) {
            const bool noisy = below_noise(r, step) || below_noise(*ref, step);
            std::fprintf(out, "%s%6.2fx | ", noisy ? "~" : " ", ref->median / r.median);
        } else {
            std::fprintf(out, "%8s | ", "-");
        }
        const PaperFigures *pf = paper_figures(rn, r.variant->name);
        if (pf) {
            std::fprintf(out, "%8ld %5s | %8ld %5s | ", pf->p4_130nm_total,
                         pf->p4_130nm_per_element, pf->p4_90nm_total, pf->p4_90nm_per_element);
        } else {
            std::fprintf(out, "%8s %5s | %8s %5s | ", "-", "-", "-", "-");
        }
        std::fprintf(out, "ok\n");
    }
}

} // namespace

const char *routine_name(Routine r) {
    return kRoutineNames[(int)r];
}

bool routine_by_name(const std::string &name, Routine *r) {
    for (int i = 0; i < kNumRoutines; i++) {
        if (name == kRoutineNames[i]) {
            *r = kAllRoutines[i];
            return true;
        }
    }
    return false;
}

int run_cycle_table(const TableOptions &o, FILE *out) {
    const int cpu = pin_to_current_cpu();
    const Workload w = make_workload(o.seed, o.patterns);

    /* Rows: routines x variants the CPU runs x regimes, moving first. */
    std::vector<Routine> routines = o.routines;
    if (routines.empty()) {
        routines.assign(kAllRoutines, kAllRoutines + kNumRoutines);
    }
    std::vector<const sv_variant *> variants, skipped;
    if (o.variants.empty()) {
        int n = 0;
        const sv_variant *all = sv_variants(&n);
        for (int i = 0; i < n; i++) {
            if ((all[i].isa & sv_cpu_isa()) == all[i].isa) {
                variants.push_back(&all[i]);
            } else {
                skipped.push_back(&all[i]);
            }
        }
    } else {
        variants = o.variants;
    }
    /* Every buffer is allocated more aligned than any variant asks. */
    for (const sv_variant *v : variants) {
        if (kBufferAlignment % v->align_facing || kBufferAlignment % v->align_indices ||
            kBufferAlignment % v->align_shadow_indices) {
            throw std::logic_error(std::string("variant ") + v->name +
                                   " needs more alignment than the bench allocates");
        }
    }

    std::vector<Row> rows;
    for (int regime = 0; regime < 2; regime++) {
        const bool moving = regime == 0;
        if ((moving && !o.moving) || (!moving && !o.fixed)) {
            continue;
        }
        for (Routine r : routines) {
            for (const sv_variant *v : variants) {
                Row row;
                row.routine = r;
                row.variant = v;
                row.moving = moving;
                rows.push_back(row);
            }
        }
    }

    Buffers buf;
    buf.facingBytes = (size_t)w.numTriangles + 1;
    buf.outCap = sv_shadow_volume_capacity(w.numIndices, w.numSilEdges);
    buf.arm(1);

    std::vector<std::vector<Expected>> expected((size_t)kNumRoutines);
    for (Routine r : routines) {
        expected[(size_t)r] = expected_results(r, w);
        sanity_check_expected(r, w, expected[(size_t)r]);
    }

    const double tscHz = estimate_tsc_hz(o.tscSeconds);
    const Overhead ovh = measure_overhead(o.timer, o.overheadTries);
    const uint64_t step = tsc_step();
    const int autoBatch = batch_size(buf.facingBytes);
    const uint64_t iqr = empty_iqr(o.timer, o.overheadTries);
    const uint64_t threshold = batch_threshold(step, iqr);

    /* Rounds: every row measured once per round, a share of its runs each
     * time. A disturbance of the machine lasting a fraction of a second
     * (another tenant, a frequency change) then lands in one round of a row,
     * not in all of its runs; the row keeps its lowest min and its lowest
     * round median. */
    const int rounds = std::max(1, std::min(o.rounds, o.runs));
    Progress progress(o.progress, rounds, (int)rows.size());
    for (int round = 0; round < rounds; round++) {
        const int runs = o.runs / rounds + (round < o.runs % rounds ? 1 : 0);
        for (size_t i = 0; i < rows.size(); i++) {
            Row &row = rows[i];
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
            c.patterns = o.patterns;
            c.round = round;
            c.forcedBatch = o.batch;
            c.autoBatch = autoBatch;
            c.batchThreshold = threshold;
            measure(o.timer, c, row);
        }
    }
    for (Row &row : rows) {
        /* Estimated apart, the two can cross when the call is shorter than
         * the timer's jitter; the median is then shown equal to the min. */
        row.median = std::max(row.median, row.min);
    }
    progress.finish();

    print_header(out, o, w, cpu, tscHz, ovh, step, autoBatch, iqr, threshold, rows, skipped);
    for (int regime = 0; regime < 2; regime++) {
        const bool moving = regime == 0;
        if ((moving && o.moving) || (!moving && o.fixed)) {
            print_table(out, moving, rows, w, o.patterns, step);
        }
    }

    std::fprintf(out,
                 "\n/elem: per triangle (%d); create_sil_triangles per SilEdge (%d), as in "
                 "the paper.\nvs c_ref: c_ref's median over this row's median; ~: this row's "
                 "or c_ref's median is below %llu x\n  the TSC step or the spread (IQR) of "
                 "the row's empty regions: mostly timer noise.\n",
                 w.numTriangles, w.numSilEdges, (unsigned long long)kNoiseFactor);
    bool anyBatched = false;
    for (const Row &r : rows) {
        anyBatched = anyBatched || (r.ok && r.batch > 1);
    }
    if (anyBatched) {
        std::fprintf(out, "xN: N back-to-back calls per timed region, each on a fresh copy of its "
                          "input (moving light: the\n  next pattern each) and each checked; "
                          "figures per call: (batch - empty region) / N, the min and\n  median "
                          "over the batches; ~ then compares the whole batch with the noise.\n");
    }
    std::fprintf(out, "P4 columns: the paper's \"Hot Cache Clock Cycle Counts\" (core cycles) on "
                      "the row of its C (c_ref) and of its SSE2 listing (sse2_paper);\n"
                      "  create_shadow_volume = \"CreateShadowVolume, no culling\", "
                      "create_shadow_volume_cull = \"with culling\".\n");
    /* How far the rounds of a row disagreed: the noise left after taking
     * the lowest round median. */
    const Row *worst = nullptr;
    double worstSpread = 0;
    for (const Row &r : rows) {
        if (r.ok && r.rounds > 1 && r.median > 0 && !below_noise(r, step)) {
            const double spread =
                (double)(r.medianWorst - std::min(r.medianWorst, r.median)) / (double)r.median;
            if (!worst || spread > worstSpread) {
                worst = &r;
                worstSpread = spread;
            }
        }
    }
    if (worst) {
        std::fprintf(out,
                     "Rounds: the highest round median of a row was at most %.0f%% above the "
                     "row's median (%s %s, %s light;\n  rows marked ~ left out).\n",
                     100.0 * worstSpread, routine_name(worst->routine), worst->variant->name,
                     worst->moving ? "moving" : "fixed");
    }
    int failed = 0;
    for (const Row &r : rows) {
        if (!r.ok) {
            if (!failed++) {
                std::fprintf(out, "\n");
            }
            std::fprintf(out, "FAILED %s %s (%s light): %s\n", routine_name(r.routine),
                         r.variant->name, r.moving ? "moving" : "fixed", r.failure.c_str());
        }
    }
    std::fflush(out);
    if (failed) {
        std::fprintf(stderr, "shadowvol bench: %d row%s failed the check against c_ref\n", failed,
                     failed == 1 ? "" : "s");
        return 1;
    }
    return 0;
}

} // namespace svbench
