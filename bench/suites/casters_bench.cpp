/*
 * `shadowvol bench --casters` (issue 27): what the general rule costs to
 * build, per triangle, against the best paper pipeline on the same mesh.
 *
 * For each mesh (the open character ../shared/models/open/Zombie_Basic.glb,
 * the nine generated open cases of src/modelgen/open_cases.h, the demo
 * scene's open terrain) and each light (auto point, spot, directional), in
 * z-pass (facing and silhouette) and z-fail (and caps), one warm,
 * in-process call of a whole volume build, timed with the serialised TSC
 * (time_seed_row: a warm-up call, then calls for a time budget; the
 * minimum and the median), for:
 *
 *   paper      the closed rule on the same mesh: the best CalculateFacing,
 *              CountFacing, CreateSilTriangles (and CreateCapTriangles)
 *              on the surface as it is (wrong off the boundary on open
 *              meshes: the floor the general rule is measured against);
 *   two-sided  the general rule the cheap way: the same routines on the
 *              two-sided caster (shadowvol_casters.h), twice the triangles;
 *   direct     the general kernels: the best CalculateFacing on the
 *              surface, sv_general_facing_from_calculated, the best
 *              general variant's silhouette (and caps) on the general edge
 *              table;
 *   direct c   the same with the general kernels' C reference.
 *
 * The caster and the table are built once per topology and not timed
 * (the volume pass keeps them); every light's planes are the surface's.
 * Ticks per triangle divide by the surface's own triangle count, for all
 * four. Every call's output is checked outside the timed region: the
 * same count as the first call, direct's list equal to direct c's, and
 * direct's and two-sided's quads and caps the same multiset of triangles
 * where the mesh has no edge of three or more triangles.
 *
 * Copyright (C) 2026 the shadowvol authors. LGPL-2.1-or-later.
 */
#include <algorithm>
#include <array>
#include <map>
#include <string>
#include <vector>

#include "json_writer.h"
#include "open_cases.h"
#include "seed_bench.h"
#include "shadowvol.h"
#include "shadowvol_casters.h"
#include "shadowvol_scene.h"

#ifndef SV_DEMO_SCENE
#define SV_DEMO_SCENE "models/demo_scene.glb"
#endif

namespace svbench {

namespace {

enum Pipeline { kPaper, kTwoSided, kDirect, kDirectC, kNumPipelines };
const char *const kPipelineNames[kNumPipelines] = {"paper", "two-sided", "direct", "direct c"};

/* One surface with everything each pipeline keeps from frame to frame. */
struct Caster {
    sv::PreparedSurface surface;
    std::shared_ptr<sv::PreparedSurface> two_sided; /* nullptr: every shell closed */
    sv::GeneralEdgeTable table;
};

struct Mesh {
    std::string name;
    std::vector<Caster> casters;
    std::vector<std::pair<std::string, Vec4>> lights; /* kind, shadow light */
    int triangles = 0;
    bool shared_edges = false; /* some edge of 3+ triangles or run twice one way */
};

/* The buffers of one pipeline's build of every surface. */
struct Buffers {
    std::vector<sv::AlignedVector<uint8_t>> facing, general;
    std::vector<sv::AlignedVector<int>> out;
    std::vector<int> counts;
};

Mesh make_mesh(const std::string &name, const sv::Scene &scene) {
    Mesh m;
    m.name = name;
    for (const sv::SceneSurface &s : scene.surfaces) {
        Caster c;
        c.surface = s.prepared;
        const sv::ShellMap shells = sv::find_shells(c.surface);
        c.two_sided = sv::two_sided_caster(c.surface, shells, sv::CasterRule::automatic);
        c.table = sv::general_edge_table(c.surface, shells, sv::CasterRule::automatic);
        m.shared_edges = m.shared_edges || !c.table.shared.empty();
        m.triangles += c.surface.num_triangles();
        m.casters.push_back(std::move(c));
    }
    for (sv::LightKind k :
         {sv::LightKind::point, sv::LightKind::spot, sv::LightKind::directional}) {
        const sv::SceneLight l = sv::auto_light(scene, k);
        m.lights.emplace_back(k == sv::LightKind::point  ? "point"
                              : k == sv::LightKind::spot ? "spot"
                                                         : "dir",
                              l.shadow_light());
    }
    return m;
}

/* One build of every surface of M by pipeline P under light L; caps when
 * ZFAIL. Returns the indices written. */
int build(Pipeline p, const Mesh &m, const Vec4 &L, bool zfail, Buffers &b) {
    const sv_facing_variant *fv = sv_best_facing_variant();
    const sv_variant *v = sv_best_variant();
    const sv_general_variant *gv = p == kDirectC ? sv_general_variant_by_name("c_ref")
                                                 : sv_best_general_variant();
    int total = 0;
    for (std::size_t i = 0; i < m.casters.size(); i++) {
        const Caster &c = m.casters[i];
        const bool general = c.table.general_triangles > 0;
        const sv::PreparedSurface &s = p == kTwoSided && c.two_sided ? *c.two_sided : c.surface;
        const int n = s.num_triangles();
        uint8_t *facing = b.facing[i].data();
        int *out = b.out[i].data();
        int k = 0;
        b.counts[i] = 0;
        fv->calculate_facing(s.planes.data(), n, &L, facing);
        if ((p == kDirect || p == kDirectC) && general) {
            uint8_t *g = b.general[i].data();
            if (sv_general_facing_from_calculated(g, facing, c.table.lit_byte.data(), n) == 0)
                continue;
            const sv_general_edges e = c.table.view();
            k = gv->create_general_sil_triangles(out, g, &e);
            if (zfail)
                k += gv->create_general_cap_triangles(out + k, g, s.indices.data(),
                                                      s.num_indices());
        } else {
            if (v->count_facing(facing, n) == n) continue; /* nothing casts */
            k = v->create_sil_triangles(out, facing, s.sil_edges.data(), s.num_sil_edges());
            if (zfail)
                k += v->create_cap_triangles(out + k, facing, s.indices.data(), s.num_indices());
        }
        b.counts[i] = k;
        total += k;
    }
    return total;
}

Buffers make_buffers(Pipeline p, const Mesh &m) {
    Buffers b;
    for (const Caster &c : m.casters) {
        const sv::PreparedSurface &s = p == kTwoSided && c.two_sided ? *c.two_sided : c.surface;
        sv::AlignedVector<uint8_t> f((std::size_t)s.num_triangles() + 1, 1);
        b.facing.push_back(f);
        b.general.push_back(f);
        const std::size_t sil = std::max((std::size_t)6 * s.sil_edges.size(),
                                         c.table.sil_capacity());
        b.out.emplace_back(sil + 2 * (std::size_t)s.num_indices() + 16);
    }
    b.counts.assign(m.casters.size(), 0);
    return b;
}

/* The triangles of a list as a multiset, each rotated to start at its
 * smallest index (the two builds may start a triangle at another corner
 * only through the order of the quads, never within one; this is just
 * robust). */
std::map<std::array<int, 3>, int> triangles_of(const Buffers &b) {
    std::map<std::array<int, 3>, int> t;
    for (std::size_t i = 0; i < b.out.size(); i++) {
        for (int k = 0; k + 2 < b.counts[i]; k += 3) {
            std::array<int, 3> x = {b.out[i][(std::size_t)k], b.out[i][(std::size_t)k + 1],
                                    b.out[i][(std::size_t)k + 2]};
            std::rotate(x.begin(), std::min_element(x.begin(), x.end()), x.end());
            t[x]++;
        }
    }
    return t;
}

struct Row {
    std::string mesh, light;
    int triangles = 0;
    bool zfail = false;
    SeedTiming t[kNumPipelines];
    int indices[kNumPipelines] = {};
};

std::vector<Mesh> meshes(const SeedCommand &cmd, FILE *out) {
    std::vector<Mesh> ms;
    const std::string character = cmd.sharedModels + "/open/Zombie_Basic.glb";
    try {
        sv::Scene scene;
        sv::add_model(scene, character, {});
        ms.push_back(make_mesh("Zombie_Basic (open character)", scene));
    } catch (const std::exception &e) {
        std::fprintf(out, "skipped   %s: %s\n", character.c_str(), e.what());
    }
    for (const svgen::Soup &soup : svgen::open_cases()) {
        sv::Scene scene;
        sv::SceneSurface s;
        s.name = soup.name;
        s.prepared = sv::prepare_surface(soup.pos.data(), soup.pos.size() / 3, soup.idx.data(),
                                         soup.idx.size());
        sv::update_bounds(s);
        scene.surfaces.push_back(std::move(s));
        ms.push_back(make_mesh(soup.name, scene));
    }
    try {
        sv::Scene demo;
        sv::add_model(demo, SV_DEMO_SCENE, {});
        /* The terrain: the largest surface with an open shell. */
        int best = -1;
        for (int i = 0; i < (int)demo.surfaces.size(); i++) {
            const sv::ShellMap sh = sv::find_shells(demo.surfaces[(std::size_t)i].prepared);
            if (sh.closed_shells() == (int64_t)sh.shells.size()) continue;
            if (best < 0 || demo.surfaces[(std::size_t)i].prepared.num_triangles() >
                                demo.surfaces[(std::size_t)best].prepared.num_triangles())
                best = i;
        }
        if (best >= 0) {
            sv::Scene terrain;
            terrain.surfaces.push_back(demo.surfaces[(std::size_t)best]);
            ms.push_back(make_mesh("demo terrain", terrain));
        }
    } catch (const std::exception &e) {
        std::fprintf(out, "skipped   %s: %s\n", SV_DEMO_SCENE, e.what());
    }
    return ms;
}

std::string casters_json(const std::vector<Row> &rows, const SeedTimer &timer) {
    JsonWriter j;
    j.begin_object();
    seed_json_header(j, "shadowvol-casters-bench/1", timer);
    j.key("variants");
    j.begin_object(true);
    j.key("facing");
    j.value(sv_best_facing_variant()->name);
    j.key("paper");
    j.value(sv_best_variant()->name);
    j.key("general");
    j.value(sv_best_general_variant()->name);
    j.end_object();
    j.key("rows");
    j.begin_array();
    for (const Row &r : rows) {
        j.begin_object();
        j.key("mesh");
        j.value(r.mesh);
        j.key("light");
        j.value(r.light);
        j.key("mode");
        j.value(r.zfail ? "zfail" : "zpass");
        j.key("triangles");
        j.value(r.triangles);
        j.key("pipelines");
        j.begin_array();
        for (int p = 0; p < kNumPipelines; p++) {
            j.begin_object(true);
            seed_json_row(j, "volume", kPipelineNames[p], r.t[p]);
            j.key("indices");
            j.value(r.indices[p]);
            j.key("min_ticks_per_triangle");
            j.value(r.t[p].min / std::max(1, r.triangles));
            j.key("ok");
            j.value(r.t[p].ok);
            if (!r.t[p].ok) {
                j.key("failure");
                j.value(r.t[p].failure);
            }
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

int run_casters_bench(const SeedCommand &cmd) {
    return run_seed_frame(cmd, "casters", [&](FILE *out, std::string *doc) {
        const int cpu = pin_to_current_cpu();
        SeedTimer timer = make_seed_timer(cmd.timer, cmd.quick);
        timer.budget = cmd.quick ? 0.02 : 0.1;
        print_seed_header(out,
                          "shadowvol bench --casters: the general rule's volume builders against "
                          "the best paper pipeline (issue 27)",
                          timer, cpu);
        std::fprintf(out, "variants  facing %s, paper %s, general %s\n",
                     sv_best_facing_variant()->name, sv_best_variant()->name,
                     sv_best_general_variant()->name);
        std::vector<Row> rows;
        int failed = 0;
        for (const Mesh &m : meshes(cmd, out)) {
            for (const auto &light : m.lights) {
                if (cmd.quick && light.first != "point") continue;
                for (bool zfail : {false, true}) {
                    Row r;
                    r.mesh = m.name, r.light = light.first, r.triangles = m.triangles;
                    r.zfail = zfail;
                    std::map<std::array<int, 3>, int> two_sided_tris, direct_tris;
                    std::vector<int> direct_c_list;
                    for (int p = 0; p < kNumPipelines; p++) {
                        Buffers b = make_buffers((Pipeline)p, m);
                        const int first = build((Pipeline)p, m, light.second, zfail, b);
                        r.indices[p] = first;
                        auto flat = [&] {
                            std::vector<int> l;
                            for (std::size_t i = 0; i < b.out.size(); i++)
                                l.insert(l.end(), b.out[i].begin(), b.out[i].begin() + b.counts[i]);
                            return l;
                        };
                        if (p == kDirectC) direct_c_list = flat();
                        if (p == kTwoSided) two_sided_tris = triangles_of(b);
                        if (p == kDirect) direct_tris = triangles_of(b);
                        const std::vector<int> first_list = flat();
                        r.t[p] = time_seed_row(
                            timer, [&](int) { build((Pipeline)p, m, light.second, zfail, b); },
                            [&](int) -> std::string {
                                return flat() == first_list ? ""
                                                            : "a different list than its first";
                            });
                    }
                    /* direct against its C reference, and against two-sided. */
                    std::vector<int> direct_list;
                    {
                        Buffers b = make_buffers(kDirect, m);
                        build(kDirect, m, light.second, zfail, b);
                        for (std::size_t i = 0; i < b.out.size(); i++)
                            direct_list.insert(direct_list.end(), b.out[i].begin(),
                                               b.out[i].begin() + b.counts[i]);
                    }
                    if (direct_list != direct_c_list) {
                        r.t[kDirect].ok = false;
                        r.t[kDirect].failure = "its list differs from the C reference's";
                    } else if (!m.shared_edges && direct_tris != two_sided_tris) {
                        r.t[kDirect].ok = false;
                        r.t[kDirect].failure = "its triangles differ from two-sided's";
                    }
                    for (const SeedTiming &t : r.t) failed += !t.ok;
                    rows.push_back(r);
                }
            }
        }
        std::fprintf(out,
                     "\nmin TSC ticks per triangle of a whole volume build (facing, silhouette; "
                     "z-fail: and caps), warm\n");
        std::fprintf(out, "%-30s %-5s %-5s %7s | %8s %9s %8s %8s | %11s %13s\n", "mesh", "light",
                     "mode", "tris", "paper", "two-sided", "direct", "direct c", "direct/paper",
                     "direct/2-sided");
        for (const Row &r : rows) {
            const double tri = std::max(1, r.triangles);
            const double pa = r.t[kPaper].min / tri, ts = r.t[kTwoSided].min / tri,
                         di = r.t[kDirect].min / tri, dc = r.t[kDirectC].min / tri;
            std::fprintf(out, "%-30s %-5s %-5s %7d | %8.2f %9.2f %8.2f %8.2f | %11.2fx %13.2fx\n",
                         r.mesh.c_str(), r.light.c_str(), r.zfail ? "zfail" : "zpass", r.triangles,
                         pa, ts, di, dc, di / std::max(pa, 1e-9), di / std::max(ts, 1e-9));
        }
        for (const Row &r : rows)
            for (int p = 0; p < kNumPipelines; p++)
                if (!r.t[p].ok)
                    std::fprintf(out, "FAILED %s %s %s %s: %s\n", r.mesh.c_str(), r.light.c_str(),
                                 r.zfail ? "zfail" : "zpass", kPipelineNames[p],
                                 r.t[p].failure.c_str());
        *doc = casters_json(rows, timer);
        return failed;
    });
}

} // namespace svbench
