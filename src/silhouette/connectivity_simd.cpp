/*
 * The connectivity finder in AVX2 and AVX-512 (C++ intrinsics under target
 * attributes; the callers check sv_cpu_isa()). The test per use is a gather
 * of two facing bytes: the triangle's own (eight or sixteen consecutive
 * bytes, spread to the uses with a permute) and its neighbour's (a dword
 * gather at facing + neighbour, low byte kept: so facing needs
 * numTriangles + 4 readable bytes). Result identical to the scalar finders
 * as a multiset; the order is the same as find_silhouette_connectivity's
 * (AVX2) or permuted within each step (AVX-512, see below).
 *
 * Copyright (C) 2026 the shadowvol authors. LGPL-2.1-or-later.
 */
/* GCC 12's AVX-512 headers start some intrinsics from _mm512_undefined_*,
 * which -Wmaybe-uninitialized reports at every use (a known false
 * positive; the lanes are all written before they are read). */
#pragma GCC diagnostic ignored "-Wmaybe-uninitialized"
#include <immintrin.h>

#include "shadowvol_silhouette.h"
#include "silhouette_internal.h"

namespace sv {

namespace {

/* For the uses of a group of triangles, split into vectors of LANES uses:
 * lane j of vector r is use LANES * r + j of the group, i.e. corner
 * (LANES * r + j) % 3 of triangle (LANES * r + j) / 3. */
alignas(32) const int kTri8[3][8] = {{0, 0, 0, 1, 1, 1, 2, 2},
                                     {2, 3, 3, 3, 4, 4, 4, 5},
                                     {5, 5, 6, 6, 6, 7, 7, 7}};
/* The next corner's use, relative to the use: +1, +1, -2. */
const int kNext24[24] = {1, 1, -2, 1, 1, -2, 1, 1, -2, 1, 1, -2,
                         1, 1, -2, 1, 1, -2, 1, 1, -2, 1, 1, -2};

} // namespace

__attribute__((target("avx2,bmi"))) std::size_t
find_silhouette_connectivity_avx2(const ConnectivityTable &c, const int *indices, int numTriangles,
                                  const uint8_t *facing, DirectedEdge *out) {
    std::size_t n = 0;
    const int *nb = c.neighbour.data();
    const __m256i one = _mm256_set1_epi32(1);
    const __m256i low = _mm256_set1_epi32(0xFF);
    const __m256i tri0 = _mm256_load_si256((const __m256i *)kTri8[0]);
    const __m256i tri1 = _mm256_load_si256((const __m256i *)kTri8[1]);
    const __m256i tri2 = _mm256_load_si256((const __m256i *)kTri8[2]);
    const int groups = numTriangles / 8;
    for (int g = 0; g < groups; g++) {
        const int u0 = 24 * g;
        /* Eight own facing bytes; none lit (lit and unlit triangles come in
         * patches, so this is common): no neighbour can matter, as in the
         * seed's early out, but per eight triangles. */
        const __m128i own8 = _mm_loadl_epi64((const __m128i *)(facing + 8 * g));
        if (_mm_cvtsi128_si64(own8) == 0) continue;
        const __m256i own = _mm256_cvtepu8_epi32(own8);
        const __m256i tri[3] = {tri0, tri1, tri2};
        for (int r = 0; r < 3; r++) {
            const __m256i lit = _mm256_permutevar8x32_epi32(own, tri[r]);
            if (_mm256_testz_si256(lit, lit)) continue; /* skip the gather */
            const __m256i p = _mm256_loadu_si256((const __m256i *)(nb + u0 + 8 * r));
            const __m256i other =
                _mm256_and_si256(_mm256_i32gather_epi32((const int *)facing, p, 1), low);
            /* lit & !other, as 0 or 1 per lane, then to a sign for movemask. */
            const __m256i cast = _mm256_andnot_si256(other, _mm256_and_si256(lit, one));
            unsigned mask = (unsigned)_mm256_movemask_ps(
                _mm256_castsi256_ps(_mm256_cmpeq_epi32(cast, one)));
            while (mask) { /* once per silhouette use: about 5% of them */
                const int j = (int)_tzcnt_u32(mask);
                const int u = u0 + 8 * r + j;
                out[n++] = {(uint32_t)indices[u], (uint32_t)indices[u + kNext24[8 * r + j]]};
                mask = _blsr_u32(mask);
            }
        }
    }
    n = silhouette_connectivity_tail(c, indices, 8 * groups, numTriangles, facing, out, n);
    return silhouette_dangling(c, indices, facing, out, n);
}

namespace {

/* Sixteen triangles = 48 uses = three zmm vectors of uses. */
alignas(64) const
    int kTri16[3][16] = {{0, 0, 0, 1, 1, 1, 2, 2, 2, 3, 3, 3, 4, 4, 4, 5},
                         {5, 5, 6, 6, 6, 7, 7, 7, 8, 8, 8, 9, 9, 9, 10, 10},
                         {10, 11, 11, 11, 12, 12, 12, 13, 13, 13, 14, 14, 14, 15, 15, 15}};
/* Use number (within the group) of the next corner, per lane. */
alignas(64) const
    int kNextUse48[3][16] = {{1, 2, 0, 4, 5, 3, 7, 8, 6, 10, 11, 9, 13, 14, 12, 16},
                             {17, 15, 19, 20, 18, 22, 23, 21, 25, 26, 24, 28, 29, 27, 31, 32},
                             {30, 34, 35, 33, 37, 38, 36, 40, 41, 39, 43, 44, 42, 46, 47, 45}};

} // namespace

__attribute__((target("avx512f,avx512bw,avx512vl,avx512dq,bmi2,popcnt"))) std::size_t
find_silhouette_connectivity_avx512(const ConnectivityTable &c, const int *indices,
                                    int numTriangles, const uint8_t *facing, DirectedEdge *out) {
    std::size_t n = 0;
    const int *nb = c.neighbour.data();
    const __m512i one = _mm512_set1_epi32(1);
    const int groups = numTriangles / 16;
    for (int g = 0; g < groups; g++) {
        const int u0 = 48 * g;
        const __m128i own16 = _mm_loadu_si128((const __m128i *)(facing + 16 * g));
        if (_mm_testz_si128(own16, own16)) continue; /* no triangle lit: as AVX2's */
        const __m512i own = _mm512_cvtepu8_epi32(own16);
        for (int r = 0; r < 3; r++) {
            const __m512i lit = _mm512_permutexvar_epi32(_mm512_load_si512((const void *)kTri16[r]),
                                                         own);
            const __m512i p = _mm512_loadu_si512((const void *)(nb + u0 + 16 * r));
            const __m512i other = _mm512_i32gather_epi32(p, (const void *)facing, 1);
            /* lit and the neighbour's low byte 0 */
            const __mmask16 litMask = _mm512_test_epi32_mask(lit, one);
            if (!litMask) continue; /* skip the gathers */
            const __mmask16 cast = litMask &
                                   _mm512_testn_epi32_mask(other, _mm512_set1_epi32(0xFF));
            if (!cast) continue;
            const __m512i from = _mm512_loadu_si512((const void *)(indices + u0 + 16 * r));
            const __m512i nextUse = _mm512_add_epi32(_mm512_load_si512((const void *)kNextUse48[r]),
                                                     _mm512_set1_epi32(u0));
            const __m512i to = _mm512_i32gather_epi32(nextUse, (const void *)indices, 4);
            /* (from, to) pairs as qwords: unpacklo holds lanes 0,1,4,5,8,9,
             * 12,13, unpackhi lanes 2,3,6,7,...; compress each with its
             * half of the mask (so edges come out permuted within the
             * vector: the result is a multiset). */
            const __m512i lo = _mm512_unpacklo_epi32(from, to);
            const __m512i hi = _mm512_unpackhi_epi32(from, to);
            const __mmask8 mlo = (__mmask8)_pext_u32(cast, 0x3333u);
            const __mmask8 mhi = (__mmask8)_pext_u32(cast, 0xCCCCu);
            _mm512_mask_compressstoreu_epi64((void *)(out + n), mlo, lo);
            n += (std::size_t)_mm_popcnt_u32(mlo);
            _mm512_mask_compressstoreu_epi64((void *)(out + n), mhi, hi);
            n += (std::size_t)_mm_popcnt_u32(mhi);
        }
    }
    n = silhouette_connectivity_tail(c, indices, 16 * groups, numTriangles, facing, out, n);
    return silhouette_dangling(c, indices, facing, out, n);
}

} // namespace sv
