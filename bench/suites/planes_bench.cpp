/*
 * `shadowvol bench --planes`: per-frame plane derivation for deforming
 * surfaces (include/shadowvol_planes.h; the paper: planes are derived once
 * per frame and shared by every light) against facing straight from the
 * positions (id's 2012 BFG engine: no stored planes, a cross product per
 * triangle and light).
 *
 * Meshes: the bundled character (models/character_1344.glb), the real
 * characters of the shared folder (Fox, CesiumMan, RobotExpressive,
 * RiggedFigure: welded, all surfaces merged) when present, and a
 * generated 224 x 224-quad height field (100,352 triangles) in row order.
 *
 * Rows (ticks per triangle, median of calls, min in the JSON):
 *  1. derive planes, every variant the CPU runs, the floor (the same
 *     arithmetic on corners gathered beforehand: planes_floor.h), and by
 *     clusters (every clustered kernel, the clusters built once
 *     beforehand: that build's ticks too); every call's planes compared
 *     bit for bit with the C reference's.
 *  2. a frame of 1 and of 4 lights (moving: 16 point lights around the
 *     mesh, the next 1 or 4 in each call):
 *       bfg     sv_facing_from_positions per light (each variant);
 *       planes  the best derive variant once, then the best
 *               sv_calculate_facing per light;
 *     every call's facing bytes compared with the C references'.
 *  3. how often the two facings disagree over the 16 lights (they round
 *     differently near a triangle's plane).
 *  4. the skinned characters: skinning alone, skinning then planes, and
 *     both in one pass (skin_planes_bench.cpp).
 *
 * Copyright (C) 2026 the shadowvol authors. LGPL-2.1-or-later.
 */
#include <algorithm>
#include <cmath>
#include <cstring>
#include <string>
#include <vector>

#include <unistd.h>
#include <x86intrin.h>

#include "json_writer.h"
#include "shadowvol_anim.h"
#include "shadowvol_mesh.h"
#include "planes_bench.h"
#include "planes_floor.h"
#include "seed_bench.h"
#include "shadowvol_planes.h"
#include "skin_planes_bench.h"

#ifndef SV_MODELS_DIR
#define SV_MODELS_DIR "models"
#endif

namespace svbench {

namespace {

constexpr int kLightsPlanes = 16;

struct PlanesMesh {
    std::string name;
    std::vector<float> positions; /* x y z per vertex */
    std::vector<int> indices;
    int triangles = 0, vertices = 0;
};

/* Rows: what is "derive", "bfg_1", "bfg_4", "planes_1" or "planes_4". */
using PlanesRow = VariantRow;

struct PlanesResult {
    PlanesMesh mesh;
    std::vector<PlanesRow> rows;
    long long disagree = 0, compared = 0; /* bfg facing vs plane facing */
    int clusters = 0;                     /* sv::plane_clusters of the mesh */
};

PlanesMesh from_workload(const SeedMesh &m) {
    PlanesMesh p;
    p.name = m.name;
    p.vertices = m.w.numVerts;
    p.triangles = m.w.numTriangles;
    p.positions.resize(3 * (size_t)p.vertices);
    for (int v = 0; v < p.vertices; v++) {
        p.positions[3 * v] = m.w.positions[v].x;
        p.positions[3 * v + 1] = m.w.positions[v].y;
        p.positions[3 * v + 2] = m.w.positions[v].z;
    }
    p.indices.assign(m.w.indices.data(), m.w.indices.data() + m.w.numIndices);
    return p;
}

/* N x N quads of gentle hills, 2 triangles each, counter-clockwise from +y. */
PlanesMesh grid_mesh(int n) {
    PlanesMesh g;
    g.name = "grid_" + std::to_string(2 * n * n);
    const int w = n + 1;
    for (int j = 0; j < w; j++) {
        for (int i = 0; i < w; i++) {
            const double x = i * 0.25, z = j * 0.25;
            g.positions.push_back((float)x);
            g.positions.push_back((float)(0.8 * std::sin(x * 0.11) * std::cos(z * 0.07) +
                                          0.2 * std::sin(x * 0.5 + z * 0.3)));
            g.positions.push_back((float)z);
        }
    }
    for (int j = 0; j < n; j++) {
        for (int i = 0; i < n; i++) {
            const int a = j * w + i, b = a + 1, c = a + w, d = c + 1;
            const int tri[6] = {a, c, b, b, c, d};
            g.indices.insert(g.indices.end(), tri, tri + 6);
        }
    }
    g.vertices = w * w;
    g.triangles = 2 * n * n;
    return g;
}

std::string first_plane_diff(const Plane *got, const std::vector<Plane> &ref) {
    for (size_t t = 0; t < ref.size(); t++) {
        // Bit for bit is the contract (-0.0 against 0.0, a NaN's payload).
        // NOLINTNEXTLINE(bugprone-suspicious-memory-comparison): Plane is four floats, no padding
        if (std::memcmp(&got[t], &ref[t], sizeof(Plane)) != 0) {
            return "plane " + std::to_string(t) + " differs from the C reference";
        }
    }
    return "";
}

void measure(PlanesResult &res, const SeedTimer &timer, uint64_t seed, FILE *progress) {
    const PlanesMesh &m = res.mesh;
    const int n = m.triangles;
    const float *pos = m.positions.data();
    const int *idx = m.indices.data();
    const std::vector<Vec4> lights = lights_around(pos, m.vertices, kLightsPlanes, seed);

    std::vector<Plane> refPlanes((size_t)n);
    sv_derive_planes_c_ref(pos, idx, n, refPlanes.data());
    /* The C references' facing for every light: of the planes, and BFG's. */
    std::vector<std::vector<uint8_t>> refPlaneFacing(kLightsPlanes), refBfg(kLightsPlanes);
    for (int l = 0; l < kLightsPlanes; l++) {
        refPlaneFacing[l].resize((size_t)n + 1);
        refBfg[l].resize((size_t)n + 1);
        sv_calculate_facing_c_ref(refPlanes.data(), n, &lights[l], refPlaneFacing[l].data());
        sv_facing_from_positions_c_ref(pos, idx, n, &lights[l], refBfg[l].data());
        for (int t = 0; t < n; t++) res.disagree += refPlaneFacing[l][t] != refBfg[l][t];
        res.compared += n;
    }

    int count = 0;
    const sv_planes_variant *all = sv_planes_variants(&count);
    std::vector<const sv_planes_variant *> run;
    for (int i = 0; i < count; i++) {
        if ((all[i].isa & sv_cpu_isa()) == all[i].isa) run.push_back(&all[i]);
    }
    std::vector<Plane> planes((size_t)n);
    std::vector<uint8_t> facing[4];
    for (auto &f : facing) f.resize((size_t)n + 1);

    for (const sv_planes_variant *v : run) {
        if (progress) std::fprintf(progress, "\r%s: derive %s        ", m.name.c_str(), v->name);
        PlanesRow r{"derive", v->name, {}};
        r.t = time_seed_row(
            timer, [&](int) { v->derive_planes(pos, idx, n, planes.data()); },
            [&](int) { return first_plane_diff(planes.data(), refPlanes); });
        res.rows.push_back(r);
    }
    /* The floor (planes_floor.h): the same arithmetic on corners gathered
     * beforehand, untimed, so the gap to the kernels is their gather. */
    if (planes_floor_runs()) {
        const GatheredCorners gathered = gather_corners(pos, idx, n);
        if (progress) std::fprintf(progress, "\r%s: the floor        ", m.name.c_str());
        PlanesRow r{"derive", "floor_avx2", {}};
        r.t = time_seed_row(
            timer, [&](int) { planes_from_gathered_avx2(gathered, planes.data()); },
            [&](int) { return first_plane_diff(planes.data(), refPlanes); });
        res.rows.push_back(r);
    }
    /* The clustered kernels (include/shadowvol_planes.h): the clusters are
     * built once per index list, outside the timing (their cost, once, in
     * the "clusters" row: ticks per triangle of one build). */
    uint64_t b0 = __rdtsc();
    const sv::PlaneClusters clusters = sv::plane_clusters(idx, n, m.vertices);
    PlanesRow build{"cluster_build", "clusters", {}};
    build.t.median = build.t.min = (double)(__rdtsc() - b0);
    build.t.ok = true;
    build.t.calls = 1;
    res.rows.push_back(build);
    res.clusters = clusters.num_clusters();
    const sv_plane_clusters view = clusters.view();
    const sv_planes_clustered_variant *cv = sv_planes_clustered_variants(&count);
    for (int i = 0; i < count; i++) {
        if ((cv[i].isa & sv_cpu_isa()) != cv[i].isa) continue;
        const sv_planes_clustered_variant *v = &cv[i];
        if (progress)
            std::fprintf(progress, "\r%s: derive clusters %s   ", m.name.c_str(), v->name);
        PlanesRow r{"derive", std::string("clusters_") + v->name, {}};
        r.t = time_seed_row(
            timer, [&](int) { v->derive_planes(pos, &view, planes.data()); },
            [&](int) { return first_plane_diff(planes.data(), refPlanes); });
        res.rows.push_back(r);
    }
    for (int k : {1, 4}) {
        auto check_facing = [&](int i, const std::vector<std::vector<uint8_t>> &ref) {
            for (int j = 0; j < k; j++) {
                const int l = (k * i + j) % kLightsPlanes;
                if (std::memcmp(facing[j].data(), ref[l].data(), (size_t)n + 1) != 0) {
                    return std::string("facing of light ") + std::to_string(l) +
                           " differs from the C reference";
                }
            }
            return std::string();
        };
        for (const sv_planes_variant *v : run) {
            if (progress)
                std::fprintf(progress, "\r%s: bfg %s x%d        ", m.name.c_str(), v->name, k);
            PlanesRow r{"bfg_" + std::to_string(k), v->name, {}};
            r.t = time_seed_row(
                timer,
                [&](int i) {
                    for (int j = 0; j < k; j++) {
                        v->facing_from_positions(pos, idx, n, &lights[(k * i + j) % kLightsPlanes],
                                                 facing[j].data());
                    }
                },
                [&](int i) { return check_facing(i, refBfg); });
            res.rows.push_back(r);
        }
        /* The planner's planes variant for the mesh's size (the wisdom
         * file's measured choice, else the static one), as a scene uses. */
        const sv_planes_variant *bp = sv::deform_plan_for(n).planes;
        const sv_facing_variant *bf = sv_best_facing_variant();
        PlanesRow r{"planes_" + std::to_string(k), std::string(bp->name) + "+" + bf->name, {}};
        r.t = time_seed_row(
            timer,
            [&](int i) {
                bp->derive_planes(pos, idx, n, planes.data());
                for (int j = 0; j < k; j++) {
                    bf->calculate_facing(planes.data(), n, &lights[(k * i + j) % kLightsPlanes],
                                         facing[j].data());
                }
            },
            [&](int i) { return check_facing(i, refPlaneFacing); });
        res.rows.push_back(r);
    }
    if (progress) std::fprintf(progress, "\r%60s\r", "");
}

void print_tables(FILE *out, const std::vector<PlanesResult> &results) {
    std::vector<std::string> variants, derive;
    for (const PlanesRow &r : results.front().rows) {
        if (r.what == "derive") derive.push_back(r.variant);
        if (r.what == "bfg_1") variants.push_back(r.variant);
    }
    std::fprintf(out,
                 "\nderive planes, ticks per triangle (median; every call bit-identical to "
                 "c_ref, else FAIL)\n"
                 "  floor_avx2: not a kernel: the same arithmetic on corners gathered "
                 "beforehand, untimed, into nine arrays (a kernel's time beyond it is its "
                 "gather; bench/suites/planes_floor.h)\n"
                 "  clusters_*: by clusters of at most %d vertices, built once per index "
                 "list (build: ticks per triangle, once; tri/cl: triangles per cluster)\n",
                 SV_PLANE_CLUSTER_VERTICES);
    std::fprintf(out, "%-24s %9s", "mesh", "triangles");
    for (const std::string &v : derive)
        std::fprintf(out, " %*s", v.size() > 11 ? 15 : 11, v.c_str());
    std::fprintf(out, " %7s %7s\n", "build", "tri/cl");
    for (const PlanesResult &r : results) {
        std::fprintf(out, "%-24s %9d", r.mesh.name.c_str(), r.mesh.triangles);
        for (const std::string &v : derive) {
            std::fprintf(
                out, " %*s", v.size() > 11 ? 15 : 11,
                ticks_cell(find_variant_row(r.rows, "derive", v), r.mesh.triangles).c_str());
        }
        std::fprintf(
            out, " %7s %7.1f\n",
            ticks_cell(find_variant_row(r.rows, "cluster_build", ""), r.mesh.triangles).c_str(),
            r.clusters ? (double)r.mesh.triangles / r.clusters : 0.0);
    }

    std::fprintf(out,
                 "\nfacing for a frame of 1 and 4 moving lights, ticks per triangle "
                 "(median; every call checked against the C references)\n"
                 "  bfg:    sv_facing_from_positions per light (the variant planned for the "
                 "mesh's size: sv::deform_plan_for)\n"
                 "  planes: derive planes once (that variant) + sv_calculate_facing per light "
                 "(%s)\n",
                 sv_best_facing_variant()->name);
    std::fprintf(out, "%-24s %9s %9s %9s %9s %9s %12s\n", "mesh", "triangles", "bfg 1", "planes 1",
                 "bfg 4", "planes 4", "disagree");
    for (const PlanesResult &r : results) {
        const std::string best = sv::deform_plan_for(r.mesh.triangles).planes->name;
        char dis[48];
        std::snprintf(dis, sizeof dis, "%lld/%lld", r.disagree, r.compared);
        std::fprintf(out, "%-24s %9d %9s %9s %9s %9s %12s\n", r.mesh.name.c_str(), r.mesh.triangles,
                     ticks_cell(find_variant_row(r.rows, "bfg_1", best), r.mesh.triangles).c_str(),
                     ticks_cell(find_variant_row(r.rows, "planes_1", ""), r.mesh.triangles).c_str(),
                     ticks_cell(find_variant_row(r.rows, "bfg_4", best), r.mesh.triangles).c_str(),
                     ticks_cell(find_variant_row(r.rows, "planes_4", ""), r.mesh.triangles).c_str(),
                     dis);
    }
    std::fprintf(out,
                 "  disagree: triangles whose BFG facing differs from the derived planes' "
                 "facing (C references), over %d lights\n",
                 kLightsPlanes);

    std::fprintf(out, "\nbfg facing by variant, ticks per triangle for 1 light | 4 lights\n");
    std::fprintf(out, "%-24s", "mesh");
    for (const std::string &v : variants) std::fprintf(out, " %17s", v.c_str());
    std::fprintf(out, "\n");
    for (const PlanesResult &r : results) {
        std::fprintf(out, "%-24s", r.mesh.name.c_str());
        for (const std::string &v : variants) {
            const std::string c =
                ticks_cell(find_variant_row(r.rows, "bfg_1", v), r.mesh.triangles) + " | " +
                ticks_cell(find_variant_row(r.rows, "bfg_4", v), r.mesh.triangles);
            std::fprintf(out, " %17s", c.c_str());
        }
        std::fprintf(out, "\n");
    }
}

std::string planes_json(const std::vector<PlanesResult> &results,
                        const std::vector<SkinPlanesResult> &skinned, const SeedTimer &t) {
    JsonWriter j;
    j.begin_object();
    seed_json_header(j, "shadowvol-planes/1", t);
    j.key("lights");
    j.value(kLightsPlanes);
    j.key("meshes");
    j.begin_array();
    for (const PlanesResult &r : results) {
        j.begin_object();
        j.key("mesh");
        j.value(r.mesh.name);
        j.key("triangles");
        j.value(r.mesh.triangles);
        j.key("vertices");
        j.value(r.mesh.vertices);
        j.key("bfg_vs_planes_facing_differ");
        j.value(r.disagree);
        j.key("facing_compared");
        j.value(r.compared);
        j.key("clusters");
        j.value(r.clusters);
        variant_rows_json(j, r.rows, std::max(1, r.mesh.triangles));
        j.end_object();
    }
    j.end_array();
    skin_planes_json(j, skinned);
    j.end_object();
    return j.str();
}

} // namespace

std::vector<Vec4> lights_around(const float *positions, int vertices, int count, uint64_t seed) {
    float lo[3] = {1e30f, 1e30f, 1e30f}, hi[3] = {-1e30f, -1e30f, -1e30f};
    for (int v = 0; v < vertices; v++) {
        for (int c = 0; c < 3; c++) {
            lo[c] = std::min(lo[c], positions[3 * v + c]);
            hi[c] = std::max(hi[c], positions[3 * v + c]);
        }
    }
    const double cx = 0.5 * (lo[0] + hi[0]), cy = 0.5 * (lo[1] + hi[1]), cz = 0.5 * (lo[2] + hi[2]);
    const double r = 1.5 * std::max({hi[0] - lo[0], hi[1] - lo[1], hi[2] - lo[2]}) + 1e-3;
    std::vector<Vec4> out;
    uint64_t s = seed * 0x9E3779B97F4A7C15ull + 1;
    for (int i = 0; i < count; i++) {
        s = s * 6364136223846793005ull + 1442695040888963407ull;
        const double jitter = (double)(s >> 40) / (double)(1ull << 24);
        const double a = 2 * M_PI * (i + jitter) / count;
        const double e = 0.2 + 0.9 * ((i * 7) % count) / count;
        out.push_back(Vec4{(float)(cx + r * std::cos(a) * std::cos(e)),
                           (float)(cy + r * std::sin(e)),
                           (float)(cz + r * std::sin(a) * std::cos(e)), 1.0f});
    }
    return out;
}

const VariantRow *find_variant_row(const std::vector<VariantRow> &rows, const std::string &what,
                                   const std::string &variant) {
    for (const VariantRow &row : rows) {
        if (row.what == what && (variant.empty() || row.variant == variant)) return &row;
    }
    return nullptr;
}

void variant_rows_json(JsonWriter &j, const std::vector<VariantRow> &rows, int per_triangle) {
    j.key("rows");
    j.begin_array();
    for (const VariantRow &row : rows) {
        j.begin_object(true);
        seed_json_row(j, row.what.c_str(), row.variant, row.t);
        j.key("ok");
        j.value(row.t.ok);
        if (!row.t.ok) {
            j.key("failure");
            j.value(row.t.failure);
        }
        if (per_triangle > 0) {
            j.key("ticks_per_triangle");
            j.value(row.t.median / per_triangle);
        }
        j.end_object();
    }
    j.end_array();
}

std::string ticks_cell(const VariantRow *row, double per) {
    if (!row) return "-";
    char buf[32];
    std::snprintf(buf, sizeof buf, "%.2f%s", row->t.median / std::max(1.0, per),
                  row->t.ok ? "" : " FAIL");
    return buf;
}

int print_failed_rows(FILE *out, const std::string &mesh, const std::vector<VariantRow> &rows) {
    int failed = 0;
    for (const VariantRow &row : rows) {
        if (!row.t.ok) {
            failed++;
            std::fprintf(out, "FAILED %s %s %s: %s\n", mesh.c_str(), row.what.c_str(),
                         row.variant.c_str(), row.t.failure.c_str());
        }
    }
    return failed;
}

int run_planes_bench(const SeedCommand &cmd) {
    return run_seed_frame(cmd, "planes", [&](FILE *out, std::string *doc) {
        const int cpu = pin_to_current_cpu();
        const SeedTimer timer = make_seed_timer(cmd.timer, cmd.quick);
        print_seed_header(out,
                          "shadowvol bench --planes: per-frame planes (derive once, facing "
                          "per light) against BFG's facing from positions",
                          timer, cpu);
        std::vector<PlanesResult> results;
        {
            PlanesResult r;
            r.mesh = from_workload(loaded_seed_mesh(SV_MODELS_DIR "/character_1344.glb"));
            results.push_back(std::move(r));
        }
        if (!cmd.quick) {
            for (const char *name :
                 {"Fox.glb", "CesiumMan.glb", "RobotExpressive.glb", "RiggedFigure.glb"}) {
                const std::string p = cmd.sharedModels + "/" + name;
                if (access(p.c_str(), R_OK) != 0) {
                    std::fprintf(out, "note      %s not found: left out\n", p.c_str());
                    continue;
                }
                PlanesResult r;
                r.mesh = from_workload(loaded_seed_mesh(p));
                results.push_back(std::move(r));
            }
        }
        const int gridN = cmd.quick ? 64 : 224;
        if (!cmd.maxTriangles || 2L * gridN * gridN <= cmd.maxTriangles) {
            PlanesResult r;
            r.mesh = grid_mesh(gridN);
            results.push_back(std::move(r));
        }
        FILE *progress = isatty(fileno(stderr)) ? stderr : nullptr;
        for (PlanesResult &r : results) measure(r, timer, cmd.seed, progress);
        print_tables(out, results);
        const std::vector<SkinPlanesResult> skinned = measure_skin_planes(timer, cmd.sharedModels,
                                                                          cmd.quick, out, progress);
        print_skin_planes(out, skinned);
        int failed = 0;
        for (const SkinPlanesResult &r : skinned) failed += print_failed_rows(out, r.name, r.rows);
        for (const PlanesResult &r : results) failed += print_failed_rows(out, r.mesh.name, r.rows);
        *doc = planes_json(results, skinned, timer);
        return failed;
    });
}

} // namespace svbench
