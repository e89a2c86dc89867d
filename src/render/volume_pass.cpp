/*
 * The volume pass of volume_pass.h: per (light, surface) job, the
 * shortcuts' decisions, then the facing, culling and volume routines of
 * the library (or the cached volume), in parallel over the jobs.
 *
 * Copyright (C) 2026 the shadowvol authors. LGPL-2.1-or-later.
 */
#include "volume_pass.h"

#include <algorithm>
#include <array>
#include <cstring>
#include <memory>
#include <vector>

#include "frame_math.h"
#include "pass_bins.h"
#include "reach.h"

namespace sv::render {

using namespace detail;

namespace {

/* The cache's key compares bits, not values: any change of a light or its
 * planes, -0 against +0 included, rebuilds the volume. Vec4 and Plane are
 * four floats with no padding. */
template <class T> bool same_bits(const T &a, const T &b) {
    return std::memcmp(&a, &b, sizeof a) == 0; // NOLINT(bugprone-suspicious-memory-comparison)
}

/* The rule surface S's volumes follow: a declared ground keeps the
 * paper's rule under auto, unless the hints are ignored. */
CasterRule surface_rule(const VolumePassInputs &in, const SceneSurface &s) {
    return surface_caster_rule(in.caster_rule, in.ground_hints && s.declared_ground);
}

} // namespace

/* What a (light, surface) pair keeps from frame to frame. */
struct VolumeCache::Entry {
    bool valid = false;
    /* The key: the surface's revision, the light, the kernels and the
     * shortcuts that shape the result. */
    uint64_t revision = 0;
    Vec4 light{};
    Plane planes[SV_NUM_LIGHT_PLANES]{};
    bool has_planes = false;
    const sv_variant *variant = nullptr;
    const sv_facing_variant *facing_variant = nullptr;
    unsigned config = 0;
    /* The volume. */
    AlignedVector<uint8_t> facing;        /* calculate_facing's bytes: the lighting pass's */
    AlignedVector<uint8_t> volume_facing; /* after culling */
    bool straddles = false, cull_bits = false;
    int casting = 0; /* triangles that cast */
    AlignedVector<int> sil, caps;
    int sil_count = -1, caps_count = -1; /* -1: not built yet */
    bool dark_cap_dropped = false;
};

/* What a surface keeps from frame to frame: its shells and the mesh its
 * volumes are built from (nullptr: the surface itself). */
struct VolumeCache::CasterEntry {
    bool valid = false;
    uint64_t revision = 0;
    CasterRule rule = CasterRule::automatic;
    GeneralBuild build = GeneralBuild::direct;
    std::shared_ptr<PreparedSurface> caster;   /* two-sided */
    std::shared_ptr<GeneralEdgeTable> general; /* direct */
    /* The surface's triangles when no two-sided caster was made (to tell a
     * moved surface from a new one without sorting again). */
    std::vector<int> indices;
};

VolumeCache::VolumeCache()
    : entries_(new std::vector<Entry>), casters_(new std::vector<CasterEntry>) {}
VolumeCache::~VolumeCache() {
    delete entries_;
    delete casters_;
}
void VolumeCache::clear() {
    entries_->clear();
    casters_->clear();
    lights = surfaces = 0;
}

void VolumeCache::fit(int num_lights, int num_surfaces) {
    if (lights == num_lights && surfaces == num_surfaces) return;
    clear();
    lights = num_lights;
    surfaces = num_surfaces;
    entries_->resize((std::size_t)num_lights * (std::size_t)num_surfaces);
    casters_->resize((std::size_t)num_surfaces);
}

uint64_t volume_pass(const VolumePassInputs &in, VolumeCache &cache,
                     std::vector<LightFrame> &lights) {
    const Scene &scene = *in.scene;
    const Shortcuts &sc = in.shortcuts;
    const ShortcutFaults &fault = in.faults;
    const sv_variant *variant = in.variant;
    const sv_facing_variant *facing_v = in.facing;
    const double aspect = in.aspect;
    const int num_surfaces = (int)scene.surfaces.size(), num_lights = (int)scene.lights.size();
    cache.fit(num_lights, num_surfaces);
    lights.resize((std::size_t)num_lights);
    std::vector<std::array<uint64_t, 3>> job_ticks((std::size_t)num_lights * num_surfaces);
    std::vector<Volume> job_volume((std::size_t)num_lights * num_surfaces);
    for (int li = 0; li < num_lights; li++) {
        LightFrame &lf = lights[(std::size_t)li];
        lf.light = scene.lights[(std::size_t)li];
        lf.shadow_light = lf.light.shadow_light();
        lf.decisions.resize((std::size_t)num_surfaces);
    }
    const uint64_t k_jobs = ticks();
    /* Each surface's caster under the rule: the surface itself where
     * every shell keeps the paper's rule (closed shells under auto: no
     * extra work at all), else either the surface with its general shells
     * made two-sided, or its general edge table for the direct kernels
     * (shadowvol_casters.h). Kept while the surface stands. */
    parallel(num_surfaces, [&](int si) {
        const SceneSurface &s = scene.surfaces[(std::size_t)si];
        VolumeCache::CasterEntry &c = cache.casters()[(std::size_t)si];
        /* A declared ground keeps the paper's rule under auto. */
        const CasterRule rule = surface_rule(in, s);
        const bool same_rule = c.valid && c.rule == rule && c.build == in.general_build;
        if (same_rule && c.revision == s.revision) return;
        /* The same triangles moved (a posed skin): the shells and their
         * rules stay as decided on the first pose (find_shells sorts; a
         * frame should not); only the positions and planes follow (the
         * general edge table has none). */
        const bool same_topology = same_rule &&
                                   (c.caster ? two_sided_caster_fits(s.prepared, *c.caster)
                                             : c.indices.size() == s.prepared.indices.size() &&
                                                   std::equal(c.indices.begin(), c.indices.end(),
                                                              s.prepared.indices.begin()));
        c.valid = true;
        c.revision = s.revision;
        c.rule = rule;
        c.build = in.general_build;
        if (same_topology) {
            if (c.caster) refresh_two_sided_caster(s.prepared, *c.caster);
            return;
        }
        c.caster = nullptr;
        c.general = nullptr;
        if (rule != CasterRule::closed) {
            const ShellMap shells = find_shells(s.prepared);
            if (in.general_build == GeneralBuild::two_sided)
                c.caster = two_sided_caster(s.prepared, shells, rule);
            else if (auto t = std::make_shared<GeneralEdgeTable>(
                         general_edge_table(s.prepared, shells, rule));
                     t->general_triangles > 0)
                c.general = std::move(t); /* else the paper's routines, as they are */
        }
        if (c.caster)
            c.indices.clear();
        else
            c.indices.assign(s.prepared.indices.begin(), s.prepared.indices.end());
    });
    parallel(num_lights * num_surfaces, [&](int job) {
        const int li = job / num_surfaces, si = job % num_surfaces;
        LightFrame &lf = lights[(std::size_t)li];
        const SceneSurface &s = scene.surfaces[(std::size_t)si];
        const VolumeCache::CasterEntry &caster = cache.casters()[(std::size_t)si];
        /* The caster's first triangles are the surface's: its facing bytes
         * serve the lighting pass as the surface's own. */
        const PreparedSurface &p = caster.caster ? *caster.caster : s.prepared;
        const GeneralEdgeTable *general = caster.general.get();
        const SceneLight &light = lf.light;
        const Vec4 L = lf.shadow_light;
        VolumeDecision &d = lf.decisions[(std::size_t)si];
        VolumeCache::Entry &e = cache.entries()[(std::size_t)job];
        auto &tk = job_ticks[(std::size_t)job];
        d.surface = si;
        d.general_rule = caster.caster != nullptr || general != nullptr;
        /* 1 and 2: no volume at all. */
        if (sc.light_reach && !light_reaches_box(light, s.lo, s.hi, fault.light_reach_scale)) {
            d.fate = VolumeFate::out_of_reach;
            e.valid = false;
            return;
        }
        if (sc.view_reach &&
            !shadow_may_reach_view(in.view_proj, s.lo, s.hi, L, !fault.view_reach_no_extrusion)) {
            d.fate = VolumeFate::out_of_view;
            return; /* the entry stays for a later frame */
        }
        Plane planes[SV_NUM_LIGHT_PLANES];
        const bool has_planes = (sc.cull_straddling || sc.cull_always) &&
                                light_volume_planes(light, planes,
                                                    fault.cull_inside_planes ? 0.5 : 1.0);
        const bool dark_drop = (sc.no_directional_dark_cap &&
                                light.kind == LightKind::directional) ||
                               fault.drop_dark_cap_always;
        const unsigned config = (sc.cull_straddling ? 1u : 0u) | (dark_drop ? 2u : 0u) |
                                (fault.cull_inside_planes ? 4u : 0u) | (sc.cull_always ? 8u : 0u) |
                                ((unsigned)surface_rule(in, s) << 4) |
                                ((unsigned)in.general_build << 6);
        const bool same_light = e.valid && same_bits(e.light, L) && e.has_planes == has_planes &&
                                (!has_planes || same_bits(e.planes, planes));
        const bool reuse = sc.reuse_static && e.valid && same_light && e.variant == variant &&
                           e.facing_variant == facing_v && e.config == config &&
                           (e.revision == s.revision || fault.reuse_ignores_motion);
        if (!reuse) {
            e = VolumeCache::Entry{};
            e.valid = true;
            e.revision = s.revision;
            e.light = L;
            e.has_planes = has_planes;
            if (has_planes) std::memcpy(e.planes, planes, sizeof planes);
            e.variant = variant;
            e.facing_variant = facing_v;
            e.config = config;
            const int n = p.num_triangles();
            e.facing.assign((std::size_t)n + 1, 1);
            uint64_t k0 = ticks();
            facing_v->calculate_facing(p.planes.data(), n, &L, e.facing.data());
            tk[0] += ticks() - k0;
            if (general) {
                /* The general bytes (shadowvol.h): 0 casts, 1 nothing, 2
                 * its reverse casts; the sentinel stays 1 for the paper's
                 * class. */
                e.volume_facing.assign((std::size_t)n + 1, SV_GENERAL_NONE);
                e.casting = sv_general_facing_from_calculated(e.volume_facing.data(),
                                                              e.facing.data(),
                                                              general->lit_byte.data(), n);
            } else {
                e.volume_facing = e.facing;
            }
            tk[0] += ticks() - k0;
            k0 = ticks();
            if (has_planes) {
                const BoxSide side = classify_box(planes, s.lo, s.hi);
                e.straddles = side != BoxSide::inside;
                if (e.straddles || sc.cull_always) {
                    /* 3: the culling routine, only here. */
                    const std::vector<Vec4> pos = positions_vec4(p);
                    const Vec3d c = mul(add(s.lo, s.hi), 0.5), x = mul(sub(s.hi, s.lo), 0.5);
                    const Bounds bounds{{(float)c.x, (float)c.y, (float)c.z, 1},
                                        {(float)x.x * (1 + 1e-6f), (float)x.y * (1 + 1e-6f),
                                         (float)x.z * (1 + 1e-6f), 0}};
                    AlignedVector<uint8_t> bits((std::size_t)p.num_vertices() + 1, 0);
                    const int inside = facing_v->calculate_cull_bits(pos.data(), p.num_vertices(),
                                                                     &bounds, planes, bits.data());
                    if (!inside || sc.cull_always) {
                        /* (cull_always: bits all 0 where the routine
                         * found the box inside, as it leaves them.) */
                        e.cull_bits = true;
                        e.casting = general ? sv_general_cull_c_ref(e.volume_facing.data(), n,
                                                                    p.indices.data(), bits.data())
                                            : n - variant->count_facing_cull(e.volume_facing.data(),
                                                                             n, p.indices.data(),
                                                                             bits.data());
                    }
                }
            }
            tk[1] += ticks() - k0;
            k0 = ticks();
            if (!e.cull_bits && !general)
                e.casting = n - variant->count_facing(e.volume_facing.data(), n);
            tk[2] += ticks() - k0;
        }
        d.fate = reuse ? VolumeFate::reused : VolumeFate::built;
        d.straddles = e.straddles;
        d.cull_bits = e.cull_bits;
        if (e.casting == 0) {
            if (!reuse) d.fate = VolumeFate::no_shadow;
            return;
        }
        /* 4: caps only for z-fail. */
        bool zfail;
        if (in.mode == ModeChoice::zpass) {
            zfail = false;
        } else if (in.mode == ModeChoice::zfail || !sc.zpass_when_safe) {
            zfail = true;
        } else {
            zfail = !fault.zpass_always &&
                    near_plane_may_be_shadowed(scene.camera, aspect, s, light);
        }
        const uint64_t k0 = ticks();
        if (e.sil_count < 0) {
            if (general) {
                const sv_general_edges edges = general->view();
                e.sil.resize(general->sil_capacity() + 8);
                e.sil_count = in.general_variant->create_general_sil_triangles(
                    e.sil.data(), e.volume_facing.data(), &edges);
            } else {
                e.sil.resize(6 * (std::size_t)p.num_sil_edges() + 8);
                e.sil_count = variant->create_sil_triangles(e.sil.data(), e.volume_facing.data(),
                                                            p.sil_edges.data(), p.num_sil_edges());
            }
            d.indices_built += e.sil_count;
        }
        if (zfail && e.caps_count < 0) {
            e.caps.resize(2 * (std::size_t)p.num_indices() + 8);
            int n = general
                        ? in.general_variant->create_general_cap_triangles(e.caps.data(),
                                                                           e.volume_facing.data(),
                                                                           p.indices.data(),
                                                                           p.num_indices())
                        : variant->create_cap_triangles(e.caps.data(), e.volume_facing.data(),
                                                        p.indices.data(), p.num_indices());
            if (dark_drop) {
                /* 5: each cap pair is the near cap (3 indices) then the
                 * dark cap (3): keep the near ones. */
                int k = 0;
                for (int i = 0; i < n; i += 6) {
                    for (int j = 0; j < 3; j++)
                        e.caps[(std::size_t)k + j] = e.caps[(std::size_t)i + j];
                    k += 3;
                }
                n = k;
                e.dark_cap_dropped = true;
            }
            e.caps_count = n;
            d.indices_built += n;
        }
        tk[2] += ticks() - k0;
        d.zfail = zfail;
        d.dark_cap_dropped = zfail && e.dark_cap_dropped;
        Volume &vol = job_volume[(std::size_t)job];
        vol.surface = si;
        vol.zfail = zfail;
        vol.silhouette_indices = e.sil_count;
        vol.indices.assign(e.sil.begin(), e.sil.begin() + e.sil_count);
        if (zfail)
            vol.indices.insert(vol.indices.end(), e.caps.begin(), e.caps.begin() + e.caps_count);
        d.indices_drawn = vol.drawn_indices();
    });
    const uint64_t ticks_jobs = ticks() - k_jobs;
    for (int li = 0; li < num_lights; li++) {
        LightFrame &lf = lights[(std::size_t)li];
        for (int si = 0; si < num_surfaces; si++) {
            const std::size_t job = (std::size_t)li * num_surfaces + si;
            const VolumeDecision &d = lf.decisions[(std::size_t)si];
            lf.ticks_facing += job_ticks[job][0];
            lf.ticks_culling += job_ticks[job][1];
            lf.ticks_volume += job_ticks[job][2];
            lf.built += d.fate == VolumeFate::built || d.fate == VolumeFate::no_shadow;
            lf.reused += d.fate == VolumeFate::reused;
            lf.out_of_reach += d.fate == VolumeFate::out_of_reach;
            lf.out_of_view += d.fate == VolumeFate::out_of_view;
            lf.culled += d.cull_bits;
            lf.built_indices += d.indices_built;
            Volume &vol = job_volume[job];
            if (vol.indices.empty()) continue;
            lf.zfail_volumes += vol.zfail;
            lf.indices += (int64_t)vol.indices.size();
            lf.drawn_indices += vol.drawn_indices();
            lf.volumes.push_back(std::move(vol));
        }
    }
    return ticks_jobs;
}

std::vector<const uint8_t *> lit_facing(const Scene &scene, const std::vector<LightFrame> &lights,
                                        VolumeCache &cache) {
    const int num_surfaces = (int)scene.surfaces.size(), num_lights = (int)lights.size();
    std::vector<const uint8_t *> out((std::size_t)num_lights * num_surfaces, nullptr);
    for (int li = 0; li < num_lights; li++) {
        const Vec4 L = lights[(std::size_t)li].shadow_light;
        for (int si = 0; si < num_surfaces; si++) {
            const SceneSurface &s = scene.surfaces[(std::size_t)si];
            const VolumeCache::Entry &e = cache.entries()[(std::size_t)li * num_surfaces + si];
            if (light_reaches_box(scene.lights[(std::size_t)li], s.lo, s.hi) && e.valid &&
                e.revision == s.revision && same_bits(e.light, L) && !e.facing.empty()) {
                out[(std::size_t)li * num_surfaces + si] = e.facing.data();
            }
        }
    }
    return out;
}

} // namespace sv::render
