/*
 * shadowvol: a static scene to render shadow volumes in (issue 12): glTF
 * surfaces placed by a transform, an optional ground plane, lights (point
 * with an optional range, spot with an inner and outer cone, directional)
 * and a perspective camera with the infinite far plane of Everitt and
 * Kilgard, "Practical and Robust Stenciled Shadow Volumes" (2002).
 *
 * Every surface casts and receives. World space is glTF's: +y up, metres;
 * characters face +z.
 *
 * Copyright (C) 2026 the shadowvol authors. LGPL-2.1-or-later.
 */
#ifndef SHADOWVOL_SCENE_H
#define SHADOWVOL_SCENE_H

#include <array>
#include <cstdint>
#include <stdexcept>
#include <string>
#include <vector>

#include "shadowvol.h"
#include "shadowvol_mesh.h"

namespace sv {

struct Vec3d {
    double x = 0, y = 0, z = 0;
};

/* A 4x4 matrix in double, column-major as OpenGL: element (row r, column
 * c) is m[c * 4 + r]; a point p maps to m * (p, 1). */
struct Mat4d {
    double m[16] = {1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1};
    double at(int r, int c) const { return m[c * 4 + r]; }
    Mat4d operator*(const Mat4d &b) const;
    /* (x, y, z, w) -> this * (x, y, z, w) */
    std::array<double, 4> apply(double x, double y, double z, double w) const;
};

/* How a model file is placed: p' = translation + scale * R_y(yaw) * p. */
struct Placement {
    Vec3d translation;
    double yaw_degrees = 0;
    double scale = 1;
};

/* One surface of the scene: a glTF mesh instance (or the ground), placed
 * in world space and prepared for the routines (welded, SilEdges, planes). */
struct SceneSurface {
    std::string name; /* "FILE: <glTF surface name>", or "ground" */
    bool ground = false;
    /* The top of a solid never seen from below (the ground quad; a glTF
     * surface with extras "shadowvol_ground": true): under --caster-rule
     * auto it keeps the paper's rule (shadowvol_casters.h). */
    bool declared_ground = false;
    PreparedSurface prepared; /* positions in world space */
    std::array<float, 3> albedo{0.8f, 0.8f, 0.8f};
    /* World-space box of the welded vertices. */
    Vec3d lo, hi;
    /* Changes whenever the positions (so the planes and the box) change:
     * a frame reuses a volume built earlier only while it is the same
     * (render::VolumeCache). */
    uint64_t revision = 0;
};

enum class LightKind { point, spot, directional };

struct SceneLight {
    LightKind kind = LightKind::point;
    Vec3d position; /* point and spot */
    /* The direction the light travels (unit): a spot's axis, or the rays
     * of a directional light (glTF KHR_lights_punctual: a light shines
     * along its -z; "dir:0,-1,0" is a sun straight overhead). */
    Vec3d direction{0, -1, 0};
    double range = 0;                             /* point and spot: 0 means unlimited */
    double inner_degrees = 0, outer_degrees = 45; /* spot: half-angles */
    std::array<float, 3> color{1, 1, 1};
    double intensity = 1;
    /* Given as "KIND:auto" on the command line: to be replaced by
     * auto_light once the scene's surfaces are known. */
    bool placed_automatically = false;
    /* The light as shadowvol.h takes it: (x, y, z, 1) for point and spot,
     * (-direction, 0) for directional (xyz TOWARDS the light). */
    Vec4 shadow_light() const;
    std::string describe() const;
};

struct Camera {
    Vec3d eye{0, 1.5, 4}, target{0, 1, 0}, up{0, 1, 0};
    double fov_y_degrees = 45;
    /* Distance of the near plane; the far plane is at infinity. */
    double near_distance = 0.05;
};

/* Everitt and Kilgard's infinite projection with an epsilon, so that
 * points at infinity (w = 0) land at NDC depth 1 - eps, inside the far
 * plane, instead of exactly on it:
 *   [ f/a  0   0          0          ]
 *   [ 0    f   0          0          ]    f = 1 / tan(fov_y / 2)
 *   [ 0    0   eps - 1    (eps - 2) n]
 *   [ 0    0  -1          0          ]
 * eps = 2^-20: window depth of infinity is 1 - 2^-21, exact in float. */
constexpr double kInfiniteFarEpsilon = 1.0 / (1 << 20);
Mat4d infinite_projection(double fov_y_degrees, double aspect, double near_distance);
/* Right-handed look-at: the camera looks down its -z. */
Mat4d look_at(const Vec3d &eye, const Vec3d &target, const Vec3d &up);

struct Scene {
    std::vector<SceneSurface> surfaces;
    std::vector<SceneLight> lights;
    Camera camera;
    /* Messages about what was adjusted (one line each): notes of the glTF
     * loader, a light inside a closed surface, ... */
    std::vector<std::string> notes;

    /* Bounds of every surface (the ground too when WITH_GROUND). */
    void bounds(Vec3d &lo, Vec3d &hi, bool with_ground) const;
    int64_t triangles() const;
};

/* Bad scene input: the message names the file, light or value. */
class SceneError : public std::runtime_error {
public:
    using std::runtime_error::runtime_error;
};

/* Loads every mesh instance of the glTF file PATH, places it, prepares it
 * and appends it to the scene. Throws GltfError (the file) or
 * PrepareError / SceneError (a placement that is not finite, a scale of 0
 * or below). */
void add_model(Scene &scene, const std::string &path, const Placement &placement);

/* Throws SceneError naming PATH when PL has a number that is not finite or
 * a scale of 0 or below. */
void check_placement(const std::string &path, const Placement &pl);
/* PL as a matrix: translation + scale * R_y(yaw), for posed surfaces
 * (add_model places its vertices by the same formula, term by term). */
Mat4d placement_matrix(const Placement &pl);
/* S's box from its prepared positions. */
void update_bounds(SceneSurface &s);

/* A square ground plane (two triangles, facing +y) at the lowest y of the
 * surfaces, centred under them, with a side of 8 times their horizontal
 * radius (at least 1): large enough for the shadows of lights above. */
void add_ground(Scene &scene);

/* A camera that frames every non-ground surface from the front (+z) and
 * above, with room for the shadows around them. */
Camera frame_camera(const Scene &scene, double aspect);

/* A near distance for CAMERA that keeps float depth fine at the scene:
 * half the distance from the eye to the bounds of every surface (with
 * the ground), at least 1/1000 of the distance to their centre; 1/100 of
 * their radius when the eye is inside them. */
double fitting_near_distance(const Scene &scene, const Camera &camera);

/* One point light (above, left and behind) and one directional light
 * (from above right), placed so that the surfaces' shadows fall on the
 * ground in front of the camera. */
std::vector<SceneLight> default_lights(const Scene &scene);

/* A light of KIND placed around the non-ground surfaces' bounds so that
 * their shadows fall on the ground in view of frame_camera: a point light
 * in front, left and above; a spot above right aimed at the bounds' foot
 * (cone 20..40 degrees); a directional light from above, in front and to
 * the right. Intensity: irradiance 1 at the bounds' centre. */
SceneLight auto_light(const Scene &scene, LightKind kind);

/* Checks the scene for what would make a silent wrong picture and throws
 * SceneError: no surface with a triangle, a light at a vertex (its
 * extrusion direction is 0), NaN or infinite numbers, a zero light
 * direction, cone angles outside 0 <= inner <= outer < 90, a camera whose
 * eye equals its target or whose up is parallel to the view direction.
 * Also refused: a light coordinate beyond float's range, a point or spot
 * light exactly on a triangle's plane (that triangle's flat prism makes
 * the stencil count anything). Appends notes (not errors) for: a light
 * inside a closed surface, the eye inside a closed surface. */
void validate_scene(Scene &scene);

} // namespace sv

#endif /* SHADOWVOL_SCENE_H */
