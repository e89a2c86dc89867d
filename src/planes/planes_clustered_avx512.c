/*
 * Plane derivation by clusters with AVX-512 (include/shadowvol_planes.h,
 * "Planes by clusters"), BIT-IDENTICAL to sv_derive_planes_c_ref: the same
 * float operations in the same order, no FMA (built with
 * -ffp-contract=off, no FMA intrinsics), sqrt and division correctly
 * rounded, the zero plane by the same ordered compares.
 *
 * New (not a listing of the paper). The trick: the corner gather moves
 * from memory to the permute unit. Per cluster (at most 32 vertices):
 *   - each vertex one masked 16-byte load (x, y, z, 0) (mask 0111: the 12
 *     bytes of the vertex only, no fault past the array), four per
 *     register by lane inserts; an in-lane 4x4 transpose makes the x, y, z
 *     columns, so that table entry 4L + r (lane L of load register r) is
 *     vertex list entry 4L + r;
 *   - X0/X1, Y0/Y1, Z0/Z1: entries 0..15 and 16..31.
 * Per 16 triangles (one 48-byte corner group):
 *   - three vpmovzxbd: the first, second and third corners as 32-bit
 *     table entries;
 *   - nine vpermt2ps: px = X[i0], ..., bz = Z[i2] (two-register permutes,
 *     32 entries);
 *   - the reference's arithmetic on 16 lanes; lanes outside
 *     0 < len2 < inf become the zero plane by zero-masking;
 *   - an in-lane 4x4 transpose back to planes, and 16 scattered 16-byte
 *     stores to the triangles' places (a lane extracted to memory is a
 *     store, no shuffle).
 * Register map (per step): zmm X0..Z1 the cluster's table; i0..i2 the
 * corners; px..bz the corners' coordinates and edges; nx..nz, len2, inv;
 * a..d; R0..R3 the planes as rows. k-mask ok: the lanes with a plane.
 *
 * Input contracts: the clusters' (sv::plane_clusters); positions 3 floats
 * per vertex, no alignment; planes: no alignment, only the clusters'
 * triangles written.
 *
 * Copyright (C) 2026 the shadowvol authors. LGPL-2.1-or-later.
 */
#include <immintrin.h>
#include <stdint.h>

#include "planes_avx512_normal.h"
#include "planes_internal.h"
#include "../core/simd_exit.h"

#define SV_TARGET_AVX512 __attribute__((target("avx512f,avx512bw,avx512vl,avx512dq,avx2")))

/* Vertex list entry K as (x, y, z, 0): one load of its byte offset, one
 * masked load. */
SV_TARGET_AVX512 static inline __m128 vertex_row(const float *positions, const uint32_t *vertices,
                                                 int k) {
    return _mm_maskz_loadu_ps(0x7, (const char *)positions + vertices[k]);
}

/* Entries 4L + R for lanes L = 0..3 of load register R. */
SV_TARGET_AVX512 static inline __m512 vertex_rows4(const float *positions, const uint32_t *vertices,
                                                   int r) {
    const __m256 lo =
        _mm256_insertf128_ps(_mm256_castps128_ps256(vertex_row(positions, vertices, r)),
                             vertex_row(positions, vertices, 4 + r), 1);
    const __m256 hi =
        _mm256_insertf128_ps(_mm256_castps128_ps256(vertex_row(positions, vertices, 8 + r)),
                             vertex_row(positions, vertices, 12 + r), 1);
    return _mm512_insertf32x8(_mm512_castps256_ps512(lo), hi, 1);
}

/* Entries 0 .. 15 of VERTICES: x, y, z columns. */
SV_TARGET_AVX512 static inline void load_table16(const float *positions, const uint32_t *vertices,
                                                 __m512 *x, __m512 *y, __m512 *z) {
    const __m512 r0 = vertex_rows4(positions, vertices, 0);
    const __m512 r1 = vertex_rows4(positions, vertices, 1);
    const __m512 r2 = vertex_rows4(positions, vertices, 2);
    const __m512 r3 = vertex_rows4(positions, vertices, 3);
    const __m512 t0 = _mm512_unpacklo_ps(r0, r1); /* x0 x1 y0 y1 */
    const __m512 t1 = _mm512_unpacklo_ps(r2, r3); /* x2 x3 y2 y3 */
    const __m512 t2 = _mm512_unpackhi_ps(r0, r1); /* z0 z1 .  .  */
    const __m512 t3 = _mm512_unpackhi_ps(r2, r3); /* z2 z3 .  .  */
    *x = _mm512_shuffle_ps(t0, t1, _MM_SHUFFLE(1, 0, 1, 0));
    *y = _mm512_shuffle_ps(t0, t1, _MM_SHUFFLE(3, 2, 3, 2));
    *z = _mm512_shuffle_ps(t2, t3, _MM_SHUFFLE(1, 0, 1, 0));
}

SV_TARGET_AVX512 void sv_derive_planes_clustered_avx512(const float *positions,
                                                        const sv_plane_clusters *clusters,
                                                        Plane *planes) {
    for (int c = 0; c < clusters->num_clusters; c++) {
        const uint32_t *vertices = clusters->vertex_offsets + clusters->vertex_begin[c];
        __m512 x0, y0, z0, x1, y1, z1;
        load_table16(positions, vertices, &x0, &y0, &z0);
        if (clusters->vertex_begin[c + 1] - clusters->vertex_begin[c] > 16) {
            load_table16(positions, vertices + 16, &x1, &y1, &z1);
        } else {
            x1 = y1 = z1 = _mm512_setzero_ps();
        }
        for (int g = clusters->group_begin[c]; g < clusters->group_begin[c + 1]; g++) {
            const uint8_t *group = clusters->corners + 48 * (size_t)g;
            const __m512i i0 = _mm512_cvtepu8_epi32(_mm_loadu_si128((const __m128i *)group));
            const __m512i i1 = _mm512_cvtepu8_epi32(_mm_loadu_si128((const __m128i *)(group + 16)));
            const __m512i i2 = _mm512_cvtepu8_epi32(_mm_loadu_si128((const __m128i *)(group + 32)));
            const __m512 px = _mm512_permutex2var_ps(x0, i0, x1);
            const __m512 py = _mm512_permutex2var_ps(y0, i0, y1);
            const __m512 pz = _mm512_permutex2var_ps(z0, i0, z1);
            const __m512 ax = _mm512_sub_ps(_mm512_permutex2var_ps(x0, i1, x1), px);
            const __m512 ay = _mm512_sub_ps(_mm512_permutex2var_ps(y0, i1, y1), py);
            const __m512 az = _mm512_sub_ps(_mm512_permutex2var_ps(z0, i1, z1), pz);
            const __m512 bx = _mm512_sub_ps(_mm512_permutex2var_ps(x0, i2, x1), px);
            const __m512 by = _mm512_sub_ps(_mm512_permutex2var_ps(y0, i2, y1), py);
            const __m512 bz = _mm512_sub_ps(_mm512_permutex2var_ps(z0, i2, z1), pz);
            __m512 nx, ny, nz, len2;
            const __mmask16 ok = sv_normal16_avx512(ax, ay, az, bx, by, bz, &nx, &ny, &nz, &len2);
            const __m512 inv = _mm512_div_ps(_mm512_set1_ps(1.0f), _mm512_sqrt_ps(len2));
            const __m512 a = _mm512_maskz_mul_ps(ok, nx, inv);
            const __m512 b = _mm512_maskz_mul_ps(ok, ny, inv);
            const __m512 cc = _mm512_maskz_mul_ps(ok, nz, inv);
            const __m512 sum = _mm512_add_ps(_mm512_add_ps(_mm512_mul_ps(a, px),
                                                           _mm512_mul_ps(b, py)),
                                             _mm512_mul_ps(cc, pz));
            const __m512 d = _mm512_maskz_xor_ps(ok, sum, _mm512_set1_ps(-0.0f));
            /* Row r, lane L: the plane of triangle 4L + r of the group. */
            const __m512 u0 = _mm512_unpacklo_ps(a, b), u1 = _mm512_unpacklo_ps(cc, d);
            const __m512 u2 = _mm512_unpackhi_ps(a, b), u3 = _mm512_unpackhi_ps(cc, d);
            const __m512 r0 = _mm512_shuffle_ps(u0, u1, _MM_SHUFFLE(1, 0, 1, 0));
            const __m512 r1 = _mm512_shuffle_ps(u0, u1, _MM_SHUFFLE(3, 2, 3, 2));
            const __m512 r2 = _mm512_shuffle_ps(u2, u3, _MM_SHUFFLE(1, 0, 1, 0));
            const __m512 r3 = _mm512_shuffle_ps(u2, u3, _MM_SHUFFLE(3, 2, 3, 2));
            const uint32_t *at = clusters->plane_offsets + 16 * (size_t)g;
            char *out = (char *)planes;
#define SV_STORE_LANES(R, r)                                                                       \
    _mm_storeu_ps((float *)(out + at[(r)]), _mm512_castps512_ps128(R));                            \
    _mm_storeu_ps((float *)(out + at[4 + (r)]), _mm512_extractf32x4_ps(R, 1));                     \
    _mm_storeu_ps((float *)(out + at[8 + (r)]), _mm512_extractf32x4_ps(R, 2));                     \
    _mm_storeu_ps((float *)(out + at[12 + (r)]), _mm512_extractf32x4_ps(R, 3))
            SV_STORE_LANES(r0, 0);
            SV_STORE_LANES(r1, 1);
            SV_STORE_LANES(r2, 2);
            SV_STORE_LANES(r3, 3);
#undef SV_STORE_LANES
        }
    }
    SV_VZEROUPPER_IF_UNOPTIMISED();
}
