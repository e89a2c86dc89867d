/*
 * The scenes `shadowvol bench --scene --preset` measures (issue 28, seed
 * 004's Table 1 in our terms), each a scene in time, frame by frame 1/8 s
 * apart:
 *
 *  - "simple": a few boxes on a ground plane under a point light that
 *    circles above them (a handful of volume triangles);
 *  - "knights": a crowd of animated characters (../shared/models'
 *    CesiumMan, RobotExpressive, RiggedFigure and Fox, each at a knight's
 *    height, among copies of the bundled character; the bundled character
 *    alone where ../shared is absent) on the ground under a circling point
 *    light;
 *  - "demo": the demo scene (build/models/demo_scene.glb) with its own
 *    lights and camera;
 *  - a FILE: that glTF scene with its own animation, lights and camera.
 *
 * Copyright (C) 2026 the shadowvol authors. LGPL-2.1-or-later.
 */
#ifndef SV_BENCH_SCENE_PRESETS_H
#define SV_BENCH_SCENE_PRESETS_H

#include <memory>
#include <string>

#include "shadowvol_scene.h"

namespace svbench {

class ScenePreset {
public:
    virtual ~ScenePreset() = default;
    /* The scene at frame FRAME (0, 1, ...: FRAME / 8 seconds in). */
    virtual const sv::Scene &at(int frame) = 0;
    /* One line: what the scene holds. */
    virtual std::string describe() const = 0;
};

/* NAME: simple, knights, demo or a glTF file. ASPECT: the frame's
 * width / height. MODELS_DIR: the bundled models; SHARED_DIR: the real
 * characters' folder (may be missing); DEMO_FILE: the demo scene. Throws
 * GltfError / SceneError as SceneSequence does. */
std::unique_ptr<ScenePreset> make_scene_preset(const std::string &name, double aspect,
                                               const std::string &models_dir,
                                               const std::string &shared_dir,
                                               const std::string &demo_file);

/* "simple, knights, demo" (for usage messages). */
const char *scene_preset_names();

} // namespace svbench

#endif
