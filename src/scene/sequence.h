/*
 * A scene in time (issue 13): glTF files whose nodes, skins, lights and
 * cameras move, posed frame by frame into a render-ready Scene.
 *
 * Each frame (set_time): every animated file's pose; every surface that
 * moves gets its world positions (skinned on the CPU, or its node's
 * transform) and its planes derived again, once for all lights (the
 * paper, section 3: the planes of a deforming surface are derived per
 * frame); its box and revision change, so the frame's volume cache builds
 * its volumes again. Surfaces that did not move keep their revision, and
 * their volumes are reused for lights that did not move either.
 *
 * Copyright (C) 2026 the shadowvol authors. LGPL-2.1-or-later.
 */
#ifndef SV_SCENE_SEQUENCE_H
#define SV_SCENE_SEQUENCE_H

#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include "scene_options.h"
#include "shadowvol_anim.h"
#include "shadowvol_planes.h"
#include "shadowvol_scene.h"

namespace sv {

struct SequenceOptions {
    /* The main file: its animation, lights and camera are the scene's. */
    std::string file;
    Placement placement;
    /* NAME or INDEX of the main file's animation; empty: its first one (a
     * file without animations is a still scene). */
    std::string animation;
    /* More files, placed; each plays its own animation (ModelPlacement's),
     * else its first, if any. */
    std::vector<ModelPlacement> adds;
    bool ground = false;
    /* Lights added to the file's (KIND:auto placed around the surfaces at
     * the first frame). With neither: auto point, spot and directional. */
    std::vector<SceneLight> lights;
    bool has_camera = false;
    Camera camera; /* else the file's first camera, else frame_camera */
    double aspect = 1.25;
    const SkinningKernel *skinning = nullptr;  /* nullptr: the planned or static choice */
    const sv_planes_variant *planes = nullptr; /* nullptr: the planned or static choice */
    /* Skinned surfaces: positions and planes in one pass by this kernel
     * (nullptr: two passes). With none of the four set, each surface runs
     * what deform_plan_for() chooses for its size (the planner's
     * measurement or wisdom, else the static choice); with any set, the
     * ones not set are the static choices and two passes. */
    const SkinPlanesKernel *skin_planes = nullptr;
    /* Two passes: the planes by clusters with this kernel instead of
     * PLANES (nullptr: PLANES). */
    const sv_planes_clustered_variant *clustered = nullptr;
};

/* What set_time did. */
struct PoseStats {
    uint64_t ticks_pose = 0;        /* node matrices, lights, camera */
    uint64_t ticks_skinning = 0;    /* world positions of the moving surfaces */
    uint64_t ticks_planes = 0;      /* their planes */
    uint64_t ticks_skin_planes = 0; /* skinned surfaces' positions and planes in one pass */
    int64_t planes_derived = 0;     /* triangles (both ways) */
    int surfaces_moved = 0;
    int lights_moved = 0;
};

class SceneSequence {
public:
    /* Loads every file and poses the first frame. Throws GltfError (a
     * file), PrepareError or SceneError (a placement, a light). */
    explicit SceneSequence(const SequenceOptions &options);

    /* The scene at the current time. */
    const Scene &scene() const { return scene_; }
    Scene &scene() { return scene_; }

    /* The time range of the main file's animation (both 0 when none). */
    double start() const { return start_; }
    double end() const { return end_; }
    std::string animation_name() const { return animation_name_; }
    bool animated() const { return animated_; }

    /* Poses every file at TIME (seconds; each animation clamps it to its
     * own range) and updates the scene. */
    PoseStats set_time(double time);

    /* One line per file: what it contributes. */
    std::vector<std::string> describe() const;

    /* Scene surface SURFACE's animated surface (nullptr: the ground, or no
     * such surface), and, for a skinned one, its joint matrices at the
     * current time (16 floats a joint, the file's placement included: the
     * matrices its world positions were skinned with; empty when it has no
     * skin). For what reads a skin per frame beside the positions: seed
     * 002's skinned normals (`scene --skinned-normals`, docs/EXTRUSION.md). */
    const AnimatedSurface *animated_surface(int surface) const;
    std::vector<float> joint_matrices(int surface) const;

private:
    struct Model;
    struct SurfaceLink {
        int model = -1, surface = -1; /* in models_ and their asset's surfaces */
    };
    std::vector<std::shared_ptr<Model>> models_;
    std::vector<SurfaceLink> links_;             /* per scene surface (ground: model -1) */
    std::vector<int> light_model_, light_index_; /* per scene light: from a file (-1: given) */
    int camera_model_ = -1, camera_index_ = -1;
    Scene scene_;
    double start_ = 0, end_ = 0;
    bool animated_ = false;
    std::string animation_name_;
    const SkinningKernel *skinning_;
    const sv_planes_variant *planes_;
    const SkinPlanesKernel *skin_planes_;          /* nullptr: two passes */
    const sv_planes_clustered_variant *clustered_; /* nullptr: planes_ */
    bool forced_;                                  /* the options named a kernel */
    DeformPlan deform_for(int num_triangles) const;
    double aspect_;
};

} // namespace sv

#endif
