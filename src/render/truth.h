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
 *
 * Copyright (C) 2026 the shadowvol authors. LGPL-2.1-or-later.
 */
#ifndef SV_RENDER_TRUTH_H
#define SV_RENDER_TRUTH_H

#include <cstdint>
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
    kTruthDark = 3      /* faces away from the light, or its back side is seen */
};

struct Truth {
    std::vector<uint8_t> cls; /* TruthClass per pixel */
    uint64_t rays = 0;
    double seconds = 0;
};

struct Comparison {
    uint64_t compared = 0;           /* pixels of class lit or shadowed */
    uint64_t lit = 0, shadowed = 0;  /* by the truth */
    uint64_t boundary = 0;           /* compared pixels on a boundary */
    uint64_t mismatches = 0;         /* stencil says otherwise */
    uint64_t boundary_mismatches = 0;
    uint64_t off_boundary_mismatches = 0;
    std::vector<int> first_off_boundary; /* pixel numbers (y * width + x), up to 16 */
};

class TruthCaster {
public:
    explicit TruthCaster(const Scene &scene);
    ~TruthCaster();
    /* The truth for light LIGHT of the frame, with THREADS threads. */
    Truth cast(const Frame &f, int light, int threads) const;

private:
    const Scene &scene_;
    std::unique_ptr<SceneRays> rays_;
};

/* Truth against a stencil (0 = lit). */
Comparison compare_with_stencil(const Truth &truth, const std::vector<uint8_t> &stencil,
                                int width, int height);

/* Pixels of class lit/shadowed on which a boundary lies (see above). */
bool on_boundary(const Truth &truth, int width, int height, int x, int y);

} // namespace sv::render

#endif
