/*
 * Where a light can light and a shadow can be seen (DESIGN.md section 9):
 * conservative tests on a surface's box, made per frame, light and surface
 * before any volume is built. The volume pass (volume_pass.h) takes its
 * shortcuts from them; the shading pass and the proofs use the same tests,
 * so the shortcuts can never change a lit pixel.
 *
 * Copyright (C) 2026 the shadowvol authors. LGPL-2.1-or-later.
 */
#ifndef SV_RENDER_REACH_H
#define SV_RENDER_REACH_H

#include "shadowvol_scene.h"

namespace sv::render {

/* Would the lighting pass light SURFACE at all: its box meets the light's
 * range and (spot) its cone. Where it does not, the light adds nothing to
 * it (with or without shortcuts: the test is part of the lighting model,
 * as Doom 3's light-surface interactions are), and shortcut 1 builds no
 * volume for it: its shadow lies wholly beyond the range or the cone. */
bool light_reaches_box(const SceneLight &light, const Vec3d &lo, const Vec3d &hi, double scale = 1);

/* Can the shadow volume of a surface in box [lo, hi] have a fragment in
 * view (shortcut 2)? False when the box's eight corners and their eight
 * extrusions from L (the double-length buffer's odd vertices, w = 0) all
 * lie outside one of the five clip planes the rasteriser clips against:
 * every vertex of the volume is a non-negative combination of them, so
 * every triangle of it is then dropped whole. */
bool shadow_may_reach_view(const Mat4d &view_proj, const Vec3d &lo, const Vec3d &hi, const Vec4 &L,
                           bool with_extrusion = true);

/* The light volume of appendix B as six planes pointing into it: a point
 * light's range as a cube, a spot light's cone as a square pyramid (its
 * apex plane and, with a range, a far plane). False for lights without
 * one (directional, or a point light without a range). SHRINK < 1 is for
 * the fault tests only. */
bool light_volume_planes(const SceneLight &light, Plane planes[SV_NUM_LIGHT_PLANES],
                         double shrink = 1);
/* Where box [lo, hi] lies against those planes. */
enum class BoxSide { inside, straddles, outside };
BoxSide classify_box(const Plane planes[SV_NUM_LIGHT_PLANES], const Vec3d &lo, const Vec3d &hi);

/* Is world point P inside LIGHT's range (when it has one) and cone (a
 * spot)? Where it is not, the lighting adds nothing (the KHR window and
 * the cone's smoothstep are 0 there). */
bool point_in_light_reach(const SceneLight &light, const Vec3d &P);

/* Would z-pass be wrong for this surface and light: can a point of the
 * camera's near-plane rectangle lie in the surface's shadow volume? A
 * conservative test: the surface's box against the convex hull of the
 * near rectangle and the light (swept towards a directional light). */
bool near_plane_may_be_shadowed(const Camera &camera, double aspect, const SceneSurface &s,
                                const SceneLight &light);

} // namespace sv::render

#endif
