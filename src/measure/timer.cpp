/*
 * Copyright (C) 2026 the shadowvol authors. LGPL-2.1-or-later.
 */
#include "timer.h"

#include <algorithm>
#include <vector>

#include <cpuid.h>
#include <sched.h>
#include <time.h>

namespace svbench {

static bool extended_edx_bit(unsigned leaf, unsigned bit) {
    unsigned a, b, c, d;
    if ((unsigned)__get_cpuid_max(0x80000000u, nullptr) < leaf) {
        return false;
    }
    if (!__get_cpuid(leaf, &a, &b, &c, &d)) {
        return false;
    }
    return (d >> bit) & 1u;
}

bool cpu_has_rdtscp() { return extended_edx_bit(0x80000001u, 27); }

bool cpu_has_invariant_tsc() { return extended_edx_bit(0x80000007u, 8); }

const char *timer_name(TimerKind kind) {
    switch (kind) {
    case TimerKind::rdtscp: return "rdtscp";
    case TimerKind::cpuid: return "cpuid";
    case TimerKind::lfence: return "lfence";
    }
    return "?";
}

const char *timer_sequence(TimerKind kind) {
    switch (kind) {
    case TimerKind::rdtscp: return "lfence; rdtsc; lfence | call | rdtscp; lfence";
    case TimerKind::cpuid: return "cpuid; rdtsc | call | cpuid; rdtsc";
    case TimerKind::lfence: return "lfence; rdtsc; lfence | call | lfence; rdtsc; lfence";
    }
    return "?";
}

TimerKind timer_auto() { return cpu_has_rdtscp() ? TimerKind::rdtscp : TimerKind::cpuid; }

template <class Timer> static Overhead overhead_with(int tries) {
    std::vector<uint64_t> t((size_t)tries);
    for (int i = 0; i < 64; i++) { /* warm the path and the predictor */
        uint64_t t0 = Timer::begin();
        uint64_t t1 = Timer::end();
        (void)t0;
        (void)t1;
    }
    for (int i = 0; i < tries; i++) {
        uint64_t t0 = Timer::begin();
        uint64_t t1 = Timer::end();
        t[(size_t)i] = t1 - t0;
    }
    std::sort(t.begin(), t.end());
    return Overhead{t.front(), t[t.size() / 2], t[t.size() * 9 / 10], tries};
}

Overhead measure_overhead(TimerKind kind, int tries) {
    if (tries < 1) {
        tries = 1;
    }
    switch (kind) {
    case TimerKind::rdtscp: return overhead_with<TscRdtscp>(tries);
    case TimerKind::cpuid: return overhead_with<TscCpuid>(tries);
    case TimerKind::lfence: return overhead_with<TscLfence>(tries);
    }
    return Overhead{0, 0, 0, 0};
}

double monotonic_seconds() {
    struct timespec ts;
    clock_gettime(CLOCK_MONOTONIC, &ts);
    return (double)ts.tv_sec + (double)ts.tv_nsec * 1e-9;
}

uint64_t tsc_step() {
    uint64_t step = UINT64_MAX;
    uint64_t prev = __builtin_ia32_rdtsc();
    for (int seen = 0; seen < 1000;) {
        const uint64_t t = __builtin_ia32_rdtsc();
        if (t != prev) {
            step = std::min(step, t - prev);
            prev = t;
            seen++;
        }
    }
    return step;
}

double estimate_tsc_hz(double seconds) {
    /* Bracket each clock read by two TSC reads and keep their midpoint, so
     * the cost of clock_gettime does not bias the rate. */
    uint64_t a0 = TscLfence::stamp();
    double s0 = monotonic_seconds();
    uint64_t b0 = TscLfence::stamp();
    double s1;
    uint64_t a1, b1;
    do {
        a1 = TscLfence::stamp();
        s1 = monotonic_seconds();
        b1 = TscLfence::stamp();
    } while (s1 - s0 < seconds);
    const uint64_t mid0 = a0 + (b0 - a0) / 2, mid1 = a1 + (b1 - a1) / 2;
    double ticks = (double)mid1 - (double)mid0;
    return ticks / (s1 - s0);
}

int pin_to_current_cpu() {
    int cpu = sched_getcpu();
    if (cpu < 0) {
        return -1;
    }
    cpu_set_t set;
    CPU_ZERO(&set);
    CPU_SET(cpu, &set);
    if (sched_setaffinity(0, sizeof set, &set) != 0) {
        return -1;
    }
    return cpu;
}

} // namespace svbench
