/*
 * The volume pass (issues 12 and 13): for every (light, surface) pair, the
 * shortcuts' conservative tests (reach.h) decide whether it needs a volume
 * at all, with or without cull bits and caps; then the library's routines
 * build it (sv_calculate_facing, the culling routine, sv_create_sil_-
 * triangles, sv_create_cap_triangles) or the cache hands back last
 * frame's. The jobs run in parallel; the results are the same at every
 * thread count.
 *
 * Copyright (C) 2026 the shadowvol authors. LGPL-2.1-or-later.
 */
#ifndef SV_RENDER_VOLUME_PASS_H
#define SV_RENDER_VOLUME_PASS_H

#include <cstdint>
#include <vector>

#include "frame.h"

namespace sv::render {

struct VolumePassInputs {
    const Scene *scene = nullptr;
    Mat4d view_proj;
    double aspect = 1; /* the frame's width / height */
    ModeChoice mode = ModeChoice::automatic;
    CasterRule caster_rule = CasterRule::automatic;
    GeneralBuild general_build = GeneralBuild::direct;
    bool ground_hints = true; /* RenderOptions::ground_hints */
    Shortcuts shortcuts;
    ShortcutFaults faults;
    const sv_variant *variant = nullptr;                 /* the volume routines */
    const sv_facing_variant *facing = nullptr;           /* facing and cull bits */
    const sv_general_variant *general_variant = nullptr; /* the general rule's, direct */
};

/* Fills LIGHTS (resized to the scene's lights) with each light's
 * decisions, its volumes (surfaces that cast, in surface order) and their
 * counts and routine ticks; CACHE keeps the volumes for the next frame
 * (shortcut 6; a cache for this frame only works as well). Returns the
 * wall TSC ticks of the jobs. Runs on the calling task arena's threads. */
uint64_t volume_pass(const VolumePassInputs &in, VolumeCache &cache,
                     std::vector<LightFrame> &lights);

/* For the shading pass, per (light, surface) (light-major): the facing
 * bytes its volume was built from this frame (or reused: the same surface
 * revision and light), or nullptr where the light does not reach the
 * surface. A surface whose volume was skipped out of view has no pixel
 * (and would be left unlit if it had one: the proof would see it). */
std::vector<const uint8_t *> lit_facing(const Scene &scene, const std::vector<LightFrame> &lights,
                                        VolumeCache &cache);

} // namespace sv::render

#endif
