/*
 * The lighting pass's row kernel in AVX2: four pixels per step, in double,
 * lane by lane the operations of shading_terms.h (separate vmulpd and
 * vaddpd, vdivpd and vsqrtpd, which round as the scalar ones do), so the
 * bytes equal shade_row_c's.
 *
 * The trick: ShadeTriangle is nine 8-byte words, so the four lanes'
 * triangles are read as three 4x4 transposes of doubles (n and the
 * numerator; the normal and the facing bits; surface and ground), not as
 * 36 scalar inserts; a step whose four pixels show one triangle (most of
 * a large triangle's rows) broadcasts it instead. A light is skipped for
 * the step when no lane may receive it (stencil, facing, side) or when
 * every lane is past its range; the rest of the arithmetic runs on all
 * four lanes and is masked to +0 where a lane takes no light, which
 * leaves the sum's bits unchanged.
 *
 * Copyright (C) 2026 the shadowvol authors. LGPL-2.1-or-later.
 */
#include <immintrin.h>

#include <cstring>

#include "shading_rows.h"

#define SV_TARGET_AVX2 __attribute__((target("avx2")))

namespace sv::render::detail {
namespace {

struct Vec3x4 {
    __m256d x, y, z;
};

SV_TARGET_AVX2 inline __m256d dot4(const Vec3x4 &a, const Vec3x4 &b) {
    return _mm256_add_pd(_mm256_add_pd(_mm256_mul_pd(a.x, b.x), _mm256_mul_pd(a.y, b.y)),
                         _mm256_mul_pd(a.z, b.z));
}

/* Rows r0..r3 of four doubles each become columns c0..c3. */
SV_TARGET_AVX2 inline void transpose4(__m256d r0, __m256d r1, __m256d r2, __m256d r3, __m256d &c0,
                                      __m256d &c1, __m256d &c2, __m256d &c3) {
    const __m256d t0 = _mm256_unpacklo_pd(r0, r1), t1 = _mm256_unpackhi_pd(r0, r1);
    const __m256d t2 = _mm256_unpacklo_pd(r2, r3), t3 = _mm256_unpackhi_pd(r2, r3);
    c0 = _mm256_permute2f128_pd(t0, t2, 0x20);
    c1 = _mm256_permute2f128_pd(t1, t3, 0x20);
    c2 = _mm256_permute2f128_pd(t0, t2, 0x31);
    c3 = _mm256_permute2f128_pd(t1, t3, 0x31);
}

/* The four lanes' triangle terms. */
struct Triangles4 {
    Vec3x4 n, normal;
    __m256d numerator;
    __m256i facing_bits, surface_ground; /* surface in the low, ground in the high half */
};

SV_TARGET_AVX2 inline void load_triangles(const ShadeTriangle *const t[4], Triangles4 &out) {
    const double *w0 = &t[0]->n[0], *w1 = &t[1]->n[0], *w2 = &t[2]->n[0], *w3 = &t[3]->n[0];
    transpose4(_mm256_loadu_pd(w0), _mm256_loadu_pd(w1), _mm256_loadu_pd(w2), _mm256_loadu_pd(w3),
               out.n.x, out.n.y, out.n.z, out.numerator);
    __m256d bits;
    transpose4(_mm256_loadu_pd(w0 + 4), _mm256_loadu_pd(w1 + 4), _mm256_loadu_pd(w2 + 4),
               _mm256_loadu_pd(w3 + 4), out.normal.x, out.normal.y, out.normal.z, bits);
    out.facing_bits = _mm256_castpd_si256(bits);
    long long sg[4];
    std::memcpy(&sg[0], &t[0]->surface, 8);
    std::memcpy(&sg[1], &t[1]->surface, 8);
    std::memcpy(&sg[2], &t[2]->surface, 8);
    std::memcpy(&sg[3], &t[3]->surface, 8);
    out.surface_ground = _mm256_loadu_si256(reinterpret_cast<const __m256i *>(sg));
}

SV_TARGET_AVX2 inline void broadcast_triangle(const ShadeTriangle &t, Triangles4 &out) {
    out.n = {_mm256_set1_pd(t.n[0]), _mm256_set1_pd(t.n[1]), _mm256_set1_pd(t.n[2])};
    out.numerator = _mm256_set1_pd(t.numerator);
    out.normal = {_mm256_set1_pd(t.normal[0]), _mm256_set1_pd(t.normal[1]),
                  _mm256_set1_pd(t.normal[2])};
    out.facing_bits = _mm256_set1_epi64x((long long)t.facing_bits);
    long long sg;
    std::memcpy(&sg, &t.surface, 8);
    out.surface_ground = _mm256_set1_epi64x(sg);
}

SV_TARGET_AVX2 inline __m256d clamp01(__m256d x) {
    return _mm256_min_pd(_mm256_max_pd(x, _mm256_setzero_pd()), _mm256_set1_pd(1.0));
}

/* irradiance() of shading_terms.h on four lanes. SKIP is set when no lane
 * in LIVE can get light (every one past the range). */
SV_TARGET_AVX2 inline __m256d irradiance4(const ShadeLight &l, const Vec3x4 &p, const Vec3x4 &n,
                                          __m256d live, bool &skip) {
    const __m256d zero = _mm256_setzero_pd(), sign = _mm256_set1_pd(-0.0);
    skip = false;
    if (l.kind == 2) {
        const Vec3x4 d{_mm256_set1_pd(l.direction[0]), _mm256_set1_pd(l.direction[1]),
                       _mm256_set1_pd(l.direction[2])};
        return _mm256_mul_pd(_mm256_set1_pd(l.intensity),
                             _mm256_max_pd(_mm256_xor_pd(dot4(n, d), sign), zero));
    }
    const Vec3x4 d{_mm256_sub_pd(_mm256_set1_pd(l.position[0]), p.x),
                   _mm256_sub_pd(_mm256_set1_pd(l.position[1]), p.y),
                   _mm256_sub_pd(_mm256_set1_pd(l.position[2]), p.z)};
    const __m256d dist2 = dot4(d, d);
    __m256d dark = zero; /* lanes outside the spot's cone for certain: 0, as the C returns */
    if (l.dark_cos2 > 0) {
        /* shading_terms.h's quick test of the spot's cone, on every lane. */
        const Vec3x4 axis{_mm256_set1_pd(l.direction[0]), _mm256_set1_pd(l.direction[1]),
                          _mm256_set1_pd(l.direction[2])};
        const __m256d along = _mm256_xor_pd(dot4(d, axis), sign);
        dark = _mm256_or_pd(_mm256_cmp_pd(along, zero, _CMP_LE_OQ),
                            _mm256_cmp_pd(_mm256_mul_pd(along, along),
                                          _mm256_mul_pd(_mm256_set1_pd(l.dark_cos2), dist2),
                                          _CMP_LT_OQ));
        if ((_mm256_movemask_pd(_mm256_andnot_pd(dark, live))) == 0) {
            skip = true;
            return zero;
        }
    }
    __m256d window = _mm256_set1_pd(1.0);
    if (l.has_range) {
        const __m256d q = _mm256_mul_pd(dist2, _mm256_set1_pd(l.inv_range2));
        const __m256d w = clamp01(_mm256_sub_pd(_mm256_set1_pd(1.0), _mm256_mul_pd(q, q)));
        if (_mm256_movemask_pd(_mm256_and_pd(live, _mm256_cmp_pd(w, zero, _CMP_NEQ_UQ))) == 0) {
            skip = true;
            return zero;
        }
        window = _mm256_mul_pd(w, w);
    }
    const __m256d inv = _mm256_div_pd(_mm256_set1_pd(1.0), _mm256_sqrt_pd(dist2));
    const Vec3x4 dir{_mm256_mul_pd(d.x, inv), _mm256_mul_pd(d.y, inv), _mm256_mul_pd(d.z, inv)};
    __m256d a = _mm256_div_pd(_mm256_mul_pd(_mm256_set1_pd(l.intensity),
                                            _mm256_max_pd(dot4(n, dir), zero)),
                              dist2);
    if (l.has_range) a = _mm256_mul_pd(a, window);
    if (l.kind == 1) {
        const Vec3x4 axis{_mm256_set1_pd(l.direction[0]), _mm256_set1_pd(l.direction[1]),
                          _mm256_set1_pd(l.direction[2])};
        const __m256d c = _mm256_xor_pd(dot4(dir, axis), sign);
        const __m256d co = _mm256_set1_pd(l.cos_outer);
        const __m256d s = l.has_soft_cone
                              ? clamp01(_mm256_div_pd(_mm256_sub_pd(c, co),
                                                      _mm256_set1_pd(l.cos_inner - l.cos_outer)))
                              : _mm256_and_pd(_mm256_cmp_pd(c, co, _CMP_GE_OQ),
                                              _mm256_set1_pd(1.0));
        a = _mm256_mul_pd(a, _mm256_mul_pd(s, s));
    }
    return _mm256_andnot_pd(dark, a);
}

} // namespace

SV_TARGET_AVX2 void shade_row_avx2(const ShadeRowInputs &row) {
    static const ShadeTriangle kNone{}; /* a sky or padding lane reads this */
    const __m256d zero = _mm256_setzero_pd();
    const Vec3x4 eye{_mm256_set1_pd(row.eye[0]), _mm256_set1_pd(row.eye[1]),
                     _mm256_set1_pd(row.eye[2])};
    const __m256d ny = _mm256_set1_pd(row.ny);
    const Vec3x4 up_ny{_mm256_mul_pd(_mm256_set1_pd(row.up[0]), ny),
                       _mm256_mul_pd(_mm256_set1_pd(row.up[1]), ny),
                       _mm256_mul_pd(_mm256_set1_pd(row.up[2]), ny)};
    for (int px = 0; px < row.width; px += 4) {
        const int lanes = row.width - px < 4 ? row.width - px : 4;
        /* The ids as one vector (four scalar stores read back as a vector
         * would stall on store forwarding), then as scalars. */
        __m128i ids4;
        if (lanes == 4) {
            ids4 = _mm_loadu_si128(reinterpret_cast<const __m128i *>(row.ids + px));
        } else {
            int32_t tail[4] = {-1, -1, -1, -1};
            for (int k = 0; k < lanes; k++) tail[k] = row.ids[px + k];
            ids4 = _mm_loadu_si128(reinterpret_cast<const __m128i *>(tail));
        }
        if (_mm_movemask_ps(_mm_castsi128_ps(ids4)) == 0xf) { /* every lane sky */
            if (row.last_group) {
                for (int k = 0; k < lanes; k++) std::memcpy(row.rgb + 3 * (px + k), row.sky, 3);
            }
            continue;
        }
        const int32_t id[4] = {_mm_cvtsi128_si32(ids4), _mm_extract_epi32(ids4, 1),
                               _mm_extract_epi32(ids4, 2), _mm_extract_epi32(ids4, 3)};
        Triangles4 tri;
        if (id[0] >= 0 && id[0] == id[1] && id[0] == id[2] && id[0] == id[3]) {
            broadcast_triangle(row.triangles[id[0]], tri);
        } else {
            const ShadeTriangle *t[4];
            for (int k = 0; k < 4; k++) t[k] = id[k] >= 0 ? &row.triangles[id[k]] : &kNone;
            load_triangles(t, tri);
        }
        const __m256d visible = _mm256_castsi256_pd(
            _mm256_cmpgt_epi64(_mm256_cvtepi32_epi64(ids4), _mm256_set1_epi64x(-1)));

        /* The camera ray through the four centres meets each plane. */
        const __m256d nx = _mm256_loadu_pd(row.column_nx + px);
        const Vec3x4 dir{
            _mm256_add_pd(_mm256_set1_pd(row.forward[0]),
                          _mm256_add_pd(_mm256_mul_pd(_mm256_set1_pd(row.right[0]), nx), up_ny.x)),
            _mm256_add_pd(_mm256_set1_pd(row.forward[1]),
                          _mm256_add_pd(_mm256_mul_pd(_mm256_set1_pd(row.right[1]), nx), up_ny.y)),
            _mm256_add_pd(_mm256_set1_pd(row.forward[2]),
                          _mm256_add_pd(_mm256_mul_pd(_mm256_set1_pd(row.right[2]), nx), up_ny.z))};
        const __m256d den = dot4(tri.n, dir);
        const __m256d t = _mm256_andnot_pd(_mm256_cmp_pd(den, zero, _CMP_EQ_OQ),
                                           _mm256_div_pd(tri.numerator, den));
        const Vec3x4 p{_mm256_add_pd(eye.x, _mm256_mul_pd(dir.x, t)),
                       _mm256_add_pd(eye.y, _mm256_mul_pd(dir.y, t)),
                       _mm256_add_pd(eye.z, _mm256_mul_pd(dir.z, t))};

        /* The radiance planes of the sweeps before and after (none in a
         * frame of one sweep). */
        auto saved = [&](int c) { return row.accum + (std::size_t)c * row.accum_stride + px; };
        __m256d acc[3];
        if (row.first_group) {
            __m256d base = _mm256_set1_pd(row.ambient);
            const __m256i ground = _mm256_srli_epi64(tri.surface_ground, 32);
            const __m256d is_ground = _mm256_castsi256_pd(
                _mm256_cmpgt_epi64(ground, _mm256_setzero_si256()));
            if (_mm256_movemask_pd(is_ground) != 0) {
                const __m256d two = _mm256_set1_pd(2.0);
                const __m256d sum = _mm256_add_pd(_mm256_floor_pd(_mm256_mul_pd(p.x, two)),
                                                  _mm256_floor_pd(_mm256_mul_pd(p.z, two)));
                const __m256d half_floor = _mm256_floor_pd(_mm256_mul_pd(sum, _mm256_set1_pd(0.5)));
                const __m256d odd = _mm256_cmp_pd(_mm256_sub_pd(sum,
                                                                _mm256_mul_pd(two, half_floor)),
                                                  zero, _CMP_NEQ_UQ);
                const __m256d factor = _mm256_blendv_pd(_mm256_set1_pd(1.0), _mm256_set1_pd(0.9),
                                                        odd);
                base = _mm256_blendv_pd(base, _mm256_mul_pd(base, factor), is_ground);
            }
            acc[0] = acc[1] = acc[2] = base;
        } else {
            for (int c = 0; c < 3; c++) acc[c] = _mm256_loadu_pd(saved(c));
        }
        const Vec3x4 to_eye{_mm256_sub_pd(eye.x, p.x), _mm256_sub_pd(eye.y, p.y),
                            _mm256_sub_pd(eye.z, p.z)};
        const __m256d front = _mm256_and_pd(visible, _mm256_cmp_pd(dot4(tri.normal, to_eye), zero,
                                                                   _CMP_GT_OQ));
        if (_mm256_movemask_pd(front) != 0) {
            for (int li = 0; li < row.num_lights; li++) {
                const ShadeLight &l = row.lights[li];
                uint32_t st4 = 0xffffffffu;
                if (lanes == 4) {
                    std::memcpy(&st4, row.stencil[li] + px, 4);
                } else {
                    for (int k = 0; k < lanes; k++) ((uint8_t *)&st4)[k] = row.stencil[li][px + k];
                }
                const __m256i st = _mm256_cvtepu8_epi64(_mm_cvtsi32_si128((int)st4));
                const __m256i bit = _mm256_and_si256(_mm256_srli_epi64(tri.facing_bits, li),
                                                     _mm256_set1_epi64x(1));
                /* Stencil 0 and the facing bit set. */
                const __m256d ok =
                    _mm256_and_pd(front, _mm256_castsi256_pd(_mm256_andnot_si256(
                                             _mm256_cmpeq_epi64(bit, _mm256_setzero_si256()),
                                             _mm256_cmpeq_epi64(st, _mm256_setzero_si256()))));
                if (_mm256_movemask_pd(ok) == 0) continue;
                bool skip = false;
                const __m256d en = _mm256_and_pd(ok, irradiance4(l, p, tri.normal, ok, skip));
                if (skip) continue;
                if (l.kind != 2 && row.divider_lanes) *row.divider_lanes += 4;
                for (int c = 0; c < 3; c++) {
                    acc[c] = _mm256_add_pd(acc[c], _mm256_mul_pd(en, _mm256_set1_pd(l.color[c])));
                }
            }
        }
        if (!row.last_group) {
            for (int c = 0; c < 3; c++) _mm256_storeu_pd(saved(c), acc[c]);
            continue;
        }
        alignas(32) int32_t surface[8];
        _mm256_store_si256(reinterpret_cast<__m256i *>(surface), tri.surface_ground);
        alignas(16) int32_t index[3][4];
        for (int c = 0; c < 3; c++) {
            const __m256d albedo = _mm256_set_pd(row.albedo[3 * surface[6] + c],
                                                 row.albedo[3 * surface[4] + c],
                                                 row.albedo[3 * surface[2] + c],
                                                 row.albedo[3 * surface[0] + c]);
            const __m256d v = _mm256_min_pd(_mm256_max_pd(_mm256_mul_pd(acc[c], albedo), zero),
                                            _mm256_set1_pd((double)kDisplayMax));
            _mm_store_si128(reinterpret_cast<__m128i *>(index[c]),
                            _mm256_cvttpd_epi32(_mm256_add_pd(
                                _mm256_mul_pd(v, _mm256_set1_pd((double)kDisplaySteps)),
                                _mm256_set1_pd(0.5))));
        }
        for (int k = 0; k < lanes; k++) {
            uint8_t *out = row.rgb + 3 * (px + k);
            if (id[k] < 0) {
                std::memcpy(out, row.sky, 3);
                continue;
            }
            out[0] = row.display[index[0][k]], out[1] = row.display[index[1][k]],
            out[2] = row.display[index[2][k]];
        }
    }
}

} // namespace sv::render::detail
