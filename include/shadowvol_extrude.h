/*
 * shadowvol: shadow volumes extruded by a vertex program (issue 31; seed
 * 002: C. Brennan, "Shadow Volume Extrusion using a Vertex Shader",
 * ShaderX, 2002), the seed's preprocessing and its vertex program emulated
 * on the CPU, in C and SIMD. docs/EXTRUSION.md says what the seed does and
 * what is measured.
 *
 * No silhouette search: once per surface, every face gets three vertices
 * of its own carrying the face's normal, and every edge shared by two
 * faces a degenerate quad (two triangles) between their copies of it. Per
 * light, a vertex program moves the vertices of the faces that do not face
 * the light away from it; the quads of the edges where that splits the
 * mesh open into the volume's sides, the others stay degenerate.
 *
 * Copyright (C) 2026 the shadowvol authors. LGPL-2.1-or-later.
 */
#ifndef SHADOWVOL_EXTRUDE_H
#define SHADOWVOL_EXTRUDE_H

#include <stdint.h>

#include "shadowvol.h"

#ifdef __cplusplus
extern "C" {
#endif

/* Floats per vertex of the shadow mesh's stream: the seed's declaration,
 * float v0[3] (position) then float v1[3] (the face's normal). */
#define SV_EXTRUDE_STREAM_FLOATS 6

/* ---- The vertex program ---------------------------------------------------
 * The seed's program (its m4x4 / m3x3 world*view transforms left to the
 * renderer: here everything is in the space of the inputs, object space),
 * for vertex i with position p = stream[6i .. 6i+2], face normal
 * n = stream[6i+3 .. 6i+5], and LIGHT's position l (x, y, z, w as
 * sv_calculate_facing takes it: w = 1 a point light, w = 0 a direction
 * towards the light) and range RANGE. Every operation in float, rounded one at a time, in this order
 * (the C is built with -ffp-contract=off; no FMA):
 *   dx = p.x*l.w - l.x,  dy = p.y*l.w - l.y,  dz = p.z*l.w - l.z
 *                                  (the seed's sub r1, r0, c91: vLP, from
 *                                   the light to the point, for w = 1)
 *   len2 = (dx*dx + dy*dy) + dz*dz              (dp3)
 *   inv  = 1.0f / sqrtf(len2)                   (rsq: correctly rounded
 *                                   sqrt, then one correctly rounded
 *                                   division; not rsqrtps)
 *   ux = dx*inv,  uy = dy*inv,  uz = dz*inv     (mul: normalised vLP)
 *   dot  = (n.x*ux + n.y*uy) + n.z*uz           (dp3 r10.z, r3, r1)
 *   keep = dot < 0  ||  !(len2 > 0)             (slt; see below)
 * and the output out[i] (x, y, z, w):
 *   keep:                 (p.x, p.y, p.z, 1)    the vertex stays
 *   else, FINITE:         len = 1.0f / inv      (rcp)
 *                         ext = range - len;  ext = ext > 0 ? ext : 0
 *                                               (sub, max with 0)
 *                         (ux*ext + p.x, uy*ext + p.y, uz*ext + p.z, 1)
 *                                               (mad: a product rounded,
 *                                                then a sum rounded)
 *   else, not FINITE:     (dx, dy, dz, 0)       to infinity
 * FINITE is  l.w != 0 && range > 0 && range < +inf : a point light with a
 * range extrudes by the seed's clamp0(range - |vLP|), so a vertex at or
 * beyond the range stays. A light without range (range 0 = unlimited, as
 * in shadowvol_scene.h; a negative, infinite or NaN range likewise) and a
 * directional light (w = 0) extrude to infinity, w = 0, as the paper's
 * shadow vertices do: (dx, dy, dz, 0) is exactly the paper's odd vertex
 * (sv::shadow_vertices_for_light), so a silhouette built either way meets
 * the same points at infinity. The length is |p*l.w - l| (the distance
 * for w = 1, every light of the project).
 * Facing: the seed's slt keeps a vertex whose normal points towards the
 * light (vLP.vN < 0; its comment "pointing away" names the extruded case)
 * and extrudes the rest: dot = 0 (a face edge-on to the light, or a zero
 * normal: a zero-area face) and a NaN dot are extruded, as the paper's
 * facing (plane.light > 0) leaves such a face dark. Beyond the seed:
 * !(len2 > 0), the light on the vertex itself (where rsq(0) = +inf would
 * make every coordinate NaN), keeps the vertex where it is; so does a NaN
 * len2. No NaN is written for finite inputs and finite, nonzero light.
 * The selection is exact (the seed's mul/mad by 0 and 1 select too, for
 * finite values).
 *   stream       SV_EXTRUDE_STREAM_FLOATS floats per vertex; no alignment.
 *   numVertices  >= 0; a negative count writes nothing.
 *   light        read once. (The range is in the struct, not a float
 *                argument: every routine takes integers and pointers.)
 *   out          numVertices Vec4; nothing after out[numVertices-1] is
 *                written. No alignment needed.
 * Every variant is BIT-IDENTICAL to sv_extrude_c_ref, for every input,
 * under the same MXCSR. */
typedef struct sv_extrude_light {
    Vec4 position; /* x, y, z, w: w = 1 a point light, w = 0 a direction towards it */
    float range;   /* the seed's light.Range (c90.x); 0 = unlimited */
} sv_extrude_light;

typedef void (*sv_extrude_fn)(const float *stream, int numVertices, const sv_extrude_light *light,
                              Vec4 *out);

void sv_extrude_c_ref(const float *stream, int numVertices, const sv_extrude_light *light,
                      Vec4 *out);
/* AVX2: 8 vertices a step, six vgatherdps (the stream's columns), the
 * outputs back to rows by 4x4 transposes; the last < 8 by the reference
 * expression. */
void sv_extrude_avx2(const float *stream, int numVertices, const sv_extrude_light *light,
                     Vec4 *out);
/* AVX-512 (F, VL, DQ): 16 vertices a step; the last < 16 by masked gathers
 * and masked stores. */
void sv_extrude_avx512(const float *stream, int numVertices, const sv_extrude_light *light,
                       Vec4 *out);

/* Not bit-identical, and not in the table: the AVX2 variant with rsqrtps
 * refined by one Newton-Raphson step, y = y0 * (1.5 - (0.5*len2) * y0^2),
 * in place of the correctly rounded 1/sqrt (the last < 8 vertices by
 * rsqrtss and the same step), everything else as above. What a GPU's rsq
 * may do. Its 1/sqrt is within a few 2^-23 of the exact one, so an
 * extruded vertex (finite range) lies within 1e-6 * (range + |vLP|)
 * of the reference's, the kept vertices and the infinite ones are the
 * reference's bit for bit unless the facing flips: only where dot is within
 * a few float ulps of 0 (a face nearly edge-on to the light), where u's
 * rounding differs. tests/unit/test_extrude.cpp bounds both;
 * `shadowvol bench --extrude` measures them on the real meshes. */
void sv_extrude_avx2_rsqrt(const float *stream, int numVertices, const sv_extrude_light *light,
                           Vec4 *out);

/* ---- The table -------------------------------------------------------------
 * c_ref, avx2, avx512: the reference first, then from the slowest to the
 * fastest. Check isa against sv_cpu_isa() first. */
typedef struct sv_extrude_variant {
    const char *name;
    unsigned isa; /* SV_ISA_* bits the CPU must have */
    sv_extrude_fn extrude;
} sv_extrude_variant;

const sv_extrude_variant *sv_extrude_variants(int *count);
const sv_extrude_variant *sv_extrude_variant_by_name(const char *name);
/* The last entry sv_cpu_isa() allows (never NULL). */
const sv_extrude_variant *sv_best_extrude_variant(void);

#ifdef __cplusplus
}

#include "shadowvol_casters.h"
#include "shadowvol_mesh.h"

namespace sv {

/* The seed's shadow mesh of one surface. */
struct ShadowMesh {
    /* SV_EXTRUDE_STREAM_FLOATS floats per vertex: vertex 3t + k is corner k
     * of face t (position), with face t's normal. The normal is the face's
     * float plane (a, b, c) of the prepared surface (sv::triangle_plane:
     * computed in double, rounded once; a zero-area face has (0, 0, 0) and
     * is always extruded, as the paper's zero plane is always dark). A
     * deforming surface gets its planes per frame (shadowvol_planes.h) and
     * its stream again. 64-byte aligned. */
    AlignedVector<float> stream;
    /* The draw list, in the seed's order: for each face t, the face
     * (3t, 3t+1, 3t+2), then one degenerate quad (two triangles) for each of
     * its edges that closes a pair with an earlier face. 64-byte aligned. */
    AlignedVector<int> indices;
    int64_t faces = 0;
    int64_t quads = 0;      /* edges shared by two faces (the surface's regular SilEdges) */
    int64_t open_edges = 0; /* uses left in the seed's checklist (dangling SilEdges) */
    /* The seed's flag: false ("the geometry is not a closed volume") when an
     * edge use found no partner. The volume is then not closed. */
    bool closed_volume = true;

    int num_vertices() const { return (int)(stream.size() / SV_EXTRUDE_STREAM_FLOATS); }
    int num_indices() const { return (int)indices.size(); }
    int num_triangles() const { return (int)(indices.size() / 3); }
};

/* The seed's preprocessing of the triangles of CASTER as they are: faces
 * and planes from CASTER, an edge pair wherever CASTER's SilEdges pair two
 * uses (the pairing of prepare_surface: non-manifold edges are paired two
 * by two, the rest left open). A closed mesh of F faces gives 3F vertices
 * and 4F triangles (F faces, 3F/2 quads): the DirectX SDK's GenShadowMesh
 * counts. Quad of SilEdge (v1, v2, p1, p2), with a1, b1 face p1's copies of
 * v1, v2 and a2, b2 face p2's:
 *   (a1, b2, b1), (a1, a2, b2)
 * which is the paper's silhouette quad (sv_create_sil_triangles_c_ref),
 * vertex for vertex, whichever of p1, p2 is extruded. The volume's near cap
 * is the faces that face the light, its far cap the others, extruded.
 * Throws PrepareError when 3 * triangles vertices do not fit an int. */
ShadowMesh build_shadow_mesh(const PreparedSurface &caster);

/* The shadow mesh of S under the project's caster rule
 * (shadowvol_casters.h): the shells under the general rule made two-sided
 * first (two_sided_caster), so every edge is paired and the extruded
 * volume is exact for open and non-manifold shells too (docs/CASTERS.md):
 * each open triangle and its reverse extrude to the triangle's own prism.
 * Under CasterRule::closed an open S keeps its open edges and is flagged,
 * as the seed flags it. */
ShadowMesh build_shadow_mesh(const PreparedSurface &s, CasterRule rule);

} // namespace sv
#endif /* __cplusplus */

#endif /* SHADOWVOL_EXTRUDE_H */
