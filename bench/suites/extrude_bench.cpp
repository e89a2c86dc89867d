/*
 * `shadowvol bench --extrude`: seed 002 (Brennan, ShaderX 2002), shadow
 * volumes extruded by a vertex program, its program emulated on the CPU
 * (include/shadowvol_extrude.h), against the paper's pipeline
 * (sv_shadow_volume_for_light: facing and count fused, silhouette quads and
 * caps, the planner's kernels) on the same meshes and lights.
 *
 * Meshes: the bundled character (closed), and when present the real
 * characters of the shared folder (Fox, CesiumMan, RobotExpressive,
 * RiggedFigure) and the open asset pack character (open/Zombie_Basic.glb);
 * all surfaces merged, the caster rule auto applied to both methods (open
 * shells two-sided, docs/CASTERS.md), so both build the exact volume.
 * Lights: 16 point lights around the mesh (planes_bench.h), the next in
 * each call; a range 1.5 times the farthest light-vertex distance for the
 * seed's finite rows.
 *
 * Rows (ticks per call, median; per vertex or per triangle in the table):
 *   extrude VARIANT range|inf   every variant; every call's output
 *                               compared bit for bit with the C reference's
 *   paper                       sv_shadow_volume_for_light; every call's
 *                               index list compared with the C references'
 * Counts: the seed's vertices and indices (static: 3F vertices, 3F + 6
 * quads indices) against the paper's shadow vertices (2V) and its index
 * list per light (mean); the quads that open (a silhouette: their two
 * faces extrude differently) against the paper's silhouette quads; and the
 * faces the seed splits (its three vertices disagree on facing: the
 * per-vertex dp3 rounds differently at each corner of a face nearly
 * edge-on to the light), summed over the lights.
 *
 * The skinned characters (the demo scene's, and the shared folder's
 * skinned ones; --quick: the demo scene's alone), posed at the middle of
 * their first animation, their skinned surfaces: what each normal source
 * of the seed's Figure 4 (src/extrude/skinned_normals.h) costs a frame for
 * one light (the next of 16), warm, beside the seed's program alone on the
 * same stream:
 *   skinned_program VARIANT      the program alone (best variant; c_ref)
 *   skinned_straightforward      the skinned positions into the stream,
 *   skinned_face_weights         the normals that way, then the program
 *   skinned_recomputed           (best variant)
 *   skinned_neighbours           the neighbour stream from the skinned
 *                                positions, then its program (C)
 * every call's output compared bit for bit with the reference's (c_ref on
 * the same stream; the neighbours' program once, before the timing, which
 * must split no face); and the bytes each source's vertex carries.
 *
 * Copyright (C) 2026 the shadowvol authors. LGPL-2.1-or-later.
 */
#include <algorithm>
#include <cmath>
#include <cstring>
#include <memory>
#include <string>
#include <vector>

#include <unistd.h>

#include "extrude_bench.h"
#include "json_writer.h"
#include "planes_bench.h"
#include "shadowvol_casters.h"
#include "shadowvol_extrude.h"
#include "shadowvol_plan.h"
#include "skinned_normals.h"

#ifndef SV_MODELS_DIR
#define SV_MODELS_DIR "models"
#endif
#ifndef SV_DEMO_SCENE
#define SV_DEMO_SCENE "models/demo_scene.glb"
#endif

namespace svbench {

namespace {

constexpr int kLightsExtrude = 16;

/* Rows: what is "extrude_range", "extrude_inf" or "paper". */
using ExtrudeRow = VariantRow;

struct ExtrudeResult {
    std::string name;
    sv::PreparedSurface caster; /* under the caster rule auto */
    sv::ShadowMesh mesh;
    std::vector<ExtrudeRow> rows;
    double paperIndicesMean = 0, paperQuadsMean = 0, openQuadsMean = 0;
    long long splitFaces = 0; /* over the lights */
    /* avx2_rsqrt against c_ref over its checked calls: the largest distance
     * of a vertex both extrude, per unit of range; facing that differs. */
    double rsqrtMaxError = 0;
    long long rsqrtFlips = 0, rsqrtCompared = 0;
};

/* The workload's welded mesh prepared again (no change: it is welded and
 * has no degenerate triangle), then the caster rule auto. */
sv::PreparedSurface caster_of(const SeedMesh &m) {
    const Workload &w = m.w;
    std::vector<float> pos(3 * (size_t)w.numVerts);
    for (int v = 0; v < w.numVerts; v++) {
        pos[3 * (size_t)v] = w.positions[v].x;
        pos[3 * (size_t)v + 1] = w.positions[v].y;
        pos[3 * (size_t)v + 2] = w.positions[v].z;
    }
    std::vector<uint32_t> idx(w.indices.data(), w.indices.data() + w.numIndices);
    sv::PreparedSurface s = sv::prepare_surface(pos.data(), (size_t)w.numVerts, idx.data(),
                                                idx.size());
    const auto two = sv::two_sided_caster(s, sv::find_shells(s), sv::CasterRule::automatic);
    return two ? *two : s;
}

std::string first_vec4_diff(const Vec4 *got, const std::vector<Vec4> &ref) {
    // NOLINTNEXTLINE(bugprone-suspicious-memory-comparison): Vec4 is four floats, no padding
    if (std::memcmp(got, ref.data(), ref.size() * sizeof(Vec4)) == 0) return "";
    for (size_t i = 0; i < ref.size(); i++) {
        // NOLINTNEXTLINE(bugprone-suspicious-memory-comparison): as above
        if (std::memcmp(&got[i], &ref[i], sizeof(Vec4)) != 0)
            return "vertex " + std::to_string(i) + " differs from the C reference";
    }
    return "";
}

void measure(ExtrudeResult &res, const SeedTimer &timer, uint64_t seed, FILE *progress) {
    const sv::PreparedSurface &c = res.caster;
    const sv::ShadowMesh &m = res.mesh;
    const int nv = m.num_vertices();
    const std::vector<Vec4> lights = lights_around(c.positions.data(), c.num_vertices(),
                                                   kLightsExtrude, seed);
    float range = 0;
    for (const Vec4 &l : lights) {
        for (int v = 0; v < c.num_vertices(); v++) {
            const float *p = c.positions.data() + 3 * (size_t)v;
            range = std::max(range, std::hypot(p[0] - l.x, p[1] - l.y, p[2] - l.z));
        }
    }
    range *= 1.5f;

    /* The references: the seed's outputs per light, both kinds; the paper's
     * index lists by the C reference kernels. */
    std::vector<std::vector<Vec4>> refRange(kLightsExtrude), refInf(kLightsExtrude);
    int numVariants = 0;
    const sv_variant *cref = &sv_variants(&numVariants)[0]; /* c_ref */
    const size_t cap = sv_shadow_volume_capacity(c.num_indices(), c.num_sil_edges());
    std::vector<std::vector<int>> refPaper(kLightsExtrude);
    std::vector<uint8_t> facing((size_t)c.num_triangles() + 1);
    for (int l = 0; l < kLightsExtrude; l++) {
        refRange[l].resize((size_t)nv);
        refInf[l].resize((size_t)nv);
        const sv_extrude_light lr{lights[l], range}, li{lights[l], 0.0f};
        sv_extrude_c_ref(m.stream.data(), nv, &lr, refRange[l].data());
        sv_extrude_c_ref(m.stream.data(), nv, &li, refInf[l].data());
        std::vector<int> idx(cap);
        sv_calculate_facing_c_ref(c.planes.data(), c.num_triangles(), &lights[l], facing.data());
        const int n = sv_create_shadow_volume(cref, idx.data(), c.indices.data(), c.num_indices(),
                                              c.sil_edges.data(), c.num_sil_edges(), facing.data(),
                                              nullptr);
        idx.resize((size_t)std::max(n, 0));
        refPaper[l] = idx;
        res.paperIndicesMean += n;
        int sil = 0;
        for (const SilEdge &e : c.sil_edges) sil += facing[(size_t)e.p1] != facing[(size_t)e.p2];
        res.paperQuadsMean += sil;
        /* The seed's opened quads and split faces (infinite extrusion: kept
         * vertices have w = 1, extruded ones w = 0). */
        const std::vector<Vec4> &o = refInf[l];
        const int *q = m.indices.data();
        for (size_t i = 0; i < m.indices.size();) {
            /* A face is (3t, 3t+1, 3t+2); a quad's first triangle never is
             * (its second vertex is on the other face). */
            if (q[i] % 3 == 0 && q[i + 1] == q[i] + 1 && q[i + 2] == q[i] + 2) {
                const float w0 = o[(size_t)q[i]].w, w1 = o[(size_t)q[i + 1]].w,
                            w2 = o[(size_t)q[i + 2]].w;
                res.splitFaces += !(w0 == w1 && w1 == w2);
                i += 3;
            } else {
                /* (a1, b2, b1), (a1, a2, b2): open when a side moved. */
                const int a1 = q[i], b2 = q[i + 1], b1 = q[i + 2], a2 = q[i + 4];
                res.openQuadsMean += o[(size_t)a1].w != o[(size_t)a2].w ||
                                     o[(size_t)b1].w != o[(size_t)b2].w;
                i += 6;
            }
        }
    }
    res.paperIndicesMean /= kLightsExtrude;
    res.paperQuadsMean /= kLightsExtrude;
    res.openQuadsMean /= kLightsExtrude;

    int count = 0;
    const sv_extrude_variant *all = sv_extrude_variants(&count);
    std::vector<Vec4> out((size_t)nv);
    for (int i = 0; i < count; i++) {
        const sv_extrude_variant *v = &all[i];
        if ((v->isa & sv_cpu_isa()) != v->isa) continue;
        for (int finite = 1; finite >= 0; finite--) {
            if (progress)
                std::fprintf(progress, "\r%s: extrude %s        ", res.name.c_str(), v->name);
            const auto &ref = finite ? refRange : refInf;
            ExtrudeRow r{finite ? "extrude_range" : "extrude_inf", v->name, {}};
            r.t = time_seed_row(
                timer,
                [&](int k) {
                    const sv_extrude_light el{lights[(size_t)(k % kLightsExtrude)],
                                              finite ? range : 0.0f};
                    v->extrude(m.stream.data(), nv, &el, out.data());
                },
                [&](int k) {
                    return first_vec4_diff(out.data(), ref[(size_t)(k % kLightsExtrude)]);
                });
            res.rows.push_back(r);
        }
    }

    /* The rsqrt variant, not bit-identical: each call's outputs against
     * the reference's, the largest distance of a vertex that both extrude
     * (relative to the range) and the vertices whose facing differs. */
    if ((SV_ISA_SSE2 | SV_ISA_AVX2) == ((SV_ISA_SSE2 | SV_ISA_AVX2) & sv_cpu_isa())) {
        for (int finite = 1; finite >= 0; finite--) {
            const auto &ref = finite ? refRange : refInf;
            ExtrudeRow r{finite ? "extrude_range" : "extrude_inf", "avx2_rsqrt", {}};
            r.t = time_seed_row(
                timer,
                [&](int k) {
                    const sv_extrude_light el{lights[(size_t)(k % kLightsExtrude)],
                                              finite ? range : 0.0f};
                    sv_extrude_avx2_rsqrt(m.stream.data(), nv, &el, out.data());
                },
                [&](int k) {
                    const std::vector<Vec4> &rv = ref[(size_t)(k % kLightsExtrude)];
                    for (int i = 0; i < nv; i++) {
                        const Vec4 &a = out[(size_t)i], &b = rv[(size_t)i];
                        const float *p = m.stream.data() + (size_t)i * SV_EXTRUDE_STREAM_FLOATS;
                        const bool keptA = a.w == 1 && a.x == p[0] && a.y == p[1] && a.z == p[2];
                        const bool keptB = b.w == 1 && b.x == p[0] && b.y == p[1] && b.z == p[2];
                        if (keptA != keptB) {
                            res.rsqrtFlips++;
                        } else if (!keptA) {
                            const double e = std::hypot(a.x - b.x, a.y - b.y, a.z - b.z);
                            if (b.w == 0 && e != 0)
                                return std::string("an infinite vertex differs from c_ref");
                            res.rsqrtMaxError = std::max(res.rsqrtMaxError, e / range);
                        }
                    }
                    res.rsqrtCompared += nv;
                    return std::string();
                });
            res.rows.push_back(r);
        }
    }

    if (progress) std::fprintf(progress, "\r%s: paper        ", res.name.c_str());
    const std::vector<Vec4> positions = sv::positions_vec4(c);
    sv_surface surf{};
    surf.planes = c.planes.data();
    surf.indices = c.indices.data();
    surf.numIndices = c.num_indices();
    surf.silEdges = c.sil_edges.data();
    surf.numSilEdges = c.num_sil_edges();
    surf.positions = positions.data();
    surf.numVerts = c.num_vertices();
    surf.bounds = sv::surface_bounds(c);
    sv::AlignedVector<int> idx(cap);
    sv::AlignedVector<uint8_t> facingScratch((size_t)c.num_triangles() + 1);
    int written = 0;
    ExtrudeRow r{"paper", sv_plan_for(c.num_triangles(), SV_PLAN_ESTIMATE)->kernels.name, {}};
    r.t = time_seed_row(
        timer,
        [&](int k) {
            written = sv_shadow_volume_for_light(nullptr, &surf,
                                                 &lights[(size_t)(k % kLightsExtrude)], nullptr,
                                                 idx.data(), cap, facingScratch.data(), nullptr);
        },
        [&](int k) {
            const std::vector<int> &ref = refPaper[(size_t)(k % kLightsExtrude)];
            if (written != (int)ref.size() ||
                std::memcmp(idx.data(), ref.data(), ref.size() * sizeof(int)) != 0)
                return std::string("index list differs from the C references'");
            return std::string();
        });
    res.rows.push_back(r);
    if (progress) std::fprintf(progress, "\r%60s\r", "");
}

/* ---- The skinned normal sources ---------------------------------------- */

/* The normal sources timed, in the tables' order. */
constexpr sv::SkinnedNormals kSources[] = {sv::SkinnedNormals::straightforward,
                                           sv::SkinnedNormals::face_weights,
                                           sv::SkinnedNormals::recomputed,
                                           sv::SkinnedNormals::neighbours};

std::string source_row(sv::SkinnedNormals n) {
    std::string name = sv::skinned_normals_name(n);
    std::replace(name.begin(), name.end(), ' ', '_');
    return "skinned_" + name;
}

/* One skinned surface of a character, posed. */
struct SkinnedPart {
    const sv::AnimatedSurface *surface = nullptr;
    sv::SkinnedNormalData data;
    sv::SkinnedFrame frame;
    std::vector<float> stream, neighbours; /* the seed's, the neighbour fix's */
    std::vector<Vec4> out;
};

struct SkinnedResult {
    std::string name;
    long long faces = 0, influences = 0; /* influences: summed over the shadow mesh's vertices */
    long long faceJoints = 0;            /* face weights' joints, summed over the faces */
    /* Bytes a shadow-mesh vertex carries, over all of them: position and
     * normal 24; the skin (a uint16 joint and a float weight) 6 an
     * influence. */
    double bytes[4] = {0, 0, 0, 0}; /* per kSources */
    long long neighbourSplits = 0;  /* the neighbours' reference, over the lights */
    std::vector<ExtrudeRow> rows;
};

/* The skinned positions of PART into its seed stream's position columns. */
void write_positions(SkinnedPart &part) {
    const int *ix = part.surface->prepared.indices.data();
    const std::size_t n = part.stream.size() / SV_EXTRUDE_STREAM_FLOATS;
    const float *pos = part.frame.positions.data();
    for (std::size_t j = 0; j < n; j++) {
        const float *p = pos + 3 * (std::size_t)ix[j];
        float *o = &part.stream[j * SV_EXTRUDE_STREAM_FLOATS];
        o[0] = p[0], o[1] = p[1], o[2] = p[2];
    }
}

void measure_skinned(SkinnedResult &res, const sv::AnimatedAsset &asset, bool skinnedOnly,
                     const SeedTimer &timer, uint64_t seed, FILE *progress) {
    const sv::Animation &a = asset.animations[0];
    const sv::Pose pose = sv::pose_at(asset, 0, 0.5 * (a.start + a.end));
    std::vector<SkinnedPart> parts;
    std::vector<float> all; /* every part's skinned positions: the lights' ring */
    long long shadowVertices = 0;
    for (const sv::AnimatedSurface &s : asset.surfaces) {
        if (skinnedOnly && (s.skin < 0 || !s.influences)) continue;
        SkinnedPart p;
        p.surface = &s;
        p.data = sv::skinned_normal_data(s);
        p.frame = sv::skinned_frame(asset, s, pose);
        const std::size_t nv = 3 * (std::size_t)s.prepared.num_triangles();
        p.stream.assign(nv * SV_EXTRUDE_STREAM_FLOATS, 0.0f);
        p.neighbours.assign(nv * sv::kNeighbourStreamFloats, 0.0f);
        p.out.resize(nv);
        all.insert(all.end(), p.frame.positions.begin(), p.frame.positions.end());
        res.faces += s.prepared.num_triangles();
        const long long inf = s.skin >= 0 ? s.influences : 0;
        res.influences += (long long)nv * inf;
        res.faceJoints += p.data.face_start.back();
        shadowVertices += (long long)nv;
        parts.push_back(std::move(p));
    }
    /* Bytes per vertex: straightforward 24 + its skin; face weights that
     * and its face's weights (each of the face's three vertices carries
     * them); recomputed 24 written each frame (the CPU derives the normal;
     * the position is skinned on the CPU too); neighbours three positions,
     * each with its skin, and no normal. */
    const double sv_ = (double)std::max(shadowVertices, 1LL);
    const double skin = 6.0 * (double)res.influences / sv_;
    res.bytes[0] = 24 + skin;
    res.bytes[1] = 24 + skin + 6.0 * 3.0 * (double)res.faceJoints / sv_;
    res.bytes[2] = 24;
    res.bytes[3] = 3 * (12 + skin);
    const std::vector<Vec4> lights = lights_around(all.data(), (int)(all.size() / 3),
                                                   kLightsExtrude, seed);

    /* The references, light by light: the seed's program by c_ref on each
     * source's stream; the neighbours' program, which splits no face. */
    const std::size_t numParts = parts.size();
    std::vector<std::vector<std::vector<Vec4>>> ref(4, std::vector<std::vector<Vec4>>(
                                                           (std::size_t)kLightsExtrude * numParts));
    for (int l = 0; l < kLightsExtrude; l++) {
        const sv_extrude_light el{lights[(std::size_t)l], 0.0f};
        for (std::size_t pi = 0; pi < numParts; pi++) {
            SkinnedPart &p = parts[pi];
            const sv::PreparedSurface &ps = p.surface->prepared;
            const int nv = 3 * ps.num_triangles();
            for (int k = 0; k < 4; k++) {
                std::vector<Vec4> &r = ref[(std::size_t)k][(std::size_t)l * numParts + pi];
                r.resize((std::size_t)nv);
                if (kSources[k] == sv::SkinnedNormals::neighbours) {
                    sv::write_neighbour_stream(ps.indices.data(), ps.num_triangles(),
                                               p.frame.positions.data(), p.neighbours.data());
                    sv::extrude_neighbours(p.neighbours.data(), nv, el, r.data());
                    for (int t = 0; t < ps.num_triangles(); t++) {
                        const float w0 = r[3 * (std::size_t)t].w, w1 = r[3 * (std::size_t)t + 1].w,
                                    w2 = r[3 * (std::size_t)t + 2].w;
                        res.neighbourSplits += !(w0 == w1 && w1 == w2);
                    }
                } else {
                    write_positions(p);
                    sv::write_skinned_normals(*p.surface, p.data, p.frame, kSources[k],
                                              p.stream.data());
                    sv_extrude_c_ref(p.stream.data(), nv, &el, r.data());
                }
            }
        }
    }
    auto check = [&](int source) {
        return [&, source](int k) {
            const std::size_t l = (std::size_t)(k % kLightsExtrude);
            for (std::size_t pi = 0; pi < numParts; pi++) {
                const std::string d = first_vec4_diff(parts[pi].out.data(),
                                                      ref[(std::size_t)source][l * numParts + pi]);
                if (!d.empty()) return d;
            }
            if (source == 3 && res.neighbourSplits != 0)
                return std::string("the neighbour fix split a face");
            return std::string();
        };
    };

    /* The program alone, on the recomputed normals' stream (left there by
     * the references' last light), checked against that source's
     * reference. */
    const sv_extrude_variant *best = sv_best_extrude_variant();
    for (const sv_extrude_variant *v : {sv_extrude_variant_by_name("c_ref"), best}) {
        if (progress) std::fprintf(progress, "\r%s: program %s        ", res.name.c_str(), v->name);
        for (SkinnedPart &p : parts) {
            write_positions(p);
            sv::write_skinned_normals(*p.surface, p.data, p.frame, sv::SkinnedNormals::recomputed,
                                      p.stream.data());
        }
        ExtrudeRow r{"skinned_program", v->name, {}};
        r.t = time_seed_row(
            timer,
            [&](int k) {
                const sv_extrude_light el{lights[(size_t)(k % kLightsExtrude)], 0.0f};
                for (SkinnedPart &p : parts)
                    v->extrude(p.stream.data(), (int)p.out.size(), &el, p.out.data());
            },
            check(2));
        res.rows.push_back(r);
        if (v == best) break; /* c_ref is the best on a CPU without AVX2 */
    }
    for (int src = 0; src < 4; src++) {
        const sv::SkinnedNormals way = kSources[src];
        if (progress)
            std::fprintf(progress, "\r%s: %s        ", res.name.c_str(),
                         sv::skinned_normals_name(way));
        const bool neighbours = way == sv::SkinnedNormals::neighbours;
        ExtrudeRow r{source_row(way), neighbours ? "c" : best->name, {}};
        r.t = time_seed_row(
            timer,
            [&](int k) {
                const sv_extrude_light el{lights[(size_t)(k % kLightsExtrude)], 0.0f};
                for (SkinnedPart &p : parts) {
                    const sv::PreparedSurface &ps = p.surface->prepared;
                    if (neighbours) {
                        sv::write_neighbour_stream(ps.indices.data(), ps.num_triangles(),
                                                   p.frame.positions.data(), p.neighbours.data());
                        sv::extrude_neighbours(p.neighbours.data(), (int)p.out.size(), el,
                                               p.out.data());
                    } else {
                        write_positions(p);
                        sv::write_skinned_normals(*p.surface, p.data, p.frame, way,
                                                  p.stream.data());
                        best->extrude(p.stream.data(), (int)p.out.size(), &el, p.out.data());
                    }
                }
            },
            check(src));
        res.rows.push_back(r);
    }
    if (progress) std::fprintf(progress, "\r%60s\r", "");
}

void print_skinned_tables(FILE *out, const std::vector<SkinnedResult> &results) {
    if (results.empty()) return;
    const std::string best = sv_best_extrude_variant()->name;
    std::fprintf(out,
                 "\nthe skinned normal sources (the seed's Figure 4 and its fixes), one frame "
                 "(the middle of the first animation) and one light, ticks per frame (median; "
                 "every call's output bit-identical to the reference, else FAIL); x: over the "
                 "program alone (%s), the neighbours' C over the program's c_ref\n",
                 best.c_str());
    std::fprintf(out, "%-22s %7s %10s %10s %17s %17s %17s %10s %17s\n", "character", "faces",
                 "program", "c_ref", "straightforward", "face weights", "recomputed", "",
                 "neighbours (C)");
    for (const SkinnedResult &r : results) {
        const VariantRow *prog = find_variant_row(r.rows, "skinned_program", best),
                         *cref = find_variant_row(r.rows, "skinned_program", "c_ref");
        auto cell = [&](const VariantRow *row, const VariantRow *base) {
            char c[48];
            std::snprintf(c, sizeof c, "%s %5.2fx", ticks_cell(row, 1).c_str(),
                          row && base ? row->t.median / std::max(1.0, base->t.median) : 0.0);
            return std::string(c);
        };
        std::fprintf(out, "%-22s %7lld %10s %10s %17s %17s %17s %10s %17s\n", r.name.c_str(),
                     r.faces, ticks_cell(prog, 1).c_str(), ticks_cell(cref, 1).c_str(),
                     cell(find_variant_row(r.rows, source_row(kSources[0]), ""), prog).c_str(),
                     cell(find_variant_row(r.rows, source_row(kSources[1]), ""), prog).c_str(),
                     cell(find_variant_row(r.rows, source_row(kSources[2]), ""), prog).c_str(), "",
                     cell(find_variant_row(r.rows, source_row(kSources[3]), ""), cref).c_str());
    }
    std::fprintf(out, "\nthe bytes a shadow-mesh vertex carries (x 3 a face; a skin influence 6 "
                      "bytes: a uint16 joint, a float weight)\n");
    std::fprintf(out, "%-22s %9s %10s %16s %13s %11s %11s %12s\n", "character", "vertices",
                 "influences", "straightforward", "face weights", "recomputed", "neighbours",
                 "neighb. split");
    for (const SkinnedResult &r : results) {
        std::fprintf(out, "%-22s %9lld %10.2f %16.1f %13.1f %11.1f %11.1f %12lld\n", r.name.c_str(),
                     3 * r.faces, (double)r.influences / std::max(1.0, 3.0 * (double)r.faces),
                     r.bytes[0], r.bytes[1], r.bytes[2], r.bytes[3], r.neighbourSplits);
    }
    std::fprintf(out, "  straightforward: position, rest normal, the vertex's skin; face weights: "
                      "and its face's weights; recomputed: position and normal written by the CPU "
                      "each frame; neighbours: the face's three positions with their skins, no "
                      "normal\n");
}

void print_tables(FILE *out, const std::vector<ExtrudeResult> &results) {
    std::vector<std::string> variants;
    for (const ExtrudeRow &r : results.front().rows)
        if (r.what == "extrude_range" && r.variant != "avx2_rsqrt") variants.push_back(r.variant);
    std::fprintf(out, "\nseed 002's vertex program on the CPU, ticks per vertex (median; every "
                      "call bit-identical to c_ref, else FAIL), range | infinite\n");
    std::fprintf(out, "%-26s %9s", "mesh", "vertices");
    for (const std::string &v : variants) std::fprintf(out, " %15s", v.c_str());
    std::fprintf(out, "\n");
    for (const ExtrudeResult &r : results) {
        const double nv = r.mesh.num_vertices();
        std::fprintf(out, "%-26s %9d", r.name.c_str(), r.mesh.num_vertices());
        for (const std::string &v : variants) {
            const std::string c = ticks_cell(find_variant_row(r.rows, "extrude_range", v), nv) +
                                  " | " +
                                  ticks_cell(find_variant_row(r.rows, "extrude_inf", v), nv);
            std::fprintf(out, " %15s", c.c_str());
        }
        std::fprintf(out, "\n");
    }

    const std::string best = sv_best_extrude_variant()->name;
    std::fprintf(out,
                 "\none light, ticks per call (median): the seed's extrusion (%s, infinite) "
                 "against the paper's pipeline (sv_shadow_volume_for_light, every call's "
                 "indices checked)\n",
                 best.c_str());
    std::fprintf(out, "%-26s %9s %12s %12s %8s\n", "mesh", "triangles", "seed", "paper", "ratio");
    for (const ExtrudeResult &r : results) {
        const ExtrudeRow *s = find_variant_row(r.rows, "extrude_inf", best),
                         *p = find_variant_row(r.rows, "paper", "");
        std::fprintf(out, "%-26s %9d %12s %12s %8.2f\n", r.name.c_str(), r.caster.num_triangles(),
                     ticks_cell(s, 1).c_str(), ticks_cell(p, 1).c_str(),
                     s && p ? s->t.median / std::max(1.0, p->t.median) : 0.0);
    }

    std::fprintf(out, "\navx2_rsqrt (rsqrtps and one Newton step; not bit-identical, not in the "
                      "table): ticks per vertex, its largest distance from c_ref per unit of "
                      "range, its facing decisions that differ\n");
    std::fprintf(out, "%-26s %9s %15s %12s %14s\n", "mesh", "vertices", "range | inf", "max error",
                 "facing differs");
    for (const ExtrudeResult &r : results) {
        const double nv = r.mesh.num_vertices();
        const std::string c =
            ticks_cell(find_variant_row(r.rows, "extrude_range", "avx2_rsqrt"), nv) + " | " +
            ticks_cell(find_variant_row(r.rows, "extrude_inf", "avx2_rsqrt"), nv);
        char flips[48];
        std::snprintf(flips, sizeof flips, "%lld/%lld", r.rsqrtFlips, r.rsqrtCompared);
        std::fprintf(out, "%-26s %9d %15s %12.2e %14s\n", r.name.c_str(), r.mesh.num_vertices(),
                     c.c_str(), r.rsqrtMaxError, flips);
    }

    std::fprintf(out,
                 "\ncounts: the seed's static buffers against the paper's per light (mean "
                 "over %d lights)\n",
                 kLightsExtrude);
    std::fprintf(out, "%-26s %9s %10s %10s %10s %10s %10s %10s %7s\n", "mesh", "faces",
                 "seed verts", "seed idx", "paper vts", "paper idx", "seed open", "paper sil",
                 "split");
    for (const ExtrudeResult &r : results) {
        std::fprintf(out, "%-26s %9lld %10d %10d %10d %10.0f %10.1f %10.1f %7lld\n", r.name.c_str(),
                     (long long)r.mesh.faces, r.mesh.num_vertices(), r.mesh.num_indices(),
                     2 * r.caster.num_vertices(), r.paperIndicesMean, r.openQuadsMean,
                     r.paperQuadsMean, r.splitFaces);
    }
    std::fprintf(out,
                 "  seed open: quads whose two faces extrude differently (the volume's sides); "
                 "paper sil: SilEdges whose faces differ in facing;\n"
                 "  split: faces whose three vertices disagree on facing (summed over the "
                 "lights)\n");
}

void skinned_json(JsonWriter &j, const std::vector<SkinnedResult> &results) {
    j.key("skinned");
    j.begin_array();
    for (const SkinnedResult &r : results) {
        j.begin_object();
        j.key("character");
        j.value(r.name);
        j.key("faces");
        j.value(r.faces);
        j.key("shadow_vertices");
        j.value(3 * r.faces);
        j.key("bytes_per_vertex");
        j.begin_object(true);
        for (int k = 0; k < 4; k++) {
            j.key(source_row(kSources[k]).substr(8));
            j.value(r.bytes[k]);
        }
        j.end_object();
        j.key("neighbours_split_faces");
        j.value(r.neighbourSplits);
        variant_rows_json(j, r.rows);
        j.end_object();
    }
    j.end_array();
}

std::string extrude_json(const std::vector<ExtrudeResult> &results,
                         const std::vector<SkinnedResult> &skinned, const SeedTimer &t) {
    JsonWriter j;
    j.begin_object();
    seed_json_header(j, "shadowvol-extrude/1", t);
    j.key("lights");
    j.value(kLightsExtrude);
    j.key("meshes");
    j.begin_array();
    for (const ExtrudeResult &r : results) {
        j.begin_object();
        j.key("mesh");
        j.value(r.name);
        j.key("faces");
        j.value((long long)r.mesh.faces);
        j.key("seed_vertices");
        j.value(r.mesh.num_vertices());
        j.key("seed_indices");
        j.value(r.mesh.num_indices());
        j.key("paper_shadow_vertices");
        j.value(2 * r.caster.num_vertices());
        j.key("paper_indices_mean");
        j.value(r.paperIndicesMean);
        j.key("seed_open_quads_mean");
        j.value(r.openQuadsMean);
        j.key("paper_silhouette_mean");
        j.value(r.paperQuadsMean);
        j.key("split_faces");
        j.value(r.splitFaces);
        j.key("rsqrt_max_error_per_range");
        j.value(r.rsqrtMaxError);
        j.key("rsqrt_facing_differs");
        j.value(r.rsqrtFlips);
        j.key("rsqrt_compared");
        j.value(r.rsqrtCompared);
        variant_rows_json(j, r.rows);
        j.end_object();
    }
    j.end_array();
    skinned_json(j, skinned);
    j.end_object();
    return j.str();
}

} // namespace

int run_extrude_bench(const SeedCommand &cmd) {
    return run_seed_frame(cmd, "extrude", [&](FILE *out, std::string *doc) {
        const int cpu = pin_to_current_cpu();
        const SeedTimer timer = make_seed_timer(cmd.timer, cmd.quick);
        print_seed_header(out,
                          "shadowvol bench --extrude: seed 002's vertex program on the CPU "
                          "against the paper's pipeline",
                          timer, cpu);
        std::vector<std::string> paths = {SV_MODELS_DIR "/character_1344.glb"};
        if (!cmd.quick) {
            for (const char *name : {"Fox.glb", "CesiumMan.glb", "RobotExpressive.glb",
                                     "RiggedFigure.glb", "open/Zombie_Basic.glb"}) {
                const std::string p = cmd.sharedModels + "/" + name;
                if (access(p.c_str(), R_OK) != 0) {
                    std::fprintf(out, "note      %s not found: left out\n", p.c_str());
                    continue;
                }
                paths.push_back(p);
            }
        }
        std::vector<ExtrudeResult> results;
        for (const std::string &p : paths) {
            const SeedMesh sm = loaded_seed_mesh(p);
            if (cmd.maxTriangles && sm.w.numTriangles > cmd.maxTriangles) continue;
            ExtrudeResult r;
            r.name = sm.name;
            r.caster = caster_of(sm);
            r.mesh = sv::build_shadow_mesh(r.caster);
            results.push_back(std::move(r));
        }
        FILE *progress = isatty(fileno(stderr)) ? stderr : nullptr;
        for (ExtrudeResult &r : results) measure(r, timer, cmd.seed, progress);
        /* The skinned characters: the demo scene's (its skinned surface
         * alone), then the shared folder's. */
        std::vector<std::pair<std::string, bool>> characters = {{SV_DEMO_SCENE, true}};
        if (!cmd.quick) {
            for (const char *name : {"CesiumMan.glb", "Fox.glb", "RiggedFigure.glb",
                                     "RobotExpressive.glb", "open/Zombie_Basic.glb"}) {
                const std::string p = cmd.sharedModels + "/" + name;
                if (access(p.c_str(), R_OK) == 0) characters.emplace_back(p, false);
            }
        }
        std::vector<SkinnedResult> skinned;
        for (const auto &[path, skinnedOnly] : characters) {
            const sv::AnimatedAsset asset = sv::load_animated_gltf(path);
            if (asset.animations.empty()) continue;
            SkinnedResult r;
            r.name = path.substr(path.rfind('/') + 1);
            measure_skinned(r, asset, skinnedOnly, timer, cmd.seed, progress);
            if (r.faces > 0) skinned.push_back(std::move(r));
        }
        print_tables(out, results);
        print_skinned_tables(out, skinned);
        int failed = 0;
        for (const ExtrudeResult &r : results) failed += print_failed_rows(out, r.name, r.rows);
        for (const SkinnedResult &r : skinned) failed += print_failed_rows(out, r.name, r.rows);
        *doc = extrude_json(results, skinned, timer);
        return failed;
    });
}

} // namespace svbench
