/*
 * The fill rule: which triangle owns a pixel centre that lies exactly on
 * an edge. The one place that decides it.
 *
 * Edges are taken in a triangle whose corners run clockwise on the screen
 * with y down (the rasteriser reorders every triangle so; that is
 * positive area in window coordinates with y down). An edge from (x0, y0)
 * to (x1, y1) is
 *   left    when y1 < y0 (it runs up the screen: the triangle lies to its right),
 *   bottom  when y1 == y0 and x1 < x0 (horizontal, the triangle above it).
 * A centre on a left or bottom edge is covered; on any other edge it is
 * not. Two triangles sharing an edge see it in opposite directions, so
 * exactly one of them owns a centre on it: that is what makes a closed
 * mesh sum to zero in the stencil.
 *
 * Why bottom-left and not Direct3D's top-left: it is the rule of Mesa's
 * llvmpipe for OpenGL's default lower-left origin (src/judge/
 * mesa_stencil.cpp found it by experiment, and its tests pin it). With y
 * up, llvmpipe owns left edges and the horizontal edge with the interior
 * above it: the triangle's bottom edge, in GL's window and in the image
 * alike (only the row numbering flips). With the same rule the project's
 * stencil and Mesa's differ only where their sub-pixel rounding does.
 *
 * Copyright (C) 2026 the shadowvol authors. LGPL-2.1-or-later.
 */
#ifndef SV_RASTER_FILL_RULE_H
#define SV_RASTER_FILL_RULE_H

#include <cstdint>

namespace sv::raster {

/* Bias added to an edge function (E >= 0 inside) so that "covered" is
 * E + bias >= 0: 0 for an owning edge, -1 otherwise (E is an integer, so
 * E - 1 >= 0 is E > 0). DX, DY: the edge's vector in 1/256 pixels, y down. */
inline int64_t fill_rule_bias(int64_t dx, int64_t dy) {
    const bool left = dy < 0;
    const bool bottom = dy == 0 && dx < 0;
    return (left || bottom) ? 0 : -1;
}

} // namespace sv::raster

#endif
