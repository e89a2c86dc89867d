/*
 * The first judge of the renderer (issue 12, "Proof 1"): ray-cast truth at
 * every pixel. For the point seen through a pixel's centre (reconstructed
 * in double from the depth pass's triangle id: the camera ray meets that
 * triangle's plane), is the segment to the light (or the ray towards a
 * directional light) blocked by any triangle of the scene?
 *
 * Rays use the verifier's bounding-volume hierarchy (src/verify/
 * ray_triangles.h, double precision, exact Moller-Trumbore test per
 * candidate): the scenes here have at most a few hundred thousand
 * triangles, and two threads cast a 1280 x 1024 frame's rays in seconds
 * (the render command prints rays per second), so Embree is not needed.
 *
 * Compared with the stencil only where the visible side of the triangle
 * faces the light (its facing byte is 1 and the camera sees its front):
 * elsewhere the surface is dark whatever the stencil says. A mismatch is
 * allowed only on a boundary: where the 3 x 3 neighbourhood of the pixel
 * holds both truth values (a pixel that is dark because it faces away
 * counts as shadowed there), the shadow edge passes within a pixel and the
 * 1/256-pixel snapping of the volume may put the centre on either side.
 * The neighbourhood is first judged by its nine pixel centres; a mismatch
 * whose nine centres agree is judged again on a 7 x 7 grid of points over
 * the 3 x 3 pixels, each with its own camera ray (the nearest triangle it
 * meets) and shadow ray: a triangle seen at one pixel only, edge-on at a
 * silhouette, can carry a shadow edge that no neighbouring centre shows.
 * And the point the depth test itself used, the camera ray at the stored
 * depth, is judged too: a receiver seen almost edge-on is a sliver on the
 * screen, and the depth plane of its snapped corners can lie a long way
 * off the exact surface there (measured: RiggedFigure at 128 x 104, a
 * triangle 9 mm from the eye's plane, its stored depth behind a volume
 * face that the exact point is in front of). Where the two points differ
 * in truth, the pixel is on a boundary in depth.
 * Last, a mismatch where a drawn volume face passes within 128 float ulps
 * of the stored depth is on a boundary in depth too: a light grazing a
 * triangle (its plane a few thousandths of a unit from the light, 200
 * units away: measured on Fox at 0.5 s of its run) makes the silhouette
 * quad along that triangle's edge lie in the triangle's own plane, and the
 * depth test between the two decides the pixel. They are counted apart.
 * (At most 2000 mismatches a light are looked at so; a frame with more
 * fails anyway.)
 *
 * The truth does not take the depth pass on trust: the visible triangle of
 * every pixel comes from the depth pass's ids, so an error there would
 * move the truth and the stencil together. On one pixel in 16 (those with
 * (x + 5 y) mod 16 = 0) whose 3 x 3 neighbourhood shows one triangle id
 * (off every edge of the depth pass), the truth casts its own camera ray
 * through the pixel's centre and finds the nearest triangle beyond the
 * near plane. Another triangle than the depth pass's is a disagreement,
 * unless the ray meets the depth pass's triangle too within a relative
 * 1e-6 of the same distance (coincident triangles: either is right). A
 * disagreement counts as a mismatch off the boundary.
 *
 * Copyright (C) 2026 the shadowvol authors. LGPL-2.1-or-later.
 */
#ifndef SV_RENDER_TRUTH_H
#define SV_RENDER_TRUTH_H

#include <cstdint>
#include <functional>
#include <memory>
#include <vector>

#include "frame.h"

namespace sv::render {

class SceneRays; /* truth.cpp: the scene's triangles and their hierarchy */

/* Per pixel. */
enum TruthClass : uint8_t {
    kTruthNone = 0,     /* background */
    kTruthLit = 1,      /* faces the light, segment free */
    kTruthShadowed = 2, /* faces the light, segment blocked */
    kTruthDark = 3      /* faces away from the light, or its back side is seen, or the
                           point is beyond the light's range or outside its cone */
};

struct Truth {
    std::vector<uint8_t> cls; /* TruthClass per pixel */
    uint64_t rays = 0;
    double seconds = 0;
    /* The depth pass checked by the truth's own camera rays (see above). */
    uint64_t primary_checked = 0;
    uint64_t primary_disagreements = 0;
    std::vector<int> first_primary_disagreements; /* pixel numbers, up to 16 */
};

struct Comparison {
    uint64_t compared = 0;          /* pixels of class lit or shadowed */
    uint64_t lit = 0, shadowed = 0; /* by the truth */
    uint64_t boundary = 0;          /* compared pixels on a boundary */
    uint64_t mismatches = 0;        /* stencil says otherwise */
    uint64_t boundary_mismatches = 0;
    uint64_t off_boundary_mismatches = 0;
    uint64_t subpixel_boundary_mismatches =
        0; /* of boundary_mismatches: found by the closer look */
    /* Of boundary_mismatches: a drawn volume face passes through the
     * receiver at the pixel (within kDepthTieUlps of its stored depth, see
     * volume_faces.h): the stencil was decided by a depth tie, the light
     * grazing the receiver's own plane. */
    uint64_t depth_tie_mismatches = 0;
    std::vector<int> first_off_boundary; /* pixel numbers (y * width + x), up to 16 */
    /* Truth's own camera rays against the depth pass (see above); each
     * disagreement is counted in off_boundary_mismatches too. */
    uint64_t primary_checked = 0;
    uint64_t primary_disagreements = 0;
};

class TruthCaster {
public:
    explicit TruthCaster(const Scene &scene);
    ~TruthCaster();
    /* The truth for light LIGHT of the frame, with THREADS threads. */
    Truth cast(const Frame &f, int light, int threads) const;
    /* TRUTH against the stencil of light LIGHT, with the finer look at
     * mismatches whose nine centres agree (see above). */
    Comparison compare(const Frame &f, int light, const Truth &truth) const;
    /* The truth at window point (x, y) (pixels, y down): kTruthNone when
     * the camera ray meets nothing. */
    uint8_t classify_point(const Frame &f, int light, double x, double y) const;

private:
    const Scene &scene_;
    std::unique_ptr<SceneRays> rays_;
    uint8_t light_class(const Frame &f, const std::vector<std::vector<uint8_t>> &facing,
                        const LightFrame &lf, int si, int t, const Vec3d &P, uint64_t *rays) const;
    std::vector<std::vector<uint8_t>> facing_bytes(const Vec4 &L) const;
    uint8_t classify_point(const Frame &f, const std::vector<std::vector<uint8_t>> &facing,
                           const LightFrame &lf, double x, double y) const;
    uint8_t classify_stored_depth(const Frame &f, const std::vector<std::vector<uint8_t>> &facing,
                                  const LightFrame &lf, int x, int y) const;
    bool primary_ray_agrees(const Frame &f, int x, int y) const;
};

/* Truth against a stencil (0 = lit), by the nine centres only; REFINE,
 * when given, is asked about each mismatch they do not explain. */
Comparison compare_with_stencil(const Truth &truth, const std::vector<uint8_t> &stencil, int width,
                                int height, const std::function<bool(int x, int y)> &refine = {});

/* Pixels of class lit/shadowed on which a boundary lies (see above). */
bool on_boundary(const Truth &truth, int width, int height, int x, int y);

} // namespace sv::render

#endif
