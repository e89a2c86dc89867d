/*
 * Serialised time-stamp counter reads for the cycle table (DESIGN.md
 * section 5), the overhead of an empty timed region, the TSC rate, and
 * pinning the measuring thread to one CPU.
 *
 * The unit is the TSC "tick". On the paper's Pentium 4 the TSC counted core
 * clocks; on every CPU since (invariant TSC) it counts at a fixed reference
 * rate whatever the core clock does, so ticks are not core cycles.
 *
 * Three ways to fence the counter, one struct each, so the timed loop is a
 * template with nothing but the fences around the measured call:
 *
 *   rdtscp  begin: lfence; rdtsc; lfence   end: rdtscp; lfence
 *           lfence before rdtsc waits for earlier instructions to finish; the
 *           lfence after it keeps the measured code from starting before the
 *           stamp; rdtscp waits for the measured code to finish before it
 *           reads, and the final lfence keeps later code out of the region.
 *   cpuid   begin: cpuid; rdtsc            end: cpuid; rdtsc
 *           For CPUs without RDTSCP. cpuid is fully serialising, so the end
 *           stamp is taken only after the measured code has retired (a plain
 *           rdtsc there could execute while the routine is still in flight).
 *           Costly where a hypervisor traps cpuid (~10^4 ticks) but steady;
 *           the overhead is measured and subtracted.
 *   lfence  begin and end: lfence; rdtsc; lfence
 *           Cheapest. Exact on Intel and on AMD where LFENCE is dispatch-
 *           serialising (Zen 2 and later; older AMD only with the MSR bit
 *           the kernel sets for Spectre mitigation).
 *
 * Copyright (C) 2026 the shadowvol authors. LGPL-2.1-or-later.
 */
#ifndef SV_BENCH_TIMER_H
#define SV_BENCH_TIMER_H

#include <cstdint>

namespace svbench {

enum class TimerKind { rdtscp, cpuid, lfence };

struct TscRdtscp {
    static inline uint64_t begin() {
        uint32_t lo, hi;
        __asm__ __volatile__("lfence\n\trdtsc\n\tlfence" : "=a"(lo), "=d"(hi) : : "memory");
        return (uint64_t)hi << 32 | lo;
    }
    static inline uint64_t end() {
        uint32_t lo, hi, aux;
        __asm__ __volatile__("rdtscp\n\tlfence" : "=a"(lo), "=d"(hi), "=c"(aux) : : "memory");
        (void)aux;
        return (uint64_t)hi << 32 | lo;
    }
};

struct TscCpuid {
    static inline uint64_t stamp() {
        uint32_t lo, hi;
        /* cpuid leaf 0 writes eax, ebx, ecx, edx; rdtsc then overwrites eax
         * and edx with the stamp. */
        __asm__ __volatile__("cpuid\n\trdtsc"
                             : "=a"(lo), "=d"(hi)
                             : "0"(0u)
                             : "rbx", "rcx", "memory");
        return (uint64_t)hi << 32 | lo;
    }
    static inline uint64_t begin() { return stamp(); }
    static inline uint64_t end() { return stamp(); }
};

struct TscLfence {
    static inline uint64_t stamp() {
        uint32_t lo, hi;
        __asm__ __volatile__("lfence\n\trdtsc\n\tlfence" : "=a"(lo), "=d"(hi) : : "memory");
        return (uint64_t)hi << 32 | lo;
    }
    static inline uint64_t begin() { return stamp(); }
    static inline uint64_t end() { return stamp(); }
};

/* CPUID 0x80000001 EDX bit 27. */
bool cpu_has_rdtscp();
/* CPUID 0x80000007 EDX bit 8 (the TSC runs at a constant rate in all
 * power states). Hypervisors often hide it even when the TSC is steady. */
bool cpu_has_invariant_tsc();

/* "rdtscp", "cpuid", "lfence". */
const char *timer_name(TimerKind kind);
/* The instruction sequences, for the table header. */
const char *timer_sequence(TimerKind kind);
/* auto: rdtscp where the CPU has it, else cpuid. */
TimerKind timer_auto();

struct Overhead {
    uint64_t min;    /* the cost of the fences alone */
    uint64_t median; /* with min and p90: how much the empty region jitters */
    uint64_t p90;
    int tries;
};
/* Times an empty region TRIES times (after a short warm-up). */
Overhead measure_overhead(TimerKind kind, int tries);

/* The smallest step between two back-to-back rdtsc reads that differ: the
 * counter's resolution as this thread sees it (a hypervisor may scale the
 * TSC so that it advances in steps of many ticks). */
uint64_t tsc_step();

/* TSC ticks per second: rdtsc against CLOCK_MONOTONIC over SECONDS. */
double estimate_tsc_hz(double seconds);

/* Pins the calling thread to the CPU it runs on now. Returns that CPU, or
 * -1 when pinning failed (the table header says so). */
int pin_to_current_cpu();

/* Seconds on CLOCK_MONOTONIC. */
double monotonic_seconds();

} // namespace svbench

#endif
