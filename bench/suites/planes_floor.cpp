/*
 * The planes' floor: sv_derive_planes_c_ref's arithmetic on corners
 * gathered beforehand (planes_floor.h). AVX2, 8 triangles a step: nine
 * loads, the edges, the cross product, len2, one sqrt and one divide, the
 * plane, the zero plane by masking, a 4x8 transpose and four stores.
 * target("avx2") without "fma", so the compiler cannot contract a
 * multiply and an add the reference keeps apart.
 *
 * Copyright (C) 2026 the shadowvol authors. LGPL-2.1-or-later.
 */
#include "planes_floor.h"

#include <cmath>
#include <cstddef>
#include <cstring>

#include <immintrin.h>

#include "planes_store_avx2.h"

namespace svbench {

GatheredCorners gather_corners(const float *positions, const int *indices, int numTriangles) {
    GatheredCorners g;
    g.triangles = numTriangles;
    const std::size_t padded = ((std::size_t)numTriangles + 7) / 8 * 8;
    for (auto &c : g.corner) c.assign(padded, 0.0f);
    for (int t = 0; t < numTriangles; t++) {
        for (int c = 0; c < 3; c++) {
            const float *p = positions + 3 * (std::ptrdiff_t)indices[3 * t + c];
            for (int k = 0; k < 3; k++) g.corner[3 * c + k][(std::size_t)t] = p[k];
        }
    }
    return g;
}

bool planes_floor_runs() { return (sv_cpu_isa() & SV_ISA_AVX2) != 0; }

__attribute__((target("avx2"))) void planes_from_gathered_avx2(const GatheredCorners &g,
                                                               Plane *planes) {
    const float *c[9];
    for (int i = 0; i < 9; i++) c[i] = g.corner[i].data();
    for (int t = 0; t < g.triangles; t += 8) {
        const __m256 px = _mm256_loadu_ps(c[0] + t), py = _mm256_loadu_ps(c[1] + t),
                     pz = _mm256_loadu_ps(c[2] + t);
        const __m256 ax = _mm256_sub_ps(_mm256_loadu_ps(c[3] + t), px);
        const __m256 ay = _mm256_sub_ps(_mm256_loadu_ps(c[4] + t), py);
        const __m256 az = _mm256_sub_ps(_mm256_loadu_ps(c[5] + t), pz);
        const __m256 bx = _mm256_sub_ps(_mm256_loadu_ps(c[6] + t), px);
        const __m256 by = _mm256_sub_ps(_mm256_loadu_ps(c[7] + t), py);
        const __m256 bz = _mm256_sub_ps(_mm256_loadu_ps(c[8] + t), pz);
        const __m256 nx = _mm256_sub_ps(_mm256_mul_ps(ay, bz), _mm256_mul_ps(az, by));
        const __m256 ny = _mm256_sub_ps(_mm256_mul_ps(az, bx), _mm256_mul_ps(ax, bz));
        const __m256 nz = _mm256_sub_ps(_mm256_mul_ps(ax, by), _mm256_mul_ps(ay, bx));
        const __m256 len2 = _mm256_add_ps(_mm256_add_ps(_mm256_mul_ps(nx, nx),
                                                        _mm256_mul_ps(ny, ny)),
                                          _mm256_mul_ps(nz, nz));
        const __m256 ok = _mm256_and_ps(_mm256_cmp_ps(len2, _mm256_setzero_ps(), _CMP_GT_OQ),
                                        _mm256_cmp_ps(len2, _mm256_set1_ps(INFINITY), _CMP_LT_OQ));
        const __m256 inv = _mm256_div_ps(_mm256_set1_ps(1.0f), _mm256_sqrt_ps(len2));
        const __m256 a = _mm256_mul_ps(nx, inv), b = _mm256_mul_ps(ny, inv),
                     cc = _mm256_mul_ps(nz, inv);
        const __m256 d =
            _mm256_xor_ps(_mm256_add_ps(_mm256_add_ps(_mm256_mul_ps(a, px), _mm256_mul_ps(b, py)),
                                        _mm256_mul_ps(cc, pz)),
                          _mm256_set1_ps(-0.0f));
        /* The reference's zero plane outside 0 < len2 < inf: +0.0 each. */
        const __m256 za = _mm256_and_ps(a, ok), zb = _mm256_and_ps(b, ok),
                     zc = _mm256_and_ps(cc, ok), zd = _mm256_and_ps(d, ok);
        if (g.triangles - t >= 8) {
            sv_store_planes8_avx2(planes + t, za, zb, zc, zd);
        } else {
            Plane tail[8];
            sv_store_planes8_avx2(tail, za, zb, zc, zd);
            std::memcpy(planes + t, tail, sizeof(Plane) * (std::size_t)(g.triangles - t));
        }
    }
    _mm256_zeroupper();
}

} // namespace svbench
