/*
 * `shadowvol bench --planes` (planes_bench.cpp): per-frame plane derivation
 * against facing from positions. Takes the options of the seed benchmarks
 * (seed_bench.h); exit status as theirs.
 *
 * Copyright (C) 2026 the shadowvol authors. LGPL-2.1-or-later.
 */
#ifndef SV_BENCH_PLANES_BENCH_H
#define SV_BENCH_PLANES_BENCH_H

#include <cstdint>
#include <cstdio>
#include <string>
#include <vector>

#include "seed_bench.h"
#include "shadowvol.h"

namespace svbench {

int run_planes_bench(const SeedCommand &cmd);

/* COUNT point lights (w = 1) on a jittered ring at 1.5 times the largest
 * extent of the VERTICES positions (x, y, z each) around their box's
 * centre, at elevations from 0.2 to 1.1 radians (--planes, --extrude). */
std::vector<Vec4> lights_around(const float *positions, int vertices, int count, uint64_t seed);

/* A timed row of --planes and --extrude: what was timed, by which variant. */
struct VariantRow {
    std::string what;
    std::string variant;
    SeedTiming t;
};
/* The row WHAT of VARIANT ("" any variant), or nullptr. */
const VariantRow *find_variant_row(const std::vector<VariantRow> &rows, const std::string &what,
                                   const std::string &variant);
/* The row's median ticks per PER units ("%.2f", " FAIL" when its check
 * failed), or "-" without a row. */
std::string ticks_cell(const VariantRow *row, double per);
/* ROWS as the JSON array "rows" (J's key written here): per row its
 * seed_json_row fields, "ok", "failure" where it failed, and where
 * PER_TRIANGLE > 0 its median ticks per triangle ("ticks_per_triangle",
 * over PER_TRIANGLE triangles). */
void variant_rows_json(JsonWriter &j, const std::vector<VariantRow> &rows, int per_triangle = 0);
/* A line "FAILED MESH WHAT VARIANT: why" per failed row; returns how many. */
int print_failed_rows(FILE *out, const std::string &mesh, const std::vector<VariantRow> &rows);

} // namespace svbench

#endif
