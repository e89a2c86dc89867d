/*
 * What the silhouette finders' files share (not public).
 *
 * Copyright (C) 2026 the shadowvol authors. LGPL-2.1-or-later.
 */
#ifndef SV_SILHOUETTE_INTERNAL_H
#define SV_SILHOUETTE_INTERNAL_H

#include "shadowvol_silhouette.h"

namespace sv {

/* Use u is edge u % 3 of triangle u / 3, from corner u to the next corner. */
inline int silhouette_next_use(int u) { return u % 3 == 2 ? u - 2 : u + 1; }

/* The edges of the dangling uses of unlit triangles, appended at OUT + N;
 * returns the new count. */
std::size_t silhouette_dangling(const ConnectivityTable &c, const int *indices,
                                const uint8_t *facing, DirectedEdge *out, std::size_t n);

/* The branch-free scalar loop over triangles [firstTriangle, numTriangles),
 * appending at OUT + N (writes one edge past the returned count); the SIMD
 * kernels' tail. */
std::size_t silhouette_connectivity_tail(const ConnectivityTable &c, const int *indices,
                                         int firstTriangle, int numTriangles, const uint8_t *facing,
                                         DirectedEdge *out, std::size_t n);

} // namespace sv

#endif
