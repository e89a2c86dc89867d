/*
 * The whole shadowed frame drawn by Mesa's llvmpipe (issue 29): the frame
 * src/render draws, as an OpenGL renderer of the Doom 3 kind draws it, so
 * our frame can be timed against Mesa's and the pictures compared.
 *
 * Per frame: a depth pre-pass that writes the ambient term (the same
 * receivers, ambient times albedo, the ground's checker); then per light
 * the stencil cleared, its volumes counted into it exactly as the stencil
 * judge draws them (mesa_stencil.h: the same index lists over the same
 * double-length vertex buffers, the paper's vertex program), and the
 * receivers drawn again with depth test EQUAL, stencil test EQUAL 0 and
 * additive blending, through a fragment shader with the lighting pass's
 * formula (Lambert on the triangle's plane normal, 1/d^2 with the
 * KHR_lights_punctual range window, the spot cone), front faces only.
 * Radiance is summed in a 32-bit float colour buffer and read back linear:
 * the display mapping (a table lookup per channel on our side) is left to
 * the caller and timed on neither side.
 *
 * In float and with the normal from the screen-space derivatives of the
 * position, Mesa's radiance differs from ours in its last bits: pictures
 * are compared within a tolerance (frame_vs_mesa.h).
 *
 * Copyright (C) 2026 the shadowvol authors. LGPL-2.1-or-later.
 */
#ifndef SV_GLJUDGE_MESA_FRAME_H
#define SV_GLJUDGE_MESA_FRAME_H

#include <cstdint>
#include <vector>

#include "mesa_stencil.h"

namespace sv::gl {

struct MesaFrameSurface {
    MesaMesh mesh;
    float albedo[3] = {0.8f, 0.8f, 0.8f};
    bool ground = false; /* the faint checker */
};

struct MesaFrameLight {
    int kind = 0; /* 0 point, 1 spot, 2 directional */
    float position[3] = {0, 0, 0}, direction[3] = {0, -1, 0};
    float color[3] = {1, 1, 1};
    float intensity = 1;
    float inv_range2 = 0; /* 1 / range^2; 0: unlimited */
    float cos_outer = 0, cos_inner = 0;
    Vec4 shadow_light{0, 0, 0, 1}; /* the volumes' light, as MesaStencilJob::light */
    std::vector<MesaVolume> volumes;
};

struct MesaFrameJob {
    int width = 0, height = 0; /* must equal the context's */
    double view_proj[16] = {}; /* column-major, as MesaStencilJob */
    float ambient = 0.12f;
    std::vector<MesaFrameSurface> surfaces;
    std::vector<MesaFrameLight> lights;
    /* true: glFinish after every pass, so each pass is timed (the total
     * then pays for the waits); false: one glFinish at the end, the total
     * only. */
    bool time_each_pass = false;
    /* true: read back the depth after the pre-pass and each light's
     * stencil after its volumes (for the comparison; not in timed runs). */
    bool read_stencils = false;
};

struct MesaFrameResult {
    /* Per pixel (row 0 = top): linear radiance times albedo, red, green,
     * blue; and whether a surface covers it (else it is sky). */
    std::vector<float> radiance;
    std::vector<uint8_t> covered;
    double depth_seconds = 0;    /* the depth pre-pass with the ambient term */
    double stencil_seconds = 0;  /* every light's volumes (time_each_pass) */
    double lighting_seconds = 0; /* every light's lighting pass (time_each_pass) */
    double total_seconds = 0;    /* the frame, glFinish to glFinish */
    /* read_stencils: the depth after the pre-pass and each light's stencil
     * (row 0 = top), as MesaStencilResult holds them. */
    std::vector<float> depth;
    std::vector<std::vector<uint8_t>> stencils;
};

} // namespace sv::gl

#endif
