/*
 * Plane derivation and facing from positions (include/shadowvol_planes.h)
 * with SSE2, AVX2 and AVX-512, BIT-IDENTICAL to the C references in
 * planes_internal.h: the same float operations in the same order, no FMA
 * (the file is built with -ffp-contract=off and uses no FMA intrinsics);
 * sqrt and division are correctly rounded in both; the zero-plane rule is
 * the same ordered compares. Triangles the SIMD path finds outside
 * 0 < len2 < inf (rare: zero area, under- or overflow, NaN) are rewritten
 * after the step by the scalar reference expression.
 *
 * The work is in the data movement: a triangle's nine coordinates come
 * from three random vertices, as three rows (x, y, z, .), and the
 * arithmetic wants them as columns (eight x0, eight y0, ...).
 *
 *  - avx2_gather: nine vgatherdps per 8 triangles (the indices
 *    deinterleaved from three loads by blends and vpermd). No transpose on
 *    the way in; 4x4 transposes on the way out.
 *  - sse2: each corner loaded as 8 + 4 bytes (movsd, movss, movlhps), a
 *    4x4 transpose (7 shuffles for 3 columns) per corner.
 *  - avx2 (derive): see "sv_derive_planes_avx2" below: blocks in two
 *    passes, every row (0, x, y, z) by one masked load, 4x4 transposes.
 *  - avx2 (facing) / avx512: each corner one masked 16-byte load that cannot fault
 *    on its masked-out float and never reads past the array: EVEN rows from
 *    the vertex itself with mask (1,1,1,0) -> (x, y, z, 0), ODD rows from
 *    one float before it with mask (0,1,1,1) -> (0, x, y, z). Two such rows
 *    give (x0, x1, z0, z1) and (x0, y0, y1, 0) by one blend each (blends run
 *    on all four FP pipes of Zen 3, shuffles on two), so three columns of
 *    four rows cost 4 blends + 3 shuffles instead of 7 shuffles. The edges
 *    are subtracted on the rows (e1 = row(p1) - row(p0), lane by lane: the
 *    same subtraction as the column one).
 *    Planes go back to rows by a 4x4 transpose; the rows are paired so
 *    that each 256-bit (512-bit) register holds consecutive planes: one
 *    full-width unaligned store each.
 *
 * Tails: AVX-512 hands the last < 16 triangles to AVX2, AVX2 the last < 8
 * to the scalar reference expression, SSE2 likewise.
 *
 * Copyright (C) 2026 the shadowvol authors. LGPL-2.1-or-later.
 */
#include <immintrin.h>
#include <stdint.h>
#include <string.h>

#include "planes_avx512_normal.h"
#include "planes_internal.h"
#include "planes_store_avx2.h"
#include "../core/mask_bytes.h"
#include "../core/simd_exit.h"

/* The address of vertex I minus SHIFT floats (shift 1 for the odd rows),
 * through uintptr_t: for vertex 0 it points before the array, where the
 * masked load reads nothing. The index is taken as unsigned (a valid one
 * is >= 0), so the address is one lea and the load's own addressing. */
static inline const float *corner_shifted(const float *positions, int index, int shift) {
    return (const float *)((uintptr_t)positions - (uintptr_t)(4 * shift) +
                           12 * (uintptr_t)(uint32_t)index);
}

/* ---- SSE2 ------------------------------------------------------------------ */

static inline __m128 load3_sse2(const float *p) {
    /* x and y as one 8-byte load (movsd); through memcpy, since a vertex
     * is only 4-byte aligned and a misaligned double is undefined in C. */
    double xy_bits;
    memcpy(&xy_bits, p, sizeof xy_bits);
    const __m128 xy = _mm_castpd_ps(_mm_set_sd(xy_bits));
    return _mm_movelh_ps(xy, _mm_load_ss(p + 2));
}

/* Rows (x, y, z, .) of four structures -> their x, y, z columns. */
#define TRANSPOSE3_SSE2(r0, r1, r2, r3, X, Y, Z)                                                   \
    do {                                                                                           \
        const __m128 t0_ = _mm_unpacklo_ps(r0, r1);                                                \
        const __m128 t1_ = _mm_unpacklo_ps(r2, r3);                                                \
        const __m128 t2_ = _mm_unpackhi_ps(r0, r1);                                                \
        const __m128 t3_ = _mm_unpackhi_ps(r2, r3);                                                \
        (X) = _mm_movelh_ps(t0_, t1_);                                                             \
        (Y) = _mm_movehl_ps(t1_, t0_);                                                             \
        (Z) = _mm_movelh_ps(t2_, t3_);                                                             \
    } while (0)

/* The columns of p0, e1 and e2 of triangles T .. T+3. */
#define LOAD_TRI4_SSE2(positions, ix)                                                              \
    __m128 px, py, pz, ax, ay, az, bx, by, bz;                                                     \
    do {                                                                                           \
        __m128 r0_[4], r1_[4], r2_[4];                                                             \
        for (int i_ = 0; i_ < 4; i_++) {                                                           \
            r0_[i_] = load3_sse2(sv_planes_corner(positions, (ix)[3 * i_]));                       \
            r1_[i_] = _mm_sub_ps(load3_sse2(sv_planes_corner(positions, (ix)[3 * i_ + 1])),        \
                                 r0_[i_]);                                                         \
            r2_[i_] = _mm_sub_ps(load3_sse2(sv_planes_corner(positions, (ix)[3 * i_ + 2])),        \
                                 r0_[i_]);                                                         \
        }                                                                                          \
        TRANSPOSE3_SSE2(r0_[0], r0_[1], r0_[2], r0_[3], px, py, pz);                               \
        TRANSPOSE3_SSE2(r1_[0], r1_[1], r1_[2], r1_[3], ax, ay, az);                               \
        TRANSPOSE3_SSE2(r2_[0], r2_[1], r2_[2], r2_[3], bx, by, bz);                               \
    } while (0)

void sv_derive_planes_sse2(const float *positions, const int *indices, int numTriangles,
                           Plane *planes) {
    const __m128 zero = _mm_setzero_ps(), inf = _mm_set1_ps(INFINITY), one = _mm_set1_ps(1.0f);
    const __m128 sign = _mm_set1_ps(-0.0f);
    int t = 0;
    for (; numTriangles - t >= 4; t += 4) {
        const int *ix = indices + 3 * t;
        LOAD_TRI4_SSE2(positions, ix);
        const __m128 nx = _mm_sub_ps(_mm_mul_ps(ay, bz), _mm_mul_ps(az, by));
        const __m128 ny = _mm_sub_ps(_mm_mul_ps(az, bx), _mm_mul_ps(ax, bz));
        const __m128 nz = _mm_sub_ps(_mm_mul_ps(ax, by), _mm_mul_ps(ay, bx));
        const __m128 len2 = _mm_add_ps(_mm_add_ps(_mm_mul_ps(nx, nx), _mm_mul_ps(ny, ny)),
                                       _mm_mul_ps(nz, nz));
        const int ok = _mm_movemask_ps(
            _mm_and_ps(_mm_cmpgt_ps(len2, zero), _mm_cmplt_ps(len2, inf)));
        const __m128 inv = _mm_div_ps(one, _mm_sqrt_ps(len2));
        __m128 a = _mm_mul_ps(nx, inv), b = _mm_mul_ps(ny, inv), c = _mm_mul_ps(nz, inv);
        __m128 d = _mm_add_ps(_mm_add_ps(_mm_mul_ps(a, px), _mm_mul_ps(b, py)), _mm_mul_ps(c, pz));
        d = _mm_xor_ps(d, sign);
        _MM_TRANSPOSE4_PS(a, b, c, d);
        _mm_storeu_ps(&planes[t].a, a);
        _mm_storeu_ps(&planes[t + 1].a, b);
        _mm_storeu_ps(&planes[t + 2].a, c);
        _mm_storeu_ps(&planes[t + 3].a, d);
        if (ok != 0xF) {
            for (int i = 0; i < 4; i++)
                if (!(ok & (1 << i))) planes[t + i] = sv_plane_one(positions, ix + 3 * i);
        }
    }
    for (; t < numTriangles; t++) planes[t] = sv_plane_one(positions, indices + 3 * t);
}

void sv_facing_from_positions_sse2(const float *positions, const int *indices, int numTriangles,
                                   const Vec4 *light, uint8_t *facing) {
    if (numTriangles < 0) return;
    const __m128 lx = _mm_set1_ps(light->x), ly = _mm_set1_ps(light->y);
    const __m128 lz = _mm_set1_ps(light->z), lw = _mm_set1_ps(light->w);
    const __m128 zero = _mm_setzero_ps();
    int t = 0;
    for (; numTriangles - t >= 4; t += 4) {
        const int *ix = indices + 3 * t;
        LOAD_TRI4_SSE2(positions, ix);
        const __m128 nx = _mm_sub_ps(_mm_mul_ps(ay, bz), _mm_mul_ps(az, by));
        const __m128 ny = _mm_sub_ps(_mm_mul_ps(az, bx), _mm_mul_ps(ax, bz));
        const __m128 nz = _mm_sub_ps(_mm_mul_ps(ax, by), _mm_mul_ps(ay, bx));
        const __m128 vx = _mm_sub_ps(lx, _mm_mul_ps(px, lw));
        const __m128 vy = _mm_sub_ps(ly, _mm_mul_ps(py, lw));
        const __m128 vz = _mm_sub_ps(lz, _mm_mul_ps(pz, lw));
        const __m128 s = _mm_add_ps(_mm_add_ps(_mm_mul_ps(nx, vx), _mm_mul_ps(ny, vy)),
                                    _mm_mul_ps(nz, vz));
        const uint32_t m = (uint32_t)_mm_movemask_ps(_mm_cmpgt_ps(s, zero));
        /* Four mask bits -> four 0/1 bytes: copies of m at bits 0, 7, 14
         * and 21 do not overlap, so the product has no carries. */
        const uint32_t bytes = (m * 0x00204081u) & 0x01010101u;
        memcpy(facing + t, &bytes, 4);
    }
    for (; t < numTriangles; t++)
        facing[t] = sv_facing_from_positions_one(positions, indices + 3 * t, light);
    facing[numTriangles] = 1;
}

/* ---- AVX2 ------------------------------------------------------------------ */

#define SV_TARGET_AVX2 __attribute__((target("avx2")))

/* Corner rows of two triangles, one per 128-bit lane; SHIFT 0: (x,y,z,0),
 * SHIFT 1: (0,x,y,z). */
SV_TARGET_AVX2 static inline __m256 row2_avx2(const float *positions, int ia, int ib, int shift) {
    const __m128i m = shift ? _mm_setr_epi32(0, -1, -1, -1) : _mm_setr_epi32(-1, -1, -1, 0);
    const __m128 lo = _mm_maskload_ps(corner_shifted(positions, ia, shift), m);
    const __m128 hi = _mm_maskload_ps(corner_shifted(positions, ib, shift), m);
    return _mm256_insertf128_ps(_mm256_castps128_ps256(lo), hi, 1);
}

/* Rows q0, q2 (x,y,z,0) and q1, q3 (0,x,y,z), in each lane -> columns. */
#define TRANSPOSE3_AVX2(q0, q1, q2, q3, X, Y, Z)                                                   \
    do {                                                                                           \
        const __m256 xz01_ = _mm256_blend_ps(q0, q1, 0xAA); /* x0 x1 z0 z1 */                      \
        const __m256 xz23_ = _mm256_blend_ps(q2, q3, 0xAA);                                        \
        const __m256 y01_ = _mm256_blend_ps(q0, q1, 0x44); /* x0 y0 y1 0 */                        \
        const __m256 y23_ = _mm256_blend_ps(q2, q3, 0x44);                                         \
        (X) = _mm256_shuffle_ps(xz01_, xz23_, _MM_SHUFFLE(1, 0, 1, 0));                            \
        (Z) = _mm256_shuffle_ps(xz01_, xz23_, _MM_SHUFFLE(3, 2, 3, 2));                            \
        (Y) = _mm256_shuffle_ps(y01_, y23_, _MM_SHUFFLE(2, 1, 2, 1));                              \
    } while (0)

/* Row r of the step holds triangles TA(r) (low lane) and TB(r) (high). */
#define LOAD_TRI8_AVX2(positions, ix, TA, TB)                                                      \
    __m256 px, py, pz, ax, ay, az, bx, by, bz;                                                     \
    do {                                                                                           \
        __m256 r0_[4], r1_[4], r2_[4];                                                             \
        for (int r_ = 0; r_ < 4; r_++) {                                                           \
            const int *ta_ = (ix) + 3 * (TA(r_)), *tb_ = (ix) + 3 * (TB(r_));                      \
            const int s_ = r_ & 1;                                                                 \
            r0_[r_] = row2_avx2(positions, ta_[0], tb_[0], s_);                                    \
            r1_[r_] = _mm256_sub_ps(row2_avx2(positions, ta_[1], tb_[1], s_), r0_[r_]);            \
            r2_[r_] = _mm256_sub_ps(row2_avx2(positions, ta_[2], tb_[2], s_), r0_[r_]);            \
        }                                                                                          \
        TRANSPOSE3_AVX2(r0_[0], r0_[1], r0_[2], r0_[3], px, py, pz);                               \
        TRANSPOSE3_AVX2(r1_[0], r1_[1], r1_[2], r1_[3], ax, ay, az);                               \
        TRANSPOSE3_AVX2(r2_[0], r2_[1], r2_[2], r2_[3], bx, by, bz);                               \
    } while (0)

#define PAIR_A(r) (2 * (r)) /* derive: rows of consecutive planes */
#define PAIR_B(r) (2 * (r) + 1)
#define SPLIT_A(r) (r) /* facing: lanes in triangle order */
#define SPLIT_B(r) ((r) + 4)

/* The plane columns of the step (see the reference's order). */
#define PLANES_AVX2(a, b, c, d, ok)                                                                \
    __m256 a, b, c, d;                                                                             \
    unsigned ok; /* NOLINT(bugprone-macro-parentheses): a name this declares */                    \
    do {                                                                                           \
        const __m256 nx_ = _mm256_sub_ps(_mm256_mul_ps(ay, bz), _mm256_mul_ps(az, by));            \
        const __m256 ny_ = _mm256_sub_ps(_mm256_mul_ps(az, bx), _mm256_mul_ps(ax, bz));            \
        const __m256 nz_ = _mm256_sub_ps(_mm256_mul_ps(ax, by), _mm256_mul_ps(ay, bx));            \
        const __m256 len2_ = _mm256_add_ps(_mm256_add_ps(_mm256_mul_ps(nx_, nx_),                  \
                                                         _mm256_mul_ps(ny_, ny_)),                 \
                                           _mm256_mul_ps(nz_, nz_));                               \
        (ok) = (unsigned)_mm256_movemask_ps(                                                       \
            _mm256_and_ps(_mm256_cmp_ps(len2_, _mm256_setzero_ps(), _CMP_GT_OQ),                   \
                          _mm256_cmp_ps(len2_, _mm256_set1_ps(INFINITY), _CMP_LT_OQ)));            \
        const __m256 inv_ = _mm256_div_ps(_mm256_set1_ps(1.0f), _mm256_sqrt_ps(len2_));            \
        (a) = _mm256_mul_ps(nx_, inv_);                                                            \
        (b) = _mm256_mul_ps(ny_, inv_);                                                            \
        (c) = _mm256_mul_ps(nz_, inv_);                                                            \
        (d) = _mm256_add_ps(_mm256_add_ps(_mm256_mul_ps(a, px), _mm256_mul_ps(b, py)),             \
                            _mm256_mul_ps(c, pz));                                                 \
        (d) = _mm256_xor_ps(d, _mm256_set1_ps(-0.0f));                                             \
    } while (0)

/* Plane columns a..d in lane order (0 2 4 6 | 1 3 5 7) -> planes T..T+7. */
SV_TARGET_AVX2 static inline void store_planes8_pairs(Plane *out, __m256 a, __m256 b, __m256 c,
                                                      __m256 d) {
    const __m256 u0 = _mm256_unpacklo_ps(a, b), u1 = _mm256_unpacklo_ps(c, d);
    const __m256 u2 = _mm256_unpackhi_ps(a, b), u3 = _mm256_unpackhi_ps(c, d);
    _mm256_storeu_ps(&out[0].a, _mm256_shuffle_ps(u0, u1, _MM_SHUFFLE(1, 0, 1, 0)));
    _mm256_storeu_ps(&out[2].a, _mm256_shuffle_ps(u0, u1, _MM_SHUFFLE(3, 2, 3, 2)));
    _mm256_storeu_ps(&out[4].a, _mm256_shuffle_ps(u2, u3, _MM_SHUFFLE(1, 0, 1, 0)));
    _mm256_storeu_ps(&out[6].a, _mm256_shuffle_ps(u2, u3, _MM_SHUFFLE(3, 2, 3, 2)));
}

/* ---- sv_derive_planes_avx2: blocks of up to 32 steps of 8 triangles -------
 * The old one-step loop (load, transpose, cross product, sqrt, div,
 * normalise, store) is one dependency chain of about 70 cycles per step
 * (the sqrt and div alone 25) in about 170 instructions: the 256-entry
 * reorder buffer of Zen 3 holds about 1.5 steps, so the loop ran at the
 * chain's latency, not at the ports' throughput. Here a block runs in two
 * passes over a stack buffer (8 KiB, L1):
 *   pass 1, per step: 24 masked row loads, three 4x4 transposes, the edges,
 *     the cross product and len2; the zero-plane test; the columns n, p0
 *     and len2 stored; and 1/sqrt(len2) of the PREVIOUS step (its len2 is
 *     ready, so the divider works beside the loads instead of at the end
 *     of a chain);
 *   pass 2, per step: a, b, c, d from the buffer, the output transpose, 4
 *     stores.
 * Rows: every corner one masked 16-byte load from one float before the
 * vertex with mask (0,1,1,1) -> (0, x, y, z): it reads only the vertex's
 * 12 bytes (the masked-out float cannot fault, even before the array), and
 * every row has the same layout, so a plain 4x4 transpose (4 unpacks + 3
 * shuffles per 3 columns) makes the columns. Row r holds triangles 2r (low
 * lane) and 2r+1 (high lane), so each 256-bit store holds two consecutive
 * planes. Each operation is the reference's, in its order; lanes outside
 * 0 < len2 < inf are rewritten afterwards by the scalar reference. */
#define SV_PLANES_BLOCK 32

typedef struct {
    __m256 nx, ny, nz, l2, px, py, pz, pad_;
} sv_planes_step;

/* Corners A (low lane) and B (high lane) as (0, x, y, z). */
SV_TARGET_AVX2 static inline __m256 row2_shifted_avx2(const float *positions, int ia, int ib) {
    const __m128i m = _mm_setr_epi32(0, -1, -1, -1);
    const __m128 lo = _mm_maskload_ps(corner_shifted(positions, ia, 1), m);
    const __m128 hi = _mm_maskload_ps(corner_shifted(positions, ib, 1), m);
    return _mm256_insertf128_ps(_mm256_castps128_ps256(lo), hi, 1);
}

/* Rows (., x, y, z) of four structures, per lane -> their x, y, z columns. */
#define TRANSPOSE3_SHIFTED_AVX2(r0, r1, r2, r3, X, Y, Z)                                           \
    do {                                                                                           \
        const __m256 t0_ = _mm256_unpacklo_ps(r0, r1); /* . . x0 x1 */                             \
        const __m256 t1_ = _mm256_unpacklo_ps(r2, r3);                                             \
        const __m256 t2_ = _mm256_unpackhi_ps(r0, r1); /* y0 y1 z0 z1 */                           \
        const __m256 t3_ = _mm256_unpackhi_ps(r2, r3);                                             \
        (X) = _mm256_shuffle_ps(t0_, t1_, _MM_SHUFFLE(3, 2, 3, 2));                                \
        (Y) = _mm256_shuffle_ps(t2_, t3_, _MM_SHUFFLE(1, 0, 1, 0));                                \
        (Z) = _mm256_shuffle_ps(t2_, t3_, _MM_SHUFFLE(3, 2, 3, 2));                                \
    } while (0)

SV_TARGET_AVX2 static inline __m256 inv_len_avx2(__m256 len2) {
    return _mm256_div_ps(_mm256_set1_ps(1.0f), _mm256_sqrt_ps(len2));
}

/* Pass 1 of one step: triangles ix[0..24) into *st; returns the lanes
 * (bit l: see the row order above) that fail 0 < len2 < inf. */
SV_TARGET_AVX2 static inline unsigned planes_pass1_avx2(const float *positions, const int *ix,
                                                        sv_planes_step *st) {
    __m256 q0[4], q1[4], q2[4];
    for (int r = 0; r < 4; r++) {
        const int *ta = ix + 6 * r, *tb = ix + 6 * r + 3;
        q0[r] = row2_shifted_avx2(positions, ta[0], tb[0]);
        q1[r] = row2_shifted_avx2(positions, ta[1], tb[1]);
        q2[r] = row2_shifted_avx2(positions, ta[2], tb[2]);
    }
    __m256 px, py, pz, ax, ay, az, bx, by, bz;
    TRANSPOSE3_SHIFTED_AVX2(q0[0], q0[1], q0[2], q0[3], px, py, pz);
    TRANSPOSE3_SHIFTED_AVX2(q1[0], q1[1], q1[2], q1[3], ax, ay, az);
    TRANSPOSE3_SHIFTED_AVX2(q2[0], q2[1], q2[2], q2[3], bx, by, bz);
    ax = _mm256_sub_ps(ax, px);
    ay = _mm256_sub_ps(ay, py);
    az = _mm256_sub_ps(az, pz);
    bx = _mm256_sub_ps(bx, px);
    by = _mm256_sub_ps(by, py);
    bz = _mm256_sub_ps(bz, pz);
    const __m256 nx = _mm256_sub_ps(_mm256_mul_ps(ay, bz), _mm256_mul_ps(az, by));
    const __m256 ny = _mm256_sub_ps(_mm256_mul_ps(az, bx), _mm256_mul_ps(ax, bz));
    const __m256 nz = _mm256_sub_ps(_mm256_mul_ps(ax, by), _mm256_mul_ps(ay, bx));
    const __m256 len2 = _mm256_add_ps(_mm256_add_ps(_mm256_mul_ps(nx, nx), _mm256_mul_ps(ny, ny)),
                                      _mm256_mul_ps(nz, nz));
    const unsigned ok = (unsigned)_mm256_movemask_ps(
        _mm256_and_ps(_mm256_cmp_ps(len2, _mm256_setzero_ps(), _CMP_GT_OQ),
                      _mm256_cmp_ps(len2, _mm256_set1_ps(INFINITY), _CMP_LT_OQ)));
    st->nx = nx;
    st->ny = ny;
    st->nz = nz;
    st->l2 = len2;
    st->px = px;
    st->py = py;
    st->pz = pz;
    return ok ^ 0xFFu;
}

SV_TARGET_AVX2 void sv_derive_planes_avx2(const float *positions, const int *indices,
                                          int numTriangles, Plane *planes) {
    sv_planes_step buf[SV_PLANES_BLOCK];
    uint8_t bad[SV_PLANES_BLOCK];
    int t = 0;
    while (numTriangles - t >= 8) {
        int steps = (numTriangles - t) / 8;
        if (steps > SV_PLANES_BLOCK) steps = SV_PLANES_BLOCK;
        const int *ix = indices + 3 * t;
        unsigned anyBad = 0;
        for (int s = 0; s < steps; s++) {
            const unsigned b = planes_pass1_avx2(positions, ix + 24 * s, &buf[s]);
            bad[s] = (uint8_t)b;
            anyBad |= b;
            /* The previous step's 1 / sqrt(len2), in place of its len2. */
            if (s > 0) buf[s - 1].l2 = inv_len_avx2(buf[s - 1].l2);
        }
        buf[steps - 1].l2 = inv_len_avx2(buf[steps - 1].l2);
        for (int s = 0; s < steps; s++) {
            const __m256 inv = buf[s].l2;
            const __m256 a = _mm256_mul_ps(buf[s].nx, inv);
            const __m256 b = _mm256_mul_ps(buf[s].ny, inv);
            const __m256 c = _mm256_mul_ps(buf[s].nz, inv);
            __m256 d = _mm256_add_ps(_mm256_add_ps(_mm256_mul_ps(a, buf[s].px),
                                                   _mm256_mul_ps(b, buf[s].py)),
                                     _mm256_mul_ps(c, buf[s].pz));
            d = _mm256_xor_ps(d, _mm256_set1_ps(-0.0f));
            store_planes8_pairs(planes + t + 8 * s, a, b, c, d);
        }
        if (anyBad) {
            for (int s = 0; s < steps; s++) {
                for (unsigned m = bad[s]; m; m &= m - 1) {
                    const int l = __builtin_ctz(m);
                    const int tt = 8 * s + (l < 4 ? 2 * l : 2 * (l - 4) + 1);
                    planes[t + tt] = sv_plane_one(positions, ix + 3 * tt);
                }
            }
        }
        t += 8 * steps;
    }
    for (; t < numTriangles; t++) planes[t] = sv_plane_one(positions, indices + 3 * t);
    SV_VZEROUPPER_IF_UNOPTIMISED();
}

#define FACING_AVX2(m)                                                                             \
    unsigned m;                                                                                    \
    do {                                                                                           \
        const __m256 nx_ = _mm256_sub_ps(_mm256_mul_ps(ay, bz), _mm256_mul_ps(az, by));            \
        const __m256 ny_ = _mm256_sub_ps(_mm256_mul_ps(az, bx), _mm256_mul_ps(ax, bz));            \
        const __m256 nz_ = _mm256_sub_ps(_mm256_mul_ps(ax, by), _mm256_mul_ps(ay, bx));            \
        const __m256 vx_ = _mm256_sub_ps(lx, _mm256_mul_ps(px, lw));                               \
        const __m256 vy_ = _mm256_sub_ps(ly, _mm256_mul_ps(py, lw));                               \
        const __m256 vz_ = _mm256_sub_ps(lz, _mm256_mul_ps(pz, lw));                               \
        const __m256 s_ = _mm256_add_ps(_mm256_add_ps(_mm256_mul_ps(nx_, vx_),                     \
                                                      _mm256_mul_ps(ny_, vy_)),                    \
                                        _mm256_mul_ps(nz_, vz_));                                  \
        (m) = (unsigned)_mm256_movemask_ps(_mm256_cmp_ps(s_, _mm256_setzero_ps(), _CMP_GT_OQ));    \
    } while (0)

SV_TARGET_AVX2 void sv_facing_from_positions_avx2(const float *positions, const int *indices,
                                                  int numTriangles, const Vec4 *light,
                                                  uint8_t *facing) {
    if (numTriangles < 0) {
        SV_VZEROUPPER_IF_UNOPTIMISED();
        return;
    }
    const __m256 lx = _mm256_set1_ps(light->x), ly = _mm256_set1_ps(light->y);
    const __m256 lz = _mm256_set1_ps(light->z), lw = _mm256_set1_ps(light->w);
    int t = 0;
    for (; numTriangles - t >= 8; t += 8) {
        const int *ix = indices + 3 * t;
        LOAD_TRI8_AVX2(positions, ix, SPLIT_A, SPLIT_B);
        FACING_AVX2(m);
        memcpy(facing + t, &kMaskBytes[m], 8); /* mask_bytes.h: not pdep */
    }
    for (; t < numTriangles; t++)
        facing[t] = sv_facing_from_positions_one(positions, indices + 3 * t, light);
    facing[numTriangles] = 1;
    SV_VZEROUPPER_IF_UNOPTIMISED();
}

/* ---- AVX2 with gathers ------------------------------------------------------ */

/* The corner-K vertex numbers of 8 triangles from their 24 indices
 * (three loads): element j is index 3j + K, in register (3j+K)/8 at
 * (3j+K)%8; a blend picks, per position, the one register whose element
 * there belongs to corner K, and vpermd puts them in triangle order. */
SV_TARGET_AVX2 static inline void corners8(const int *ix, __m256i *c0, __m256i *c1, __m256i *c2) {
    const __m256i A = _mm256_loadu_si256((const __m256i *)(const void *)ix);
    const __m256i B = _mm256_loadu_si256((const __m256i *)(const void *)(ix + 8));
    const __m256i C = _mm256_loadu_si256((const __m256i *)(const void *)(ix + 16));
    const __m256i m0 = _mm256_blend_epi32(_mm256_blend_epi32(A, B, 0x92), C, 0x24);
    const __m256i m1 = _mm256_blend_epi32(_mm256_blend_epi32(A, B, 0x24), C, 0x49);
    const __m256i m2 = _mm256_blend_epi32(_mm256_blend_epi32(A, B, 0x49), C, 0x92);
    *c0 = _mm256_permutevar8x32_epi32(m0, _mm256_setr_epi32(0, 3, 6, 1, 4, 7, 2, 5));
    *c1 = _mm256_permutevar8x32_epi32(m1, _mm256_setr_epi32(1, 4, 7, 2, 5, 0, 3, 6));
    *c2 = _mm256_permutevar8x32_epi32(m2, _mm256_setr_epi32(2, 5, 0, 3, 6, 1, 4, 7));
}

#define LOAD_TRI8_GATHER(positions, ix)                                                            \
    __m256 px, py, pz, ax, ay, az, bx, by, bz;                                                     \
    do {                                                                                           \
        __m256i c0_, c1_, c2_;                                                                     \
        corners8(ix, &c0_, &c1_, &c2_);                                                            \
        c0_ = _mm256_add_epi32(c0_, _mm256_add_epi32(c0_, c0_)); /* 3 * index */                   \
        c1_ = _mm256_add_epi32(c1_, _mm256_add_epi32(c1_, c1_));                                   \
        c2_ = _mm256_add_epi32(c2_, _mm256_add_epi32(c2_, c2_));                                   \
        px = _mm256_i32gather_ps(positions, c0_, 4);                                               \
        py = _mm256_i32gather_ps((positions) + 1, c0_, 4);                                         \
        pz = _mm256_i32gather_ps((positions) + 2, c0_, 4);                                         \
        ax = _mm256_sub_ps(_mm256_i32gather_ps(positions, c1_, 4), px);                            \
        ay = _mm256_sub_ps(_mm256_i32gather_ps((positions) + 1, c1_, 4), py);                      \
        az = _mm256_sub_ps(_mm256_i32gather_ps((positions) + 2, c1_, 4), pz);                      \
        bx = _mm256_sub_ps(_mm256_i32gather_ps(positions, c2_, 4), px);                            \
        by = _mm256_sub_ps(_mm256_i32gather_ps((positions) + 1, c2_, 4), py);                      \
        bz = _mm256_sub_ps(_mm256_i32gather_ps((positions) + 2, c2_, 4), pz);                      \
    } while (0)

/* The gathers index with 32-bit 3 * index: vertex numbers must be below
 * 2^31 / 3 = 715,827,882 here (a positions array of 8.6 GB). */

SV_TARGET_AVX2 void sv_derive_planes_avx2_gather(const float *positions, const int *indices,
                                                 int numTriangles, Plane *planes) {
    int t = 0;
    for (; numTriangles - t >= 8; t += 8) {
        const int *ix = indices + 3 * t;
        LOAD_TRI8_GATHER(positions, ix);
        PLANES_AVX2(a, b, c, d, ok);
        sv_store_planes8_avx2(planes + t, a, b, c, d);
        if (ok != 0xFF) {
            for (int l = 0; l < 8; l++)
                if (!(ok & (1u << l))) planes[t + l] = sv_plane_one(positions, ix + 3 * l);
        }
    }
    for (; t < numTriangles; t++) planes[t] = sv_plane_one(positions, indices + 3 * t);
    SV_VZEROUPPER_IF_UNOPTIMISED();
}

SV_TARGET_AVX2 void sv_facing_from_positions_avx2_gather(const float *positions, const int *indices,
                                                         int numTriangles, const Vec4 *light,
                                                         uint8_t *facing) {
    if (numTriangles < 0) {
        SV_VZEROUPPER_IF_UNOPTIMISED();
        return;
    }
    const __m256 lx = _mm256_set1_ps(light->x), ly = _mm256_set1_ps(light->y);
    const __m256 lz = _mm256_set1_ps(light->z), lw = _mm256_set1_ps(light->w);
    int t = 0;
    for (; numTriangles - t >= 8; t += 8) {
        const int *ix = indices + 3 * t;
        LOAD_TRI8_GATHER(positions, ix);
        FACING_AVX2(m);
        memcpy(facing + t, &kMaskBytes[m], 8); /* mask_bytes.h: not pdep */
    }
    for (; t < numTriangles; t++)
        facing[t] = sv_facing_from_positions_one(positions, indices + 3 * t, light);
    facing[numTriangles] = 1;
    SV_VZEROUPPER_IF_UNOPTIMISED();
}

/* ---- AVX-512 ------------------------------------------------------------------ */

#define SV_TARGET_AVX512 __attribute__((target("avx512f,avx512bw,avx512vl,avx512dq,avx2,bmi2")))

SV_TARGET_AVX512 static inline __m128 load_row_512(const float *positions, int index, int shift) {
    return shift ? _mm_maskz_loadu_ps(0xE, corner_shifted(positions, index, 1))
                 : _mm_maskz_loadu_ps(0x7, corner_shifted(positions, index, 0));
}

/* Corner K rows of triangles T(0) .. T(3), one per 128-bit lane. */
SV_TARGET_AVX512 static inline __m512 row4_512(const float *positions, const int *ix, int k,
                                               const int tri[4], int shift) {
    const __m256 lo = _mm256_insertf128_ps(_mm256_castps128_ps256(
                                               load_row_512(positions, ix[3 * tri[0] + k], shift)),
                                           load_row_512(positions, ix[3 * tri[1] + k], shift), 1);
    const __m256 hi = _mm256_insertf128_ps(_mm256_castps128_ps256(
                                               load_row_512(positions, ix[3 * tri[2] + k], shift)),
                                           load_row_512(positions, ix[3 * tri[3] + k], shift), 1);
    return _mm512_insertf32x8(_mm512_castps256_ps512(lo), hi, 1);
}

#define TRANSPOSE3_512(q0, q1, q2, q3, X, Y, Z)                                                    \
    do {                                                                                           \
        const __m512 xz01_ = _mm512_mask_blend_ps(0xAAAA, q0, q1);                                 \
        const __m512 xz23_ = _mm512_mask_blend_ps(0xAAAA, q2, q3);                                 \
        const __m512 y01_ = _mm512_mask_blend_ps(0x4444, q0, q1);                                  \
        const __m512 y23_ = _mm512_mask_blend_ps(0x4444, q2, q3);                                  \
        (X) = _mm512_shuffle_ps(xz01_, xz23_, _MM_SHUFFLE(1, 0, 1, 0));                            \
        (Z) = _mm512_shuffle_ps(xz01_, xz23_, _MM_SHUFFLE(3, 2, 3, 2));                            \
        (Y) = _mm512_shuffle_ps(y01_, y23_, _MM_SHUFFLE(2, 1, 2, 1));                              \
    } while (0)

/* ORDER 0: row r, lane L = triangle 4r + L (rows of consecutive planes);
 * ORDER 1: triangle r + 4L (columns in triangle order). */
#define LOAD_TRI16_512(positions, ix, ORDER)                                                       \
    __m512 px, py, pz, ax, ay, az, bx, by, bz;                                                     \
    do {                                                                                           \
        __m512 r0_[4], r1_[4], r2_[4];                                                             \
        for (int r_ = 0; r_ < 4; r_++) {                                                           \
            int tri_[4];                                                                           \
            for (int L_ = 0; L_ < 4; L_++) tri_[L_] = (ORDER) ? r_ + 4 * L_ : 4 * r_ + L_;         \
            const int s_ = r_ & 1;                                                                 \
            r0_[r_] = row4_512(positions, ix, 0, tri_, s_);                                        \
            r1_[r_] = _mm512_sub_ps(row4_512(positions, ix, 1, tri_, s_), r0_[r_]);                \
            r2_[r_] = _mm512_sub_ps(row4_512(positions, ix, 2, tri_, s_), r0_[r_]);                \
        }                                                                                          \
        TRANSPOSE3_512(r0_[0], r0_[1], r0_[2], r0_[3], px, py, pz);                                \
        TRANSPOSE3_512(r1_[0], r1_[1], r1_[2], r1_[3], ax, ay, az);                                \
        TRANSPOSE3_512(r2_[0], r2_[1], r2_[2], r2_[3], bx, by, bz);                                \
    } while (0)

SV_TARGET_AVX512 void sv_derive_planes_avx512(const float *positions, const int *indices,
                                              int numTriangles, Plane *planes) {
    int t = 0;
    for (; numTriangles - t >= 16; t += 16) {
        const int *ix = indices + 3 * t;
        LOAD_TRI16_512(positions, ix, 0);
        __m512 nx, ny, nz, len2;
        const unsigned ok = sv_normal16_avx512(ax, ay, az, bx, by, bz, &nx, &ny, &nz, &len2);
        const __m512 inv = _mm512_div_ps(_mm512_set1_ps(1.0f), _mm512_sqrt_ps(len2));
        const __m512 a = _mm512_mul_ps(nx, inv), b = _mm512_mul_ps(ny, inv);
        const __m512 c = _mm512_mul_ps(nz, inv);
        __m512 d = _mm512_add_ps(_mm512_add_ps(_mm512_mul_ps(a, px), _mm512_mul_ps(b, py)),
                                 _mm512_mul_ps(c, pz));
        d = _mm512_xor_ps(d, _mm512_set1_ps(-0.0f));
        /* In-lane 4x4 transpose: row r, lane L = plane 4r + L. */
        const __m512 u0 = _mm512_unpacklo_ps(a, b), u1 = _mm512_unpacklo_ps(c, d);
        const __m512 u2 = _mm512_unpackhi_ps(a, b), u3 = _mm512_unpackhi_ps(c, d);
        _mm512_storeu_ps(&planes[t].a, _mm512_shuffle_ps(u0, u1, _MM_SHUFFLE(1, 0, 1, 0)));
        _mm512_storeu_ps(&planes[t + 4].a, _mm512_shuffle_ps(u0, u1, _MM_SHUFFLE(3, 2, 3, 2)));
        _mm512_storeu_ps(&planes[t + 8].a, _mm512_shuffle_ps(u2, u3, _MM_SHUFFLE(1, 0, 1, 0)));
        _mm512_storeu_ps(&planes[t + 12].a, _mm512_shuffle_ps(u2, u3, _MM_SHUFFLE(3, 2, 3, 2)));
        if (ok != 0xFFFF) {
            for (int i = 0; i < 16; i++) {
                const int tt = 4 * (i & 3) + (i >> 2); /* lane L = i/4, position r = i%4 */
                if (!(ok & (1u << i))) planes[t + tt] = sv_plane_one(positions, ix + 3 * tt);
            }
        }
    }
    if (t < numTriangles)
        sv_derive_planes_avx2(positions, indices + 3 * t, numTriangles - t, planes + t);
    SV_VZEROUPPER_IF_UNOPTIMISED();
}

SV_TARGET_AVX512 void sv_facing_from_positions_avx512(const float *positions, const int *indices,
                                                      int numTriangles, const Vec4 *light,
                                                      uint8_t *facing) {
    if (numTriangles < 0) {
        SV_VZEROUPPER_IF_UNOPTIMISED();
        return;
    }
    const __m512 lx = _mm512_set1_ps(light->x), ly = _mm512_set1_ps(light->y);
    const __m512 lz = _mm512_set1_ps(light->z), lw = _mm512_set1_ps(light->w);
    int t = 0;
    for (; numTriangles - t >= 16; t += 16) {
        const int *ix = indices + 3 * t;
        LOAD_TRI16_512(positions, ix, 1);
        const __m512 nx = _mm512_sub_ps(_mm512_mul_ps(ay, bz), _mm512_mul_ps(az, by));
        const __m512 ny = _mm512_sub_ps(_mm512_mul_ps(az, bx), _mm512_mul_ps(ax, bz));
        const __m512 nz = _mm512_sub_ps(_mm512_mul_ps(ax, by), _mm512_mul_ps(ay, bx));
        const __m512 vx = _mm512_sub_ps(lx, _mm512_mul_ps(px, lw));
        const __m512 vy = _mm512_sub_ps(ly, _mm512_mul_ps(py, lw));
        const __m512 vz = _mm512_sub_ps(lz, _mm512_mul_ps(pz, lw));
        const __m512 s = _mm512_add_ps(_mm512_add_ps(_mm512_mul_ps(nx, vx), _mm512_mul_ps(ny, vy)),
                                       _mm512_mul_ps(nz, vz));
        const __mmask16 m = _mm512_cmp_ps_mask(s, _mm512_setzero_ps(), _CMP_GT_OQ);
        _mm_storeu_si128((__m128i *)(void *)(facing + t), _mm_maskz_mov_epi8(m, _mm_set1_epi8(1)));
    }
    sv_facing_from_positions_avx2(positions, indices + 3 * t, numTriangles - t, light, facing + t);
    SV_VZEROUPPER_IF_UNOPTIMISED();
}
