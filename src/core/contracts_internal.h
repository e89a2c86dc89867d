/*
 * The contract checks of the *_checked entry points (src/core/contracts.c)
 * that other parts of the library reuse (the planner, on a caller's
 * surface); not part of the public API.
 *
 * Copyright (C) 2026 the shadowvol authors. LGPL-2.1-or-later.
 */
#ifndef SV_CONTRACTS_INTERNAL_H
#define SV_CONTRACTS_INTERNAL_H

#include "shadowvol.h"

#ifdef __cplusplus
extern "C" {
#endif

/* SV_OK, or SV_E_INDEX_RANGE for a vertex number outside [0, numVerts). */
int sv_check_vertex_indices(const int *indices, int numIndices, int numVerts);
/* SV_OK, or SV_E_INDEX_RANGE / SV_E_ODD_VERTEX: each edge names triangles
 * in [0, numTriangles] (numTriangles is the dangling edges' slot) and even
 * vertex numbers, below 2 * numVerts when numVerts >= 0. */
int sv_check_sil_edges(const SilEdge *edges, int numEdges, int numTriangles, int numVerts);

#ifdef __cplusplus
}
#endif

#endif
