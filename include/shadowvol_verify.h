/*
 * shadowvol: the proof that a shadow volume is right (shadowvol verify).
 *
 * Two checks of the index list that sv_create_shadow_volume returns:
 *
 *  1. Closed and consistently wound: every directed edge a->b of the list
 *     appears exactly as often as b->a.
 *
 *  2. Right in space. The paper's volume is, as a chain of triangles, the
 *     sum over the triangles t that cast (facing byte 0 after culling) of
 *     the prism of t: t itself (reversed), t pushed away from the light, and
 *     a quad per edge; the quads between two casting triangles cancel, and
 *     what is left are the caps and the silhouette quads the routines emit.
 *     So the volume's winding number around a point P (the stencil count)
 *     must equal
 *         sum over casting t crossed by the segment P -> light of s(t),
 *     s(t) = +1 when the light is geometrically behind t's plane, -1 when
 *     float rounding made an edge-on triangle cast while the light is (just)
 *     in front (its prism is then turned inside out). This holds for every
 *     mesh, closed or not. For a closed, outward-wound mesh, an unculled
 *     light and P outside the solid (the mesh's own winding number around
 *     P is 0) it gives the statement: P is in shadow (winding !=
 *     0) exactly when the segment P -> light crosses the mesh (walking
 *     from P, the first crossing enters the solid through a triangle that
 *     has P in front and the light behind: a casting one, and every
 *     casting crossing counts +1); that is checked too.
 *
 * Geometry is in double, from the float positions (exact in double). The
 * odd (extruded) vertices are pushed away from the light to a large finite
 * distance: v + D * (v - L) / |v - L| for a point light (the point stays on
 * the ray from the light through v, so each silhouette quad stays in the
 * plane of the light and its edge), v - D * dir for a directional light.
 * The winding number is counted with signed ray crossings; a ray that
 * passes within a relative 1e-9 of a triangle's edge is replaced by another
 * random ray, and a point within 1e-9 * size of a triangle it crosses, or
 * whose segment to the light passes that close to an edge of a casting
 * triangle, is skipped (counted, and the run fails if more than a few
 * percent are skipped).
 *
 * Copyright (C) 2026 the shadowvol authors. LGPL-2.1-or-later.
 */
#ifndef SHADOWVOL_VERIFY_H
#define SHADOWVOL_VERIFY_H

#include "shadowvol.h"
#include "shadowvol_casters.h"
#include "shadowvol_mesh.h"

#include <cstdint>
#include <memory>
#include <string>
#include <vector>

namespace sv {

class RayTriangles; /* src/verify/ray_triangles.h */

/* ---- Check 1: closure --------------------------------------------------- */

struct ClosureResult {
    bool closed = true;
    std::string problem; /* empty when closed: else the first unbalanced edge */
};

/* Every directed edge a->b of the triangles in shadowIndices (numIndices
 * ints) appears as often as b->a; also numIndices % 3 == 0 and every index
 * in [0, 2 * numVertices). */
ClosureResult check_closure(const int *shadowIndices, int numIndices, int numVertices);

/* ---- Check 2: in space -------------------------------------------------- */

/* A light for verify: a point light (w = 1) or a directional light (w = 0,
 * xyz = unit direction TOWARDS the light), optionally with a light volume
 * (six inward planes, appendix B) that culls triangles outside it. */
struct VerifyLight {
    Vec4 light{0, 0, 0, 1};
    bool culled = false;
    Plane planes[SV_NUM_LIGHT_PLANES]{};
    std::string describe() const;
};

/* COUNT lights around surface S, drawn from SEED: half point lights (a
 * quarter of those close to or inside the bounds, the rest 1.5 to 4 radii
 * from the center; every other point light has a light box that cuts the
 * mesh), half directional. */
std::vector<VerifyLight> make_verify_lights(const PreparedSurface &s, int count, uint64_t seed);

struct InSpaceCounts {
    int64_t points = 0;           /* points checked */
    int64_t in_shadow = 0;        /* winding != 0 */
    int64_t lit = 0;              /* winding == 0 */
    int64_t inside_mesh = 0;      /* closed mesh: points inside the solid (its
                                    winding number != 0; checked by the
                                    identity only) */
    int64_t crossing_checked = 0; /* closed mesh, unculled, P outside: the
                                    "in shadow iff the segment crosses" check */
    int64_t skipped = 0;          /* too close to a boundary to decide */
    int64_t ray_retries = 0;      /* rays replaced (passed near an edge) */
    int64_t inverted_prisms = 0;  /* crossings of casting triangles that have
                                    the light (just) in front: s(t) = -1 */
    void add(const InSpaceCounts &o);
};

/* The sizes verify can decide (issue 17): a surface whose bounds' half
 * diagonal (its radius) lies in [kVerifyMinRadius, kVerifyMaxRadius]. The
 * lights are verify's own, 0.3 to 4 radii from the center (directional
 * ones at infinity), so their distances scale with it. Outside the range,
 * or where more than max_skipped_fraction of the points lie too close to a
 * boundary to decide (degenerate or collinear triangles, three vertices at
 * one position, features below about 1e-7 of the radius), the result is
 * "cannot decide" (LightResult::undecided, with the reason): neither a
 * pass nor a failure. Measured (tests/unit/test_verify.cpp): tetrahedra of
 * radius 1.7e-38 to 8.7e35 decide and pass; scaled 1e-40 they pass too, but
 * at 1e-45 (coordinates on float's denormal grid, where the lights' float
 * positions fall onto the mesh's own grid) too many points are undecidable:
 * below FLT_MIN the range stops. */
constexpr double kVerifyMinRadius = 1.1754943508222875e-38; /* FLT_MIN */
constexpr double kVerifyMaxRadius = 1e36;

struct LightResult {
    bool ok = true;
    std::string failure; /* names the variant, the light and the point */
    /* ok, but the check could not decide (see kVerifyMinRadius): why. */
    bool undecided = false;
    std::string undecided_reason;
    int variants_checked = 0;
    int distinct_volumes = 0; /* index lists differing between variants */
    int64_t volume_triangles = 0;
    int64_t casting_triangles = 0; /* facing byte 0, after culling */
    int64_t culled_triangles = 0;  /* would cast, but outside the light volume */
    InSpaceCounts counts;
};

struct VerifyOptions {
    int points_per_light = 1000;
    double max_skipped_fraction = 0.02;
    /* Distance the odd vertices are pushed, in radii of the surface. */
    double extrusion_radii = 1000.0;
};

/* Builds the volume of S for L with every variant in VARIANTS (through
 * sv_create_shadow_volume, with the facing bytes of
 * sv_calculate_facing_c_ref and, for a culled light, the cull bits of
 * sv_calculate_cull_bits_c_ref), checks each closed, and checks each
 * distinct index list in space at points_per_light random points (half
 * uniform around the bounds, half just behind or in front of random points
 * of the mesh). Stops at the first failure. */
LightResult verify_light(const PreparedSurface &s, const VerifyLight &l,
                         const std::vector<const sv_variant *> &variants,
                         const VerifyOptions &options, uint64_t seed);

/* The general rule's volume (issue 27, docs/CASTERS.md) as the direct
 * kernels build it from TABLE, S's general edge table (general_edge_table
 * under any rule): the general bytes from the same reference facing and
 * cull bits (sv_general_facing_from_calculated, sv_general_cull_c_ref),
 * the silhouette quads with their multiplicities and the caps of every
 * variant in VARIANTS, each list checked closed (every directed edge as
 * often as its reverse: the multiplicities balance), then in space: the
 * winding number at each point must equal the signed count of the
 * casting triangles its segment to the light crosses, where a triangle
 * of byte 0 counts +1 with the light behind it and one of byte 2 (its
 * reverse casts) +1 with the light in front. Where every triangle takes
 * the general rule that is the number of triangles crossed, so there each
 * point is also checked in shadow exactly when its segment crosses the
 * mesh, closed or not (counted in crossing_checked). */
LightResult verify_general_light(const PreparedSurface &s, const GeneralEdgeTable &table,
                                 const VerifyLight &l,
                                 const std::vector<const sv_general_variant *> &variants,
                                 const VerifyOptions &options, uint64_t seed);

/* The variants this CPU can run. */
std::vector<const sv_variant *> supported_variants();
std::vector<const sv_general_variant *> supported_general_variants();

/* ---- The pieces, for tests ---------------------------------------------- */

struct Point3 {
    double x, y, z;
};

/* A closed triangle volume in double for winding numbers. */
class WindingVolume {
public:
    /* Triangles of INDICES into VERTICES (3 ints per triangle). */
    WindingVolume(const std::vector<Point3> &vertices, const int *indices, int numIndices);
    enum class Status { ok, on_boundary, undecided };
    /* Signed crossings of random rays from P (+1 per crossing of a triangle
     * that faces along the ray, i.e. +1 inside a closed counter-clockwise
     * outward volume) into *out. seed_state advances per ray drawn;
     * *retries counts rays replaced. */
    Status winding(const Point3 &p, uint64_t &seed_state, int *out, int64_t *retries) const;
    std::size_t triangles() const;

private:
    std::shared_ptr<const RayTriangles> tris_;
    double eps_dist_ = 0;
};

} // namespace sv

#endif /* SHADOWVOL_VERIFY_H */
