/*
 * The input contracts of the kernels, as code: the *_checked entry points
 * verify every documented precondition (O(n), so they are for callers that
 * cannot guarantee the input, and for tests), then run the kernel.
 *
 * Copyright (C) 2026 the shadowvol authors. LGPL-2.1-or-later.
 */
#include <limits.h>

#include "shadowvol.h"
#include "contracts_internal.h"

const char *sv_status_string(int status) {
    switch (status) {
    case SV_OK: return "ok";
    case SV_E_NULL: return "a required pointer is NULL";
    case SV_E_COUNT: return "count is negative or numIndices is not a multiple of 3";
    case SV_E_ALIGNMENT: return "an array is less aligned than the variant needs";
    case SV_E_FACING_NOT_BOOL: return "a facing byte is neither 0 nor 1";
    case SV_E_INDEX_RANGE: return "a triangle or vertex number is outside its array";
    case SV_E_ODD_VERTEX: return "a SilEdge vertex number is odd (they must be doubled)";
    case SV_E_CAPACITY: return "the output buffer is smaller than the documented bound";
    case SV_E_OVERFLOW:
        return "more than INT_MAX indices (in the input, 3 * numTriangles, or in the output)";
    case SV_E_CPU: return "this CPU lacks the variant's instruction set";
    case SV_E_FACING_SENTINEL: return "facing[numTriangles] (the dangling edges' byte) is not 1";
    case SV_E_CULL_BITS:
        return "a cull byte has bit 7 set, which sse2_paper's CountFacingCull does not honour "
               "(erratum D-5)";
    case SV_E_GENERAL_FACING:
        return "a general facing byte is not 0, 1 or 2 (or is 2 on a triangle of the paper's "
               "class)";
    default: return status >= 0 ? "ok" : "unknown error";
    }
}

static int aligned(const void *p, unsigned alignment) {
    return ((uintptr_t)p & (uintptr_t)(alignment - 1)) == 0;
}

static int check_variant(const sv_variant *v) {
    if (!v) {
        return SV_E_NULL;
    }
    if ((v->isa & sv_cpu_isa()) != v->isa) {
        return SV_E_CPU;
    }
    return SV_OK;
}

static int check_facing_bytes(const uint8_t *facing, int n) {
    int i;
    for (i = 0; i < n; i++) {
        if (facing[i] > 1) {
            return SV_E_FACING_NOT_BOOL;
        }
    }
    return SV_OK;
}

/* facing[numTriangles] is the byte every dangling SilEdge (p2 =
 * numTriangles) points at: it must be 1, or the volume is open there. Read
 * on its own so that numTriangles = INT_MAX needs no numTriangles + 1. */
static int check_facing_sentinel(const uint8_t *facing, int numTriangles) {
    if (facing[numTriangles] > 1) {
        return SV_E_FACING_NOT_BOOL;
    }
    return facing[numTriangles] == 1 ? SV_OK : SV_E_FACING_SENTINEL;
}

/* sse2_paper's CountFacingCull compares the AND of a triangle's cull bytes
 * SIGNED (pcmpgtb, erratum D-5): an AND with bit 7 set reads as negative and
 * the triangle is not culled. Its contract is bits 0..6; a cull byte with
 * bit 7 is refused for it (the other variants honour all 8 bits). */
static int check_cull_bits(const sv_variant *v, const uint8_t *cullBits, int numVerts) {
#if defined(SV_HAVE_ASM_SSE2)
    int i;
    if (v->count_facing_cull != sv_count_facing_cull_sse2_paper) {
        return SV_OK;
    }
    for (i = 0; i < numVerts; i++) {
        if (cullBits[i] & 0x80u) {
            return SV_E_CULL_BITS;
        }
    }
    return SV_OK;
#else
    /* No sse2_paper on this platform (docs/PLATFORMS.md): every variant
     * built honours all 8 bits. */
    (void)v;
    (void)cullBits;
    (void)numVerts;
    return SV_OK;
#endif
}

int sv_check_vertex_indices(const int *indices, int numIndices, int numVerts) {
    int i;
    for (i = 0; i < numIndices; i++) {
        if (indices[i] < 0 || indices[i] >= numVerts) {
            return SV_E_INDEX_RANGE;
        }
    }
    return SV_OK;
}

/* Each edge names triangles in [0, numTriangles] (numTriangles is the
 * dangling edges' slot) and even vertex numbers; below 2 * numVerts when the
 * vertex count is known (numVerts >= 0). */
int sv_check_sil_edges(const SilEdge *edges, int numEdges, int numTriangles, int numVerts) {
    int i;
    for (i = 0; i < numEdges; i++) {
        const SilEdge *e = &edges[i];
        if (e->p1 < 0 || e->p1 > numTriangles || e->p2 < 0 || e->p2 > numTriangles || e->v1 < 0 ||
            e->v2 < 0) {
            return SV_E_INDEX_RANGE;
        }
        if (numVerts >= 0 && (e->v1 / 2 >= numVerts || e->v2 / 2 >= numVerts)) {
            return SV_E_INDEX_RANGE;
        }
        if ((e->v1 & 1) || (e->v2 & 1)) {
            return SV_E_ODD_VERTEX;
        }
    }
    return SV_OK;
}

int sv_count_facing_checked(const sv_variant *v, const uint8_t *facing, int numTriangles) {
    int s = check_variant(v);
    if (s) return s;
    if (numTriangles < 0) return SV_E_COUNT;
    if (numTriangles > 0 && !facing) return SV_E_NULL;
    if (!aligned(facing, v->align_facing)) return SV_E_ALIGNMENT;
    if ((s = check_facing_bytes(facing, numTriangles))) return s;
    return v->count_facing(facing, numTriangles);
}

int sv_count_facing_cull_checked(const sv_variant *v, uint8_t *facing, int numTriangles,
                                 const int *indices, const uint8_t *cullBits, int numVerts) {
    int s = check_variant(v);
    if (s) return s;
    if (numTriangles < 0 || numVerts < 0) return SV_E_COUNT;
    /* 3 * numTriangles indices must be an int. */
    if (numTriangles > INT_MAX / 3) return SV_E_OVERFLOW;
    if (numTriangles > 0 && (!facing || !indices || !cullBits)) return SV_E_NULL;
    if ((s = check_facing_bytes(facing, numTriangles))) return s;
    if ((s = sv_check_vertex_indices(indices, 3 * numTriangles, numVerts))) return s;
    if (numTriangles > 0 && (s = check_cull_bits(v, cullBits, numVerts))) return s;
    return v->count_facing_cull(facing, numTriangles, indices, cullBits);
}

int sv_create_sil_triangles_checked(const sv_variant *v, int *shadowIndices, size_t capacity,
                                    const uint8_t *facing, int numTriangles,
                                    const SilEdge *silEdges, int numSilEdges) {
    int s = check_variant(v);
    if (s) return s;
    if (numSilEdges < 0 || numTriangles < 0) return SV_E_COUNT;
    if (numSilEdges > INT_MAX / 6) return SV_E_OVERFLOW;
    if (!facing || (numSilEdges > 0 && (!silEdges || !shadowIndices))) return SV_E_NULL;
    if (!aligned(shadowIndices, v->align_shadow_indices)) return SV_E_ALIGNMENT;
    if (capacity < 6u * (size_t)numSilEdges) return SV_E_CAPACITY;
    /* facing holds numTriangles + 1 bytes: the last is the dangling edges' 1
     * (checked apart: numTriangles + 1 overflows at INT_MAX) */
    if ((s = check_facing_bytes(facing, numTriangles))) return s;
    if ((s = check_facing_sentinel(facing, numTriangles))) return s;
    if ((s = sv_check_sil_edges(silEdges, numSilEdges, numTriangles, -1))) return s;
    return v->create_sil_triangles(shadowIndices, facing, silEdges, numSilEdges);
}

int sv_create_cap_triangles_checked(const sv_variant *v, int *shadowIndices, size_t capacity,
                                    const uint8_t *facing, const int *indices, int numIndices,
                                    int numVerts) {
    int s = check_variant(v);
    if (s) return s;
    if (numIndices < 0 || numIndices % 3 != 0 || numVerts < 0) return SV_E_COUNT;
    /* 6 outputs per 3 inputs; doubled vertex numbers must stay below 2^31 */
    if (numIndices > INT_MAX / 2) return SV_E_OVERFLOW;
    if (numVerts > (1 << 30)) return SV_E_INDEX_RANGE;
    if (numIndices > 0 && (!facing || !indices || !shadowIndices)) return SV_E_NULL;
    if (!aligned(indices, v->align_indices) || !aligned(shadowIndices, v->align_shadow_indices)) {
        return SV_E_ALIGNMENT;
    }
    if (capacity < 2u * (size_t)numIndices) return SV_E_CAPACITY;
    if ((s = check_facing_bytes(facing, numIndices / 3))) return s;
    if ((s = sv_check_vertex_indices(indices, numIndices, numVerts))) return s;
    return v->create_cap_triangles(shadowIndices, facing, indices, numIndices);
}

int sv_create_shadow_volume_checked(const sv_variant *v, int *shadowIndices, size_t capacity,
                                    const int *indices, int numIndices, int numVerts,
                                    const SilEdge *silEdges, int numSilEdges, uint8_t *facing,
                                    const uint8_t *cullBits) {
    int s = check_variant(v);
    int numTriangles;
    if (s) return s;
    if (numIndices < 0 || numIndices % 3 != 0 || numSilEdges < 0 || numVerts < 0) {
        return SV_E_COUNT;
    }
    /* the returned count is an int: 6 per edge + 6 per triangle must fit */
    if (6ll * numSilEdges + 2ll * numIndices > INT_MAX) return SV_E_OVERFLOW;
    if (numVerts > (1 << 30)) return SV_E_INDEX_RANGE;
    numTriangles = numIndices / 3;
    if (!facing || ((numIndices > 0 || numSilEdges > 0) && !shadowIndices)) return SV_E_NULL;
    if ((numIndices > 0 && !indices) || (numSilEdges > 0 && !silEdges)) return SV_E_NULL;
    if (capacity < sv_shadow_volume_capacity(numIndices, numSilEdges)) return SV_E_CAPACITY;
    if ((!cullBits && !aligned(facing, v->align_facing)) || !aligned(indices, v->align_indices) ||
        !aligned(shadowIndices, v->align_shadow_indices)) {
        return SV_E_ALIGNMENT;
    }
    if ((s = check_facing_bytes(facing, numTriangles))) return s;
    if ((s = check_facing_sentinel(facing, numTriangles))) return s;
    if ((s = sv_check_vertex_indices(indices, numIndices, numVerts))) return s;
    if ((s = sv_check_sil_edges(silEdges, numSilEdges, numTriangles, numVerts))) return s;
    if (cullBits && numTriangles > 0 && (s = check_cull_bits(v, cullBits, numVerts))) return s;
    return sv_create_shadow_volume(v, shadowIndices, indices, numIndices, silEdges, numSilEdges,
                                   facing, cullBits);
}

/* ---- The general rule (issue 27) ----------------------------------------- */

static int check_general_variant(const sv_general_variant *v) {
    if (!v) return SV_E_NULL;
    if ((v->isa & sv_cpu_isa()) != v->isa) return SV_E_CPU;
    return SV_OK;
}

static int check_general_bytes(const uint8_t *facing, int n) {
    int i;
    for (i = 0; i < n; i++) {
        if (facing[i] > SV_GENERAL_LIT) return SV_E_GENERAL_FACING;
    }
    return SV_OK;
}

static int check_doubled_vertex(int v, int numVerts) {
    if (v < 0 || v / 2 >= numVerts) return SV_E_INDEX_RANGE;
    return (v & 1) ? SV_E_ODD_VERTEX : SV_OK;
}

/* A pair or open edge: triangles below numTriangles, even vertices below
 * 2 * numVerts; an open edge names its triangle twice. */
static int check_general_sil_edges(const SilEdge *edges, int n, int numTriangles, int numVerts,
                                   int open) {
    int i, s;
    for (i = 0; i < n; i++) {
        const SilEdge *e = &edges[i];
        if (e->p1 < 0 || e->p1 >= numTriangles || e->p2 < 0 || e->p2 >= numTriangles) {
            return SV_E_INDEX_RANGE;
        }
        if (open && e->p2 != e->p1) return SV_E_INDEX_RANGE;
        if ((s = check_doubled_vertex(e->v1, numVerts))) return s;
        if ((s = check_doubled_vertex(e->v2, numVerts))) return s;
    }
    return SV_OK;
}

int sv_create_general_sil_triangles_checked(const sv_general_variant *v, int *shadowIndices,
                                            size_t capacity, const uint8_t *facing,
                                            int numTriangles, int numVerts,
                                            const sv_general_edges *e) {
    int s = check_general_variant(v);
    int i;
    size_t bound;
    if (s) return s;
    if (!e) return SV_E_NULL;
    if (numTriangles < 0 || numVerts < 0) return SV_E_COUNT;
    bound = sv_general_sil_capacity(e);
    if (bound == SIZE_MAX) return SV_E_COUNT;
    /* The count returned is an int: 6 * k per edge of k triangles. */
    if (bound > (size_t)INT_MAX) return SV_E_OVERFLOW;
    if (!facing) return SV_E_NULL;
    if ((e->numPaper > 0 && !e->paper) || (e->numPairs > 0 && !e->pairs) ||
        (e->numOpens > 0 && !e->opens) || (e->numShared > 0 && !e->shared) ||
        (e->numSharedUses > 0 && !e->sharedUses) || (bound > 0 && !shadowIndices)) {
        return SV_E_NULL;
    }
    if (capacity < bound) return SV_E_CAPACITY;
    if ((s = check_general_bytes(facing, numTriangles))) return s;
    if (e->numPaper > 0) {
        /* The paper's class: its routine's contract (bytes 0 or 1, the
         * sentinel 1 for dangling edges). */
        if ((s = sv_check_sil_edges(e->paper, e->numPaper, numTriangles, numVerts))) return s;
        for (i = 0; i < e->numPaper; i++) {
            if (e->paper[i].p2 == numTriangles && facing[numTriangles] != 1) {
                return SV_E_FACING_SENTINEL;
            }
            if (facing[e->paper[i].p1] > 1 ||
                (e->paper[i].p2 < numTriangles && facing[e->paper[i].p2] > 1)) {
                return SV_E_GENERAL_FACING;
            }
        }
    }
    if ((s = check_general_sil_edges(e->pairs, e->numPairs, numTriangles, numVerts, 0))) return s;
    if ((s = check_general_sil_edges(e->opens, e->numOpens, numTriangles, numVerts, 1))) return s;
    for (i = 0; i < e->numShared; i++) {
        const sv_shared_edge *x = &e->shared[i];
        int k;
        if (x->numUses < 1 || x->firstUse < 0 || x->firstUse > e->numSharedUses - x->numUses) {
            return SV_E_INDEX_RANGE;
        }
        if ((s = check_doubled_vertex(x->v1, numVerts))) return s;
        if ((s = check_doubled_vertex(x->v2, numVerts))) return s;
        for (k = 0; k < x->numUses; k++) {
            const int u = e->sharedUses[x->firstUse + k];
            if (u < 0 || (u >> 1) >= numTriangles) return SV_E_INDEX_RANGE;
        }
    }
    return v->create_general_sil_triangles(shadowIndices, facing, e);
}

int sv_create_general_cap_triangles_checked(const sv_general_variant *v, int *shadowIndices,
                                            size_t capacity, const uint8_t *facing,
                                            const int *indices, int numIndices, int numVerts) {
    int s = check_general_variant(v);
    if (s) return s;
    if (numIndices < 0 || numIndices % 3 != 0 || numVerts < 0) return SV_E_COUNT;
    if (numIndices > INT_MAX / 2) return SV_E_OVERFLOW;
    if (numVerts > (1 << 30)) return SV_E_INDEX_RANGE;
    if (numIndices > 0 && (!facing || !indices || !shadowIndices)) return SV_E_NULL;
    if (capacity < 2u * (size_t)numIndices) return SV_E_CAPACITY;
    if ((s = check_general_bytes(facing, numIndices / 3))) return s;
    if ((s = sv_check_vertex_indices(indices, numIndices, numVerts))) return s;
    return v->create_general_cap_triangles(shadowIndices, facing, indices, numIndices);
}
