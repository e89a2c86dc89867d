/*
 * A glTF model as a cycle-table workload.
 *
 * Every mesh instance of the model's scene (sv::load_gltf: world space,
 * skinned meshes in bind pose) is MERGED into one surface before
 * preparation: the whole character is one occluder, as the paper's player
 * model is, and a model of many parts (RobotExpressive has 14) is timed at
 * its full size rather than by its largest part. Welding then also joins
 * parts that touch at exactly equal positions; what preparation finds
 * (dangling SilEdges of open parts, dropped degenerate triangles) is printed
 * in the header.
 *
 * Copyright (C) 2026 the shadowvol authors. LGPL-2.1-or-later.
 */
#ifndef SV_BENCH_MODEL_WORKLOAD_H
#define SV_BENCH_MODEL_WORKLOAD_H

#include <cstdint>
#include <string>

#include "lights.h"
#include "workload.h"

namespace svbench {

/* Loads PATH, merges and prepares its surfaces: the mesh arrays, no
 * lights yet (place_lights adds them). Throws WorkloadError naming the file
 * and the problem when it cannot be loaded or prepared, or has no
 * triangle. */
Workload load_model_surface(const std::string &path);

/* load_model_surface, then place_lights with NUM_LIGHTS lights (lights.h;
 * FIXED, when not null, is the fixed light). Throws WorkloadError. */
Workload make_model_workload(const std::string &path, const LightTargets &targets, int numLights,
                             uint64_t seed, const Vec4 *fixed);

} // namespace svbench

#endif
