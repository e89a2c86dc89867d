/*
 * Skinning and planes, per skinned character (skin_planes_bench.h): the
 * work a deforming surface needs each frame before any light, three ways
 * in one run:
 *   skin        each skinning kernel alone (positions only);
 *   two_passes  skinning kernel K, then planes variant P over the output;
 *   one_pass    each one-pass kernel (K and P segment by segment).
 * Ticks per triangle (median of calls; each call all of the character's
 * skinned surfaces at one pose, the joint matrices made beforehand), and
 * every call's positions and planes compared bit for bit with skinning by
 * the C reference and sv_derive_planes_c_ref.
 *
 * Copyright (C) 2026 the shadowvol authors. LGPL-2.1-or-later.
 */
#include "skin_planes_bench.h"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <memory>

#include <unistd.h>

#include "fnv1a.h"
#include "json_writer.h"
#include "shadowvol_anim.h"
#include "shadowvol_plan.h"
#include "shadowvol_planes.h"
#include "shadowvol_skin.h"

#ifndef SV_DEMO_SCENE
#define SV_DEMO_SCENE "models/demo_scene.glb"
#endif

namespace svbench {

namespace {

/* One skinned surface at one pose, with its references and outputs. */
struct PosedSurface {
    const sv::AnimatedSurface *as = nullptr;
    sv::AlignedVector<float> jm, pos;
    sv::AlignedVector<Plane> planes;
    std::vector<float> want_pos;
    std::vector<Plane> want_planes;
    sv::SkinPlanesSchedule schedule;
    sv::PlaneClusters clusters; /* for the clustered planes kernels */
    sv_skin_planes_args args{};
    /* The per-light job: the posed positions as Vec4, the stored planes
     * (the reference's, made beforehand), and per light of a frame (up to
     * 4) its own output and facing, so each volume can be checked. */
    std::vector<Vec4> pos4;
    Bounds bounds{};
    sv::AlignedVector<int> out[4];
    sv::AlignedVector<uint8_t> facing[4];
    int count[4] = {0, 0, 0, 0};
    std::size_t vertices() const { return as->rest_positions.size() / 3; }
};

constexpr int kJobLights = 16;

void skin(const sv::SkinningKernel &k, PosedSurface &s) {
    k.fn(s.jm.data(), s.as->rest_positions.data(), s.as->joints.data(), s.as->weights.data(),
         s.as->influences, s.vertices(), s.pos.data());
}

std::string compare(const std::vector<std::unique_ptr<PosedSurface>> &surfaces, bool planes) {
    for (const auto &s : surfaces) {
        if (std::memcmp(s->pos.data(), s->want_pos.data(), 4 * s->want_pos.size()) != 0) {
            return s->as->name + ": positions differ from the C reference";
        }
        // NOLINTNEXTLINE(bugprone-suspicious-memory-comparison): Plane is four floats, no padding
        if (planes && std::memcmp(s->planes.data(), s->want_planes.data(),
                                  sizeof(Plane) * s->want_planes.size()) != 0) {
            return s->as->name + ": planes differ from sv_derive_planes_c_ref";
        }
    }
    return "";
}

/* 16 point lights on a ring around the posed character (1.5 of its size
 * out), as bench --planes's other tables place them. */
std::vector<Vec4> ring_lights(const std::vector<std::unique_ptr<PosedSurface>> &surfaces) {
    float lo[3] = {1e30f, 1e30f, 1e30f}, hi[3] = {-1e30f, -1e30f, -1e30f};
    for (const auto &s : surfaces) {
        for (std::size_t i = 0; i < s->want_pos.size(); i++) {
            lo[i % 3] = std::min(lo[i % 3], s->want_pos[i]);
            hi[i % 3] = std::max(hi[i % 3], s->want_pos[i]);
        }
    }
    const double r = 1.5 * std::max({hi[0] - lo[0], hi[1] - lo[1], hi[2] - lo[2]}) + 1e-3;
    std::vector<Vec4> out;
    for (int i = 0; i < kJobLights; i++) {
        const double a = 2 * M_PI * (i + 0.37) / kJobLights, e = 0.3 + 0.8 * (i % 5) / 5.0;
        out.push_back(Vec4{(float)(0.5 * (lo[0] + hi[0]) + r * std::cos(a) * std::cos(e)),
                           (float)(0.5 * (lo[1] + hi[1]) + r * std::sin(e)),
                           (float)(0.5 * (lo[2] + hi[2]) + r * std::sin(a) * std::cos(e)), 1.0f});
    }
    return out;
}

/* The volume of S for LIGHT into slot J: the plan's one call on PLANES
 * (none: BFG's way, facing from the positions, then the plan's kernels). */
void volume(PosedSurface &s, const sv_plan *plan, const Plane *planes, const Vec4 &light, int j,
            const sv_planes_variant *bfg) {
    const sv::PreparedSurface &p = s.as->prepared;
    if (bfg) {
        bfg->facing_from_positions(s.want_pos.data(), p.indices.data(), p.num_triangles(), &light,
                                   s.facing[j].data());
        s.count[j] = sv_create_shadow_volume(&plan->kernels, s.out[j].data(), p.indices.data(),
                                             p.num_indices(), p.sil_edges.data(), p.num_sil_edges(),
                                             s.facing[j].data(), nullptr);
        return;
    }
    const sv_surface v{
        planes,        p.indices.data(), p.num_indices(), p.sil_edges.data(), p.num_sil_edges(),
        s.pos4.data(), p.num_vertices(), s.bounds};
    s.count[j] = sv_shadow_volume_for_light(plan, &v, &light, nullptr, s.out[j].data(),
                                            s.out[j].size(), s.facing[j].data(), nullptr);
}

/* The C references' volume of S for LIGHT: facing of the planes (or, BFG,
 * of the positions), then the c_ref kernels; its fingerprint. */
uint64_t reference_volume(PosedSurface &s, const Vec4 &light, bool bfg, uint64_t h) {
    const sv::PreparedSurface &p = s.as->prepared;
    std::vector<uint8_t> f((std::size_t)p.num_triangles() + 1);
    if (bfg) {
        sv_facing_from_positions_c_ref(s.want_pos.data(), p.indices.data(), p.num_triangles(),
                                       &light, f.data());
    } else {
        sv_calculate_facing_c_ref(s.want_planes.data(), p.num_triangles(), &light, f.data());
    }
    std::vector<int> out(s.out[0].size());
    const int n = sv_create_shadow_volume(sv_variant_by_name("c_ref"), out.data(), p.indices.data(),
                                          p.num_indices(), p.sil_edges.data(), p.num_sil_edges(),
                                          f.data(), nullptr);
    h = sv::fnv1a64(&n, sizeof n, h);
    return sv::fnv1a64(out.data(), sizeof(int) * (std::size_t)std::max(n, 0), h);
}

/* The per-light job rows: stored planes, planes derived once per frame,
 * and (4 lights) BFG's facing from positions, each checked volume by
 * volume against the C references. */
void measure_jobs(SkinPlanesResult &r, std::vector<std::unique_ptr<PosedSurface>> &surfaces,
                  const SeedTimer &timer) {
    const std::vector<Vec4> lights = ring_lights(surfaces);
    const sv_plan *plan = sv_plan_for(r.triangles / std::max(1, r.surfaces), SV_PLAN_ESTIMATE);
    const sv::DeformPlan deform = sv::deform_plan_for(r.triangles / std::max(1, r.surfaces));
    const sv_planes_variant *pv = deform.planes;
    const sv_planes_clustered_variant *cv = nullptr;
    int nc = 0;
    const sv_planes_clustered_variant *all_clustered = sv_planes_clustered_variants(&nc);
    for (int i = 1; i < nc; i++) { /* past the C reference */
        if ((all_clustered[i].isa & sv_cpu_isa()) == all_clustered[i].isa) cv = &all_clustered[i];
    }
    for (auto &s : surfaces) {
        const sv::PreparedSurface &p = s->as->prepared;
        for (std::size_t v = 0; v < s->vertices(); v++) {
            s->pos4.push_back(
                Vec4{s->want_pos[3 * v], s->want_pos[3 * v + 1], s->want_pos[3 * v + 2], 1.0f});
        }
        s->bounds = sv::surface_bounds(p);
        s->clusters = sv::plane_clusters(p.indices.data(), p.num_triangles(), p.num_vertices());
        for (int j = 0; j < 4; j++) {
            s->out[j].resize(sv_shadow_volume_capacity(p.num_indices(), p.num_sil_edges()));
            s->facing[j].resize((std::size_t)p.num_triangles() + 1);
        }
    }
    /* The references' fingerprints per light, with planes and BFG's. */
    std::vector<uint64_t> ref_planes(kJobLights), ref_bfg(kJobLights);
    for (int l = 0; l < kJobLights; l++) {
        uint64_t hp = sv::kFnv1a64OffsetBasis, hb = sv::kFnv1a64OffsetBasis;
        for (auto &s : surfaces) {
            hp = reference_volume(*s, lights[(std::size_t)l], false, hp);
            hb = reference_volume(*s, lights[(std::size_t)l], true, hb);
        }
        ref_planes[(std::size_t)l] = hp, ref_bfg[(std::size_t)l] = hb;
    }
    auto check = [&](int i, int k, const std::vector<uint64_t> &ref) {
        for (int j = 0; j < k; j++) {
            const int l = (k * i + j) % kJobLights;
            uint64_t h = sv::kFnv1a64OffsetBasis;
            for (auto &s : surfaces) {
                h = sv::fnv1a64(&s->count[j], sizeof s->count[j], h);
                h = sv::fnv1a64(s->out[j].data(),
                                sizeof(int) * (std::size_t)std::max(s->count[j], 0), h);
            }
            if (h != ref[(std::size_t)l]) {
                return "light " + std::to_string(l) + ": the volumes differ from the C references'";
            }
        }
        return std::string();
    };
    for (int k = 1; k <= 4; k++) {
        const std::string n = std::to_string(k);
        /* 2 and 3 lights: derived and BFG's only, for the crossover. */
        const bool every_way = k == 1 || k == 4;
        if (every_way) {
            SkinPlanesRow stored{"job_stored_" + n, "plan", {}};
            stored.t = time_seed_row(
                timer,
                [&](int i) {
                    for (auto &s : surfaces) {
                        for (int j = 0; j < k; j++) {
                            volume(*s, plan, s->want_planes.data(),
                                   lights[(std::size_t)((k * i + j) % kJobLights)], j, nullptr);
                        }
                    }
                },
                [&](int i) { return check(i, k, ref_planes); });
            r.rows.push_back(stored);
        }
        SkinPlanesRow derived{"job_derived_" + n, pv->name, {}};
        derived.t = time_seed_row(
            timer,
            [&](int i) {
                for (auto &s : surfaces) {
                    const sv::PreparedSurface &p = s->as->prepared;
                    pv->derive_planes(s->want_pos.data(), p.indices.data(), p.num_triangles(),
                                      s->planes.data());
                    for (int j = 0; j < k; j++) {
                        volume(*s, plan, s->planes.data(),
                               lights[(std::size_t)((k * i + j) % kJobLights)], j, nullptr);
                    }
                }
            },
            [&](int i) { return check(i, k, ref_planes); });
        r.rows.push_back(derived);
        /* The planes by clusters (the widest clustered kernel here). */
        if (cv && every_way) {
            SkinPlanesRow clustered{"job_clustered_" + n, std::string("clusters_") + cv->name, {}};
            clustered.t = time_seed_row(
                timer,
                [&](int i) {
                    for (auto &s : surfaces) {
                        const sv_plane_clusters view = s->clusters.view();
                        cv->derive_planes(s->want_pos.data(), &view, s->planes.data());
                        for (int j = 0; j < k; j++) {
                            volume(*s, plan, s->planes.data(),
                                   lights[(std::size_t)((k * i + j) % kJobLights)], j, nullptr);
                        }
                    }
                },
                [&](int i) { return check(i, k, ref_planes); });
            r.rows.push_back(clustered);
        }
        SkinPlanesRow bfg{"job_bfg_" + n, pv->name, {}};
        bfg.t = time_seed_row(
            timer,
            [&](int i) {
                for (auto &s : surfaces) {
                    for (int j = 0; j < k; j++) {
                        volume(*s, plan, nullptr, lights[(std::size_t)((k * i + j) % kJobLights)],
                               j, pv);
                    }
                }
            },
            [&](int i) { return check(i, k, ref_bfg); });
        r.rows.push_back(bfg);
    }
}

SkinPlanesResult measure_character(const std::string &path, const SeedTimer &timer,
                                   FILE *progress) {
    SkinPlanesResult r;
    r.name = path.substr(path.find_last_of('/') + 1);
    const sv::AnimatedAsset a = sv::load_animated_gltf(path);
    const int animation = a.animations.empty() ? -1 : 0;
    double time = 0;
    if (animation >= 0)
        time = a.animations[0].start + (a.animations[0].end - a.animations[0].start) / 3;
    const sv::Pose pose = sv::pose_at(a, animation, time);
    const sv::SkinningKernel *cref = sv::skinning_kernel_by_name("c_ref");

    std::vector<std::unique_ptr<PosedSurface>> surfaces;
    for (const sv::AnimatedSurface &as : a.surfaces) {
        if (as.skin < 0) continue;
        auto s = std::make_unique<PosedSurface>();
        s->as = &as;
        const sv::PreparedSurface &p = as.prepared;
        s->jm.resize(16 * a.skins[(std::size_t)as.skin].joints.size());
        sv::joint_matrices(a, as.skin, pose, sv::Mat4d{}, s->jm.data());
        s->pos.resize(3 * s->vertices());
        s->planes.resize(p.planes.size());
        s->want_pos.resize(3 * s->vertices());
        s->want_planes.resize(p.planes.size());
        cref->fn(s->jm.data(), as.rest_positions.data(), as.joints.data(), as.weights.data(),
                 as.influences, s->vertices(), s->want_pos.data());
        sv_derive_planes_c_ref(s->want_pos.data(), p.indices.data(), p.num_triangles(),
                               s->want_planes.data());
        s->schedule = sv::skin_planes_schedule(p.indices.data(), p.num_triangles(), s->vertices());
        s->args = sv::skin_planes_args(as, s->jm.data(), s->schedule, s->pos.data(),
                                       s->planes.data());
        const int segments = s->args.segments;
        r.surfaces++;
        r.triangles += p.num_triangles();
        r.vertices += (int)s->vertices();
        r.segments += segments;
        surfaces.push_back(std::move(s));
    }
    if (surfaces.empty()) return r;
    const unsigned isa = sv_cpu_isa();
    auto note = [&](const std::string &what) {
        if (progress) std::fprintf(progress, "\r%s: %s          ", r.name.c_str(), what.c_str());
    };

    int nk = 0;
    const sv::SkinningKernel *kernels = sv::skinning_kernels(&nk);
    for (int i = 0; i < nk; i++) {
        const sv::SkinningKernel &k = kernels[i];
        if ((k.isa & isa) != k.isa) continue;
        note(std::string("skin ") + k.name);
        SkinPlanesRow row{"skin", k.name, {}};
        row.t = time_seed_row(
            timer,
            [&](int) {
                for (auto &s : surfaces) skin(k, *s);
            },
            [&](int) { return compare(surfaces, false); });
        r.rows.push_back(row);
    }
    int nf = 0;
    const sv::SkinPlanesKernel *fused = sv::skin_planes_kernels(&nf);
    for (int i = 0; i < nf; i++) {
        const sv::SkinPlanesKernel &f = fused[i];
        if ((f.isa & isa) != f.isa) continue;
        const sv::SkinningKernel &k = *sv::skinning_kernel_by_name(f.skinning);
        const sv_planes_variant &p = *sv_planes_variant_by_name(f.planes);
        note(std::string("two passes ") + f.name);
        SkinPlanesRow two{"two_passes", std::string(k.name) + "+" + p.name, {}};
        two.t = time_seed_row(
            timer,
            [&](int) {
                for (auto &s : surfaces) {
                    skin(k, *s);
                    p.derive_planes(s->pos.data(), s->as->prepared.indices.data(),
                                    s->as->prepared.num_triangles(), s->planes.data());
                }
            },
            [&](int) { return compare(surfaces, true); });
        r.rows.push_back(two);
        note(std::string("one pass ") + f.name);
        SkinPlanesRow one{"one_pass", f.name, {}};
        one.t = time_seed_row(
            timer,
            [&](int) {
                for (auto &s : surfaces) f.fn(&s->args);
            },
            [&](int) { return compare(surfaces, true); });
        r.rows.push_back(one);
    }
    note("the per-light job");
    measure_jobs(r, surfaces, timer);
    return r;
}

} // namespace

std::vector<SkinPlanesResult> measure_skin_planes(const SeedTimer &timer, const std::string &shared,
                                                  bool quick, FILE *out, FILE *progress) {
    std::vector<std::string> paths = {SV_DEMO_SCENE};
    if (!quick) {
        for (const char *name : {"Fox.glb", "CesiumMan.glb", "RobotExpressive.glb",
                                 "RiggedFigure.glb", "open/Zombie_Basic.glb"}) {
            const std::string p = shared + "/" + name;
            if (access(p.c_str(), R_OK) != 0) {
                std::fprintf(out, "note      %s not found: left out of the skinned table\n",
                             p.c_str());
                continue;
            }
            paths.push_back(p);
        }
    }
    std::vector<SkinPlanesResult> results;
    for (const std::string &p : paths) {
        SkinPlanesResult r = measure_character(p, timer, progress);
        if (r.surfaces > 0) results.push_back(std::move(r));
    }
    if (progress) std::fprintf(progress, "\r%60s\r", "");
    return results;
}

void print_jobs(FILE *out, const std::vector<SkinPlanesResult> &results);
void print_crossover(FILE *out, const std::vector<SkinPlanesResult> &results);

void print_skin_planes(FILE *out, const std::vector<SkinPlanesResult> &results) {
    if (results.empty()) return;
    std::fprintf(out,
                 "\nskinning and planes of the skinned characters, ticks per triangle (median; "
                 "every call's positions and planes bit-identical to the C references, else "
                 "FAIL)\n"
                 "  skin K: skinning alone; K+P: skinning, then the planes, two passes; one pass: "
                 "the same kernels segment by segment (schedule of %d triangles);\n"
                 "  beyond: one pass minus skinning alone with the same skinning kernel\n",
                 sv::kSkinPlanesSegmentTriangles);
    std::fprintf(out, "%-22s %9s %8s %-12s %8s %9s %9s %7s\n", "character", "triangles", "vertices",
                 "kernels", "skin K", "two pass", "one pass", "beyond");
    for (const SkinPlanesResult &r : results) {
        for (const SkinPlanesRow &one : r.rows) {
            if (one.what != "one_pass") continue;
            const sv::SkinPlanesKernel *f = sv::skin_planes_kernel_by_name(one.variant.c_str());
            const SkinPlanesRow *sk = find_variant_row(r.rows, "skin", f->skinning);
            const SkinPlanesRow *two = find_variant_row(r.rows, "two_passes",
                                                        std::string(f->skinning) + "+" + f->planes);
            char beyond[32] = "-";
            if (sk) {
                std::snprintf(beyond, sizeof beyond, "%.2f",
                              (one.t.median - sk->t.median) / std::max(1, r.triangles));
            }
            std::fprintf(out, "%-22s %9d %8d %-12s %8s %9s %9s %7s\n", r.name.c_str(), r.triangles,
                         r.vertices, one.variant.c_str(), ticks_cell(sk, r.triangles).c_str(),
                         ticks_cell(two, r.triangles).c_str(),
                         ticks_cell(&one, r.triangles).c_str(), beyond);
        }
    }
    print_jobs(out, results);
}

void print_jobs(FILE *out, const std::vector<SkinPlanesResult> &results) {
    std::fprintf(out, "\nthe per-light job of a skinned character, positions already skinned: "
                      "planes + facing + volume (sv_shadow_volume_for_light), ticks per triangle "
                      "(median; every volume checked against the C references)\n"
                      "  stored: the planes made beforehand; derived: derived once per frame "
                      "(the planned variant); clusters: derived by the widest clustered kernel "
                      "(- where none runs); bfg: facing from positions per light, no planes\n");
    std::fprintf(out, "%-22s %9s %8s %8s %8s %8s %8s %8s %8s %8s %8s %8s %8s %8s\n", "character",
                 "triangles", "stored 1", "derived", "ratio", "clusters", "ratio", "bfg 1",
                 "stored 4", "derived", "ratio", "clusters", "ratio", "bfg 4");
    for (const SkinPlanesResult &r : results) {
        auto row = [&](const char *what) { return find_variant_row(r.rows, what, ""); };
        auto ratio = [&](const char *a, const char *b) {
            char buf[16] = "-";
            const SkinPlanesRow *x = row(a), *y = row(b);
            if (x && y && y->t.median > 0) {
                std::snprintf(buf, sizeof buf, "%.2f", x->t.median / y->t.median);
            }
            return std::string(buf);
        };
        std::fprintf(out, "%-22s %9d %8s %8s %8s %8s %8s %8s %8s %8s %8s %8s %8s %8s\n",
                     r.name.c_str(), r.triangles,
                     ticks_cell(row("job_stored_1"), r.triangles).c_str(),
                     ticks_cell(row("job_derived_1"), r.triangles).c_str(),
                     ratio("job_derived_1", "job_stored_1").c_str(),
                     ticks_cell(row("job_clustered_1"), r.triangles).c_str(),
                     ratio("job_clustered_1", "job_stored_1").c_str(),
                     ticks_cell(row("job_bfg_1"), r.triangles).c_str(),
                     ticks_cell(row("job_stored_4"), r.triangles).c_str(),
                     ticks_cell(row("job_derived_4"), r.triangles).c_str(),
                     ratio("job_derived_4", "job_stored_4").c_str(),
                     ticks_cell(row("job_clustered_4"), r.triangles).c_str(),
                     ratio("job_clustered_4", "job_stored_4").c_str(),
                     ticks_cell(row("job_bfg_4"), r.triangles).c_str());
    }
    std::fprintf(out, "  ratio: derived (or clusters) / stored, same run\n");
    print_crossover(out, results);
}

/* Where deriving the planes once per frame (then facing from the planes
 * per light) beats BFG's facing from the positions per light: the ratio
 * derived / bfg at 1 to 4 lights a frame, and the first light count at
 * which it drops below 1. By the minimum of each row's calls, not the
 * median: the crossover is a comparison of two costs, and the minimum is
 * the one least moved by whatever else the machine runs. */
void print_crossover(FILE *out, const std::vector<SkinPlanesResult> &results) {
    std::fprintf(out, "\nlights per frame: the per-light job with planes derived once (the "
                      "planned variant) against BFG's facing from positions per light, ticks "
                      "per triangle per frame (minimum of the calls; every volume checked)\n"
                      "  ratio derived/bfg below 1: deriving the planes once pays; from: the "
                      "fewest lights a frame from which it does at every count up to 4 "
                      "(- : not at 4)\n");
    std::fprintf(out, "%-22s %9s", "character", "triangles");
    for (int k = 1; k <= 4; k++) std::fprintf(out, "  derived %d   bfg %d  ratio", k, k);
    std::fprintf(out, "  %4s\n", "from");
    for (const SkinPlanesResult &r : results) {
        auto row = [&](const std::string &what) { return find_variant_row(r.rows, what, ""); };
        auto cell = [&](const SkinPlanesRow *x) {
            char buf[32] = "-";
            if (x) {
                std::snprintf(buf, sizeof buf, "%.2f%s", x->t.min / std::max(1, r.triangles),
                              x->t.ok ? "" : " FAIL");
            }
            return std::string(buf);
        };
        std::fprintf(out, "%-22s %9d", r.name.c_str(), r.triangles);
        int from = 0;
        for (int k = 1; k <= 4; k++) {
            const std::string n = std::to_string(k);
            const SkinPlanesRow *d = row("job_derived_" + n), *b = row("job_bfg_" + n);
            char ratio[16] = "-";
            if (d && b && b->t.min > 0) {
                const double q = d->t.min / b->t.min;
                std::snprintf(ratio, sizeof ratio, "%.2f", q);
                if (q >= 1.0)
                    from = 0;
                else if (from == 0)
                    from = k;
            }
            std::fprintf(out, "  %9s %5s %6s", cell(d).c_str(), cell(b).c_str(), ratio);
        }
        std::fprintf(out, "  %4s\n", from ? std::to_string(from).c_str() : "-");
    }
}

void skin_planes_json(JsonWriter &j, const std::vector<SkinPlanesResult> &results) {
    j.key("skinned");
    j.begin_array();
    for (const SkinPlanesResult &r : results) {
        j.begin_object();
        j.key("character");
        j.value(r.name);
        j.key("surfaces");
        j.value(r.surfaces);
        j.key("triangles");
        j.value(r.triangles);
        j.key("vertices");
        j.value(r.vertices);
        j.key("segments");
        j.value(r.segments);
        variant_rows_json(j, r.rows, std::max(1, r.triangles));
        j.end_object();
    }
    j.end_array();
}

} // namespace svbench
