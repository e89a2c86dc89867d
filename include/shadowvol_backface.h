/*
 * shadowvol: seed 001's view back-face culling (Levi, Zohar, Barad,
 * Klimovitski, "compact backface culling", Gamasutra 1999): the camera, not
 * the light. Each routine counts the front-facing triangles and sets the
 * bit of every vertex of a front-facing triangle in a bit array (bit v % 32
 * of word v / 32, all other bits cleared), as the seed's listings do.
 *
 * THE VIEW. A Vec4 as the library's lights: (x, y, z, 1) a camera at (x, y,
 * z); (x, y, z, 0) an orthographic camera whose direction towards the
 * viewer is (x, y, z) (the seed has only the first). A triangle is front-
 * facing when the viewer is not strictly behind its plane:
 *   noncompact  TN = (P w - V) . N  (float; P a vertex, N the float unit
 *               normal)              front = TN <= 0     (the seed's test)
 *   compact     s  = ((qx*vx + qy*vy) + qz*vz) - tn*w,  v = V.xyz / 32767
 *               front = s >= 0  (the seed's TN <= 0 with TN = -s)
 * where q, tn are sv::triangle_plane16's 16-bit normal and precomputed dot
 * product (tn = NaN for a triangle with a NaN or infinite corner, so that
 * it is never front-facing, as in the non-compact method; a zero-area
 * triangle has q = 0, tn = 0: s = 0, front-facing, as the seed's zero
 * normal gives TN = 0): exactly the arithmetic of sv_calculate_facing_fixed16, so its
 * error bound holds (include/shadowvol_accuracy.h): front == (exact signed
 * distance of the viewer >= 0) wherever |D| > B_fixed16. A NaN makes a
 * triangle back-facing in both. The noncompact routine is the seed's
 * listing in C and the reference of its own layout, bit for bit.
 *
 * LAYOUTS (the seed's structures):
 *   sv_cull_triangle    32 bytes: float point, float normal, three 16-bit
 *                       vertex numbers, padding
 *   sv_cull_triangle16  16 bytes: float tn, int16 normal, three 16-bit
 *                       vertex numbers
 *   sv_cull_block4      64 bytes per four triangles, structure of arrays
 *                       (F32vec4 tn; Is16vec4 nx, ny, nz; WORD v[4][3]): one
 *                       cache line. The SSE2, AVX2 and AVX-512 routines read
 *                       one, two or four blocks per step. Lanes past
 *                       numTriangles in the last block are never counted.
 * Vertex numbers are 16 bits (the seed's WORD): at most 65536 vertices.
 *
 * FLOATING POINT. Every routine runs under round-to-nearest with FTZ and
 * DAZ off (MXCSR set for the call and restored), like the accuracy
 * variants: results do not depend on the caller's MXCSR.
 *
 * CONTRACT of every routine:
 *   numTriangles >= 0 (a negative count returns 0 and writes nothing);
 *   vertexBits: (numVertices + 31) / 32 words, all written (cleared, then
 *     the front-facing triangles' vertices set); NULL: no vertex bits (the
 *     decision alone, for the accuracy study);
 *   front: NULL, or numTriangles bytes that get each triangle's decision
 *     (1 front-facing, 0 not); the count is their sum.
 * Returns the number of front-facing triangles.
 *
 * Copyright (C) 2026 the shadowvol authors. LGPL-2.1-or-later.
 */
#ifndef SHADOWVOL_BACKFACE_H
#define SHADOWVOL_BACKFACE_H

#include <stddef.h>
#include <stdint.h>

#include "shadowvol.h"

#ifdef __cplusplus
extern "C" {
#endif

typedef struct sv_cull_triangle {
    float px, py, pz; /* a point of the triangle (its first vertex) */
    float nx, ny, nz; /* its unit normal (sv::triangle_plane's a, b, c) */
    uint16_t v1, v2, v3;
    uint16_t stub; /* the seed's padding to 32 bytes */
} sv_cull_triangle;

typedef struct sv_cull_triangle16 {
    float tn;           /* sv::triangle_plane16's tn (NaN: a non-finite corner) */
    int16_t nx, ny, nz; /* and its q */
    uint16_t v1, v2, v3;
} sv_cull_triangle16;

#define SV_CULL_BLOCK 4
typedef struct sv_cull_block4 {
    float tn[SV_CULL_BLOCK];
    int16_t nx[SV_CULL_BLOCK], ny[SV_CULL_BLOCK], nz[SV_CULL_BLOCK];
    uint16_t v[SV_CULL_BLOCK][3];
} sv_cull_block4;

/* The seed's first method: 32-byte triangles, float arithmetic. */
int sv_backface_noncompact(const sv_cull_triangle *tris, int numTriangles, int numVertices,
                           const Vec4 *view, uint32_t *vertexBits, uint8_t *front);
/* Its second: 16-byte triangles, the fixed-point normal. */
int sv_backface_compact(const sv_cull_triangle16 *tris, int numTriangles, int numVertices,
                        const Vec4 *view, uint32_t *vertexBits, uint8_t *front);

/* The SIMD methods over blocks of four; (numTriangles + 3) / 4 blocks.
 * The same decisions as sv_backface_compact, bit for bit. */
typedef int (*sv_backface_blocks_fn)(const sv_cull_block4 *blocks, int numTriangles,
                                     int numVertices, const Vec4 *view, uint32_t *vertexBits,
                                     uint8_t *front);
/* Its third: SSE2, four triangles per step. */
int sv_backface_compact_sse2(const sv_cull_block4 *blocks, int numTriangles, int numVertices,
                             const Vec4 *view, uint32_t *vertexBits, uint8_t *front);
/* Its fourth: the third with prefetcht0 1 KiB (16 blocks) ahead. */
int sv_backface_compact_sse2_prefetch(const sv_cull_block4 *blocks, int numTriangles,
                                      int numVertices, const Vec4 *view, uint32_t *vertexBits,
                                      uint8_t *front);
/* Beyond the seed: eight (AVX2, x86-64-v3) and sixteen (AVX-512,
 * x86-64-v4) triangles per step. Check sv_cpu_isa() first. */
int sv_backface_compact_avx2(const sv_cull_block4 *blocks, int numTriangles, int numVertices,
                             const Vec4 *view, uint32_t *vertexBits, uint8_t *front);
int sv_backface_compact_avx512(const sv_cull_block4 *blocks, int numTriangles, int numVertices,
                               const Vec4 *view, uint32_t *vertexBits, uint8_t *front);

#ifdef __cplusplus
}
#endif

#ifdef __cplusplus

#include <stdexcept>
#include <string>
#include <vector>

#include "shadowvol_mesh.h"

namespace sv {

/* A surface the 16-bit layouts cannot hold (more than 65536 vertices). */
class BackfaceError : public std::runtime_error {
public:
    using std::runtime_error::runtime_error;
};

/* The seed's per-surface data, built once. With keepIndices false the
 * vertex numbers are stored as 0 (for surfaces of more than 65536
 * vertices: the decisions can still be measured, with vertexBits NULL);
 * with it true such a surface throws BackfaceError. */
AlignedVector<sv_cull_triangle> cull_triangles(const PreparedSurface &s, bool keepIndices = true);
AlignedVector<sv_cull_triangle16> cull_triangles16(const PreparedSurface &s,
                                                   bool keepIndices = true);
AlignedVector<sv_cull_block4> cull_blocks(const PreparedSurface &s, bool keepIndices = true);
/* The same blocks from N 16-byte triangles (their transpose, four by four). */
AlignedVector<sv_cull_block4> cull_blocks(const sv_cull_triangle16 *tris, std::size_t n);

/* The block kernels by name: compact_sse2, compact_sse2_prefetch,
 * compact_avx2, compact_avx512. */
struct BackfaceBlockVariant {
    const char *name;
    unsigned isa;
    sv_backface_blocks_fn fn;
};
const std::vector<BackfaceBlockVariant> &backface_block_variants();

} // namespace sv

#endif /* __cplusplus */

#endif /* SHADOWVOL_BACKFACE_H */
