/*
 * Which triangles of a shadow volume touch an open edge (internal to
 * src/render). The hierarchical and depth-bounds stencil methods skip
 * pixels on the argument that a volume's count is the same on both sides
 * of every edge inside a tile: true where the triangles on an edge close
 * it (its directed uses cancel, as in a closed mesh), not at an open edge
 * (a z-pass volume's silhouette quads end at the caster and at infinity;
 * a culled volume is open where it was cut). Those triangles are walked
 * per pixel wherever they count.
 *
 * Copyright (C) 2026 the shadowvol authors. LGPL-2.1-or-later.
 */
#ifndef SV_RENDER_OPEN_EDGES_H
#define SV_RENDER_OPEN_EDGES_H

#include <cstdint>
#include <vector>

namespace sv::render::detail {

/* INDICES: NUM_TRIANGLES triangles into the double-length shadow vertex
 * buffer (even 2v: the vertex, odd 2v + 1: extruded). SKIP[t] != 0: the
 * triangle draws nothing (zero area after snapping) and closes nothing.
 * EXTRUDED_SHARED: a directional light, where every extruded vertex is the
 * same point at infinity. Returns OPEN[t]: bit k set where triangle t's
 * edge k (corner k to corner k + 1 mod 3) is one whose directed uses (by
 * the triangles not skipped) do not cancel. */
std::vector<uint8_t> triangles_on_open_edges(const int *indices, int num_triangles,
                                             const std::vector<uint8_t> &skip,
                                             bool extruded_shared);

} // namespace sv::render::detail

#endif
