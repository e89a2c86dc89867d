/*
 * Our whole frame against Mesa's (issue 29): the frame F of SCENE drawn
 * again by llvmpipe (mesa_frame.h) with the same receivers, the same
 * volumes and the same lights, timed warm, and its picture compared with
 * ours pixel by pixel.
 *
 * Mesa shades in float with the normal from screen derivatives, we in
 * double with the stored plane: a pixel is "equal" when every channel is
 * within kFrameTolerance of ours; one that is not is "on an edge" when its
 * 3x3 neighbourhood shows another triangle, another shadow-mask value of
 * some light or a line of the ground's checker (float against double
 * there), or when some light's stencil in Mesa's frame differs from ours
 * there on a volume's edge or at a depth tie (gl_compare.h's classes, from
 * Mesa's stencils read back in an untimed drawing); else "other". A stencil
 * difference gl_compare.h calls "other" is counted apart
 * (stencil_other).
 *
 * Copyright (C) 2026 the shadowvol authors. LGPL-2.1-or-later.
 */
#ifndef SV_JUDGE_FRAME_VS_MESA_H
#define SV_JUDGE_FRAME_VS_MESA_H

#include <cstdint>
#include <string>
#include <vector>

#include "frame.h"

namespace sv::render {

constexpr int kFrameTolerance = 3; /* 8-bit levels per channel */

struct MesaFrameComparison {
    bool ran = false;         /* false: no GL context (NOTE says why) */
    std::string renderer;     /* GL_RENDERER, GL_VERSION */
    int lp_num_threads = 0;   /* LP_NUM_THREADS that took effect (0: one per CPU) */
    int runs = 0;             /* timed runs (after one warm-up), the minimum kept */
    double total_seconds = 0; /* the frame, no waits between passes */
    double depth_seconds = 0, stencil_seconds = 0, lighting_seconds = 0; /* with waits */
    uint64_t compared = 0; /* pixels a surface covers in both */
    uint64_t equal = 0, on_edge = 0, other = 0;
    uint64_t stencil_other = 0;   /* stencil pixels gl_compare.h calls other, over the lights */
    int max_difference_other = 0; /* levels, over the "other" pixels */
    std::vector<std::string> first_other; /* the first "other" pixels: where, ours and Mesa's */
    std::vector<uint8_t> mesa_rgb;        /* Mesa's picture, displayed as ours (sky: ours) */
};

/* AMBIENT: the frame's (RenderOptions::ambient). THREADS: LP_NUM_THREADS
 * for the first context of the process (a later call cannot change it:
 * run a child process per count). RUNS >= 1. */
MesaFrameComparison compare_frame_with_mesa(const Scene &scene, const Frame &f, double ambient,
                                            int threads, int runs, std::string *note);

} // namespace sv::render

#endif
