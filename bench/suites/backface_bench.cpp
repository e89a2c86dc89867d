/*
 * `shadowvol bench --backface`: seed 001's view back-face culling methods
 * (routine backface_cull: noncompact, compact, compact_sse2,
 * compact_sse2_prefetch, compact_avx2, compact_avx512) across mesh sizes
 * from the L1 data cache to beyond the L3, to check the seed's claim: the
 * compact layout halves the memory traffic (16 bytes a triangle against
 * 32); does it pay, and from which size on?
 *
 * Meshes: the generated character subdivided n x n (1344 to 108,864
 * triangles, under the layouts' 65536 vertices), then 4, 16 and 64
 * translated copies of the largest (435k to 7M triangles) whose vertex
 * numbers are the original's: instances drawn from one vertex pool, the
 * only way to grow past 65536 vertices with 16-bit indices. The camera
 * moves: 16 views at 2 to 4 radii in turn, one per call.
 *
 * Every call is checked outside the timed region: its count and vertex
 * bits equal those that follow from its method's front bytes (noncompact:
 * its own, which the tests prove equal to the C reference; the compact
 * ones: the scalar compact routine's). Per size the compact decisions are also compared
 * with the float non-compact ones, and each disagreement is judged by the
 * exact predicate (is it within fixed16's error bound, where the compact
 * method may be wrong, or is the float one wrong?).
 *
 * Copyright (C) 2026 the shadowvol authors. LGPL-2.1-or-later.
 */
#include <algorithm>
#include <cmath>
#include <cstring>
#include <string>
#include <vector>

#include <unistd.h>

#include "cache_info.h"
#include "json_writer.h"
#include "model_gen.h"
#include "rng.h"
#include "scaling_report.h"
#include "seed_bench.h"
#include "shadowvol_accuracy.h"
#include "shadowvol_backface.h"

namespace svbench {

namespace {

constexpr int kViews = 16;

struct Method {
    const char *name;
    unsigned isa;
    bool compact; /* 16 bytes a triangle, fixed16 arithmetic */
    double bytesPerTriangle;
};

struct CullRow {
    std::string variant;
    bool bits = true; /* vertex bits written (the seed's job), or the count alone */
    SeedTiming t;
};

struct CullSize {
    std::string name;
    int triangles = 0, vertices = 0, copies = 1;
    double disagree = 0;       /* compact != noncompact, over all views */
    double disagreeInBand = 0; /* ... with |D| <= fixed16's bound: compact may be wrong */
    double floatWrong = 0;     /* ... outside it: compact exact, the float method wrong */
    double frontRatio = 0;
    std::vector<CullRow> rows;
};

/* The layouts of a surface, COPIES times, each copy translated a little
 * (its own planes' points and tn; the same vertex numbers). */
struct Layouts {
    sv::AlignedVector<sv_cull_triangle> t32;
    sv::AlignedVector<sv_cull_triangle16> t16;
    sv::AlignedVector<sv_cull_block4> blocks;
    std::vector<int> indices;                  /* for the checks: 3 per triangle */
    std::vector<const float *> corners;        /* 3 per triangle, for the exact predicate */
    std::vector<std::vector<float>> positions; /* per copy */
};

Layouts make_layouts(const sv::PreparedSurface &base, int copies, float radius) {
    Layouts L;
    const size_t nt = (size_t)base.num_triangles();
    L.t32.reserve(nt * copies);
    L.t16.reserve(nt * copies);
    L.positions.resize((size_t)copies);
    sv::PreparedSurface s = base;
    for (int k = 0; k < copies; k++) {
        /* 1% of a radius per copy along a diagonal: new data, similar views */
        const float off = 0.01f * radius * (float)k;
        for (size_t i = 0; i < base.positions.size(); i++) s.positions[i] = base.positions[i] + off;
        L.positions[(size_t)k] = s.positions;
        const auto a = sv::cull_triangles(s);
        const auto b = sv::cull_triangles16(s);
        L.t32.insert(L.t32.end(), a.begin(), a.end());
        L.t16.insert(L.t16.end(), b.begin(), b.end());
        L.indices.insert(L.indices.end(), base.indices.begin(), base.indices.end());
    }
    /* Blocks of four over the concatenation (a copy may end mid-block). */
    L.blocks = sv::cull_blocks(L.t16.data(), L.t16.size());
    for (int k = 0; k < copies; k++) {
        const float *p = L.positions[(size_t)k].data();
        for (size_t u = 0; u < 3 * nt; u++) L.corners.push_back(p + 3 * (size_t)base.indices[u]);
    }
    return L;
}

struct Expected {
    int count = 0;
    std::vector<uint32_t> bits;
};

/* Count and bits as the front bytes and the indices make them. */
Expected expected_from(const std::vector<uint8_t> &front, const std::vector<int> &indices, int nv) {
    Expected e;
    e.bits.assign(((size_t)nv + 31) / 32, 0);
    for (size_t t = 0; t < front.size(); t++) {
        if (!front[t]) continue;
        e.count++;
        for (int k = 0; k < 3; k++) {
            const int v = indices[3 * t + (size_t)k];
            e.bits[(size_t)v >> 5] |= 1u << (v & 31);
        }
    }
    return e;
}

std::string compare(int count, const std::vector<uint32_t> &bits, const Expected &e) {
    if (count != e.count) {
        return "count " + std::to_string(count) + ", expected " + std::to_string(e.count);
    }
    if (bits != e.bits) return "vertex bits differ";
    return "";
}

void measure_size(CullSize &cs, const Layouts &L, int nv, const Bounds &b,
                  const std::vector<Method> &methods, const SeedTimer &timer, Rng &rng,
                  FILE *progress) {
    const int nt = (int)L.t16.size();
    cs.triangles = nt;
    cs.vertices = nv;
    const float r = std::max({b.extents.x, b.extents.y, b.extents.z});
    std::vector<Vec4> views;
    for (int i = 0; i < kViews; i++) {
        double d[3], len = 0;
        for (double &c : d) {
            c = 2 * rng.unit() - 1;
            len += c * c;
        }
        len = std::sqrt(len) + 1e-12;
        const double dist = r * (2 + 2 * rng.unit());
        views.push_back(Vec4{b.center.x + (float)(dist * d[0] / len),
                             b.center.y + (float)(dist * d[1] / len),
                             b.center.z + (float)(dist * d[2] / len), 1});
    }
    /* What each call must return: per view, from the definitions. */
    std::vector<Expected> wantNc, wantC;
    std::vector<uint8_t> fnc((size_t)nt), fc((size_t)nt);
    for (const Vec4 &v : views) {
        sv_backface_noncompact(L.t32.data(), nt, nv, &v, nullptr, fnc.data());
        sv_backface_compact(L.t16.data(), nt, nv, &v, nullptr, fc.data());
        wantNc.push_back(expected_from(fnc, L.indices, nv));
        wantC.push_back(expected_from(fc, L.indices, nv));
        cs.frontRatio += (double)wantC.back().count / std::max(1, nt);
        for (int t = 0; t < nt; t++) {
            if (fnc[(size_t)t] == fc[(size_t)t]) continue;
            cs.disagree++;
            const float *const *c = &L.corners[3 * (size_t)t];
            const sv::TriangleErrorModel em = sv::triangle_error_model(c[0], c[1], c[2]);
            const double D = sv::exact_signed_distance(c[0], c[1], c[2], v);
            if (std::fabs(D) <= sv::facing_error_bound(sv::FacingArithmetic::fixed16, em, v)) {
                cs.disagreeInBand++;
            } else {
                cs.floatWrong++;
            }
        }
    }
    cs.frontRatio /= kViews;

    std::vector<uint32_t> bitArray(((size_t)nv + 31) / 32 + 1);
    int count = 0;
    for (const bool withBits : {true, false}) {
        /* withBits false: the decision and the count alone (vertexBits NULL),
         * to see the layouts' arithmetic and memory traffic without the
         * vertex bits' scattered stores. */
        uint32_t *bitsOut = withBits ? bitArray.data() : nullptr;
        for (const Method &m : methods) {
            if (progress) std::fprintf(progress, "\r%s %-24s", cs.name.c_str(), m.name);
            sv_backface_blocks_fn blockFn = nullptr;
            for (const sv::BackfaceBlockVariant &v : sv::backface_block_variants()) {
                if (std::strcmp(v.name, m.name) == 0) blockFn = v.fn;
            }
            std::function<void(int)> run;
            if (std::strcmp(m.name, "noncompact") == 0) {
                run = [&](int i) {
                    count = sv_backface_noncompact(L.t32.data(), nt, nv,
                                                   &views[(size_t)(i % kViews)], bitsOut, nullptr);
                };
            } else if (std::strcmp(m.name, "compact") == 0) {
                run = [&](int i) {
                    count = sv_backface_compact(L.t16.data(), nt, nv, &views[(size_t)(i % kViews)],
                                                bitsOut, nullptr);
                };
            } else {
                run = [&, blockFn](int i) {
                    count = blockFn(L.blocks.data(), nt, nv, &views[(size_t)(i % kViews)], bitsOut,
                                    nullptr);
                };
            }
            CullRow row;
            row.variant = m.name;
            row.bits = withBits;
            row.t = time_seed_row(timer, run, [&](int i) {
                const Expected &e = (m.compact ? wantC : wantNc)[(size_t)(i % kViews)];
                if (!withBits) {
                    return count == e.count ? std::string()
                                            : "count " + std::to_string(count) + ", expected " +
                                                  std::to_string(e.count);
                }
                const std::vector<uint32_t> got(bitArray.begin(), bitArray.end() - 1);
                return compare(count, got, e);
            });
            cs.rows.push_back(row);
        }
    }
    if (progress) std::fprintf(progress, "\r%60s\r", "");
}

std::vector<Method> methods_run(std::vector<std::string> &skipped) {
    std::vector<Method> all = {{"noncompact", SV_ISA_NONE, false, 32},
                               {"compact", SV_ISA_NONE, true, 16}};
    for (const sv::BackfaceBlockVariant &v : sv::backface_block_variants()) {
        all.push_back({v.name, v.isa, true, 16});
    }
    std::vector<Method> run;
    for (const Method &m : all) {
        if ((m.isa & sv_cpu_isa()) == m.isa) {
            run.push_back(m);
        } else {
            skipped.push_back(m.name);
        }
    }
    return run;
}

const CullRow *row_of(const CullSize &s, const char *name, bool bits) {
    for (const CullRow &r : s.rows) {
        if (r.variant == name && r.bits == bits && r.t.ok) return &r;
    }
    return nullptr;
}

void print_table(FILE *out, const std::vector<CullSize> &sizes, const std::vector<Method> &methods,
                 bool bits) {
    const CacheSizes &c = cache_sizes();
    std::fprintf(out,
                 "\nbackface_cull %s, median ticks per triangle (moving camera); working set = "
                 "the layout + the vertex bits; cache = the smallest holding the compact one's\n",
                 bits ? "with the vertex bits (the seed's job)" : "count only (vertexBits NULL)");
    std::fprintf(out, "%-30s %10s %9s %9s %6s", "mesh", "triangles", "32 B/tri", "16 B/tri",
                 "cache");
    for (const Method &m : methods) std::fprintf(out, " %13s", m.name);
    std::fprintf(out, " %12s\n", "compact/nc");
    for (const CullSize &s : sizes) {
        const double bitBytes = ((double)s.vertices + 31) / 32 * 4;
        const double ws32 = 32.0 * s.triangles + bitBytes, ws16 = 16.0 * s.triangles + bitBytes;
        std::fprintf(out, "%-30s %10d %9s %9s %6s", s.name.c_str(), s.triangles,
                     format_bytes(ws32).c_str(), format_bytes(ws16).c_str(),
                     smallest_cache_holding(c, ws16));
        for (const CullRow &r : s.rows) {
            if (r.bits != bits) continue;
            if (r.t.ok) {
                std::fprintf(out, " %13.3f", r.t.median / std::max(1, s.triangles));
            } else {
                std::fprintf(out, " %13s", "FAILED");
            }
        }
        const CullRow *nc = row_of(s, "noncompact", bits);
        const CullRow *best = nullptr;
        for (const CullRow &r : s.rows) {
            if (r.t.ok && r.bits == bits && r.variant != "noncompact" &&
                (!best || r.t.median < best->t.median)) {
                best = &r;
            }
        }
        if (nc && best) {
            std::fprintf(out, " %12.2f", nc->t.median / std::max(1.0, best->t.median));
        }
        std::fprintf(out, "\n");
    }
    std::fprintf(
        out, "compact/nc: how many times faster the best compact method is than the non-compact "
             "one\n");
}

void print_accuracy(FILE *out, const std::vector<CullSize> &sizes) {
    std::fprintf(out,
                 "\naccuracy: compact (16-bit normal) against non-compact (float) decisions, over "
                 "%d views per mesh\n",
                 kViews);
    std::fprintf(out, "%-30s %12s %14s %14s %10s\n", "mesh", "differ", "within bound",
                 "float wrong", "front");
    for (const CullSize &s : sizes) {
        std::fprintf(out, "%-30s %12.0f %14.0f %14.0f %9.1f%%\n", s.name.c_str(), s.disagree,
                     s.disagreeInBand, s.floatWrong, 100 * s.frontRatio);
    }
    std::fprintf(out,
                 "differ: triangle x view decisions that differ (of triangles x %d); within bound: "
                 "|D| <= fixed16's bound, where the compact method may err; float wrong: outside "
                 "it, so the compact decision is the exact one and the float method erred\n",
                 kViews);
}

std::string backface_json(const std::vector<CullSize> &sizes, const SeedTimer &t) {
    JsonWriter j;
    j.begin_object();
    seed_json_header(j, "shadowvol-backface/1", t);
    j.key("routine");
    j.value("backface_cull");
    j.key("views");
    j.value(kViews);
    j.key("sizes");
    j.begin_array();
    for (const CullSize &s : sizes) {
        j.begin_object();
        j.key("mesh");
        j.value(s.name);
        j.key("triangles");
        j.value(s.triangles);
        j.key("vertices");
        j.value(s.vertices);
        j.key("copies");
        j.value(s.copies);
        j.key("front_ratio");
        j.value(s.frontRatio);
        j.key("compact_vs_noncompact_differ");
        j.value(s.disagree);
        j.key("differ_within_fixed16_bound");
        j.value(s.disagreeInBand);
        j.key("differ_float_wrong");
        j.value(s.floatWrong);
        j.key("rows");
        j.begin_array();
        for (const CullRow &r : s.rows) {
            j.begin_object(true);
            seed_json_row(j, "backface_cull", r.variant, r.t);
            j.key("vertex_bits");
            j.value(r.bits);
            j.key("ok");
            j.value(r.t.ok);
            if (!r.t.ok) {
                j.key("failure");
                j.value(r.t.failure);
            }
            j.key("ticks_per_triangle");
            j.value(r.t.median / std::max(1, s.triangles));
            j.end_object();
        }
        j.end_array();
        j.end_object();
    }
    j.end_array();
    j.end_object();
    return j.str();
}

} // namespace

int run_backface_bench(const SeedCommand &cmd) {
    return run_seed_frame(cmd, "back-face", [&](FILE *out, std::string *doc) {
        const int cpu = pin_to_current_cpu();
        const SeedTimer timer = make_seed_timer(cmd.timer, cmd.quick);
        print_seed_header(out,
                          "shadowvol bench --backface: seed 001's view back-face culling "
                          "(routine backface_cull) from L1 to beyond L3",
                          timer, cpu);
        std::fprintf(out, "caches    %s\n", cache_summary(cache_sizes()).c_str());
        std::vector<std::string> skipped;
        const std::vector<Method> methods = methods_run(skipped);
        for (const std::string &s : skipped) {
            std::fprintf(out,
                         "skipped   %s: this CPU (or the ISA limit) lacks its instruction set\n",
                         s.c_str());
        }

        struct Spec {
            int n, copies;
        };
        std::vector<Spec> specs = {{1, 1}, {2, 1}, {3, 1},  {5, 1},
                                   {9, 1}, {9, 4}, {9, 16}, {9, 64}};
        if (cmd.quick) specs = {{1, 1}, {3, 1}, {9, 1}};
        std::vector<CullSize> sizes;
        Rng rng{cmd.seed};
        FILE *progress = isatty(fileno(stderr)) ? stderr : nullptr;
        int lastN = 0;
        sv::PreparedSurface base;
        Bounds bounds{};
        for (const Spec &s : specs) {
            const long tris = 1344L * s.n * s.n * s.copies;
            if (cmd.maxTriangles && tris > cmd.maxTriangles) continue;
            if (s.n != lastN) {
                const svgen::TriMesh mesh = svgen::build_character(s.n);
                base = sv::prepare_surface(mesh.positions.data(), mesh.num_vertices(),
                                           mesh.indices.data(), mesh.indices.size());
                bounds = sv::surface_bounds(base);
                lastN = s.n;
            }
            const float r = std::max({bounds.extents.x, bounds.extents.y, bounds.extents.z});
            const Layouts L = make_layouts(base, s.copies, r);
            CullSize cs;
            cs.name = "character_" + std::to_string(1344 * s.n * s.n) +
                      (s.copies > 1 ? " x" + std::to_string(s.copies) : "");
            cs.copies = s.copies;
            measure_size(cs, L, base.num_vertices(), bounds, methods, timer, rng, progress);
            sizes.push_back(std::move(cs));
        }
        print_table(out, sizes, methods, true);
        print_table(out, sizes, methods, false);
        print_accuracy(out, sizes);

        int failed = 0;
        for (const CullSize &s : sizes) {
            for (const CullRow &r : s.rows) {
                if (!r.t.ok) {
                    failed++;
                    std::fprintf(out, "FAILED %s %s%s: %s\n", s.name.c_str(), r.variant.c_str(),
                                 r.bits ? "" : " (count only)", r.t.failure.c_str());
                }
            }
        }
        *doc = backface_json(sizes, timer);
        return failed;
    });
}

} // namespace svbench
