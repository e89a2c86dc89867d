/*
 * The scene in time of sequence.h.
 *
 * Copyright (C) 2026 the shadowvol authors. LGPL-2.1-or-later.
 */
#include "sequence.h"

#include <x86intrin.h>

#include <algorithm>
#include <cmath>
#include <cstring>

namespace sv {
namespace {

bool same_light(const SceneLight &a, const SceneLight &b) {
    return a.position.x == b.position.x && a.position.y == b.position.y &&
           a.position.z == b.position.z && a.direction.x == b.direction.x &&
           a.direction.y == b.direction.y && a.direction.z == b.direction.z && a.range == b.range &&
           a.inner_degrees == b.inner_degrees && a.outer_degrees == b.outer_degrees &&
           a.intensity == b.intensity && a.color == b.color;
}

} // namespace

struct SceneSequence::Model {
    std::string path;
    AnimatedAsset asset;
    Mat4d root;
    int animation = -1;
    /* Nodes the animation moves: animated themselves or below one. */
    std::vector<char> node_moves;
    Pose pose;
    std::vector<float> scratch;
    AlignedVector<Plane> plane_scratch;
    std::vector<float> joint_scratch;
    /* Per surface of the asset: its one-pass schedule (built the first time
     * the surface is skinned with planes). */
    std::vector<SkinPlanesSchedule> schedules;
    std::vector<PlaneClusters> clusters; /* per surface, when the plan takes clusters */

    bool surface_moves(int s) const {
        const AnimatedSurface &as = asset.surfaces[(std::size_t)s];
        if (animation < 0) return false;
        if (as.skin >= 0) {
            for (int j : asset.skins[(std::size_t)as.skin].joints) {
                if (node_moves[(std::size_t)j]) return true;
            }
            return false;
        }
        return as.node_index >= 0 && node_moves[(std::size_t)as.node_index];
    }
};

SceneSequence::SceneSequence(const SequenceOptions &o)
    : skinning_(o.skinning ? o.skinning : best_skinning_kernel()),
      planes_(o.planes ? o.planes : sv_best_planes_variant()), skin_planes_(o.skin_planes),
      clustered_(o.clustered), forced_(o.skinning || o.planes || o.skin_planes || o.clustered),
      aspect_(o.aspect) {
    std::vector<ModelPlacement> files;
    files.push_back({o.file, o.placement, o.animation});
    files.insert(files.end(), o.adds.begin(), o.adds.end());
    for (std::size_t fi = 0; fi < files.size(); fi++) {
        auto m = std::make_shared<Model>();
        m->path = files[fi].path;
        m->asset = load_animated_gltf(files[fi].path);
        check_placement(files[fi].path, files[fi].placement);
        m->root = placement_matrix(files[fi].placement);
        /* Its own (the main file: --animation), else its first. */
        const std::string &wanted = files[fi].animation;
        if (!wanted.empty())
            m->animation = find_animation(m->asset, wanted); /* names the file, lists them */
        else if (!m->asset.animations.empty())
            m->animation = 0;
        m->node_moves.assign(m->asset.nodes.size(), 0);
        if (m->animation >= 0) {
            for (const AnimChannel &c : m->asset.animations[(std::size_t)m->animation].channels) {
                m->node_moves[(std::size_t)c.node] = 1;
            }
            /* Parents come before children in node_order. */
            for (int n : m->asset.node_order) {
                const int p = m->asset.nodes[(std::size_t)n].parent;
                if (p >= 0 && m->node_moves[(std::size_t)p]) m->node_moves[(std::size_t)n] = 1;
            }
        }
        for (const std::string &n : m->asset.notes) scene_.notes.push_back(n);
        if (fi == 0 && m->animation >= 0) {
            const Animation &a = m->asset.animations[(std::size_t)m->animation];
            start_ = a.start, end_ = a.end;
            animated_ = true;
            animation_name_ = a.name;
        }
        m->pose = pose_at(m->asset, m->animation,
                          m->animation >= 0 ? m->asset.animations[(std::size_t)m->animation].start
                                            : 0);
        for (std::size_t si = 0; si < m->asset.surfaces.size(); si++) {
            const AnimatedSurface &as = m->asset.surfaces[si];
            SceneSurface s;
            s.name = m->path + ": " + as.name;
            s.declared_ground = as.declared_ground;
            s.prepared = as.prepared;
            pose_surface(m->asset, as, m->pose, m->root, s.prepared.positions.data(), skinning_);
            planes_->derive_planes(s.prepared.positions.data(), s.prepared.indices.data(),
                                   s.prepared.num_triangles(), s.prepared.planes.data());
            update_bounds(s);
            links_.push_back({(int)models_.size(), (int)si});
            scene_.surfaces.push_back(std::move(s));
        }
        for (std::size_t li = 0; li < m->asset.lights.size(); li++) {
            scene_.lights.push_back(light_at(m->asset, (int)li, m->pose, m->root));
            light_model_.push_back((int)models_.size());
            light_index_.push_back((int)li);
        }
        if (camera_model_ < 0 && !m->asset.cameras.empty()) {
            camera_model_ = (int)models_.size();
            camera_index_ = 0;
        }
        models_.push_back(std::move(m));
    }
    if (scene_.triangles() == 0)
        throw SceneError(o.file + ": the files have no triangles to render");
    if (o.ground) {
        add_ground(scene_);
        links_.push_back({-1, -1});
    }
    if (o.has_camera) {
        scene_.camera = o.camera;
        camera_model_ = -1;
    } else if (camera_model_ >= 0) {
        const Model &m = *models_[(std::size_t)camera_model_];
        scene_.camera = camera_at(m.asset, camera_index_, m.pose, m.root, nullptr);
    } else {
        scene_.camera = frame_camera(scene_, aspect_);
    }
    if (scene_.camera.near_distance == 0) {
        scene_.camera.near_distance = fitting_near_distance(scene_, scene_.camera);
    }
    std::vector<SceneLight> extra = o.lights;
    if (extra.empty() && scene_.lights.empty()) {
        for (LightKind k : {LightKind::point, LightKind::spot, LightKind::directional}) {
            SceneLight l;
            l.kind = k;
            l.placed_automatically = true;
            extra.push_back(l);
        }
    }
    const bool three_auto = o.lights.empty() && scene_.lights.empty();
    for (SceneLight l : extra) {
        if (l.placed_automatically) l = auto_light(scene_, l.kind);
        default_intensity(scene_, l);
        /* Three lights of irradiance 1 each wash the picture out. */
        if (three_auto) l.intensity *= 0.5;
        scene_.lights.push_back(l);
        light_model_.push_back(-1);
        light_index_.push_back(-1);
    }
    validate_scene(scene_);
}

DeformPlan SceneSequence::deform_for(int num_triangles) const {
    if (!forced_) return deform_plan_for(num_triangles);
    DeformPlan d;
    d.skinning = skinning_;
    d.planes = planes_;
    d.skin_planes = skin_planes_;
    d.clustered = clustered_;
    d.source = "options";
    return d;
}

PoseStats SceneSequence::set_time(double time) {
    PoseStats st;
    uint64_t k0 = __rdtsc();
    for (auto &m : models_) {
        if (m->animation >= 0) m->pose = pose_at(m->asset, m->animation, time);
    }
    for (std::size_t li = 0; li < scene_.lights.size(); li++) {
        if (light_model_[li] < 0) continue;
        const Model &m = *models_[(std::size_t)light_model_[li]];
        const SceneLight l = light_at(m.asset, light_index_[li], m.pose, m.root);
        if (!same_light(l, scene_.lights[li])) {
            scene_.lights[li] = l;
            st.lights_moved++;
        }
    }
    if (camera_model_ >= 0) {
        const Model &m = *models_[(std::size_t)camera_model_];
        const double near = scene_.camera.near_distance;
        scene_.camera = camera_at(m.asset, camera_index_, m.pose, m.root, nullptr);
        if (scene_.camera.near_distance == 0) scene_.camera.near_distance = near;
    }
    st.ticks_pose = __rdtsc() - k0;
    for (std::size_t si = 0; si < scene_.surfaces.size(); si++) {
        const SurfaceLink &link = links_[si];
        if (link.model < 0) continue;
        Model &m = *models_[(std::size_t)link.model];
        if (!m.surface_moves(link.surface)) continue;
        SceneSurface &s = scene_.surfaces[si];
        const AnimatedSurface &as = m.asset.surfaces[(std::size_t)link.surface];
        m.scratch.resize(s.prepared.positions.size());
        const DeformPlan d = deform_for(s.prepared.num_triangles());
        const bool one_pass = d.skin_planes && as.skin >= 0;
        k0 = __rdtsc();
        if (one_pass) {
            m.schedules.resize(m.asset.surfaces.size());
            SkinPlanesSchedule &sch = m.schedules[(std::size_t)link.surface];
            if (sch.triangle_end.empty() && sch.vertex_end.empty()) {
                sch = skin_planes_schedule(s.prepared.indices.data(), s.prepared.num_triangles(),
                                           static_cast<std::size_t>(s.prepared.num_vertices()));
            }
            m.plane_scratch.resize(s.prepared.planes.size());
            pose_surface_with_planes(m.asset, as, m.pose, m.root, *d.skin_planes, sch,
                                     m.scratch.data(), m.plane_scratch.data());
            st.ticks_skin_planes += __rdtsc() - k0;
        } else {
            pose_surface(m.asset, as, m.pose, m.root, m.scratch.data(), d.skinning);
            st.ticks_skinning += __rdtsc() - k0;
        }
        for (float v : m.scratch) {
            /* A pose can overflow float (a scale key of 1e30): refused, as
             * a non-finite input position is. */
            if (!std::isfinite(v)) {
                throw SceneError(s.name + ": the pose at " + std::to_string(time) +
                                 " s puts a vertex at a non-finite position");
            }
        }
        if (std::memcmp(m.scratch.data(), s.prepared.positions.data(),
                        m.scratch.size() * sizeof(float)) == 0) {
            continue;
        }
        std::swap(m.scratch, s.prepared.positions);
        if (one_pass) {
            std::swap(m.plane_scratch, s.prepared.planes);
        } else {
            if (d.clustered) {
                m.clusters.resize(m.asset.surfaces.size());
                PlaneClusters &pc = m.clusters[(std::size_t)link.surface];
                if (pc.group_begin.empty()) {
                    pc = plane_clusters(s.prepared.indices.data(), s.prepared.num_triangles(),
                                        s.prepared.num_vertices());
                }
                const sv_plane_clusters view = pc.view();
                k0 = __rdtsc();
                d.clustered->derive_planes(s.prepared.positions.data(), &view,
                                           s.prepared.planes.data());
            } else {
                k0 = __rdtsc();
                d.planes->derive_planes(s.prepared.positions.data(), s.prepared.indices.data(),
                                        s.prepared.num_triangles(), s.prepared.planes.data());
            }
            st.ticks_planes += __rdtsc() - k0;
        }
        st.planes_derived += s.prepared.num_triangles();
        update_bounds(s);
        s.revision++;
        st.surfaces_moved++;
    }
    return st;
}

const AnimatedSurface *SceneSequence::animated_surface(int surface) const {
    if (surface < 0 || surface >= (int)links_.size()) return nullptr;
    const SurfaceLink &link = links_[(std::size_t)surface];
    if (link.model < 0) return nullptr;
    return &models_[(std::size_t)link.model]->asset.surfaces[(std::size_t)link.surface];
}

std::vector<float> SceneSequence::joint_matrices(int surface) const {
    const AnimatedSurface *as = animated_surface(surface);
    if (!as || as->skin < 0) return {};
    const Model &m = *models_[(std::size_t)links_[(std::size_t)surface].model];
    std::vector<float> out(16 * m.asset.skins[(std::size_t)as->skin].joints.size());
    sv::joint_matrices(m.asset, as->skin, m.pose, m.root, out.data());
    return out;
}

std::vector<std::string> SceneSequence::describe() const {
    std::vector<std::string> out;
    for (const auto &m : models_) {
        std::string line = m->path + ": " + std::to_string(m->asset.surfaces.size()) +
                           " surface(s), " + std::to_string(m->asset.lights.size()) +
                           " light(s), " + std::to_string(m->asset.cameras.size()) + " camera(s), ";
        if (m->animation >= 0) {
            const Animation &a = m->asset.animations[(std::size_t)m->animation];
            char buf[160];
            std::snprintf(buf, sizeof buf, "animation %d '%s' (%.3f s to %.3f s) of %zu",
                          m->animation, a.name.c_str(), a.start, a.end, m->asset.animations.size());
            line += buf;
        } else {
            line += "no animation";
        }
        out.push_back(line);
    }
    return out;
}

} // namespace sv
