/*
 * The floating-point environment of the accuracy routines: round to
 * nearest even, FTZ and DAZ off, every exception masked, for the duration
 * of one call; a caller whose MXCSR differs from that gets its own back on
 * return.
 *
 * Why: the exact predicate's expansion arithmetic is exact only in round to
 * nearest, and DAZ would read a subnormal float as 0 before it is converted
 * to double; the inexact variants' error bounds assume gradual underflow.
 * With the guard, a caller's FTZ/DAZ (common in games and audio code) or
 * rounding mode changes no facing byte of these routines.
 *
 * Cost: a caller already in the default mode pays one stmxcsr; any other
 * pays two ldmxcsr per call (a few tens of cycles against thousands for a
 * surface). The exception flags our arithmetic raises (inexact, mostly)
 * stay raised, as they would for any float code.
 *
 * The guarded work must sit in a separate noinline function: the compiler
 * does not see MXCSR as a dependency of arithmetic, so arithmetic written
 * between sv_mxcsr_enter and sv_mxcsr_leave in the same function could be
 * moved across them; a call to an opaque function cannot.
 *
 * Copyright (C) 2026 the shadowvol authors. LGPL-2.1-or-later.
 */
#ifndef SV_ACCURACY_MXCSR_GUARD_H
#define SV_ACCURACY_MXCSR_GUARD_H

#include <xmmintrin.h>

/* All six exceptions masked (bits 7-12), round to nearest (bits 13-14 =
 * 0), FTZ (bit 15) and DAZ (bit 6) off. Bits 0-5 are the sticky flags. */
#define SV_MXCSR_DEFAULT 0x1F80u
#define SV_MXCSR_FLAGS 0x3Fu

static inline unsigned sv_mxcsr_enter(void) {
    const unsigned saved = _mm_getcsr();
    if ((saved & ~SV_MXCSR_FLAGS) != SV_MXCSR_DEFAULT) _mm_setcsr(SV_MXCSR_DEFAULT);
    return saved;
}

static inline void sv_mxcsr_leave(unsigned saved) {
    if ((saved & ~SV_MXCSR_FLAGS) != SV_MXCSR_DEFAULT) _mm_setcsr(saved);
}

#endif
