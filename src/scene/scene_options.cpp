/*
 * The scene's command-line placement syntax (scene_options.h).
 *
 * Copyright (C) 2026 the shadowvol authors. LGPL-2.1-or-later.
 */
#include "scene_options.h"

#include "shadowvol_gltf.h"

#include <cerrno>
#include <cmath>
#include <cstdlib>

namespace sv {

std::vector<double> parse_numbers(const std::string &text, const std::string &what) {
    std::vector<double> out;
    std::size_t start = 0;
    while (true) {
        const std::size_t comma = text.find(',', start);
        const std::string item = text.substr(start, comma == std::string::npos ? std::string::npos
                                                                               : comma - start);
        errno = 0;
        char *end = nullptr;
        const double v = item.empty() ? 0 : std::strtod(item.c_str(), &end);
        if (item.empty() || *end != 0 || errno == ERANGE || !std::isfinite(v)) {
            throw SceneError(what + ": '" + printable_text(item) + "' is not a finite number");
        }
        out.push_back(v);
        if (comma == std::string::npos) break;
        start = comma + 1;
    }
    return out;
}

ModelPlacement parse_model_placement(const std::string &text) {
    ModelPlacement m;
    const std::size_t colon = text.rfind(':');
    const std::string placed = text.substr(0, colon);
    if (colon != std::string::npos) m.animation = text.substr(colon + 1);
    const std::size_t at = placed.rfind('@');
    m.path = placed.substr(0, at);
    if (m.path.empty())
        throw SceneError("--add needs a file name, not '" + printable_text(text) + "'");
    if (at == std::string::npos) return m;
    const std::vector<double> v = parse_numbers(placed.substr(at + 1),
                                                "--add " + printable_text(text));
    if (v.size() < 3 || v.size() > 5) {
        throw SceneError("--add " + printable_text(text) +
                         ": expected FILE@x,y,z[,yaw_degrees[,scale]][:ANIMATION]");
    }
    m.placement.translation = {v[0], v[1], v[2]};
    if (v.size() > 3) m.placement.yaw_degrees = v[3];
    if (v.size() > 4) m.placement.scale = v[4];
    if (!(m.placement.scale > 0))
        throw SceneError("--add " + printable_text(text) + ": the scale must be above 0");
    return m;
}

SceneLight parse_light(const std::string &text) {
    const std::size_t colon = text.find(':');
    const std::string kind = text.substr(0, colon);
    if (colon == std::string::npos) {
        throw SceneError("--light " + printable_text(text) +
                         ": expected point:..., spot:... or dir:...");
    }
    SceneLight l;
    l.intensity = 0;
    if (text.substr(colon + 1) == "auto") {
        /* Placed by auto_light once the scene is known. */
        if (kind != "point" && kind != "spot" && kind != "dir") {
            throw SceneError("--light " + printable_text(text) + ": unknown kind '" +
                             printable_text(kind) + "' (point, spot or dir)");
        }
        l.kind = kind == "point"  ? LightKind::point
                 : kind == "spot" ? LightKind::spot
                                  : LightKind::directional;
        l.placed_automatically = true;
        return l;
    }
    const std::vector<double> v = parse_numbers(text.substr(colon + 1),
                                                "--light " + printable_text(text));
    if (kind == "point") {
        if (v.size() != 3 && v.size() != 4)
            throw SceneError("--light " + printable_text(text) + ": expected point:x,y,z[,range]");
        l.kind = LightKind::point;
        l.position = {v[0], v[1], v[2]};
        if (v.size() == 4) {
            if (!(v[3] > 0))
                throw SceneError("--light " + printable_text(text) + ": the range must be above 0");
            l.range = v[3];
        }
    } else if (kind == "spot") {
        if (v.size() != 8) {
            throw SceneError("--light " + printable_text(text) +
                             ": expected spot:x,y,z,dx,dy,dz,inner_deg,outer_deg");
        }
        l.kind = LightKind::spot;
        l.position = {v[0], v[1], v[2]};
        l.direction = {v[3], v[4], v[5]};
        l.inner_degrees = v[6];
        l.outer_degrees = v[7];
        if (v[3] == 0 && v[4] == 0 && v[5] == 0)
            throw SceneError("--light " + printable_text(text) + ": the direction is zero");
        if (!(v[6] >= 0 && v[6] <= v[7] && v[7] < 90)) {
            throw SceneError("--light " + printable_text(text) +
                             ": cone angles need 0 <= inner <= outer < 90 degrees");
        }
    } else if (kind == "dir") {
        if (v.size() != 3)
            throw SceneError("--light " + printable_text(text) + ": expected dir:x,y,z");
        if (v[0] == 0 && v[1] == 0 && v[2] == 0)
            throw SceneError("--light " + printable_text(text) + ": the direction is zero");
        l.kind = LightKind::directional;
        l.direction = {v[0], v[1], v[2]};
    } else {
        throw SceneError("--light " + printable_text(text) + ": unknown kind '" +
                         printable_text(kind) + "' (point, spot or dir)");
    }
    if (l.kind != LightKind::point) {
        const double n = std::sqrt(l.direction.x * l.direction.x + l.direction.y * l.direction.y +
                                   l.direction.z * l.direction.z);
        l.direction = {l.direction.x / n, l.direction.y / n, l.direction.z / n};
    }
    return l;
}

Camera parse_camera(const std::string &text) {
    Camera c;
    c.near_distance = 0; /* not given: the caller fits one to the scene */
    bool eye = false, target = false;
    std::size_t pos = 0;
    /* eye=x,y,z,target=x,y,z,fov=deg,near=d: a key starts after a comma
     * where the next '=' comes before the next ','. */
    while (pos < text.size()) {
        const std::size_t eq = text.find('=', pos);
        if (eq == std::string::npos)
            throw SceneError("--camera " + printable_text(text) + ": expected key=value");
        const std::string key = text.substr(pos, eq - pos);
        std::size_t end = eq + 1;
        while (true) {
            const std::size_t comma = text.find(',', end);
            if (comma == std::string::npos) {
                end = text.size();
                break;
            }
            const std::size_t next_eq = text.find('=', comma);
            const std::size_t next_comma = text.find(',', comma + 1);
            if (next_eq != std::string::npos &&
                (next_comma == std::string::npos || next_eq < next_comma)) {
                end = comma;
                break;
            }
            end = comma + 1;
        }
        const std::vector<double> v = parse_numbers(text.substr(eq + 1, end - eq - 1),
                                                    "--camera " + printable_text(key));
        if (key == "eye" || key == "target" || key == "up") {
            if (v.size() != 3) throw SceneError("--camera " + printable_text(key) + " needs x,y,z");
            (key == "eye" ? c.eye : key == "target" ? c.target : c.up) = {v[0], v[1], v[2]};
            if (key == "eye") eye = true;
            if (key == "target") target = true;
        } else if (key == "fov" || key == "near") {
            if (v.size() != 1)
                throw SceneError("--camera " + printable_text(key) + " needs one number");
            (key == "fov" ? c.fov_y_degrees : c.near_distance) = v[0];
        } else {
            throw SceneError("--camera: unknown key '" + printable_text(key) +
                             "' (eye, target, up, fov, near)");
        }
        pos = end < text.size() ? end + 1 : end;
    }
    if (!eye || !target)
        throw SceneError("--camera " + printable_text(text) + ": needs eye=x,y,z and target=x,y,z");
    if (!(c.fov_y_degrees > 0 && c.fov_y_degrees < 180))
        throw SceneError("--camera: fov must be above 0 and below 180");
    if (!(c.near_distance >= 0)) throw SceneError("--camera: near must be above 0");
    return c;
}

void default_intensity(const Scene &scene, SceneLight &l) {
    if (l.intensity != 0) return;
    if (l.kind == LightKind::directional) {
        l.intensity = 1;
        return;
    }
    Vec3d lo, hi;
    scene.bounds(lo, hi, false);
    const double dx = (lo.x + hi.x) / 2 - l.position.x, dy = (lo.y + hi.y) / 2 - l.position.y,
                 dz = (lo.z + hi.z) / 2 - l.position.z;
    l.intensity = std::max(dx * dx + dy * dy + dz * dz, 1e-6);
}

} // namespace sv
