/*
 * The skinned characters' table of `shadowvol bench --planes`
 * (skin_planes_bench.cpp): skinning alone, skinning then planes in two
 * passes, and the one-pass kernels (include/shadowvol_anim.h), in the same
 * run, every call checked bit for bit against the C references.
 *
 * Copyright (C) 2026 the shadowvol authors. LGPL-2.1-or-later.
 */
#ifndef SV_BENCH_SKIN_PLANES_BENCH_H
#define SV_BENCH_SKIN_PLANES_BENCH_H

#include <cstdio>
#include <string>
#include <vector>

#include "planes_bench.h"

namespace svbench {

/* what: "skin", "two_passes", "one_pass", "job_stored_N", "job_derived_N",
 * "job_bfg_N"; variant: a skinning kernel, "K+P", a one-pass kernel, a
 * planes variant. */
using SkinPlanesRow = VariantRow;

struct SkinPlanesResult {
    std::string name;
    int surfaces = 0, triangles = 0, vertices = 0, segments = 0;
    std::vector<SkinPlanesRow> rows;
};

/* The demo scene's character, then the skinned characters of SHARED (and
 * its open/ folder) that are there (not QUICK); notes what is missing. */
std::vector<SkinPlanesResult> measure_skin_planes(const SeedTimer &timer, const std::string &shared,
                                                  bool quick, FILE *out, FILE *progress);
void print_skin_planes(FILE *out, const std::vector<SkinPlanesResult> &results);
/* "skinned": [...] in the open JSON object. */
void skin_planes_json(JsonWriter &j, const std::vector<SkinPlanesResult> &results);

} // namespace svbench

#endif
