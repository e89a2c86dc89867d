/*
 * Seed 002 on skinned characters (issue 31; Brennan, ShaderX 2002, "Using
 * Shadow Volumes with Character Animation", its Figures 4 and 5): the face
 * normal each vertex of a skinned surface's shadow mesh carries, four ways,
 * and the faces the vertex program then splits (its three vertices
 * disagree on facing, so the volume is extruded across the face instead of
 * along the edge quads: the notch of Figure 4).
 *
 *   straightforward  the seed's "most straightforward approach": the rest
 *                    face normal skinned at each vertex with that vertex's
 *                    weights, as a vertex normal (the joints' 3x3 parts);
 *   face_weights     the seed's inexpensive fix (Figure 5): one set of
 *                    weights per face, the average of its vertices', for
 *                    the face normal; every vertex of the face carries it;
 *   recomputed       the seed's ideal: the face normal derived from the
 *                    skinned positions (sv_derive_planes_c_ref), carried
 *                    by every vertex of the face;
 *   neighbours       the seed's other fix: each vertex carries its two
 *                    neighbours' skinned positions and recomputes the face
 *                    normal by a cross product; here the three vertices of
 *                    a face also evaluate facing with one shared expression
 *                    (the face's corners in the face's order, whatever the
 *                    vertex), so their decisions cannot differ.
 *
 * The first three go through the seed's program (sv_extrude_c_ref: its
 * per-vertex dp3 with the vertex's own light direction), so even one
 * normal per face may split a face nearly edge-on to the light by
 * rounding; the fourth cannot split.
 *
 * Copyright (C) 2026 the shadowvol authors. LGPL-2.1-or-later.
 */
#ifndef SV_EXTRUDE_SKINNED_NORMALS_H
#define SV_EXTRUDE_SKINNED_NORMALS_H

#include <cstdint>
#include <string>
#include <vector>

#include "shadowvol_anim.h"
#include "shadowvol_extrude.h"

namespace sv {

enum class SkinnedNormals { straightforward, face_weights, recomputed, neighbours };
constexpr SkinnedNormals kAllSkinnedNormals[] = {SkinnedNormals::straightforward,
                                                 SkinnedNormals::face_weights,
                                                 SkinnedNormals::recomputed,
                                                 SkinnedNormals::neighbours};
const char *skinned_normals_name(SkinnedNormals n);
/* The command line's word for each ("straightforward", "face-weights",
 * "recomputed", "neighbours": the name, '-' for ' '); false for any other
 * NAME. */
bool skinned_normals_by_option(const std::string &name, SkinnedNormals &out);

/* A skinned surface posed: its joint matrices (joint_matrices(), identity
 * root) and skinned positions (sv_skin_c_ref), and its rest face normals
 * (the triangle planes of the mesh-space rest positions). */
struct SkinnedFrame {
    std::vector<float> joint_matrices; /* 16 per joint */
    std::vector<float> positions;      /* 3 per welded vertex */
};
SkinnedFrame skinned_frame(const AnimatedAsset &asset, const AnimatedSurface &s, const Pose &pose);

/* What the normal sources of a skinned surface read that does not change
 * from frame to frame: the rest face normals (the planes' a, b, c), and
 * the face weights of the seed's Figure 5: per face, the average of its
 * three vertices' weights joint by joint (a joint's weights summed over
 * the three in corner order, then divided by 3), joints in increasing
 * order, zero sums left out: up to 3 x influences joints a face. */
struct SkinnedNormalData {
    std::vector<Plane> rest_planes;
    std::vector<int> face_start; /* faces + 1: face t's joints are [start[t], start[t+1]) */
    std::vector<uint16_t> face_joints;
    std::vector<float> face_weights;
};
SkinnedNormalData skinned_normal_data(const AnimatedSurface &s);

/* The normals of the NORMALS way at FRAME into the normal columns of
 * STREAM, S's shadow mesh's (vertex 3t + k: corner k of S's triangle t;
 * the caster itself, not a two-sided one). Neighbours write the recomputed
 * normal: their own facing expression is not the seed's program, which
 * the stream feeds. DATA: skinned_normal_data(S), made once (the overload
 * without it makes it each call). */
void write_skinned_normals(const AnimatedSurface &s, const SkinnedNormalData &data,
                           const SkinnedFrame &frame, SkinnedNormals normals, float *stream);
void write_skinned_normals(const AnimatedSurface &s, const SkinnedFrame &frame,
                           SkinnedNormals normals, float *stream);

/* The same for the shadow mesh of CASTER: S itself, or its two-sided
 * caster (two_sided_caster: S's triangles, then the reverse (c, b, a) of
 * each triangle (a, b, c) of a shell under the general rule, its source
 * in triangle_source): S's faces as above, each reverse's vertex the
 * negated normal of its source's corner (corner k of the reverse is
 * corner 2 - k of the source). Throws std::invalid_argument when CASTER
 * is neither. */
void write_caster_skinned_normals(const AnimatedSurface &s, const SkinnedNormalData &data,
                                  const SkinnedFrame &frame, SkinnedNormals normals,
                                  const PreparedSurface &caster, float *stream);

/* The neighbour fix's stream: per vertex of the shadow mesh, the three
 * corners of its face in the face's order (9 floats: its own position and
 * its two neighbours', three times the seed's position data, in place of
 * the normal); vertex j is corner j % 3, which a GPU reads from its vertex
 * id. Built from MESH's positions (vertex 3t + k: corner k of face t). */
constexpr int kNeighbourStreamFloats = 9;
std::vector<float> neighbour_stream(const ShadowMesh &mesh);
/* The same from a surface's FACES triangles (INDICES) and its vertices'
 * POSITIONS (3 floats each) into OUT (9 floats for each of 3 x FACES
 * vertices). */
void write_neighbour_stream(const int *indices, int faces, const float *positions, float *out);

/* The neighbour fix's vertex program over STREAM (neighbour_stream, N
 * vertices): the face's normal by a cross product of its corners,
 * (c1 - c0) x (c2 - c0), its facing by one expression shared by the
 * face's three vertices (the normal dotted with the light's direction to
 * corner 0, c0 * l.w - l: the same operands in the same order whichever
 * vertex evaluates it, so the three decisions cannot differ), then the
 * seed's program for the vertex's own position (its length, its range,
 * infinity: sv_extrude_c_ref's, include/shadowvol_extrude.h). Beyond the
 * seed, as there, a light on the vertex itself keeps it. */
void extrude_neighbours(const float *stream, int n, const sv_extrude_light &light, Vec4 *out);

/* Faces of S whose three vertices disagree on facing under LIGHT, the
 * normals given the NORMALS way at FRAME (the neighbours by their own
 * program, extrude_neighbours; the others by the seed's). */
int64_t split_faces(const AnimatedSurface &s, const SkinnedFrame &frame, SkinnedNormals normals,
                    const sv_extrude_light &light);

} // namespace sv

#endif
