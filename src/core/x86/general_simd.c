/*
 * The general rule's kernels (issue 27, shadowvol.h: sv_general_edges)
 * with AVX2 and AVX-512. New, not listings of the paper. Each gives
 * exactly the index list of the C reference (src/core/ref/reference_
 * general.c), in the same order.
 *
 * Why intrinsics and not NASM, as the paper's routines are: the general
 * routine is a composition (the paper's class goes to the paper's NASM
 * kernel of the same instruction set, the pairs to a vector pass, the
 * rare open and shared edges to the reference's scalar loops), and the
 * vector part is short (a transpose, two gathers, compares, compresses);
 * written in C with the ISA as a function attribute it reads as the
 * reference does, beside facing_simd.c, and the compiler keeps the ABI.
 *
 * Silhouette (the pairs, the bulk of an open surface's edges): per block
 * of 16 pairs (AVX-512), p1 and p2 are transposed out of the SilEdges,
 * their facing bytes gathered (AVX2: 8 pairs, looked up one by one), and
 * the masks C1 = f1 ^ f2 (f =
 * byte != 0: the triangles' paper facing) and C2 = g1 ^ g2 (g = byte !=
 * 2: their reverses') select the pairs that draw a quad; each selected
 * pair goes to a list on the stack as 16 * pair + a code (C1, C2, f1, g1),
 * left-packed (AVX-512: vpcompressd; AVX2: a permutation made by pdep and
 * pext). Then one loop over the list writes each pair's copies: AVX-512
 * one vpermd of (v1, v2), one vpxord and one masked store of 6 or 12 ints
 * by tables of the code; AVX2 twelve scalar ints, the pointer advanced by
 * 6 per copy drawn (so up to 6 ints past the count, within the bound). No
 * branch depends on the facing bytes; the order is the reference's (a
 * pair's first copy, then its second). On open shells both copies are
 * drawn together (C1 = C2 unless a triangle is culled): one list entry
 * for the two.
 *
 * AVX-512 gathers each facing byte as the top byte of the unaligned 32-bit
 * word that ends at it, facing[p - 3 .. p] (vpgatherdd, scale 1, then a
 * shift): every byte read lies between facing[0] and the triangle's own
 * byte, so nothing past the array is read. A lane with p < 3 (the first
 * three triangles: one block in thousands) reads its byte alone, scalar.
 *
 * Caps (AVX-512): 16 triangles at a time, their 48 indices doubled, each
 * output register of 16 ints made by two vpermt2d (the triangle as it is
 * and reversed, blended by the per-triangle form) plus the far caps' +1,
 * then compressed by the triangles that cast (or stored whole when all 16
 * cast, as on a general shell where nothing is culled). AVX2: the
 * reference's caps (see sv_create_general_cap_triangles_avx2).
 *
 * Copyright (C) 2026 the shadowvol authors. LGPL-2.1-or-later.
 */
#include <immintrin.h>
#include <stdint.h>
#include <string.h>

#include "shadowvol.h"
#include "../simd_exit.h"

#if defined(SV_HAVE_ASM_AVX2)

/* Pairs per list chunk: two lists of this many ints on the stack (4 KiB). */
#define CHUNK 512

/* The paper's quad of the edge a -> b (section 6), branch-free: F = 0
 * gives (a, b, b+1, a+1, a, b+1), F = 1 (a, b+1, b, a, a+1, b+1); a and b
 * even, so + 1 is ^ 1. */
static inline int *put_quad(int *si, int f, int a, int b) {
    si[0] = a;
    si[1] = b ^ f;
    si[2] = b ^ f ^ 1;
    si[3] = a ^ f ^ 1;
    si[4] = a ^ f;
    si[5] = b ^ 1;
    return si + 6;
}

/* The code of a selected pair in the lists below: bit 0 its first copy
 * is drawn (C1: the paper facings f1, f2 differ), bit 1 its second (C2:
 * g1, g2 differ), bit 2 f1, bit 3 g1. A list entry is 16 * pair + code. */
enum { kFirst = 1, kSecond = 2, kF1 = 4, kG1 = 8 };

/* Both copies of pair E, as the reference writes them: the first at SI,
 * the second after it when the first is drawn. Writes 12 ints (6 past the
 * count when one copy is drawn: within the 12 per pair of the bound). */
static inline int *emit_pair(int *si, const SilEdge *e, int code) {
    put_quad(si, (code & kF1) != 0, e->v1, e->v2);
    si += 6 * (code & kFirst);
    put_quad(si, (code & kG1) != 0, e->v2, e->v1);
    return si + 6 * ((code & kSecond) >> 1);
}

static int *emit_list(int *si, const SilEdge *pairs, const int *list, int n) {
    for (int k = 0; k < n; k++) si = emit_pair(si, &pairs[list[k] >> 4], list[k] & 15);
    return si;
}

/* The open and shared edges: the reference's loops (few on any surface;
 * their branches follow the culling, not the light); with PAIRS, the
 * pairs too (fewer than a block of them: the vector pass's set-up costs
 * more than it saves). */
static int *rest_c(int *si, const uint8_t *facing, const sv_general_edges *e, int pairs) {
    sv_general_edges rest = *e;
    rest.numPaper = 0;
    if (!pairs) rest.numPairs = 0;
    return si + sv_create_general_sil_triangles_c_ref(si, facing, &rest);
}

/* Below this many pairs, or triangles for the caps, the reference's loops
 * are faster than a vector block's set-up (bench --casters, the generated
 * cases of one to fifty triangles). */
#define SMALL 16

/* ---- AVX2 ----------------------------------------------------------------- */

#define SV_TARGET_AVX2 __attribute__((target("avx2,bmi,bmi2,popcnt")))

/* Left-packs the lanes of V whose bit is set in MASK (8 bits) into OUT
 * (writes 8 ints, advances by the count). */
SV_TARGET_AVX2 static inline int pack8(int *out, __m256i v, unsigned mask) {
    /* pdep/pext: the lane numbers of the set bits, 3 bits each. */
    const uint32_t lanes = (uint32_t)_pext_u32(0x76543210u,
                                               (uint32_t)_pdep_u32(mask, 0x11111111u) * 0xFu);
    const __m256i idx = _mm256_srlv_epi32(_mm256_set1_epi32((int)lanes),
                                          _mm256_setr_epi32(0, 4, 8, 12, 16, 20, 24, 28));
    _mm256_storeu_si256((__m256i *)(void *)out,
                        _mm256_permutevar8x32_epi32(v,
                                                    _mm256_and_si256(idx, _mm256_set1_epi32(7))));
    return _mm_popcnt_u32(mask);
}

/* The code of a pair (above) from its two bytes, by a table of the nine
 * byte pairs, each entry the definition itself. */
#define PAIR_CODE(b1, b2)                                                                          \
    ((((b1) != 0) != ((b2) != 0)) * kFirst + (((b1) != 2) != ((b2) != 2)) * kSecond +              \
     ((b1) != 0) * kF1 + ((b1) != 2) * kG1)
static const uint8_t pair_code[3][3] = {
    {PAIR_CODE(0, 0), PAIR_CODE(0, 1), PAIR_CODE(0, 2)},
    {PAIR_CODE(1, 0), PAIR_CODE(1, 1), PAIR_CODE(1, 2)},
    {PAIR_CODE(2, 0), PAIR_CODE(2, 1), PAIR_CODE(2, 2)},
};

SV_TARGET_AVX2 static int *pairs_avx2(int *si, const uint8_t *facing, const SilEdge *pairs,
                                      int numPairs) {
    /* Scalar look-ups (a vpgatherdd of 8 lanes costs more than 16 byte
     * loads here, as the paper's AVX2 CreateSilTriangles found), the
     * selected pairs left-packed branch-free, 8 at a time by pack8. */
    int list[CHUNK + 8];
    for (int c = 0; c < numPairs; c += CHUNK) {
        const int end = numPairs - c < CHUNK ? numPairs : c + CHUNK;
        int n = 0, i = c;
        for (; i + 8 <= end; i += 8) {
            int entry[8];
            unsigned sel = 0;
            for (int k = 0; k < 8; k++) {
                const SilEdge *e = &pairs[i + k];
                const int code = pair_code[facing[e->p1]][facing[e->p2]];
                entry[k] = 16 * (i + k) + code;
                sel |= (unsigned)((code & (kFirst | kSecond)) != 0) << k;
            }
            n += pack8(list + n, _mm256_loadu_si256((const __m256i *)(const void *)entry), sel);
        }
        for (; i < end; i++) {
            const int code = pair_code[facing[pairs[i].p1]][facing[pairs[i].p2]];
            list[n] = 16 * i + code;
            n += (code & (kFirst | kSecond)) != 0;
        }
        /* emit_list is SSE code: leave the upper YMM state clean for it
         * (GCC does not always insert this before a call to a static
         * function). */
        _mm256_zeroupper();
        si = emit_list(si, pairs, list, n);
    }
    return si;
}

SV_TARGET_AVX2 int sv_create_general_sil_triangles_avx2(int *shadowIndices, const uint8_t *facing,
                                                        const sv_general_edges *edges) {
    int *si = shadowIndices;
    /* (The paper's kernel sets up a frame even for no edges.) */
    if (edges->numPaper > 0)
        si += sv_create_sil_triangles_avx2(si, facing, edges->paper, edges->numPaper);
    const int small = edges->numPairs < SMALL;
    if (!small) si = pairs_avx2(si, facing, edges->pairs, edges->numPairs);
    /* The reference is SSE code: no upper state dirty for it (the wide
     * copies of the table GCC may have used). */
    _mm256_zeroupper();
    si = rest_c(si, facing, edges, small);
    SV_VZEROUPPER_IF_UNOPTIMISED();
    return (int)(si - shadowIndices);
}

/* No AVX2 cap kernel beats the reference here: a branch-free scalar one
 * (six ints written per triangle, the pointer advanced when it casts) took
 * 1.3-1.5x its time on the open character and the demo terrain, and
 * without AVX-512's compress a vector one must left-pack 96 ints per 16
 * triangles by tables. So the AVX2 row's caps are the reference's. */
SV_TARGET_AVX2 int sv_create_general_cap_triangles_avx2(int *shadowIndices, const uint8_t *facing,
                                                        const int *indices, int numIndices) {
    return sv_create_general_cap_triangles_c_ref(shadowIndices, facing, indices, numIndices);
}

#endif /* SV_HAVE_ASM_AVX2 */

#if defined(SV_HAVE_ASM_AVX512)

/* ---- AVX-512 -------------------------------------------------------------- */

#define SV_TARGET_AVX512 __attribute__((target("avx512f,avx512bw,avx512vl,avx512dq,bmi,popcnt")))

/* facing[p] of the live lanes of P (0 in the others), read as the top byte
 * of facing[p - 3 .. p]: no byte outside facing[0 .. p] is read. */
SV_TARGET_AVX512 static inline __m512i facing_bytes16(const uint8_t *facing, __m512i p,
                                                      __mmask16 live) {
    const __mmask16 first3 = _mm512_mask_cmplt_epi32_mask(live, p, _mm512_set1_epi32(3));
    const __m512i words = _mm512_mask_i32gather_epi32(_mm512_setzero_si512(),
                                                      (__mmask16)(live & ~first3),
                                                      _mm512_sub_epi32(p, _mm512_set1_epi32(3)),
                                                      facing, 1);
    __m512i bytes = _mm512_srli_epi32(words, 24);
    if (first3) { /* rare: their words would start before facing[0] */
        int lanes[16];
        _mm512_storeu_si512(lanes, p);
        for (unsigned m = first3; m; m &= m - 1u) {
            const int k = __builtin_ctz(m);
            bytes = _mm512_mask_set1_epi32(bytes, (__mmask16)(1u << k), facing[lanes[k]]);
        }
    }
    return bytes;
}

/* emit_pair's ints by table, per code: which of (v1, v2) each of 16
 * lanes takes (a copy of v1 -> v2 takes v1 v2 v2 v1 v1 v2, the second
 * copy runs v2 -> v1), the ^ 1 pattern (0, f, f^1, f^1, f, 1 for the form
 * bit f: g1 for the second copy), and how many ints are kept (6 per copy
 * drawn; the first copy first, as emit_pair writes them). */
typedef struct PairTables {
    int32_t pick[16][16], flip[16][16], ints[16];
} PairTables;

static const PairTables pair_tables = {
    {
        {0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0},
        {0, 1, 1, 0, 0, 1, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0},
        {1, 0, 0, 1, 1, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0},
        {0, 1, 1, 0, 0, 1, 1, 0, 0, 1, 1, 0, 0, 0, 0, 0},
        {0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0},
        {0, 1, 1, 0, 0, 1, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0},
        {1, 0, 0, 1, 1, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0},
        {0, 1, 1, 0, 0, 1, 1, 0, 0, 1, 1, 0, 0, 0, 0, 0},
        {0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0},
        {0, 1, 1, 0, 0, 1, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0},
        {1, 0, 0, 1, 1, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0},
        {0, 1, 1, 0, 0, 1, 1, 0, 0, 1, 1, 0, 0, 0, 0, 0},
        {0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0},
        {0, 1, 1, 0, 0, 1, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0},
        {1, 0, 0, 1, 1, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0},
        {0, 1, 1, 0, 0, 1, 1, 0, 0, 1, 1, 0, 0, 0, 0, 0},
    },
    {
        {0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0},
        {0, 0, 1, 1, 0, 1, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0},
        {0, 0, 1, 1, 0, 1, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0},
        {0, 0, 1, 1, 0, 1, 0, 0, 1, 1, 0, 1, 0, 0, 0, 0},
        {0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0},
        {0, 1, 0, 0, 1, 1, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0},
        {0, 0, 1, 1, 0, 1, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0},
        {0, 1, 0, 0, 1, 1, 0, 0, 1, 1, 0, 1, 0, 0, 0, 0},
        {0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0},
        {0, 0, 1, 1, 0, 1, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0},
        {0, 1, 0, 0, 1, 1, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0},
        {0, 0, 1, 1, 0, 1, 0, 1, 0, 0, 1, 1, 0, 0, 0, 0},
        {0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0},
        {0, 1, 0, 0, 1, 1, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0},
        {0, 1, 0, 0, 1, 1, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0},
        {0, 1, 0, 0, 1, 1, 0, 1, 0, 0, 1, 1, 0, 0, 0, 0},
    },
    {0, 6, 6, 12, 0, 6, 6, 12, 0, 6, 6, 12, 0, 6, 6, 12},
};

SV_TARGET_AVX512 static int *emit_list_avx512(int *si, const SilEdge *pairs, const int *list,
                                              int n) {
    for (int k = 0; k < n; k++) {
        const int code = list[k] & 15;
        const __m128i vv = _mm_loadl_epi64((const __m128i *)(const void *)&pairs[list[k] >> 4].v1);
        const __m512i w =
            _mm512_xor_si512(_mm512_permutexvar_epi32(_mm512_loadu_si512(pair_tables.pick[code]),
                                                      _mm512_castsi128_si512(vv)),
                             _mm512_loadu_si512(pair_tables.flip[code]));
        _mm512_mask_storeu_epi32(si, (__mmask16)((1u << pair_tables.ints[code]) - 1u), w);
        si += pair_tables.ints[code];
    }
    return si;
}

SV_TARGET_AVX512 static int *pairs_avx512(int *si, const uint8_t *facing, const SilEdge *pairs,
                                          int numPairs) {
    int list[CHUNK + 16];
    const __m512i pick = _mm512_setr_epi32(0, 4, 8, 12, 16, 20, 24, 28, 1, 5, 9, 13, 17, 21, 25,
                                           29);
    const __m512i iota = _mm512_setr_epi32(0, 1, 2, 3, 4, 5, 6, 7, 8, 9, 10, 11, 12, 13, 14, 15);
    const __m512i zero = _mm512_setzero_si512(), two = _mm512_set1_epi32(2);
    for (int c = 0; c < numPairs; c += CHUNK) {
        const int end = numPairs - c < CHUNK ? numPairs : c + CHUNK;
        int n = 0;
        for (int i = c; i < end; i += 16) {
            /* The last block masked: missing edges read nothing. */
            const int left = end - i < 16 ? end - i : 16;
            const __mmask16 live = (__mmask16)((1u << left) - 1u);
            const __mmask64 dw = left == 16 ? ~(__mmask64)0 : (((__mmask64)1 << (4 * left)) - 1u);
            const int *src = (const int *)(const void *)&pairs[i];
            const __m512i z0 = _mm512_maskz_loadu_epi32((__mmask16)dw, src);
            const __m512i z1 = _mm512_maskz_loadu_epi32((__mmask16)(dw >> 16), src + 16);
            const __m512i z2 = _mm512_maskz_loadu_epi32((__mmask16)(dw >> 32), src + 32);
            const __m512i z3 = _mm512_maskz_loadu_epi32((__mmask16)(dw >> 48), src + 48);
            const __m512i a = _mm512_permutex2var_epi32(z0, pick, z1); /* p1 0-7, p2 0-7 */
            const __m512i b = _mm512_permutex2var_epi32(z2, pick, z3); /* of 8-15 */
            const __m512i P1 = _mm512_shuffle_i64x2(a, b, 0x44);
            const __m512i P2 = _mm512_shuffle_i64x2(a, b, 0xEE);
            const __m512i b1 = facing_bytes16(facing, P1, live);
            const __m512i b2 = facing_bytes16(facing, P2, live);
            const __mmask16 f1 = _mm512_cmpneq_epi32_mask(b1, zero);
            const __mmask16 f2 = _mm512_cmpneq_epi32_mask(b2, zero);
            const __mmask16 g1 = _mm512_cmpneq_epi32_mask(b1, two);
            const __mmask16 g2 = _mm512_cmpneq_epi32_mask(b2, two);
            const __mmask16 c1 = (__mmask16)((f1 ^ f2) & live), c2 = (__mmask16)((g1 ^ g2) & live);
            __m512i entry = _mm512_slli_epi32(_mm512_add_epi32(_mm512_set1_epi32(i), iota), 4);
            entry = _mm512_mask_or_epi32(entry, c1, entry, _mm512_set1_epi32(kFirst));
            entry = _mm512_mask_or_epi32(entry, c2, entry, _mm512_set1_epi32(kSecond));
            entry = _mm512_mask_or_epi32(entry, f1, entry, _mm512_set1_epi32(kF1));
            entry = _mm512_mask_or_epi32(entry, g1, entry, _mm512_set1_epi32(kG1));
            const __mmask16 sel = (__mmask16)(c1 | c2);
            _mm512_storeu_si512(list + n, _mm512_maskz_compress_epi32(sel, entry));
            n += _mm_popcnt_u32(sel);
        }
        si = emit_list_avx512(si, pairs, list, n);
    }
    return si;
}

SV_TARGET_AVX512 int sv_create_general_sil_triangles_avx512(int *shadowIndices,
                                                            const uint8_t *facing,
                                                            const sv_general_edges *edges) {
    int *si = shadowIndices;
    /* (The paper's kernel sets up a frame even for no edges.) */
    if (edges->numPaper > 0)
        si += sv_create_sil_triangles_avx512(si, facing, edges->paper, edges->numPaper);
    const int small = edges->numPairs < SMALL;
    if (!small) si = pairs_avx512(si, facing, edges->pairs, edges->numPairs);
    /* The reference is SSE code: no upper state dirty for it (the wide
     * copies of the table GCC may have used). */
    _mm256_zeroupper();
    si = rest_c(si, facing, edges, small);
    SV_VZEROUPPER_IF_UNOPTIMISED();
    return (int)(si - shadowIndices);
}

/* Output register r (0-5) of a block of 16 triangles holds ints 16r ..
 * 16r+15; int k is corner k % 6 of triangle k / 6. Per int: the input int
 * (of the block's 48) it comes from when its triangle casts as it is (byte
 * 2: near cap i0 i1 i2, far cap i2 i1 i0) and reversed (byte 0: i2 i1 i0,
 * then i0 i1 i2), counted from the first of the two input registers that
 * register r reads; its triangle; 1 on the far cap (the odd vertex). */
typedef struct CapTables {
    int32_t as_is[6][16], reversed[6][16], triangle[6][16], far[6][16];
} CapTables;

/* The input registers output register r reads: (0, 1) for r = 0-2, (1, 2)
 * for r = 3-5 (16 output ints need at most 9 consecutive input ints). */
static int cap_input_pair(int r) { return r < 3 ? 0 : 1; }

/* Made by k = 16 r + lane: triangle k / 6, corner c = k % 6; as_is =
 * 3 * triangle + (0, 1, 2, 2, 1, 0)[c], reversed = 3 * triangle + 2 -
 * that, both less 16 * cap_input_pair(r); far = c >= 3. */
static const CapTables cap_tables = {
    /* as_is */
    {
        {0, 1, 2, 2, 1, 0, 3, 4, 5, 5, 4, 3, 6, 7, 8, 8},
        {7, 6, 9, 10, 11, 11, 10, 9, 12, 13, 14, 14, 13, 12, 15, 16},
        {17, 17, 16, 15, 18, 19, 20, 20, 19, 18, 21, 22, 23, 23, 22, 21},
        {8, 9, 10, 10, 9, 8, 11, 12, 13, 13, 12, 11, 14, 15, 16, 16},
        {15, 14, 17, 18, 19, 19, 18, 17, 20, 21, 22, 22, 21, 20, 23, 24},
        {25, 25, 24, 23, 26, 27, 28, 28, 27, 26, 29, 30, 31, 31, 30, 29},
    },
    /* reversed */
    {
        {2, 1, 0, 0, 1, 2, 5, 4, 3, 3, 4, 5, 8, 7, 6, 6},
        {7, 8, 11, 10, 9, 9, 10, 11, 14, 13, 12, 12, 13, 14, 17, 16},
        {15, 15, 16, 17, 20, 19, 18, 18, 19, 20, 23, 22, 21, 21, 22, 23},
        {10, 9, 8, 8, 9, 10, 13, 12, 11, 11, 12, 13, 16, 15, 14, 14},
        {15, 16, 19, 18, 17, 17, 18, 19, 22, 21, 20, 20, 21, 22, 25, 24},
        {23, 23, 24, 25, 28, 27, 26, 26, 27, 28, 31, 30, 29, 29, 30, 31},
    },
    /* triangle */
    {
        {0, 0, 0, 0, 0, 0, 1, 1, 1, 1, 1, 1, 2, 2, 2, 2},
        {2, 2, 3, 3, 3, 3, 3, 3, 4, 4, 4, 4, 4, 4, 5, 5},
        {5, 5, 5, 5, 6, 6, 6, 6, 6, 6, 7, 7, 7, 7, 7, 7},
        {8, 8, 8, 8, 8, 8, 9, 9, 9, 9, 9, 9, 10, 10, 10, 10},
        {10, 10, 11, 11, 11, 11, 11, 11, 12, 12, 12, 12, 12, 12, 13, 13},
        {13, 13, 13, 13, 14, 14, 14, 14, 14, 14, 15, 15, 15, 15, 15, 15},
    },
    /* far */
    {
        {0, 0, 0, 1, 1, 1, 0, 0, 0, 1, 1, 1, 0, 0, 0, 1},
        {1, 1, 0, 0, 0, 1, 1, 1, 0, 0, 0, 1, 1, 1, 0, 0},
        {0, 1, 1, 1, 0, 0, 0, 1, 1, 1, 0, 0, 0, 1, 1, 1},
        {0, 0, 0, 1, 1, 1, 0, 0, 0, 1, 1, 1, 0, 0, 0, 1},
        {1, 1, 0, 0, 0, 1, 1, 1, 0, 0, 0, 1, 1, 1, 0, 0},
        {0, 1, 1, 1, 0, 0, 0, 1, 1, 1, 0, 0, 0, 1, 1, 1},
    },
};

SV_TARGET_AVX512 int sv_create_general_cap_triangles_avx512(int *shadowIndices,
                                                            const uint8_t *facing,
                                                            const int *indices, int numIndices) {
    if (numIndices < 3 * SMALL)
        return sv_create_general_cap_triangles_c_ref(shadowIndices, facing, indices, numIndices);
    const CapTables *tab = &cap_tables;
    const int numTriangles = numIndices / 3;
    const __m512i none = _mm512_set1_epi32(SV_GENERAL_NONE),
                  lit = _mm512_set1_epi32(SV_GENERAL_LIT);
    int *si = shadowIndices;
    for (int t = 0; t < numTriangles; t += 16) {
        const int left = numTriangles - t < 16 ? numTriangles - t : 16;
        const __mmask64 dw = ((__mmask64)1 << (3 * left)) - 1u;
        const int *src = indices + 3 * (size_t)t;
        /* The 48 indices doubled, in three registers; missing ones 0. */
        __m512i in[3];
        for (int k = 0; k < 3; k++)
            in[k] = _mm512_slli_epi32(_mm512_maskz_loadu_epi32((__mmask16)(dw >> (16 * k)),
                                                               src + 16 * k),
                                      1);
        const __mmask16 live = (__mmask16)((1u << left) - 1u);
        const __m512i bytes = _mm512_cvtepu8_epi32(_mm_maskz_loadu_epi8(live, facing + t));
        const __m512i count = _mm512_set1_epi32(left);
        for (int r = 0; r < 6; r++) {
            const __m512i tri = _mm512_loadu_si512(tab->triangle[r]);
            const __m512i b = _mm512_permutexvar_epi32(tri, bytes);
            const __mmask16 as_is = _mm512_cmpeq_epi32_mask(b, lit);
            const __mmask16 casts = (__mmask16)(_mm512_cmpneq_epi32_mask(b, none) &
                                                _mm512_cmplt_epi32_mask(tri, count));
            const int pr = cap_input_pair(r);
            const __m512i va = _mm512_permutex2var_epi32(in[pr], _mm512_loadu_si512(tab->as_is[r]),
                                                         in[pr + 1]);
            const __m512i vr =
                _mm512_permutex2var_epi32(in[pr], _mm512_loadu_si512(tab->reversed[r]), in[pr + 1]);
            const __m512i v = _mm512_add_epi32(_mm512_mask_blend_epi32(as_is, vr, va),
                                               _mm512_loadu_si512(tab->far[r]));
            if (casts == 0xFFFF) {
                _mm512_storeu_si512(si, v); /* a whole block: within 6 per triangle */
                si += 16;
            } else {
                _mm512_mask_compressstoreu_epi32(si, casts, v);
                si += _mm_popcnt_u32(casts);
            }
        }
    }
    SV_VZEROUPPER_IF_UNOPTIMISED();
    return (int)(si - shadowIndices);
}

#endif /* SV_HAVE_ASM_AVX512 */
