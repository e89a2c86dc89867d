/*
 * Exact floating-point expansion arithmetic for the orientation predicate,
 * after J. R. Shewchuk, "Adaptive Precision Floating-Point Arithmetic and
 * Fast Robust Geometric Predicates", Discrete & Computational Geometry 18,
 * 1997 (written here from the paper's algorithms).
 *
 * An expansion is a sum of doubles e[0] + e[1] + ... + e[n-1], nonoverlapping
 * and ordered by increasing magnitude, with no zero components (except the
 * single component of an expansion that is 0): its sign is the sign of its
 * last component, and its value is exact.
 *
 * Preconditions of every routine here, and why they hold in this project:
 *  - IEEE double, round to nearest even, no FMA contraction: the files that
 *    include this header are compiled with -ffp-contract=off, and the public
 *    routines set MXCSR to round-to-nearest with FTZ/DAZ off (mxcsr_guard.h).
 *  - No overflow or underflow: inputs are floats or products of two floats,
 *    so every quantity in a 3x3 determinant of float differences lies between
 *    2^-447 (the product of three subnormal granules 2^-149) and 2^390, far
 *    inside the normal doubles; Dekker's split multiplies by 2^27 + 1, still
 *    far from overflow.
 *
 * Copyright (C) 2026 the shadowvol authors. LGPL-2.1-or-later.
 */
#ifndef SV_ACCURACY_EXPANSION_H
#define SV_ACCURACY_EXPANSION_H

/* x + y = a + b exactly, x = fl(a + b). Needs |a| >= |b| (or a = 0). */
static inline void sv_fast_two_sum(double a, double b, double *x, double *y) {
    const double s = a + b;
    const double bv = s - a;
    *x = s;
    *y = b - bv;
}

/* x + y = a + b exactly, x = fl(a + b), any order of magnitude. */
static inline void sv_two_sum(double a, double b, double *x, double *y) {
    const double s = a + b;
    const double bv = s - a;
    const double av = s - bv;
    *x = s;
    *y = (a - av) + (b - bv);
}

/* x + y = a - b exactly, x = fl(a - b). */
static inline void sv_two_diff(double a, double b, double *x, double *y) {
    const double s = a - b;
    const double bv = a - s;
    const double av = s + bv;
    *x = s;
    *y = (a - av) + (bv - b);
}

/* a = hi + lo with hi and lo of at most 26 significant bits (Dekker). */
static inline void sv_split(double a, double *hi, double *lo) {
    const double c = 134217729.0 * a; /* 2^27 + 1 */
    const double big = c - a;
    *hi = c - big;
    *lo = a - *hi;
}

/* x + y = a * b exactly, x = fl(a * b) (Dekker, no FMA needed). */
static inline void sv_two_product(double a, double b, double *x, double *y) {
    double ahi, alo, bhi, blo;
    const double p = a * b;
    sv_split(a, &ahi, &alo);
    sv_split(b, &bhi, &blo);
    const double err1 = p - ahi * bhi;
    const double err2 = err1 - alo * bhi;
    const double err3 = err2 - ahi * blo;
    *x = p;
    *y = alo * blo - err3;
}

/* h = e * b; h needs room for 2 * elen components. Returns its length. */
static inline int sv_scale_expansion(int elen, const double *e, double b, double *h) {
    double q, hh, p1, p0, sum;
    int n = 0;
    sv_two_product(e[0], b, &q, &hh);
    if (hh != 0.0) h[n++] = hh;
    for (int i = 1; i < elen; i++) {
        sv_two_product(e[i], b, &p1, &p0);
        sv_two_sum(q, p0, &sum, &hh);
        if (hh != 0.0) h[n++] = hh;
        sv_fast_two_sum(p1, sum, &q, &hh);
        if (hh != 0.0) h[n++] = hh;
    }
    if (q != 0.0 || n == 0) h[n++] = q;
    return n;
}

/* h = e + f (Shewchuk's fast expansion sum with zero elimination: merge
 * the components by magnitude, then carry); h needs elen + flen. Unlike the
 * paper's code this never reads e[elen] or f[flen]. Returns its length. */
static inline int sv_expansion_sum(int elen, const double *e, int flen, const double *f,
                                   double *h) {
    int ei = 0, fi = 0, n = 0;
    double q, qnew, hh;
    double en = e[0], fn = f[0];
/* The next component of the merge: the one of smaller magnitude. */
#define SV_E_SMALLER ((fn > en) == (fn > -en))
    if (SV_E_SMALLER) {
        q = en;
        en = ++ei < elen ? e[ei] : 0.0;
    } else {
        q = fn;
        fn = ++fi < flen ? f[fi] : 0.0;
    }
    if (ei < elen && fi < flen) {
        if (SV_E_SMALLER) {
            sv_fast_two_sum(en, q, &qnew, &hh);
            en = ++ei < elen ? e[ei] : 0.0;
        } else {
            sv_fast_two_sum(fn, q, &qnew, &hh);
            fn = ++fi < flen ? f[fi] : 0.0;
        }
        q = qnew;
        if (hh != 0.0) h[n++] = hh;
        while (ei < elen && fi < flen) {
            if (SV_E_SMALLER) {
                sv_two_sum(q, en, &qnew, &hh);
                en = ++ei < elen ? e[ei] : 0.0;
            } else {
                sv_two_sum(q, fn, &qnew, &hh);
                fn = ++fi < flen ? f[fi] : 0.0;
            }
            q = qnew;
            if (hh != 0.0) h[n++] = hh;
        }
    }
#undef SV_E_SMALLER
    while (ei < elen) {
        sv_two_sum(q, en, &qnew, &hh);
        en = ++ei < elen ? e[ei] : 0.0;
        q = qnew;
        if (hh != 0.0) h[n++] = hh;
    }
    while (fi < flen) {
        sv_two_sum(q, fn, &qnew, &hh);
        fn = ++fi < flen ? f[fi] : 0.0;
        q = qnew;
        if (hh != 0.0) h[n++] = hh;
    }
    if (q != 0.0 || n == 0) h[n++] = q;
    return n;
}

/* h = e * f (every component of f scales e; the partial products summed);
 * h needs 2 * elen * flen, scratch 2 * elen * flen + 2 * elen. */
static inline int sv_expansion_product(int elen, const double *e, int flen, const double *f,
                                       double *h, double *scratch) {
    double *part = scratch;           /* 2 * elen */
    double *acc = scratch + 2 * elen; /* the running sum */
    int n = sv_scale_expansion(elen, e, f[0], h);
    for (int j = 1; j < flen; j++) {
        const int pn = sv_scale_expansion(elen, e, f[j], part);
        for (int k = 0; k < n; k++) acc[k] = h[k];
        n = sv_expansion_sum(n, acc, pn, part, h);
    }
    return n;
}

/* The expansion's value rounded: its components summed from the smallest
 * (relative error a few ulps). */
static inline double sv_expansion_estimate(int n, const double *e) {
    double s = e[0];
    for (int i = 1; i < n; i++) s += e[i];
    return s;
}

/* a - b as an expansion of 1 or 2 components (for a and b doubles). */
static inline int sv_diff_expansion(double a, double b, double out[2]) {
    double x, y;
    sv_two_diff(a, b, &x, &y);
    if (y == 0.0) {
        out[0] = x;
        return 1;
    }
    out[0] = y;
    out[1] = x;
    return 2;
}

#endif
