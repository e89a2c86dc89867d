/*
 * scene --skinned-normals (scene_skinned_normals.h).
 *
 * Copyright (C) 2026 the shadowvol authors. LGPL-2.1-or-later.
 */
#include "scene_skinned_normals.h"

namespace svcli {

SceneSkinnedNormals::SceneSkinnedNormals(const sv::SceneSequence &seq, sv::SkinnedNormals way)
    : seq_(seq), way_(way) {
    const int n = (int)seq.scene().surfaces.size();
    surfaces_.resize((std::size_t)n);
    for (int si = 0; si < n; si++) {
        const sv::AnimatedSurface *as = seq.animated_surface(si);
        if (!as || as->skin < 0 || !as->influences) continue;
        auto s = std::make_unique<Surface>();
        s->animated = as;
        s->data = sv::skinned_normal_data(*as);
        surfaces_[(std::size_t)si] = std::move(s);
    }
}

void SceneSkinnedNormals::apply(sv::render::RenderOptions &opt) {
    const sv::Scene &scene = seq_.scene();
    for (std::size_t si = 0; si < surfaces_.size(); si++) {
        Surface *s = surfaces_[si].get();
        if (!s) continue;
        s->frame.joint_matrices = seq_.joint_matrices((int)si);
        const auto &p = scene.surfaces[si].prepared.positions;
        s->frame.positions.assign(p.begin(), p.end());
    }
    opt.shadow_mesh_hook = [this](int si, const sv::PreparedSurface &caster, sv::ShadowMesh &mesh) {
        const Surface *s = si < (int)surfaces_.size() ? surfaces_[(std::size_t)si].get() : nullptr;
        if (!s) return;
        sv::write_caster_skinned_normals(*s->animated, s->data, s->frame, way_, caster,
                                         mesh.stream.data());
    };
    opt.extrude_program = nullptr;
    if (way_ == sv::SkinnedNormals::neighbours) {
        opt.extrude_program = [this](int si, const sv::ShadowMesh &mesh,
                                     const sv_extrude_light &light, Vec4 *out) {
            if (si >= (int)surfaces_.size() || !surfaces_[(std::size_t)si]) return false;
            sv::extrude_neighbours(sv::neighbour_stream(mesh).data(), mesh.num_vertices(), light,
                                   out);
            return true;
        };
    }
}

} // namespace svcli
