/*
 * The scene's command-line placement syntax (issue 12), parsed once for
 * every subcommand that builds a scene:
 *   FILE[@x,y,z[,yaw_degrees[,scale]]][:ANIMATION]
 *   point:x,y,z[,range]
 *   spot:x,y,z,dx,dy,dz,inner_degrees,outer_degrees
 *   dir:x,y,z                    (the direction the light travels)
 *   point:auto, spot:auto, dir:auto   (placed by auto_light)
 *   eye=x,y,z,target=x,y,z,fov=deg[,near=d]
 * Every number must be finite; a malformed value throws SceneError with
 * the text and what was expected.
 *
 * Copyright (C) 2026 the shadowvol authors. LGPL-2.1-or-later.
 */
#ifndef SHADOWVOL_SCENE_OPTIONS_H
#define SHADOWVOL_SCENE_OPTIONS_H

#include <string>
#include <vector>

#include "shadowvol_scene.h"

namespace sv {

struct ModelPlacement {
    std::string path;
    Placement placement;
    /* NAME or INDEX of the file's animation (issue 30); empty: its first. */
    std::string animation;
};

/* ANIMATION is the text after the last ':' (so it holds no ':'; such a
 * name is given by its index), the placement the text after the last '@'
 * before it. A file name that holds a ':' is written with a ':' after it
 * (an empty ANIMATION: the file's first), one that holds a '@' with a
 * placement after it (dir@x/a.glb@0,0,0). */
ModelPlacement parse_model_placement(const std::string &text);
/* Intensity is left at 0 (meaning: choose), see default_intensity. */
SceneLight parse_light(const std::string &text);
/* near_distance is 0 when near= is not given (fitting_near_distance). */
Camera parse_camera(const std::string &text);
/* Comma-separated finite numbers. */
std::vector<double> parse_numbers(const std::string &text, const std::string &what);

/* A light given without an intensity gets one that makes its irradiance 1
 * at the centre of the scene's bounds (point and spot: the squared
 * distance, as the 1/d^2 falloff; directional: 1). */
void default_intensity(const Scene &scene, SceneLight &light);

} // namespace sv

#endif
