/*
 * `shadowvol bench --silhouette`: seed 003's finders (routine
 * find_silhouette: classic, hash8 .. hash64 in 16 and 32 bits, scalar and
 * SSE2, the connectivity table in four kernels) beside the paper's
 * SilEdges (siledge_<variant>: CreateSilTriangles of every kernel set,
 * which finds the silhouette and writes its quads in one pass), on meshes
 * of the seed's sizes, the light above the mesh and beside it, with the
 * seed's own table printed beside ours.
 *
 * Every finder reads the same facing bytes (computed once per light by
 * sv_calculate_facing_c_ref, outside the timed region: the seed's
 * "is the triangle lit" test is the paper's appendix A, timed by the cycle
 * table). The light moves: each placement is 16 lights jittered within a
 * quarter radius around its position, one per call in turn, so neither the
 * branch predictor nor the candidate list replays one input.
 *
 * Copyright (C) 2026 the shadowvol authors. LGPL-2.1-or-later.
 */
#include <algorithm>
#include <cmath>
#include <cstring>
#include <memory>
#include <string>
#include <vector>

#include <sys/stat.h>
#include <unistd.h>

#include "cache_info.h"
#include "json_writer.h"
#include "rng.h"
#include "seed_bench.h"
#include "shadowvol_silhouette.h"

namespace svbench {

namespace {

constexpr int kLightsPerPlacement = 16;
/* The seed's O(n^2) table is built for meshes up to this many edge uses
 * (3 per triangle); above it is left out and said so. */
constexpr long kQuadraticMaxUses = 400000;

/* Seed 003's table: its laptop, milliseconds. */
struct SeedFigures {
    const char *model;
    int faces;
    double classic, fast64, fast8, connectivity;
};
const SeedFigures kSeed003[2] = {{"Dino", 28766, 9000, 160, 49, 31},
                                 {"Dragon", 63744, 2100, 270, 44, 13}};

struct SilRow {
    std::string variant;
    std::string status = "ok"; /* ok, overflow, FAILED */
    std::string note;
    SeedTiming t;
    double temporary = 0, permanent = 0; /* bytes */
    double precomputeMs = -1;            /* -1: none */
};

struct Placement {
    std::string name; /* above, beside */
    Vec4 center{};
    std::vector<AlignedArray<uint8_t>> facing; /* numTriangles + 4 bytes each */
    std::vector<std::vector<sv::DirectedEdge>> exact, net;
    double litRatio = 0, silEdges = 0;
    std::vector<SilRow> rows;
};

struct SilMesh {
    SeedMesh m;
    sv::SilhouetteMesh sm;
    int needColumns = 0;
    double linearMs = 0, quadraticMs = -1;
    bool tablesAgree = true;
    std::vector<Placement> placements;
};

sv::SilhouetteMesh silhouette_mesh_of(const Workload &w) {
    sv::SilhouetteMesh m;
    m.indices = w.indices.data();
    m.num_triangles = w.numTriangles;
    m.num_vertices = w.numVerts;
    for (int i = 0; i < w.numSilEdges; i++) {
        const SilEdge &e = w.silEdges[(size_t)i];
        if (e.p2 == w.numTriangles) {
            m.dangling.push_back({(uint32_t)(e.v1 / 2), (uint32_t)(e.v2 / 2)});
        }
    }
    return m;
}

Placement make_placement(const Workload &w, const std::string &name, int axis, Rng &rng) {
    Placement p;
    p.name = name;
    const Bounds &b = w.bounds;
    const float r = std::max({b.extents.x, b.extents.y, b.extents.z});
    float c[3] = {b.center.x, b.center.y, b.center.z};
    c[axis] += 2.5f * r; /* above: +y (the characters stand up y); beside: +x */
    p.center = {c[0], c[1], c[2], 1};
    std::vector<sv::DirectedEdge> buf((size_t)w.numSilEdges + 1);
    for (int i = 0; i < kLightsPerPlacement; i++) {
        Vec4 l = p.center;
        l.x += 0.25f * r * (float)(2 * rng.unit() - 1);
        l.y += 0.25f * r * (float)(2 * rng.unit() - 1);
        l.z += 0.25f * r * (float)(2 * rng.unit() - 1);
        AlignedArray<uint8_t> f((size_t)w.numTriangles + 4);
        sv_calculate_facing_c_ref(w.planes.data(), w.numTriangles, &l, f.data());
        std::fill(f.data() + w.numTriangles, f.data() + w.numTriangles + 4, (uint8_t)1);
        for (int t = 0; t < w.numTriangles; t++) p.litRatio += f[(size_t)t];
        const size_t n = sv::silhouette_from_sil_edges(w.silEdges.data(), w.numSilEdges, f.data(),
                                                       buf.data());
        p.silEdges += (double)n;
        p.exact.push_back(sv::canonical_silhouette(buf.data(), n));
        p.net.push_back(sv::net_silhouette(buf.data(), n));
        p.facing.push_back(std::move(f));
    }
    p.litRatio /= (double)kLightsPerPlacement * std::max(1, w.numTriangles);
    p.silEdges /= kLightsPerPlacement;
    return p;
}

std::string compare(const std::vector<sv::DirectedEdge> &got,
                    const std::vector<sv::DirectedEdge> &want) {
    if (got == want) return "";
    return std::to_string(got.size()) + " edges, the SilEdges give " + std::to_string(want.size()) +
           " (or they differ)";
}

/* The first triangle of each quad CreateSilTriangles wrote, back to the
 * edge: (v1, v2 + 1, v2) when p1 was lit, (v1, v2, v2 + 1) when not. */
std::vector<sv::DirectedEdge> edges_of_quads(const int *si, int numIndices) {
    std::vector<sv::DirectedEdge> e;
    for (int k = 0; k < numIndices; k += 6) {
        const uint32_t v1 = (uint32_t)si[k] / 2;
        e.push_back(si[k + 1] & 1 ? sv::DirectedEdge{v1, (uint32_t)si[k + 2] / 2}
                                  : sv::DirectedEdge{(uint32_t)si[k + 1] / 2, v1});
    }
    std::sort(e.begin(), e.end());
    return e;
}

/* format_bytes, with 0 as "0 B" (it prints "unknown" there). */
std::string mem_cell(double bytes) { return bytes > 0 ? format_bytes(bytes) : "0 B"; }

double ms_since(double t0) { return (monotonic_seconds() - t0) * 1e3; }

void measure_mesh(SilMesh &sm, const SeedTimer &timer, Rng &rng, FILE *progress) {
    const Workload &w = sm.m.w;
    sm.sm = silhouette_mesh_of(w);
    sm.needColumns = sv::hash_columns_needed(sm.sm);

    /* Precomputation: ours (median of three), the seed's (once). */
    sv::ConnectivityTable conn;
    std::vector<double> lin;
    for (int k = 0; k < 3; k++) {
        const double t0 = monotonic_seconds();
        conn = sv::connectivity_linear(w.indices.data(), w.numTriangles, w.numVerts);
        lin.push_back(ms_since(t0));
    }
    std::sort(lin.begin(), lin.end());
    sm.linearMs = lin[1];
    if (3L * w.numTriangles <= kQuadraticMaxUses) {
        const double t0 = monotonic_seconds();
        const sv::ConnectivityTable q = sv::connectivity_quadratic(w.indices.data(),
                                                                   w.numTriangles);
        sm.quadraticMs = ms_since(t0);
        sm.tablesAgree = q.neighbour == conn.neighbour && q.dangling_uses == conn.dangling_uses;
    }

    sm.placements.push_back(make_placement(w, "above", 1, rng));
    sm.placements.push_back(make_placement(w, "beside", 0, rng));
    const size_t cap = sv::silhouette_capacity(sm.sm) + 1;
    std::vector<sv::DirectedEdge> out(cap);
    AlignedArray<int> quads((size_t)w.numSilEdges * 6 + 8);
    size_t n = 0;

    for (Placement &p : sm.placements) {
        auto facing = [&](int i) { return p.facing[(size_t)(i % kLightsPerPlacement)].data(); };
        auto want = [&](int i, bool net) -> const std::vector<sv::DirectedEdge> & {
            return (net ? p.net : p.exact)[(size_t)(i % kLightsPerPlacement)];
        };
        auto row = [&](SilRow r, const std::function<void(int)> &run,
                       const std::function<std::string(int)> &check) {
            if (progress)
                std::fprintf(progress, "\r%s %s %-28s", sm.m.name.c_str(), p.name.c_str(),
                             r.variant.c_str());
            r.t = time_seed_row(timer, run, check);
            if (!r.t.ok) {
                const bool overflow = r.t.failure.rfind("overflow", 0) == 0;
                r.status = overflow ? "overflow" : "FAILED";
                r.note = r.t.failure;
            }
            p.rows.push_back(r);
        };

        /* The paper: CreateSilTriangles of every kernel set this CPU runs. */
        int nv = 0;
        const sv_variant *vs = sv_variants(&nv);
        for (int k = 0; k < nv; k++) {
            const sv_variant &v = vs[k];
            if ((v.isa & sv_cpu_isa()) != v.isa) continue;
            SilRow r;
            r.variant = std::string("siledge_") + v.name;
            r.permanent = (double)w.numSilEdges * sizeof(SilEdge);
            int written = 0;
            row(
                r,
                [&](int i) {
                    written = v.create_sil_triangles(quads.data(), facing(i), w.silEdges.data(),
                                                     w.numSilEdges);
                },
                [&](int i) {
                    return compare(edges_of_quads(quads.data(), written), want(i, false));
                });
        }

        {
            sv::ClassicFinder classic(sm.sm);
            SilRow r;
            r.variant = "classic";
            r.permanent = (double)sm.sm.dangling.size() * sizeof(sv::DirectedEdge);
            row(
                r, [&](int i) { n = classic.find(facing(i), out.data()); },
                [&](int i) {
                    return compare(sv::canonical_silhouette(out.data(), n), want(i, true));
                });
            p.rows.back().temporary = (double)classic.peak_bytes();
        }

        for (bool simd : {false, true}) {
            for (int bits : {16, 32}) {
                for (int cols : {8, 16, 32, 64}) {
                    SilRow r;
                    r.variant = "hash" + std::to_string(cols) + "_u" + std::to_string(bits) +
                                (simd ? "_sse2" : "");
                    if (bits == 16 && w.numVerts > 65535) {
                        r.status = "n/a";
                        r.note = "more than 65535 vertices";
                        p.rows.push_back(r);
                        continue;
                    }
                    std::unique_ptr<sv::HashFinderBase> h = sv::make_hash_finder(sm.sm, bits, cols,
                                                                                 simd);
                    r.temporary = (double)h->temporary_bytes();
                    r.permanent = (double)sm.sm.dangling.size() * sizeof(sv::DirectedEdge);
                    sv::HashStatus st = sv::HashStatus::ok;
                    row(
                        r, [&](int i) { st = h->find(facing(i), out.data(), &n); },
                        [&](int i) -> std::string {
                            if (st == sv::HashStatus::overflow) {
                                /* legitimate only for a table too narrow */
                                if (cols >= sm.needColumns)
                                    return "FAILED: overflow of a wide enough table";
                                return "overflow at vertex " +
                                       std::to_string(h->overflow_vertex()) +
                                       " (this mesh needs up to " + std::to_string(sm.needColumns) +
                                       " columns)";
                            }
                            return compare(sv::canonical_silhouette(out.data(), n), want(i, true));
                        });
                }
            }
        }

        for (const sv::ConnectivityVariant &v : sv::connectivity_variants()) {
            if ((v.isa & sv_cpu_isa()) != v.isa) continue;
            SilRow r;
            r.variant = v.name;
            r.permanent = (double)conn.permanent_bytes();
            r.precomputeMs = sm.linearMs;
            row(
                r,
                [&](int i) {
                    n = v.fn(conn, w.indices.data(), w.numTriangles, facing(i), out.data());
                },
                [&](int i) {
                    return compare(sv::canonical_silhouette(out.data(), n), want(i, false));
                });
        }
    }
    if (progress) std::fprintf(progress, "\r%60s\r", "");
}

double us(const SeedTimer &t, double ticks) { return ticks / t.tscHz * 1e6; }

void print_mesh(FILE *out, const SilMesh &sm, const SeedTimer &t) {
    const Workload &w = sm.m.w;
    std::fprintf(out, "\n%s: %d triangles, %d vertices, %d SilEdges (%d dangling); %s\n",
                 sm.m.name.c_str(), w.numTriangles, w.numVerts, w.numSilEdges, w.numDangling,
                 sm.m.source.c_str());
    std::fprintf(out, "  connectivity table: %s permanent; precomputation ours O(n) %.2f ms, ",
                 mem_cell((double)(3.0 * w.numTriangles + w.numDangling) * sizeof(int)).c_str(),
                 sm.linearMs);
    if (sm.quadraticMs >= 0) {
        std::fprintf(out, "the seed's O(n^2) %.1f ms (%s)\n", sm.quadraticMs,
                     sm.tablesAgree ? "the same table" : "FAILED: a different table");
    } else {
        std::fprintf(out, "the seed's O(n^2) not run (more than %ld edge uses)\n",
                     kQuadraticMaxUses);
    }
    std::fprintf(out, "  hash columns this mesh may need at worst: %d\n", sm.needColumns);
    for (const Placement &p : sm.placements) {
        std::fprintf(out,
                     "  light %s (16 lights around %.3g, %.3g, %.3g): %.1f%% of triangles lit, "
                     "%.0f silhouette edges on average\n",
                     p.name.c_str(), p.center.x, p.center.y, p.center.z, 100 * p.litRatio,
                     p.silEdges);
        std::fprintf(out, "    %-26s %12s %12s %10s %9s %10s %10s  %s\n", "find_silhouette",
                     "median", "min", "median", "ticks/", "temporary", "permanent", "check");
        std::fprintf(out, "    %-26s %12s %12s %10s %9s %10s %10s\n", "variant", "ticks", "ticks",
                     "us", "triangle", "memory", "memory");
        for (const SilRow &r : p.rows) {
            if (r.status == "ok") {
                std::fprintf(out, "    %-26s %12.0f %12.0f %10.1f %9.2f %10s %10s  ok (%d calls)\n",
                             r.variant.c_str(), r.t.median, r.t.min, us(t, r.t.median),
                             r.t.median / std::max(1, w.numTriangles),
                             mem_cell(r.temporary).c_str(), mem_cell(r.permanent).c_str(),
                             r.t.calls);
            } else {
                std::fprintf(out, "    %-26s %12s %12s %10s %9s %10s %10s  %s: %s\n",
                             r.variant.c_str(), "-", "-", "-", "-", mem_cell(r.temporary).c_str(),
                             mem_cell(r.permanent).c_str(), r.status.c_str(), r.note.c_str());
            }
        }
    }
}

const SilRow *find_row(const Placement &p, const std::string &v) {
    for (const SilRow &r : p.rows) {
        if (r.variant == v && r.status == "ok") return &r;
    }
    return nullptr;
}

std::string ms_cell(const SeedTimer &t, const SilRow *r) {
    if (!r) return "-";
    char buf[32];
    std::snprintf(buf, sizeof buf, "%.3f", us(t, r->t.median) / 1000);
    return buf;
}

/* The seed's table, and ours for the meshes closest to its two models. */
void print_seed_table(FILE *out, const std::vector<SilMesh> &meshes, const SeedTimer &t) {
    std::fprintf(out,
                 "\nseed 003's table (its laptop, ms per silhouette) beside ours (this CPU, "
                 "median ms per silhouette; hash = the 16-bit scalar table as the seed used)\n");
    std::fprintf(out, "  %-40s %10s %10s %10s %13s %12s\n", "model, light", "classic", "hash64",
                 "hash8", "connectivity", "best of ours");
    for (const SeedFigures &s : kSeed003) {
        std::fprintf(
            out, "  %-40s %10.0f %10.0f %10.0f %13.0f\n",
            (std::string(s.model) + " (" + std::to_string(s.faces) + " faces), seed").c_str(),
            s.classic, s.fast64, s.fast8, s.connectivity);
        /* Ours: the mesh nearest in size to the seed's. */
        const SilMesh *best = nullptr;
        for (const SilMesh &m : meshes) {
            if (!best || std::fabs(m.m.w.numTriangles - s.faces) <
                             std::fabs(best->m.w.numTriangles - s.faces)) {
                best = &m;
            }
        }
        if (!best) continue;
        for (const Placement &p : best->placements) {
            const SilRow *fastest = nullptr;
            for (const SilRow &r : p.rows) {
                if (r.status == "ok" && (!fastest || r.t.median < fastest->t.median)) fastest = &r;
            }
            std::fprintf(
                out, "  %-40s %10s %10s %10s %13s %12s\n",
                (best->m.name.substr(0, best->m.name.find(' ')) + ", light " + p.name).c_str(),
                ms_cell(t, find_row(p, "classic")).c_str(),
                ms_cell(t, find_row(p, "hash64_u16")).c_str(),
                ms_cell(t, find_row(p, "hash8_u16")).c_str(),
                ms_cell(t, find_row(p, "connectivity")).c_str(),
                fastest ? (ms_cell(t, fastest) + " " + fastest->variant).c_str() : "-");
        }
    }
}

std::string silhouette_json(const std::vector<SilMesh> &meshes, const SeedTimer &t) {
    JsonWriter j;
    j.begin_object();
    seed_json_header(j, "shadowvol-silhouette/1", t);
    j.key("routine");
    j.value("find_silhouette");
    j.key("lights_per_placement");
    j.value(kLightsPerPlacement);
    j.key("seed_003");
    j.begin_array();
    for (const SeedFigures &s : kSeed003) {
        j.begin_object(true);
        j.key("model");
        j.value(s.model);
        j.key("faces");
        j.value(s.faces);
        j.key("classic_ms");
        j.value(s.classic);
        j.key("hash64_ms");
        j.value(s.fast64);
        j.key("hash8_ms");
        j.value(s.fast8);
        j.key("connectivity_ms");
        j.value(s.connectivity);
        j.end_object();
    }
    j.end_array();
    j.key("meshes");
    j.begin_array();
    for (const SilMesh &m : meshes) {
        const Workload &w = m.m.w;
        j.begin_object();
        j.key("name");
        j.value(m.m.name);
        j.key("source");
        j.value(m.m.source);
        j.key("triangles");
        j.value(w.numTriangles);
        j.key("vertices");
        j.value(w.numVerts);
        j.key("sil_edges");
        j.value(w.numSilEdges);
        j.key("dangling");
        j.value(w.numDangling);
        j.key("hash_columns_needed");
        j.value(m.needColumns);
        j.key("connectivity_linear_ms");
        j.value(m.linearMs);
        j.key("connectivity_quadratic_ms");
        if (m.quadraticMs >= 0)
            j.value(m.quadraticMs);
        else
            j.null();
        j.key("tables_agree");
        j.value(m.tablesAgree);
        j.key("placements");
        j.begin_array();
        for (const Placement &p : m.placements) {
            j.begin_object();
            j.key("light");
            j.value(p.name);
            j.key("lit_ratio");
            j.value(p.litRatio);
            j.key("silhouette_edges");
            j.value(p.silEdges);
            j.key("rows");
            j.begin_array();
            for (const SilRow &r : p.rows) {
                j.begin_object(true);
                seed_json_row(j, "find_silhouette", r.variant, r.t);
                j.key("status");
                j.value(r.status);
                j.key("ok");
                j.value(r.status != "FAILED");
                if (!r.note.empty()) {
                    j.key("note");
                    j.value(r.note);
                }
                j.key("median_us");
                j.value(us(t, r.t.median));
                j.key("temporary_bytes");
                j.value(r.temporary);
                j.key("permanent_bytes");
                j.value(r.permanent);
                j.key("precompute_ms");
                if (r.precomputeMs >= 0)
                    j.value(r.precomputeMs);
                else
                    j.null();
                j.end_object();
            }
            j.end_array();
            j.end_object();
        }
        j.end_array();
        j.end_object();
    }
    j.end_array();
    j.end_object();
    return j.str();
}

bool file_exists(const std::string &p) {
    struct stat st;
    return stat(p.c_str(), &st) == 0;
}

} // namespace

int run_silhouette_bench(const SeedCommand &cmd) {
    return run_seed_frame(cmd, "silhouette", [&](FILE *out, std::string *doc) {
        const int cpu = pin_to_current_cpu();
        const SeedTimer timer = make_seed_timer(cmd.timer, cmd.quick);
        print_seed_header(out,
                          "shadowvol bench --silhouette: seed 003's silhouette finders beside "
                          "the paper's SilEdges (routine find_silhouette)",
                          timer, cpu);

        /* The meshes: the paper's character, the generator's nearest to
         * the seed's Dino (28,766 faces: n = 5, 33,600) and Dragon (63,744:
         * n = 7, 65,856), spot (23k) and koala (100k). */
        struct Spec {
            int n;
            const char *note;
            const char *file;
        };
        const Spec specs[] = {{1, "the paper's size", nullptr},
                              {5, "Dino size: the seed's 28,766 faces", nullptr},
                              {7, "Dragon size: the seed's 63,744 faces", nullptr},
                              {0, nullptr, "spot.glb"},
                              {0, nullptr, "koala.glb"}};
        std::vector<SilMesh> meshes;
        Rng rng{cmd.seed};
        FILE *progress = isatty(fileno(stderr)) ? stderr : nullptr;
        for (const Spec &s : specs) {
            if (cmd.quick && s.n > 5) continue;
            const long tris = s.n ? 1344L * s.n * s.n : 0;
            if (cmd.maxTriangles && tris > cmd.maxTriangles) continue;
            SilMesh m;
            if (s.n) {
                m.m = generated_seed_mesh(s.n, s.note);
            } else {
                const std::string path = cmd.sharedModels + "/" + s.file;
                if (cmd.quick) continue;
                if (!file_exists(path)) {
                    std::fprintf(out, "note      %s is missing: not measured\n", path.c_str());
                    continue;
                }
                m.m = loaded_seed_mesh(path);
                if (cmd.maxTriangles && m.m.w.numTriangles > cmd.maxTriangles) continue;
            }
            measure_mesh(m, timer, rng, progress);
            print_mesh(out, m, timer);
            meshes.push_back(std::move(m));
        }
        print_seed_table(out, meshes, timer);

        int failed = 0;
        for (const SilMesh &m : meshes) {
            failed += !m.tablesAgree;
            for (const Placement &p : m.placements) {
                for (const SilRow &r : p.rows) failed += r.status == "FAILED";
            }
        }
        *doc = silhouette_json(meshes, timer);
        return failed;
    });
}

} // namespace svbench
