/*
 * The generated open meshes of issue 27 (src/modelgen/open_cases.h) as the
 * tests draw them (test_casters.cpp, test_general_rule.cpp): each on a
 * ground at y = 0 under a point, a spot and a directional light.
 *
 * Copyright (C) 2026 the shadowvol authors. LGPL-2.1-or-later.
 */
#pragma once

#include <cmath>
#include <cstdint>
#include <string>
#include <utility>
#include <vector>

#include "open_cases.h" /* src/modelgen */
#include "shadowvol_scene.h"

namespace svtest {

using svgen::add_box;
using svgen::open_cases;
using svgen::Soup;

inline sv::SceneSurface surface_of(const Soup &s) {
    sv::SceneSurface g;
    g.name = s.name;
    g.prepared = sv::prepare_surface(s.pos.data(), s.pos.size() / 3, s.idx.data(), s.idx.size());
    sv::update_bounds(g);
    return g;
}

/* SCENE seen from EYE towards TARGET under one point light at LIGHT, its
 * only light; validated. */
inline void view_under_point_light(sv::Scene &scene, sv::Vec3d eye, sv::Vec3d target,
                                   sv::Vec3d light) {
    scene.camera.eye = eye;
    scene.camera.target = target;
    sv::SceneLight l;
    l.kind = sv::LightKind::point;
    l.position = light;
    scene.lights = {l};
    sv::validate_scene(scene);
}

/* S and the ground, framed for a WIDTH x HEIGHT picture. */
inline sv::Scene scene_of(const Soup &s, int width, int height) {
    sv::Scene scene;
    scene.surfaces.push_back(surface_of(s));
    /* A ground at y = 0 (add_ground would put it at the lowest vertex,
     * under a flat case at its own height). */
    Soup ground("ground");
    ground.quad(ground.vertex(-4, 0, 4), ground.vertex(4, 0, 4), ground.vertex(4, 0, -4),
                ground.vertex(-4, 0, -4));
    scene.surfaces.push_back(surface_of(ground));
    scene.surfaces.back().ground = true;
    scene.surfaces.back().declared_ground = true; /* as add_ground's: the cases stand on it */
    scene.camera = sv::frame_camera(scene, (double)width / height);
    scene.lights = {sv::auto_light(scene, sv::LightKind::point),
                    sv::auto_light(scene, sv::LightKind::spot),
                    sv::auto_light(scene, sv::LightKind::directional)};
    sv::validate_scene(scene);
    return scene;
}

} // namespace svtest
