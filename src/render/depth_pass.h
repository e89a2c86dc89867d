/*
 * The depth pass (issue 12): every surface's triangles drawn into the
 * target's depth and triangle ids (LESS, both faces), set up in chunks
 * and walked per screen band in parallel.
 *
 * Copyright (C) 2026 the shadowvol authors. LGPL-2.1-or-later.
 */
#ifndef SV_RENDER_DEPTH_PASS_H
#define SV_RENDER_DEPTH_PASS_H

#include <cstdint>
#include <vector>

#include "pass_bins.h"
#include "rasterizer.h"
#include "shadowvol_scene.h"

namespace sv::render {

/* Per surface, its vertices in clip space (the depth pass's input, and
 * the even vertices of every shadow volume's double-length buffer). */
using ClipVertices = std::vector<std::vector<raster::ClipVertex>>;
/* Per surface, its vertices as set-up snaps them (raster::window_vertex). */
using WindowVertices = std::vector<std::vector<raster::WindowVertex>>;
ClipVertices receivers_to_clip(const Scene &scene, const Mat4d &view_proj);

struct DepthPassResult {
    raster::PassCounters counters;
    uint64_t ticks = 0; /* wall TSC ticks */
    double seconds = 0;
};

/* Draws every surface of SCENE (its vertices CLIP) into TARGET, which must
 * be sized and cleared; triangle T of surface S gets the id
 * SURFACE_FIRST_ID[S] + T. BT: the set-up records and bins, and WINDOW:
 * the vertices snapped, emptied and filled (a FrameScratch's, kept from
 * frame to frame). Runs on the calling task arena's threads. */
DepthPassResult depth_pass(const Scene &scene, const ClipVertices &clip,
                           const std::vector<int32_t> &surface_first_id,
                           const raster::Rasterizer &rast, raster::Target &target,
                           detail::BinnedTriangles &bt, WindowVertices &window);

} // namespace sv::render

#endif
