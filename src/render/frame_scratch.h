/*
 * What a FrameScratch (frame.h) keeps between frames (internal to
 * src/render).
 *
 * Copyright (C) 2026 the shadowvol authors. LGPL-2.1-or-later.
 */
#ifndef SV_RENDER_FRAME_SCRATCH_H
#define SV_RENDER_FRAME_SCRATCH_H

#include <vector>

#include "depth_pass.h"
#include "frame.h"
#include "pass_bins.h"
#include "shading_rows.h"
#include "surface_triangles.h"

namespace sv::render {

struct FrameScratch::Buffers {
    detail::BinnedTriangles depth_bins;                 /* depth_pass: set-up records, bins */
    WindowVertices depth_window;                        /* depth_pass: the vertices snapped */
    std::vector<detail::ShadeTriangle> shade_triangles; /* shading_pass */
    detail::SurfaceTrianglesCache surface_triangles;    /* stencil_pass: db, hier */
};

} // namespace sv::render

#endif
