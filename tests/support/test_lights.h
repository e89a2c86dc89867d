/*
 * The lights the render tests place by hand (test_shortcuts.cpp,
 * test_stencil_methods.cpp): a point light, a spot light aimed at a point
 * (inner cone 0.6 of the outer), and the sun along a direction.
 *
 * Copyright (C) 2026 the shadowvol authors. LGPL-2.1-or-later.
 */
#ifndef SV_TEST_LIGHTS_H
#define SV_TEST_LIGHTS_H

#include <cmath>

#include "shadowvol_scene.h"

namespace svtest {

inline sv::SceneLight point_light(sv::Vec3d at, double range) {
    sv::SceneLight l;
    l.kind = sv::LightKind::point;
    l.position = at;
    l.range = range;
    l.intensity = 12;
    return l;
}

inline sv::SceneLight spot_light(sv::Vec3d at, sv::Vec3d towards, double outer, double range) {
    sv::SceneLight l;
    l.kind = sv::LightKind::spot;
    l.position = at;
    const sv::Vec3d d{towards.x - at.x, towards.y - at.y, towards.z - at.z};
    const double n = std::sqrt(d.x * d.x + d.y * d.y + d.z * d.z);
    l.direction = {d.x / n, d.y / n, d.z / n};
    l.inner_degrees = outer * 0.6;
    l.outer_degrees = outer;
    l.range = range;
    l.intensity = 14;
    return l;
}

inline sv::SceneLight sun(sv::Vec3d direction) {
    sv::SceneLight l;
    l.kind = sv::LightKind::directional;
    const double n = std::sqrt(direction.x * direction.x + direction.y * direction.y +
                               direction.z * direction.z);
    l.direction = {direction.x / n, direction.y / n, direction.z / n};
    l.intensity = 0.8;
    return l;
}

} // namespace svtest

#endif
