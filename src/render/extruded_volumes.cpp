/*
 * Seed 002's shadow volumes in the frame (extruded_volumes.h): the shadow
 * meshes under the frame's caster rule, the vertex program per (light,
 * surface), its output written in the paper's vertex numbering.
 *
 * Copyright (C) 2026 the shadowvol authors. LGPL-2.1-or-later.
 */
#include "extruded_volumes.h"

#include <cmath>
#include <memory>
#include <stdexcept>

#include "frame_math.h"
#include "pass_bins.h"
#include "shadowvol_casters.h"

namespace sv::render {

using namespace detail;

const char *volume_source_name(VolumeSource v) {
    return v == VolumeSource::extrude ? "extrude" : "silhouette";
}

bool volume_source_by_name(const std::string &name, VolumeSource &out) {
    if (name == "silhouette") {
        out = VolumeSource::silhouette;
        return true;
    }
    if (name == "extrude") {
        out = VolumeSource::extrude;
        return true;
    }
    return false;
}

sv_extrude_light extrude_light_for(const SceneLight &light, bool to_infinity) {
    sv_extrude_light l{};
    l.position = light.shadow_light();
    /* Range 0 is "unlimited" in both conventions; a range too large for a
     * float is unlimited too. */
    const double r = light.range;
    l.range = to_infinity || !(r > 0) || !(r < 3.0e38) ? 0.0f : (float)r;
    return l;
}

Volume extruded_volume(const PreparedSurface &caster, const ShadowMesh &mesh,
                       const sv_extrude_light &light, const sv_extrude_variant *variant,
                       uint64_t *program_ticks, const ExtrudeProgram &program) {
    const int n = mesh.num_vertices();
    if (n != 3 * caster.num_triangles()) {
        throw std::logic_error("extruded_volume: the shadow mesh is not the caster's");
    }
    AlignedVector<Vec4> out((std::size_t)n);
    const uint64_t k0 = ticks();
    if (!program || !program(mesh, light, out.data()))
        variant->extrude(mesh.stream.data(), n, &light, out.data());
    if (program_ticks) *program_ticks = ticks() - k0;
    Volume vol;
    vol.zfail = true; /* the seed's: z-fail, the whole mesh */
    vol.silhouette_indices = 0;
    vol.extruded.assign((std::size_t)caster.num_vertices(), Vec4{0, 0, 0, 0});
    std::vector<int> number((std::size_t)n);
    for (int j = 0; j < n; j++) {
        const int v = caster.indices[(std::size_t)j];
        const float *p = mesh.stream.data() + (std::size_t)j * SV_EXTRUDE_STREAM_FLOATS;
        const Vec4 &o = out[(std::size_t)j];
        /* Kept: (p, 1) exactly (the program's selection is exact), the
         * paper's vertex 2v, which the receiver's triangles use. A vertex
         * the finite extrusion leaves where it is (at or beyond the range)
         * is the same point: 2v too. */
        const bool kept = o.w == 1.0f && o.x == p[0] && o.y == p[1] && o.z == p[2];
        number[(std::size_t)j] = kept ? 2 * v : 2 * v + 1;
        if (!kept) vol.extruded[(std::size_t)v] = o;
    }
    vol.indices.resize(mesh.indices.size());
    for (std::size_t i = 0; i < mesh.indices.size(); i++) {
        vol.indices[i] = number[(std::size_t)mesh.indices[i]];
    }
    return vol;
}

void use_extruded_volumes(const Scene &scene, const RenderOptions &opt,
                          std::vector<LightFrame> &lights) {
    const int num_surfaces = (int)scene.surfaces.size(), num_lights = (int)lights.size();
    /* Where the paper's pass drew a volume. Not where nothing casts
     * (no_shadow): a closed surface's seed volume is then the surface
     * itself, which counts 0 at every pixel it shows (z-fail counts its
     * own triangle as behind: the count of a point just in front of it),
     * and an open one (the ground under its hint) would be the seed's
     * "not a closed volume", its near cap alone. */
    auto drawn = [](VolumeFate f) { return f == VolumeFate::built || f == VolumeFate::reused; };
    /* Each surface some light needs: its caster under the rule (a
     * two-sided caster keeps the surface's vertex numbers) and its shadow
     * mesh. */
    std::vector<uint8_t> needed((std::size_t)num_surfaces, 0);
    for (const LightFrame &lf : lights) {
        for (int si = 0; si < num_surfaces; si++)
            needed[(std::size_t)si] |= drawn(lf.decisions[(std::size_t)si].fate);
    }
    std::vector<std::shared_ptr<PreparedSurface>> two_sided((std::size_t)num_surfaces);
    std::vector<ShadowMesh> meshes((std::size_t)num_surfaces);
    parallel(num_surfaces, [&](int si) {
        if (!needed[(std::size_t)si]) return;
        const SceneSurface &s = scene.surfaces[(std::size_t)si];
        /* No ground hint: it lets the paper's volume, whose near cap is
         * the faces turned away from the light, stand for a surface open
         * below; the seed's near cap is the faces turned to the light, so
         * an open surface's seed volume is closed only by the general
         * rule (measured on the demo terrain under its hint: 141 pixels
         * wrong of a spot light's 160x120 frame). */
        const CasterRule rule = surface_caster_rule(opt.caster_rule, false);
        two_sided[(std::size_t)si] = two_sided_caster(s.prepared, find_shells(s.prepared), rule);
        const PreparedSurface &caster = two_sided[(std::size_t)si] ? *two_sided[(std::size_t)si]
                                                                   : s.prepared;
        meshes[(std::size_t)si] = build_shadow_mesh(caster);
        if (opt.shadow_mesh_hook) opt.shadow_mesh_hook(si, caster, meshes[(std::size_t)si]);
    });
    const sv_extrude_variant *variant = sv_best_extrude_variant();
    std::vector<Volume> job_volume((std::size_t)num_lights * (std::size_t)num_surfaces);
    std::vector<uint64_t> job_ticks(job_volume.size(), 0);
    parallel(num_lights * num_surfaces, [&](int job) {
        const int li = job / num_surfaces, si = job % num_surfaces;
        const LightFrame &lf = lights[(std::size_t)li];
        if (!drawn(lf.decisions[(std::size_t)si].fate)) return;
        const SceneSurface &s = scene.surfaces[(std::size_t)si];
        const PreparedSurface &caster = two_sided[(std::size_t)si] ? *two_sided[(std::size_t)si]
                                                                   : s.prepared;
        ExtrudeProgram program;
        if (opt.extrude_program) {
            program = [&opt, si](const ShadowMesh &m, const sv_extrude_light &l, Vec4 *out) {
                return opt.extrude_program(si, m, l, out);
            };
        }
        Volume vol = extruded_volume(caster, meshes[(std::size_t)si],
                                     extrude_light_for(lf.light, opt.extrude_to_infinity), variant,
                                     &job_ticks[(std::size_t)job], program);
        vol.surface = si;
        job_volume[(std::size_t)job] = std::move(vol);
    });
    for (int li = 0; li < num_lights; li++) {
        LightFrame &lf = lights[(std::size_t)li];
        lf.volumes.clear();
        lf.zfail_volumes = 0;
        lf.indices = lf.drawn_indices = 0;
        for (int si = 0; si < num_surfaces; si++) {
            const std::size_t job = (std::size_t)li * (std::size_t)num_surfaces + (std::size_t)si;
            VolumeDecision &d = lf.decisions[(std::size_t)si];
            Volume &vol = job_volume[job];
            lf.ticks_extrude += job_ticks[job];
            if (vol.indices.empty()) continue;
            d.zfail = true;
            d.cull_bits = false;
            d.dark_cap_dropped = false;
            d.indices_drawn = vol.drawn_indices();
            lf.zfail_volumes++;
            lf.indices += (int64_t)vol.indices.size();
            lf.drawn_indices += vol.drawn_indices();
            lf.volumes.push_back(std::move(vol));
        }
    }
}

} // namespace sv::render
