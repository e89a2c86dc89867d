/*
 * shadowvol view's overlays (issue 30), drawn over the shaded frame:
 *   - the stencil counts of one light (images.h's stencil_image, the
 *     colours of render's stencil PNGs: 1 blue, 2 green, 3 yellow, more
 *     red, a wrapped count magenta; 0 the picture dimmed);
 *   - --stencil hier's boundary tiles of one light (seed 004's Figure 1:
 *     tiles some volume was walked in per pixel), outlined;
 *   - one light's volumes as wireframe: the edges of the part drawn
 *     (the silhouette quads in z-pass, and the caps in z-fail), through
 *     the frame's own extrusion (shadow_vertex_to_clip).
 *
 * Copyright (C) 2026 the shadowvol authors. LGPL-2.1-or-later.
 */
#ifndef SV_CLI_VIEW_OVERLAYS_H
#define SV_CLI_VIEW_OVERLAYS_H

#include <cstdint>

#include "frame.h"
#include "images.h"

namespace svcli {

void overlay_stencil_counts(sv::render::Image &image, const sv::render::Frame &frame, int light);
/* TILE: the side the frame's stencil pass used (RenderOptions). Nothing
 * to draw where the method kept no tiles (bf, db). */
void overlay_boundary_tiles(sv::render::Image &image, const sv::render::Frame &frame, int light,
                            int tile);
/* At most MAX_EDGES edges (a terrain's volume has hundreds of
 * thousands); returns how many were drawn. */
int64_t overlay_volume_wireframe(sv::render::Image &image, const sv::render::Frame &frame,
                                 const sv::Scene &scene, int light, int64_t max_edges);

} // namespace svcli

#endif
