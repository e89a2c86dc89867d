/*
 * The frame's stencils against Mesa's (issue 12, "Proof 2"): the same
 * receivers, the same index lists over the same double-length vertex
 * buffers, the same matrix, drawn by llvmpipe (src/judge); every pixel
 * whose stencil differs is classified:
 *   depth tie    a drawn volume triangle covers it within 128 float ulps
 *                of the stored depth (the two depth interpolations may order the
 *                volume and the receiver differently there: a near cap
 *                lies exactly on its receiver);
 *   on an edge   else, its centre lies within 1/8 pixel of an edge of a
 *                drawn volume triangle (the two rasterisers' sub-pixel
 *                snapping meets there);
 *   other        neither: a real disagreement (the render fails).
 *
 * Copyright (C) 2026 the shadowvol authors. LGPL-2.1-or-later.
 */
#ifndef SV_RENDER_GL_COMPARE_H
#define SV_RENDER_GL_COMPARE_H

#include <cstdint>
#include <string>
#include <vector>

#include "frame.h"
#include "mesa_stencil.h"

namespace sv::render {

struct GlComparison {
    std::vector<uint8_t> cls; /* per pixel: 0 equal, 1 on an edge, 2 depth tie, 3 other */
    uint64_t differing = 0, on_edge = 0, depth_tie = 0, other = 0;
    double max_edge_distance = 0; /* pixels, over the "on an edge" ones */
    std::vector<std::string>
        first_other; /* where the first "other" ones are, and how far from a tie or an edge */
    double mesa_depth_seconds = 0, mesa_stencil_seconds = 0;
    std::vector<uint8_t> mesa_stencil; /* row 0 = top */
};

/* Surface S as the Mesa judges draw it in their depth pre-pass, and light
 * LF's volumes as their draws over BUFFERS (each surface's
 * shadow_vertices(), which must outlive the draws). */
gl::MesaMesh mesa_receiver(const SceneSurface &s);
std::vector<gl::MesaVolume> mesa_volumes(const LightFrame &lf,
                                         const std::vector<AlignedVector<Vec4>> &buffers);

/* One comparison per light of F; empty (and *NOTE says why) when no GL
 * context can be made. *RENDERER: GL_RENDERER and GL_VERSION. THREADS:
 * llvmpipe's LP_NUM_THREADS (read once per process: the first call's
 * count holds for the process; *LP_THREADS, where given, gets the count
 * that took effect, 0 for llvmpipe's own default). */
std::vector<GlComparison> compare_with_mesa(const Scene &scene, const Frame &f,
                                            std::string *renderer, std::string *note,
                                            int threads = 1, int *lp_threads = nullptr);

/* The classification alone (for tests): pixels where OURS and THEIRS
 * differ, given the frame's drawn volume triangles of light LIGHT and the
 * depth buffers. */
GlComparison classify_differences(const Scene &scene, const Frame &f, int light,
                                  const std::vector<uint8_t> &ours,
                                  const std::vector<uint8_t> &theirs,
                                  const std::vector<float> &their_depth);

} // namespace sv::render

#endif
