/*
 * What a correct call leaves behind, the check of every timed call.
 *
 * A call works in a slot: the facing bytes (numTriangles + 1), the cull
 * bytes (numVerts) and the shadow indices. Before the call the slot holds
 * the light's facing pattern (poison for CalculateFacing, which writes all
 * of it), poisoned cull bytes and poisoned indices. A correct call leaves
 * the image the reference computes from the same start: the paper's C
 * (c_ref) for the kernels and the volume, the second computation of
 * oracle.h for appendices A and B (whose only implementation today is
 * c_ref itself).
 *
 * The check compares the returned count and digests of the slot's facing
 * bytes, cull bytes (App. B) and indices [0, count) with the reference's.
 * Digests, not copies, so that the reference for 64 lights of a 100k-
 * triangle mesh fits in memory (copies of its indices would take 1.5 GB).
 * The digest mixes each 8-byte word into its state with a bijection, so a
 * difference confined to one word always changes it; differences in
 * several words collide with probability about 2^-64. When a digest
 * differs, the reference image is computed again to name the first byte or
 * index that differs.
 *
 * Copyright (C) 2026 the shadowvol authors. LGPL-2.1-or-later.
 */
#ifndef SV_BENCH_EXPECTED_H
#define SV_BENCH_EXPECTED_H

#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

#include "routines.h"
#include "workload.h"

namespace svbench {

constexpr uint8_t kPoisonByte = 0xa5; /* neither 0 nor 1, and not a cull byte */
constexpr int kPoisonIndex = -1;      /* never a valid shadow index */

uint64_t digest(const void *data, size_t bytes);

/* The slot's facing bytes before a call of R on L: numTriangles + 1. */
void initial_facing(Routine r, const Workload &w, const Light &l, uint8_t *facing);

/* The slot after a correct call. */
struct SlotImage {
    int count = 0;               /* the return value (0 for CalculateFacing) */
    std::vector<int> indices;    /* [0, count) for the index routines */
    std::vector<uint8_t> facing; /* numTriangles + 1 */
    std::vector<uint8_t> cull;   /* numVerts, for CalculateCullBits */
};
SlotImage reference_image(Routine r, const Workload &w, const Light &l);

struct Expected {
    int count = 0;
    uint64_t indices = 0, facing = 0, cull = 0; /* digests */
};
/* One per light of W. Throws std::logic_error when a count contradicts the
 * light's ratios (a broken reference or workload must not pass as "ok"). */
std::vector<Expected> expected_results(Routine r, const Workload &w);

/* Empty when the slot matches E; else what differs first (the reference
 * image is recomputed to say where). */
std::string compare_with_reference(Routine r, const Workload &w, const Light &l, const Expected &e,
                                   int got, const int *indices, const uint8_t *facing,
                                   const uint8_t *cull);

} // namespace svbench

#endif
