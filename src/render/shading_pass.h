/*
 * The shading pass (issue 12): ambient everywhere, and each light where
 * its stencil is 0, the visible side of the triangle faces it (the facing
 * bytes its volume was built from) and the light reaches the surface;
 * Lambert with the KHR_lights_punctual range window and spot cone, shown
 * through a soft shoulder and gamma 2.2.
 *
 * Copyright (C) 2026 the shadowvol authors. LGPL-2.1-or-later.
 */
#ifndef SV_RENDER_SHADING_PASS_H
#define SV_RENDER_SHADING_PASS_H

#include <cstdint>
#include <vector>

#include "frame.h"
#include "shading_rows.h"

namespace sv::render {

struct ShadingResult {
    std::vector<uint8_t> rgb;   /* 3 bytes per pixel, row 0 = top */
    uint64_t ticks = 0;         /* wall TSC ticks */
    uint64_t divider_lanes = 0; /* ShadeRowInputs::divider_lanes, summed */
};

/* Shades frame F (after its depth and stencil passes: its ids, camera
 * rays and each light's stencil) of SCENE. LIT_FACING: volume_pass.h's
 * lit_facing. ISA: the row kernels' (SV_ISA_* bits): AVX2 or AVX-512 runs
 * the AVX2 row kernel, else the C one; the bytes are the same. TRIANGLES:
 * the per-triangle table, filled (a FrameScratch's). Runs on the calling
 * task arena's threads. */
ShadingResult shading_pass(const Scene &scene, const Frame &f,
                           const std::vector<const uint8_t *> &lit_facing, double ambient,
                           unsigned isa, std::vector<detail::ShadeTriangle> &triangles);

/* Linear radiance (after the albedo) to the 8-bit value the pass writes:
 * the soft shoulder and gamma 2.2, through the pass's table. */
uint8_t display_byte(double linear);

} // namespace sv::render

#endif
