/*
 * The view's keys and mouse (view_controls.h).
 *
 * Copyright (C) 2026 the shadowvol authors. LGPL-2.1-or-later.
 */
#include "view_controls.h"

#include <algorithm>
#include <cmath>
#include <cstdio>

namespace svcli {
namespace {

using sv::Vec3d;

Vec3d add(const Vec3d &a, const Vec3d &b) { return {a.x + b.x, a.y + b.y, a.z + b.z}; }
Vec3d sub(const Vec3d &a, const Vec3d &b) { return {a.x - b.x, a.y - b.y, a.z - b.z}; }
Vec3d mul(const Vec3d &a, double s) { return {a.x * s, a.y * s, a.z * s}; }
double dot(const Vec3d &a, const Vec3d &b) { return a.x * b.x + a.y * b.y + a.z * b.z; }
Vec3d cross(const Vec3d &a, const Vec3d &b) {
    return {a.y * b.z - a.z * b.y, a.z * b.x - a.x * b.z, a.x * b.y - a.y * b.x};
}
Vec3d unit(const Vec3d &a) {
    const double n = std::sqrt(dot(a, a));
    return n > 0 ? mul(a, 1 / n) : Vec3d{0, 0, -1};
}
/* A rotated about unit axis K by ANGLE (Rodrigues). */
Vec3d rotate(const Vec3d &a, const Vec3d &k, double angle) {
    const double c = std::cos(angle), s = std::sin(angle);
    return add(add(mul(a, c), mul(cross(k, a), s)), mul(k, dot(k, a) * (1 - c)));
}

constexpr double kRadiansPerPixel = 0.01;
constexpr double kMaxPitch = 1.5; /* short of straight up or down, where yaw is lost */

template <typename T> void cycle(T &value, std::initializer_list<T> order) {
    const auto *it = std::find(order.begin(), order.end(), value);
    value = (it == order.end() || it + 1 == order.end()) ? *order.begin() : *(it + 1);
}

} // namespace

ViewControls::ViewControls(const ViewSwitches &start, int height)
    : switches_(start), height_(height) {}

bool ViewControls::key(const std::string &name) {
    using sv::render::ModeChoice;
    using sv::render::StencilMethod;
    sv::render::Shortcuts &s = switches_.shortcuts;
    bool *shortcut[6] = {&s.light_reach,
                         &s.view_reach,
                         &s.cull_straddling,
                         &s.zpass_when_safe,
                         &s.no_directional_dark_cap,
                         &s.reuse_static};
    if (name == "M") {
        cycle(switches_.mode, {ModeChoice::zpass, ModeChoice::zfail, ModeChoice::automatic});
    } else if (name == "T") {
        cycle(switches_.stencil, {StencilMethod::brute_force, StencilMethod::depth_bounds,
                                  StencilMethod::hierarchical, StencilMethod::automatic});
    } else if (name == "C") {
        cycle(switches_.caster_rule,
              {sv::CasterRule::automatic, sv::CasterRule::closed, sv::CasterRule::general});
    } else if (name.size() == 1 && name[0] >= '1' && name[0] <= '6') {
        bool &on = *shortcut[name[0] - '1'];
        on = !on;
    } else if (name == "H") {
        switches_.hud = !switches_.hud;
    } else if (name == "O") {
        switches_.overlay_stencil = !switches_.overlay_stencil;
    } else if (name == "B") {
        switches_.overlay_tiles = !switches_.overlay_tiles;
    } else if (name == "V") {
        switches_.overlay_wireframe = !switches_.overlay_wireframe;
    } else if (name == "Space") {
        switches_.paused = !switches_.paused;
    } else if (name == ".") {
        if (switches_.paused) steps_++;
    } else if (name == "L") {
        picked_ = picked_ + 1 < lights_ ? picked_ + 1 : -1;
    } else if (name == "R") {
        camera_moved_ = false;
    } else if (name == "P") {
        print_ = true;
    } else if (name == "Escape") {
        quit_ = true;
    } else if (name == "W" || name == "A" || name == "S" || name == "D" || name == "Q" ||
               name == "E") {
        if (!camera_known_) return true;
        if (!camera_moved_) orbit_from(base_);
        camera_moved_ = true;
        const sv::Camera c = orbit_camera();
        const Vec3d forward = unit(sub(c.target, c.eye));
        const Vec3d right = unit(cross(forward, c.up));
        const double step = 0.05 * distance_;
        const Vec3d move = name == "W"   ? mul(forward, step)
                           : name == "S" ? mul(forward, -step)
                           : name == "D" ? mul(right, step)
                           : name == "A" ? mul(right, -step)
                           : name == "E" ? Vec3d{0, step, 0}
                                         : Vec3d{0, -step, 0};
        target_ = add(target_, move);
    } else {
        return false;
    }
    return true;
}

void ViewControls::drag(int button, int dx, int dy) {
    if (!camera_known_) return;
    if (button == 1) {
        if (!camera_moved_) orbit_from(base_);
        camera_moved_ = true;
        yaw_ -= dx * kRadiansPerPixel;
        pitch_ = std::clamp(pitch_ + dy * kRadiansPerPixel, -kMaxPitch, kMaxPitch);
    } else if (button == 3 && picked_ >= 0 && picked_ < lights_) {
        sv::SceneLight &l = light_[(std::size_t)picked_];
        const sv::Camera c = camera_moved_ ? orbit_camera() : base_;
        const Vec3d forward = unit(sub(c.target, c.eye));
        const Vec3d right = unit(cross(forward, c.up));
        const Vec3d up = cross(right, forward);
        if (l.kind == sv::LightKind::directional) {
            l.direction = unit(rotate(rotate(l.direction, up, dx * kRadiansPerPixel), right,
                                      dy * kRadiansPerPixel));
        } else {
            /* The light follows the pointer in the plane through it that
             * faces the camera: a pixel there is this wide. */
            const double depth = std::max(1e-6, dot(sub(l.position, c.eye), forward));
            const double pixel = 2 * depth *
                                 std::tan(c.fov_y_degrees * 3.14159265358979323846 / 360) / height_;
            l.position = add(l.position, add(mul(right, dx * pixel), mul(up, -dy * pixel)));
        }
        light_moved_[(std::size_t)picked_] = 1;
    }
}

void ViewControls::wheel(int amount) {
    if (!camera_known_ || amount == 0) return;
    if (!camera_moved_) orbit_from(base_);
    camera_moved_ = true;
    distance_ = std::max(1e-3, distance_ * std::pow(0.9, amount));
}

void ViewControls::apply(sv::Scene &scene) {
    base_ = scene.camera;
    camera_known_ = true;
    if (camera_moved_) scene.camera = orbit_camera();
    if ((int)scene.lights.size() != lights_) {
        lights_ = (int)scene.lights.size();
        light_moved_.assign((std::size_t)lights_, 0);
        light_.assign(scene.lights.begin(), scene.lights.end());
        if (picked_ >= lights_) picked_ = -1;
    }
    for (int li = 0; li < lights_; li++) {
        if (light_moved_[(std::size_t)li])
            scene.lights[(std::size_t)li] = light_[(std::size_t)li];
        else
            light_[(std::size_t)li] = scene.lights[(std::size_t)li]; /* follows the file's */
    }
}

int ViewControls::take_steps() {
    const int n = steps_;
    steps_ = 0;
    return n;
}

bool ViewControls::print_requested() {
    const bool p = print_;
    print_ = false;
    return p;
}

void ViewControls::orbit_from(const sv::Camera &c) {
    target_ = c.target;
    const Vec3d offset = sub(c.eye, c.target);
    distance_ = std::max(1e-3, std::sqrt(dot(offset, offset)));
    yaw_ = std::atan2(offset.x, offset.z);
    pitch_ = std::clamp(std::asin(std::clamp(offset.y / distance_, -1.0, 1.0)), -kMaxPitch,
                        kMaxPitch);
}

sv::Camera ViewControls::orbit_camera() const {
    sv::Camera c = base_;
    c.target = target_;
    c.eye = add(target_, mul(Vec3d{std::cos(pitch_) * std::sin(yaw_), std::sin(pitch_),
                                   std::cos(pitch_) * std::cos(yaw_)},
                             distance_));
    c.up = {0, 1, 0};
    return c;
}

std::string ViewControls::camera_text(const sv::Camera &c) {
    char buf[512];
    std::snprintf(buf, sizeof buf,
                  "eye=%.17g,%.17g,%.17g,target=%.17g,%.17g,%.17g,up=%.17g,%.17g,%.17g,fov=%.17g,"
                  "near=%.17g",
                  c.eye.x, c.eye.y, c.eye.z, c.target.x, c.target.y, c.target.z, c.up.x, c.up.y,
                  c.up.z, c.fov_y_degrees, c.near_distance);
    return buf;
}

std::string ViewControls::switches_text() const {
    const sv::render::Shortcuts &s = switches_.shortcuts;
    const bool on[6] = {s.light_reach,
                        s.view_reach,
                        s.cull_straddling,
                        s.zpass_when_safe,
                        s.no_directional_dark_cap,
                        s.reuse_static};
    std::string shortcuts;
    for (int k = 0; k < 6; k++) shortcuts += on[k] ? (char)('1' + k) : '-';
    std::string overlays;
    if (switches_.overlay_stencil) overlays += "stencil,";
    if (switches_.overlay_tiles) overlays += "tiles,";
    if (switches_.overlay_wireframe) overlays += "wireframe,";
    overlays = overlays.empty() ? "-" : overlays.substr(0, overlays.size() - 1);
    return std::string("mode ") + sv::render::mode_name(switches_.mode) + " stencil " +
           sv::render::stencil_method_name(switches_.stencil) + " caster " +
           sv::caster_rule_name(switches_.caster_rule) + " shortcuts " + shortcuts + " hud " +
           (switches_.hud ? "on" : "off") + " overlays " + overlays + " paused " +
           (switches_.paused ? "yes" : "no") + " light " +
           (picked_ < 0 ? std::string("-") : std::to_string(picked_));
}

} // namespace svcli
