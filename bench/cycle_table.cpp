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
    Routine routine;
    const sv_variant *variant;
    bool moving;
    bool ok = true;
    std::string failure;
    int rounds = 0;                         /* rounds measured so far */
    uint64_t min = 0, median = 0;           /* ticks, the fences' cost subtracted */
    uint64_t emptyMedian = 0, emptyIqr = 0; /* empty regions of the round kept */
    uint64_t medianWorst = 0;               /* the highest of the rounds' medians */
};

/* The work buffers every call writes: facing (copied from the pattern
 * before each call, canary bytes after its numTriangles + 1 bytes) and the
 * output (capacity of sv_shadow_volume_capacity, canary ints after it). */
struct Buffers {
    AlignedArray<uint8_t> facing;
    AlignedArray<int> out;
    size_t facingBytes = 0;
    size_t outCap = 0;
};

struct Context {
    const Workload *w;
    const std::vector<Expected> *expected; /* per pattern, for this routine */
    Buffers *buf;
    int runs, warmup, patterns;
    int round;
};

/* A median below kNoiseFactor times the larger of the TSC's step and the
 * interquartile range of the row's empty regions is mostly timer noise: its
 * speed-up is printed with a "~". */
constexpr uint64_t kNoiseFactor = 5;

bool below_noise(const Row &r, uint64_t step) {
    return r.median < kNoiseFactor * std::max(step, r.emptyIqr);
}

bool is_index_routine(Routine r) {
    return r != Routine::count_facing && r != Routine::count_facing_cull;
}

int elements_of(Routine r, const Workload &w) {
    return r == Routine::create_sil_triangles ? w.numSilEdges : w.numTriangles;
}

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

/* Compares one call's result with the paper's C, outside the timed region:
 * the count, output[0 .. count), the whole facing array (cull routines
 * modify it; the others must not), and the canaries past both buffers.
 * Returns an empty string when all agree, else what differed first. */
std::string check_call(const Expected &e, int got, const Buffers &buf) {
    char msg[160];
    if (got != e.count) {
        std::snprintf(msg, sizeof msg, "returned %d, c_ref %d", got, e.count);
        return msg;
    }
    if (!e.out.empty() && std::memcmp(buf.out.data(), e.out.data(), e.out.size() * sizeof(int))) {
        size_t i = 0;
        while (buf.out[i] == e.out[i]) {
            i++;
        }
        std::snprintf(msg, sizeof msg, "output[%zu] = %d, c_ref %d", i, buf.out[i], e.out[i]);
        return msg;
    }
    if (std::memcmp(buf.facing.data(), e.facing.data(), e.facing.size())) {
        size_t i = 0;
        while (buf.facing[i] == e.facing[i]) {
            i++;
        }
        std::snprintf(msg, sizeof msg, "facing[%zu] = %d after the call, c_ref %d", i,
                      buf.facing[i], e.facing[i]);
        return msg;
    }
    for (int i = 0; i < kCanaryBytes; i++) {
        if (buf.facing[buf.facingBytes + (size_t)i] != (uint8_t)kCanaryValue) {
            return "wrote past the facing array";
        }
    }
    for (int i = 0; i < kCanaryInts; i++) {
        if (buf.out[buf.outCap + (size_t)i] != kCanaryValue) {
            return "wrote past the output capacity";
        }
    }
    return std::string();
}

/* The cost of the fences themselves, subtracted from the calls. It is not
 * one constant: where a hypervisor traps cpuid, its cost drifts by 20% in
 * phases of a fraction of a second to seconds (12.6k to 15.4k ticks on one
 * VM), so a minimum taken once at start-up would add the drift to every
 * figure. Each row therefore times an empty region right before every call,
 * and compares like with like over the same stretch of time:
 *   min    = min of the calls    - min of the empty regions
 *   median = median of the calls - median of the empty regions
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

template <class Timer, class Call> void measure_row(const Call &call, const Context &c, Row &row) {
    Buffers &buf = *c.buf;
    const Workload &w = *c.w;
    std::vector<uint64_t> calls((size_t)c.runs), empties((size_t)c.runs);
    /* (Re-)arm the canaries: a row that broke them failed alone. */
    std::fill_n(buf.facing.data() + buf.facingBytes, kCanaryBytes, (uint8_t)kCanaryValue);
    std::fill_n(buf.out.data() + buf.outCap, kCanaryInts, kCanaryValue);
    for (int r = -c.warmup; r < c.runs; r++) {
        const int p = row.moving ? (r + c.warmup) % c.patterns : 0;
        const Expected &e = (*c.expected)[(size_t)p];
        /* Fresh input and poisoned output, outside the timed region. */
        std::memcpy(buf.facing.data(), w.patterns[(size_t)p].facing.data(), buf.facingBytes);
        std::fill_n(buf.out.data(), e.out.size(), kPoison);
        const uint64_t empty = empty_region<Timer>();

        const uint64_t t0 = Timer::begin();
        const int got = call(buf.facing.data(), buf.out.data());
        const uint64_t t1 = Timer::end();

        std::string why = check_call(e, got, buf);
        if (!why.empty()) {
            char where[120];
            if (r < 0) {
                std::snprintf(where, sizeof where, "pattern %d, round %d, warm-up call %d: ", p,
                              c.round + 1, r + c.warmup + 1);
            } else {
                std::snprintf(where, sizeof where, "pattern %d, round %d, timed call %d: ", p,
                              c.round + 1, r + 1);
            }
            row.failure = where + why;
            row.ok = false;
            return;
        }
        if (r >= 0) {
            calls[(size_t)r] = t1 - t0;
            empties[(size_t)r] = empty;
        }
    }
    std::sort(calls.begin(), calls.end());
    std::sort(empties.begin(), empties.end());
    const size_t n = calls.size(), mid = (n - 1) / 2;
    const uint64_t min = saturating_sub(calls[0], empties[0]);
    const uint64_t median = saturating_sub(calls[mid], empties[mid]);
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
                  const Overhead &ovh, uint64_t step, const std::vector<Row> &rows,
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
                 "          before every call and subtracts their min from the calls' min, "
                 "their median from the calls'\n"
                 "          median (the rows' empty-region medians ranged %llu..%llu ticks)\n",
                 (unsigned long long)ovh.min, (unsigned long long)ovh.median,
                 (unsigned long long)ovh.p90, ovh.tries, (unsigned long long)(hi ? lo : 0),
                 (unsigned long long)hi);
    const int rounds = std::max(1, std::min(o.rounds, o.runs));
    std::fprintf(out,
                 "runs      %d timed calls per row in %d round%s over all rows, each after "
                 "%d warm-up calls; every call\n          checked against c_ref. A row keeps "
                 "its lowest min and its lowest round median\n",
                 o.runs, rounds, rounds == 1 ? "" : "s", o.warmup);
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
        std::fprintf(out, "%10llu %10llu %9.2f %9.2f ", (unsigned long long)r.min,
                     (unsigned long long)r.median, (double)r.min / el, (double)r.median / el);
        const Row *ref = nullptr;
        for (const Row &x : rows) {
            if (x.moving == moving && x.routine == r.routine &&
                std::strcmp(x.variant->name, "c_ref") == 0 && x.ok) {
                ref = &x;
            }
        }
        if (ref && r.median > 0) {
            const bool noisy = below_noise(r, step) || below_noise(*ref, step);
            std::fprintf(out, "%s%6.2fx | ", noisy ? "~" : " ",
                         (double)ref->median / (double)r.median);
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
                Row row{r, v, moving, true, {}, 0, 0, 0, 0, 0, 0};
                rows.push_back(row);
            }
        }
    }

    Buffers buf;
    buf.facingBytes = (size_t)w.numTriangles + 1;
    buf.facing = AlignedArray<uint8_t>(buf.facingBytes + kCanaryBytes);
    buf.outCap = sv_shadow_volume_capacity(w.numIndices, w.numSilEdges);
    buf.out = AlignedArray<int>(buf.outCap + kCanaryInts);

    std::vector<std::vector<Expected>> expected((size_t)kNumRoutines);
    for (Routine r : routines) {
        expected[(size_t)r] = expected_results(r, w);
        sanity_check_expected(r, w, expected[(size_t)r]);
    }

    const double tscHz = estimate_tsc_hz(o.tscSeconds);
    const Overhead ovh = measure_overhead(o.timer, o.overheadTries);
    const uint64_t step = tsc_step();

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
            Context c{&w, &expected[(size_t)row.routine], &buf, runs, o.warmup, o.patterns, round};
            measure(o.timer, c, row);
        }
    }
    for (Row &row : rows) {
        /* Estimated apart, the two can cross when the call is shorter than
         * the timer's jitter; the median is then shown equal to the min. */
        row.median = std::max(row.median, row.min);
    }
    progress.finish();

    print_header(out, o, w, cpu, tscHz, ovh, step, rows, skipped);
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
