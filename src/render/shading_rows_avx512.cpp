/*
 * The lighting pass's row kernel in AVX-512 (F, DQ, VL, BW): eight pixels
 * per step, in double, lane by lane the operations of shading_terms.h
 * (separate vmulpd and vaddpd, vdivpd and vsqrtpd, which round as the
 * scalar ones do), so the bytes equal shade_row_c's — shading_rows_avx2.cpp
 * twice as wide, with opmasks for what AVX2 does with lane masks.
 *
 * The trick, as in the AVX2 kernel: ShadeTriangle is nine 8-byte words, so
 * the eight lanes' triangles are read as two sets of three 4x4 transposes
 * of doubles, not as 72 scalar inserts; a step whose eight pixels show one
 * triangle broadcasts it. A light is skipped for the step when no lane may
 * receive it (stencil, facing, side) or when every lane is past its range
 * or outside a spot's cone for certain; the rest runs on all eight lanes
 * and is masked to +0 where a lane takes no light, which leaves the sum's
 * bits unchanged. The row's last step is a partial one under a lane mask
 * (ids, stencils, columns and the radiance planes are read and written
 * masked: nothing past the row's width).
 *
 * Register map of a step (the compiler allocates; the roles): the eye, the
 * row's up * ny and the ray (3 zmm each), the triangles' plane, numerator
 * and normal (7 zmm), the visible point (3 zmm), the three radiance sums;
 * opmasks: the lanes in the row, visible, front, and per light the lanes
 * that may take it.
 *
 * Copyright (C) 2026 the shadowvol authors. LGPL-2.1-or-later.
 */
/* GCC 12's own AVX-512 headers pass an undefined register to masked
 * builtins and then warn about it (a known false positive of
 * -Wmaybe-uninitialized). */
#pragma GCC diagnostic ignored "-Wmaybe-uninitialized"
#include <immintrin.h>

#include <cstring>

#include "shading_rows.h"

#define SV_TARGET_AVX512 __attribute__((target("avx512f,avx512dq,avx512vl,avx512bw")))

namespace sv::render::detail {
namespace {

struct Vec3x8 {
    __m512d x, y, z;
};

SV_TARGET_AVX512 inline __m512d dot8(const Vec3x8 &a, const Vec3x8 &b) {
    return _mm512_add_pd(_mm512_add_pd(_mm512_mul_pd(a.x, b.x), _mm512_mul_pd(a.y, b.y)),
                         _mm512_mul_pd(a.z, b.z));
}

SV_TARGET_AVX512 inline __m512d set8(double v) { return _mm512_set1_pd(v); }

/* Rows r0..r3 of four doubles each become columns c0..c3. */
SV_TARGET_AVX512 inline void transpose4(__m256d r0, __m256d r1, __m256d r2, __m256d r3,
                                        __m256d c[4]) {
    const __m256d t0 = _mm256_unpacklo_pd(r0, r1), t1 = _mm256_unpackhi_pd(r0, r1);
    const __m256d t2 = _mm256_unpacklo_pd(r2, r3), t3 = _mm256_unpackhi_pd(r2, r3);
    c[0] = _mm256_permute2f128_pd(t0, t2, 0x20);
    c[1] = _mm256_permute2f128_pd(t1, t3, 0x20);
    c[2] = _mm256_permute2f128_pd(t0, t2, 0x31);
    c[3] = _mm256_permute2f128_pd(t1, t3, 0x31);
}

SV_TARGET_AVX512 inline __m512d join(__m256d lo, __m256d hi) {
    return _mm512_insertf64x4(_mm512_castpd256_pd512(lo), hi, 1);
}

/* The eight lanes' triangle terms. */
struct Triangles8 {
    Vec3x8 n, normal;
    __m512d numerator;
    __m512i facing_bits, surface_ground; /* surface in the low, ground in the high half */
};

SV_TARGET_AVX512 inline void load_triangles(const ShadeTriangle *const t[8], Triangles8 &out) {
    __m256d a[2][4], b[2][4]; /* per half: n.x, n.y, n.z, numerator; normal x, y, z, bits */
    for (int h = 0; h < 2; h++) {
        const double *w[4] = {&t[4 * h]->n[0], &t[4 * h + 1]->n[0], &t[4 * h + 2]->n[0],
                              &t[4 * h + 3]->n[0]};
        transpose4(_mm256_loadu_pd(w[0]), _mm256_loadu_pd(w[1]), _mm256_loadu_pd(w[2]),
                   _mm256_loadu_pd(w[3]), a[h]);
        transpose4(_mm256_loadu_pd(w[0] + 4), _mm256_loadu_pd(w[1] + 4), _mm256_loadu_pd(w[2] + 4),
                   _mm256_loadu_pd(w[3] + 4), b[h]);
    }
    out.n = {join(a[0][0], a[1][0]), join(a[0][1], a[1][1]), join(a[0][2], a[1][2])};
    out.numerator = join(a[0][3], a[1][3]);
    out.normal = {join(b[0][0], b[1][0]), join(b[0][1], b[1][1]), join(b[0][2], b[1][2])};
    out.facing_bits = _mm512_castpd_si512(join(b[0][3], b[1][3]));
    long long sg[8];
    for (int k = 0; k < 8; k++) std::memcpy(&sg[k], &t[k]->surface, 8);
    out.surface_ground = _mm512_set_epi64(sg[7], sg[6], sg[5], sg[4], sg[3], sg[2], sg[1], sg[0]);
}

SV_TARGET_AVX512 inline void broadcast_triangle(const ShadeTriangle &t, Triangles8 &out) {
    out.n = {set8(t.n[0]), set8(t.n[1]), set8(t.n[2])};
    out.numerator = set8(t.numerator);
    out.normal = {set8(t.normal[0]), set8(t.normal[1]), set8(t.normal[2])};
    out.facing_bits = _mm512_set1_epi64((long long)t.facing_bits);
    long long sg;
    std::memcpy(&sg, &t.surface, 8);
    out.surface_ground = _mm512_set1_epi64(sg);
}

SV_TARGET_AVX512 inline __m512d clamp01(__m512d x) {
    return _mm512_min_pd(_mm512_max_pd(x, _mm512_setzero_pd()), set8(1.0));
}

SV_TARGET_AVX512 inline __m512d negate(__m512d x) { return _mm512_xor_pd(x, set8(-0.0)); }

/* irradiance() of shading_terms.h on eight lanes. SKIP is set when no lane
 * in LIVE can get light (every one past the range, or outside the cone
 * for certain). */
SV_TARGET_AVX512 inline __m512d irradiance8(const ShadeLight &l, const Vec3x8 &p, const Vec3x8 &n,
                                            __mmask8 live, bool &skip) {
    const __m512d zero = _mm512_setzero_pd();
    skip = false;
    if (l.kind == 2) {
        const Vec3x8 d{set8(l.direction[0]), set8(l.direction[1]), set8(l.direction[2])};
        return _mm512_mul_pd(set8(l.intensity), _mm512_max_pd(negate(dot8(n, d)), zero));
    }
    const Vec3x8 d{_mm512_sub_pd(set8(l.position[0]), p.x), _mm512_sub_pd(set8(l.position[1]), p.y),
                   _mm512_sub_pd(set8(l.position[2]), p.z)};
    const __m512d dist2 = dot8(d, d);
    __mmask8 dark = 0; /* lanes outside the spot's cone for certain: 0, as the C returns */
    if (l.dark_cos2 > 0) {
        const Vec3x8 axis{set8(l.direction[0]), set8(l.direction[1]), set8(l.direction[2])};
        const __m512d along = negate(dot8(d, axis));
        dark = (__mmask8)(_mm512_cmp_pd_mask(along, zero, _CMP_LE_OQ) |
                          _mm512_cmp_pd_mask(_mm512_mul_pd(along, along),
                                             _mm512_mul_pd(set8(l.dark_cos2), dist2), _CMP_LT_OQ));
        if ((__mmask8)(~dark & live) == 0) {
            skip = true;
            return zero;
        }
    }
    __m512d window = set8(1.0);
    if (l.has_range) {
        const __m512d q = _mm512_mul_pd(dist2, set8(l.inv_range2));
        const __m512d w = clamp01(_mm512_sub_pd(set8(1.0), _mm512_mul_pd(q, q)));
        if ((__mmask8)(live & _mm512_cmp_pd_mask(w, zero, _CMP_NEQ_UQ)) == 0) {
            skip = true;
            return zero;
        }
        window = _mm512_mul_pd(w, w);
    }
    const __m512d inv = _mm512_div_pd(set8(1.0), _mm512_sqrt_pd(dist2));
    const Vec3x8 dir{_mm512_mul_pd(d.x, inv), _mm512_mul_pd(d.y, inv), _mm512_mul_pd(d.z, inv)};
    __m512d a = _mm512_div_pd(_mm512_mul_pd(set8(l.intensity), _mm512_max_pd(dot8(n, dir), zero)),
                              dist2);
    if (l.has_range) a = _mm512_mul_pd(a, window);
    if (l.kind == 1) {
        const Vec3x8 axis{set8(l.direction[0]), set8(l.direction[1]), set8(l.direction[2])};
        const __m512d c = negate(dot8(dir, axis));
        const __m512d co = set8(l.cos_outer);
        const __m512d s =
            l.has_soft_cone
                ? clamp01(_mm512_div_pd(_mm512_sub_pd(c, co), set8(l.cos_inner - l.cos_outer)))
                : _mm512_maskz_mov_pd(_mm512_cmp_pd_mask(c, co, _CMP_GE_OQ), set8(1.0));
        a = _mm512_mul_pd(a, _mm512_mul_pd(s, s));
    }
    return _mm512_maskz_mov_pd((__mmask8)~dark, a);
}

} // namespace

SV_TARGET_AVX512 void shade_row_avx512(const ShadeRowInputs &row) {
    static const ShadeTriangle kNone{}; /* a sky or padding lane reads this */
    const __m512d zero = _mm512_setzero_pd();
    const Vec3x8 eye{set8(row.eye[0]), set8(row.eye[1]), set8(row.eye[2])};
    const __m512d ny = set8(row.ny);
    const Vec3x8 up_ny{_mm512_mul_pd(set8(row.up[0]), ny), _mm512_mul_pd(set8(row.up[1]), ny),
                       _mm512_mul_pd(set8(row.up[2]), ny)};
    for (int px = 0; px < row.width; px += 8) {
        const int lanes = row.width - px < 8 ? row.width - px : 8;
        const __mmask8 in_row = (__mmask8)((1u << lanes) - 1);
        const __m256i ids8 = _mm256_mask_loadu_epi32(_mm256_set1_epi32(-1), in_row, row.ids + px);
        const __mmask8 visible = _mm256_cmpgt_epi32_mask(ids8, _mm256_set1_epi32(-1));
        if (visible == 0) { /* every lane sky */
            if (row.last_group) {
                for (int k = 0; k < lanes; k++) std::memcpy(row.rgb + 3 * (px + k), row.sky, 3);
            }
            continue;
        }
        alignas(32) int32_t id[8];
        _mm256_store_si256(reinterpret_cast<__m256i *>(id), ids8);
        Triangles8 tri;
        if (id[0] >= 0 && _mm256_cmpeq_epi32_mask(ids8, _mm256_set1_epi32(id[0])) == 0xff) {
            broadcast_triangle(row.triangles[id[0]], tri);
        } else {
            const ShadeTriangle *t[8];
            for (int k = 0; k < 8; k++) t[k] = id[k] >= 0 ? &row.triangles[id[k]] : &kNone;
            load_triangles(t, tri);
        }

        /* The camera ray through the eight centres meets each plane. */
        const __m512d nx = _mm512_maskz_loadu_pd(in_row, row.column_nx + px);
        const Vec3x8 dir{
            _mm512_add_pd(set8(row.forward[0]),
                          _mm512_add_pd(_mm512_mul_pd(set8(row.right[0]), nx), up_ny.x)),
            _mm512_add_pd(set8(row.forward[1]),
                          _mm512_add_pd(_mm512_mul_pd(set8(row.right[1]), nx), up_ny.y)),
            _mm512_add_pd(set8(row.forward[2]),
                          _mm512_add_pd(_mm512_mul_pd(set8(row.right[2]), nx), up_ny.z))};
        const __m512d den = dot8(tri.n, dir);
        const __m512d t = _mm512_maskz_div_pd(_mm512_cmp_pd_mask(den, zero, _CMP_NEQ_UQ),
                                              tri.numerator, den);
        const Vec3x8 p{_mm512_add_pd(eye.x, _mm512_mul_pd(dir.x, t)),
                       _mm512_add_pd(eye.y, _mm512_mul_pd(dir.y, t)),
                       _mm512_add_pd(eye.z, _mm512_mul_pd(dir.z, t))};

        /* The radiance planes of the sweeps before and after (none in a
         * frame of one sweep). */
        auto saved = [&](int c) { return row.accum + (std::size_t)c * row.accum_stride + px; };
        __m512d acc[3];
        if (row.first_group) {
            __m512d base = set8(row.ambient);
            const __mmask8 is_ground = _mm512_cmpgt_epi64_mask(_mm512_srli_epi64(tri.surface_ground,
                                                                                 32),
                                                               _mm512_setzero_si512());
            if (is_ground != 0) {
                const __m512d two = set8(2.0);
                constexpr int kFloor = _MM_FROUND_TO_NEG_INF | _MM_FROUND_NO_EXC;
                const __m512d sum =
                    _mm512_add_pd(_mm512_roundscale_pd(_mm512_mul_pd(p.x, two), kFloor),
                                  _mm512_roundscale_pd(_mm512_mul_pd(p.z, two), kFloor));
                const __m512d half_floor = _mm512_roundscale_pd(_mm512_mul_pd(sum, set8(0.5)),
                                                                kFloor);
                const __mmask8 odd =
                    _mm512_cmp_pd_mask(_mm512_sub_pd(sum, _mm512_mul_pd(two, half_floor)), zero,
                                       _CMP_NEQ_UQ);
                const __m512d factor = _mm512_mask_mov_pd(set8(1.0), odd, set8(0.9));
                base = _mm512_mask_mov_pd(base, is_ground, _mm512_mul_pd(base, factor));
            }
            acc[0] = acc[1] = acc[2] = base;
        } else {
            for (int c = 0; c < 3; c++) acc[c] = _mm512_maskz_loadu_pd(in_row, saved(c));
        }
        const Vec3x8 to_eye{_mm512_sub_pd(eye.x, p.x), _mm512_sub_pd(eye.y, p.y),
                            _mm512_sub_pd(eye.z, p.z)};
        const __mmask8 front = (__mmask8)(visible & _mm512_cmp_pd_mask(dot8(tri.normal, to_eye),
                                                                       zero, _CMP_GT_OQ));
        if (front != 0) {
            for (int li = 0; li < row.num_lights; li++) {
                const ShadeLight &l = row.lights[li];
                const __m128i st = _mm_maskz_loadu_epi8(in_row, row.stencil[li] + px);
                /* Stencil 0 (a lane outside the row is not front) and the
                 * facing bit set. */
                const __mmask8 ok =
                    (__mmask8)(front & _mm_cmpeq_epi8_mask(st, _mm_setzero_si128()) &
                               _mm512_test_epi64_mask(tri.facing_bits,
                                                      _mm512_set1_epi64(1LL << li)));
                if (ok == 0) continue;
                bool skip = false;
                const __m512d en = _mm512_maskz_mov_pd(ok, irradiance8(l, p, tri.normal, ok, skip));
                if (skip) continue;
                if (l.kind != 2 && row.divider_lanes) *row.divider_lanes += 8;
                for (int c = 0; c < 3; c++) {
                    acc[c] = _mm512_add_pd(acc[c], _mm512_mul_pd(en, set8(l.color[c])));
                }
            }
        }
        if (!row.last_group) {
            for (int c = 0; c < 3; c++) _mm512_mask_storeu_pd(saved(c), in_row, acc[c]);
            continue;
        }
        /* Albedo: one surface in every lane (most steps) is a broadcast,
         * else a gather at 3 * surface + c. */
        const __m256i surface = _mm512_cvtepi64_epi32(tri.surface_ground);
        const int first_surface = _mm_cvtsi128_si32(_mm256_castsi256_si128(surface));
        const bool one_surface = _mm256_cmpeq_epi32_mask(surface,
                                                         _mm256_set1_epi32(first_surface)) == 0xff;
        const __m256i albedo_at = _mm256_mullo_epi32(surface, _mm256_set1_epi32(3));
        __m128i bytes[3]; /* the display bytes of the 8 lanes, per channel (low 8 bytes) */
        for (int c = 0; c < 3; c++) {
            const __m512d albedo =
                one_surface ? set8(row.albedo[3 * first_surface + c])
                            : _mm512_i32gather_pd(_mm256_add_epi32(albedo_at, _mm256_set1_epi32(c)),
                                                  row.albedo, 8);
            const __m512d v = _mm512_min_pd(_mm512_max_pd(_mm512_mul_pd(acc[c], albedo), zero),
                                            set8((double)kDisplayMax));
            const __m256i index = _mm512_cvttpd_epi32(
                _mm512_add_pd(_mm512_mul_pd(v, set8((double)kDisplaySteps)), set8(0.5)));
            /* Four bytes read at each index (the table has 3 readable bytes
             * after its last entry), the first kept. */
            const __m256i word = _mm256_i32gather_epi32(reinterpret_cast<const int *>(row.display),
                                                        index, 1);
            bytes[c] = _mm_mask_blend_epi8((__mmask16)(uint8_t)~visible, _mm256_cvtepi32_epi8(word),
                                           _mm_set1_epi8((char)row.sky[c]));
        }
        /* Planar R, G, B bytes to 8 pixels of 3 interleaved bytes: byte k of
         * the output is channel k % 3 of pixel k / 3 (two pshufb from R|G,
         * one from B). */
        const __m128i rg = _mm_unpacklo_epi64(bytes[0], bytes[1]);
        const __m128i b = bytes[2];
        const __m128i from_rg_lo = _mm_setr_epi8(0, 8, -1, 1, 9, -1, 2, 10, -1, 3, 11, -1, 4, 12,
                                                 -1, 5);
        const __m128i from_b_lo = _mm_setr_epi8(-1, -1, 0, -1, -1, 1, -1, -1, 2, -1, -1, 3, -1, -1,
                                                4, -1);
        const __m128i from_rg_hi = _mm_setr_epi8(13, -1, 6, 14, -1, 7, 15, -1, -1, -1, -1, -1, -1,
                                                 -1, -1, -1);
        const __m128i from_b_hi = _mm_setr_epi8(-1, 5, -1, -1, 6, -1, -1, 7, -1, -1, -1, -1, -1, -1,
                                                -1, -1);
        const __m128i lo = _mm_or_si128(_mm_shuffle_epi8(rg, from_rg_lo),
                                        _mm_shuffle_epi8(b, from_b_lo));
        const __m128i hi = _mm_or_si128(_mm_shuffle_epi8(rg, from_rg_hi),
                                        _mm_shuffle_epi8(b, from_b_hi));
        /* 3 bytes per lane in the row, nothing past it. */
        const unsigned out_bytes = 3u * (unsigned)lanes;
        uint8_t *out = row.rgb + 3 * px;
        _mm_mask_storeu_epi8(out, (__mmask16)(out_bytes >= 16 ? 0xffffu : (1u << out_bytes) - 1),
                             lo);
        if (out_bytes > 16) {
            _mm_mask_storeu_epi8(out + 16, (__mmask16)((1u << (out_bytes - 16)) - 1), hi);
        }
    }
}

} // namespace sv::render::detail
