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
#include <cstring>
#include <memory>

#include <unistd.h>

#include "json_writer.h"
#include "shadowvol_anim.h"
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
    sv_skin_planes_args args{};
    std::size_t vertices() const { return as->rest_positions.size() / 3; }
};

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
        sv_skin_planes_args &g = s->args;
        g.joint_matrices = s->jm.data();
        g.rest = as.rest_positions.data();
        g.joints = as.joints.data();
        g.weights = as.weights.data();
        g.influences = as.influences;
        g.num_vertices = s->vertices();
        g.indices = p.indices.data();
        g.num_triangles = p.num_triangles();
        g.segments = (int)s->schedule.triangle_end.size();
        g.vertex_end = s->schedule.vertex_end.data();
        g.triangle_end = s->schedule.triangle_end.data();
        g.out = s->pos.data();
        g.planes = s->planes.data();
        r.surfaces++;
        r.triangles += p.num_triangles();
        r.vertices += (int)s->vertices();
        r.segments += g.segments;
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
    return r;
}

const SkinPlanesRow *find(const SkinPlanesResult &r, const std::string &what,
                          const std::string &variant) {
    for (const SkinPlanesRow &row : r.rows) {
        if (row.what == what && row.variant == variant) return &row;
    }
    return nullptr;
}

std::string per_triangle(const SkinPlanesRow *row, int triangles) {
    if (!row) return "-";
    char buf[32];
    std::snprintf(buf, sizeof buf, "%.2f%s", row->t.median / std::max(1, triangles),
                  row->t.ok ? "" : " FAIL");
    return buf;
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
            const SkinPlanesRow *sk = find(r, "skin", f->skinning);
            const SkinPlanesRow *two = find(r, "two_passes",
                                            std::string(f->skinning) + "+" + f->planes);
            char beyond[32] = "-";
            if (sk) {
                std::snprintf(beyond, sizeof beyond, "%.2f",
                              (one.t.median - sk->t.median) / std::max(1, r.triangles));
            }
            std::fprintf(out, "%-22s %9d %8d %-12s %8s %9s %9s %7s\n", r.name.c_str(), r.triangles,
                         r.vertices, one.variant.c_str(), per_triangle(sk, r.triangles).c_str(),
                         per_triangle(two, r.triangles).c_str(),
                         per_triangle(&one, r.triangles).c_str(), beyond);
        }
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
        j.key("rows");
        j.begin_array();
        for (const SkinPlanesRow &row : r.rows) {
            j.begin_object(true);
            seed_json_row(j, row.what.c_str(), row.variant, row.t);
            j.key("ok");
            j.value(row.t.ok);
            j.key("ticks_per_triangle");
            j.value(row.t.median / std::max(1, r.triangles));
            j.end_object();
        }
        j.end_array();
        j.end_object();
    }
    j.end_array();
}

} // namespace svbench
