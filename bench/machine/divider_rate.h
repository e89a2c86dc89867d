/*
 * The rate of this core's floating-point divider in double precision,
 * measured in the run that uses it: the lighting pass's exact arithmetic
 * (a square root and two divides per lane of a point or spot light, a
 * divide per visible pixel for the camera ray) is bound by it (issue 29:
 * what bounds each pass, measured).
 *
 * Copyright (C) 2026 the shadowvol authors. LGPL-2.1-or-later.
 */
#ifndef SV_BENCH_DIVIDER_RATE_H
#define SV_BENCH_DIVIDER_RATE_H

namespace svbench {

struct DividerRate {
    double div_ticks_per_lane = 0;  /* vdivpd, independent, per double lane */
    double sqrt_ticks_per_lane = 0; /* vsqrtpd, the same */
    int lanes = 0;                  /* the vector measured: 8 (AVX-512), 4 (AVX2) or 2 (SSE2) */
    int runs = 0;                   /* the best of RUNS timed loops each */
};

/* Times long runs of independent divides and square roots in the widest
 * vector this CPU has (the one the lighting pass's row kernel uses), in
 * TSC ticks per lane, the best of RUNS. */
DividerRate measure_divider_rate(int runs);

} // namespace svbench

#endif
