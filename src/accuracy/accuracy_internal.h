/*
 * Internal entry points of the accuracy library, for its own C++ files and
 * for the tests (tests/unit/test_accuracy.cpp reaches the exact stage directly to
 * check the filter against it).
 *
 * Copyright (C) 2026 the shadowvol authors. LGPL-2.1-or-later.
 */
#ifndef SV_ACCURACY_INTERNAL_H
#define SV_ACCURACY_INTERNAL_H

#include "shadowvol.h"

#ifdef __cplusplus
extern "C" {
#endif

/* Upper bound on the components of det's expansion: three products of a
 * 2-component difference with a minor of at most 16 components. */
#define SV_EXACT_DET_MAX_COMPONENTS 192

/* det = ((p1 - p0) x (p2 - p0)) . (L - w p0) as an expansion (increasing
 * magnitude, nonoverlapping, zero-eliminated); returns its length (>= 1).
 * Needs finite input and round-to-nearest without FTZ/DAZ: call it with
 * the caller's MXCSR at its default (or between sv_mxcsr_enter/leave). */
int sv_exact_det_expansion(const float p0[3], const float p1[3], const float p2[3],
                           const Vec4 *light, double det[SV_EXACT_DET_MAX_COMPONENTS]);

/* The exact stage alone (no filter): the same contract as
 * sv_facing_exact_sign, for checking the filter. */
int sv_facing_exact_sign_unfiltered(const float p0[3], const float p1[3], const float p2[3],
                                    const Vec4 *light);

/* 1 when the double filter decides the sign alone, 0 when sv_facing_exact_sign
 * falls back to the exact stage (also 1 for non-finite input). */
int sv_exact_filter_decides(const float p0[3], const float p1[3], const float p2[3],
                            const Vec4 *light);

/* |(p1 - p0) x (p2 - p0)| from the exact cross product, relative error below
 * 2^-50 (finite input; 0 for a zero-area triangle). MXCSR-guarded. */
double sv_exact_normal_length(const float p0[3], const float p1[3], const float p2[3]);

/* det with relative error below 2^-45, and its exact sign (-1, 0, +1) in
 * *sign; NaN and sign 0 for non-finite input. MXCSR-guarded. */
double sv_exact_det_estimate(const float p0[3], const float p1[3], const float p2[3],
                             const Vec4 *light, int *sign);

/* D = det / |n| with relative error below 2^-44; 0 when det = 0 (including
 * every zero-area triangle); NaN for non-finite input. MXCSR-guarded. */
double sv_exact_signed_distance(const float p0[3], const float p1[3], const float p2[3],
                                const Vec4 *light);

#ifdef __cplusplus
}
#endif

#endif
