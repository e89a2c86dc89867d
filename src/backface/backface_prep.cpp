/*
 * The per-surface data of seed 001's layouts (include/shadowvol_backface.h)
 * and the table of block kernels.
 *
 * Copyright (C) 2026 the shadowvol authors. LGPL-2.1-or-later.
 */
#include <cmath>

#include "shadowvol_accuracy.h"
#include "shadowvol_backface.h"

namespace sv {

namespace {

/* C's three 16-bit vertex numbers: triangle T's (0 when not kept). */
template <class Triangle>
void set_vertices(Triangle &c, const PreparedSurface &s, int t, bool keep) {
    const int *v = &s.indices[3 * (std::size_t)t];
    c.v1 = keep ? (uint16_t)v[0] : 0;
    c.v2 = keep ? (uint16_t)v[1] : 0;
    c.v3 = keep ? (uint16_t)v[2] : 0;
}

bool keep_indices(const PreparedSurface &s, bool keepIndices) {
    if (keepIndices && s.num_vertices() > 65536) {
        throw BackfaceError("seed 001's layouts store 16-bit vertex numbers: at most 65536 "
                            "vertices, and this surface has " +
                            std::to_string(s.num_vertices()));
    }
    return keepIndices;
}

const float *corner(const PreparedSurface &s, int t, int k) {
    return &s.positions[3 * (std::size_t)s.indices[3 * (std::size_t)t + k]];
}

/* triangle_plane16, except that a triangle with a NaN or infinite corner
 * gets tn = NaN, not the zero plane: s is then NaN and the triangle is
 * never front-facing, as a NaN makes it in the non-compact method (the
 * zero plane would give s = 0, front-facing by the seed's TN <= 0). A
 * finite zero-area triangle keeps the zero plane: s = 0, front-facing, as
 * its zero normal makes it in the seed's listings. */
void cull_plane16(const PreparedSurface &s, int t, int16_t q[3], float *tn) {
    triangle_plane16(corner(s, t, 0), corner(s, t, 1), corner(s, t, 2), q, tn);
    for (int k = 0; k < 3; k++) {
        for (int i = 0; i < 3; i++) {
            if (!std::isfinite(corner(s, t, k)[i])) *tn = NAN;
        }
    }
}

} // namespace

AlignedVector<sv_cull_triangle> cull_triangles(const PreparedSurface &s, bool keepIndices) {
    const bool keep = keep_indices(s, keepIndices);
    AlignedVector<sv_cull_triangle> out((std::size_t)s.num_triangles());
    for (int t = 0; t < s.num_triangles(); t++) {
        sv_cull_triangle &c = out[(std::size_t)t];
        const float *p = corner(s, t, 0);
        const Plane &pl = s.planes[(std::size_t)t];
        c = sv_cull_triangle{p[0], p[1], p[2], pl.a, pl.b, pl.c, 0, 0, 0, 0};
        set_vertices(c, s, t, keep);
    }
    return out;
}

AlignedVector<sv_cull_triangle16> cull_triangles16(const PreparedSurface &s, bool keepIndices) {
    const bool keep = keep_indices(s, keepIndices);
    AlignedVector<sv_cull_triangle16> out((std::size_t)s.num_triangles());
    for (int t = 0; t < s.num_triangles(); t++) {
        sv_cull_triangle16 &c = out[(std::size_t)t];
        int16_t q[3];
        cull_plane16(s, t, q, &c.tn);
        c.nx = q[0];
        c.ny = q[1];
        c.nz = q[2];
        set_vertices(c, s, t, keep);
    }
    return out;
}

AlignedVector<sv_cull_block4> cull_blocks(const sv_cull_triangle16 *tris, std::size_t n) {
    /* Zero-initialised: the last block's unused lanes stay 0 (the kernels
     * mask them off). */
    AlignedVector<sv_cull_block4> out((n + SV_CULL_BLOCK - 1) / SV_CULL_BLOCK);
    for (std::size_t t = 0; t < n; t++) {
        sv_cull_block4 &b = out[t / SV_CULL_BLOCK];
        const std::size_t k = t % SV_CULL_BLOCK;
        const sv_cull_triangle16 &c = tris[t];
        b.tn[k] = c.tn;
        b.nx[k] = c.nx;
        b.ny[k] = c.ny;
        b.nz[k] = c.nz;
        b.v[k][0] = c.v1;
        b.v[k][1] = c.v2;
        b.v[k][2] = c.v3;
    }
    return out;
}

AlignedVector<sv_cull_block4> cull_blocks(const PreparedSurface &s, bool keepIndices) {
    const AlignedVector<sv_cull_triangle16> t = cull_triangles16(s, keepIndices);
    return cull_blocks(t.data(), t.size());
}

const std::vector<BackfaceBlockVariant> &backface_block_variants() {
    static const std::vector<BackfaceBlockVariant> v = {
        {"compact_sse2", SV_ISA_SSE2, sv_backface_compact_sse2},
        {"compact_sse2_prefetch", SV_ISA_SSE2, sv_backface_compact_sse2_prefetch},
        {"compact_avx2", SV_ISA_SSE2 | SV_ISA_AVX2, sv_backface_compact_avx2},
        {"compact_avx512", SV_ISA_SSE2 | SV_ISA_AVX2 | SV_ISA_AVX512, sv_backface_compact_avx512},
    };
    return v;
}

static_assert(sizeof(sv_cull_triangle) == 32, "the seed's 32-byte triangle");
static_assert(sizeof(sv_cull_triangle16) == 16, "the seed's 16-byte triangle");
static_assert(sizeof(sv_cull_block4) == 64, "four triangles per cache line");

} // namespace sv
