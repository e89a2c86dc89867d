/*
 * libFuzzer target: the command lines of `shadowvol render`, `shadowvol
 * scene` and `shadowvol view` (issue 17: the render and scene option
 * parsers; issue 30: view's, and its --script reader), and the placement
 * syntax they share (--add, --light, --camera; scene_options.h).
 *
 * The input is split at NUL bytes into at most 64 arguments; its first byte
 * chooses the parser (render, scene, view, or one of the single-value
 * parsers and the script reader fed the whole rest). Nothing is run and no file is opened: parsing only.
 *
 * A finding: a crash or sanitizer report; an exception other than the
 * documented refusals (svcli::UsageError, sv::SceneError; the script
 * reader's std::runtime_error); a refusal whose
 * message is not bounded printable UTF-8; or an accepted command line that
 * breaks what the parsers promise: every number finite, sizes within
 * kMaxFrameSide / kMaxFramePixels, counts within their ranges, light
 * directions non-zero, cone angles 0 <= inner <= outer < 90, scales > 0.
 *
 * Copyright (C) 2026 the shadowvol authors. LGPL-2.1-or-later.
 */
#include <cmath>
#include <cstdint>
#include <stdexcept>
#include <string>
#include <vector>

#include "cli_args.h"
#include "fuzz_support.h"
#include "render_args.h"
#include "scene_args.h"
#include "scene_options.h"
#include "view_args.h"
#include "view_script.h"

namespace {

using svfuzz::check_message;
using svfuzz::finding;

constexpr std::size_t kMaxArgs = 64;

bool finite3(const sv::Vec3d &v) {
    return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z);
}

void check_placement(const sv::ModelPlacement &m) {
    if (m.path.empty()) finding("a model placement with an empty path was accepted");
    const sv::Placement &p = m.placement;
    if (!finite3(p.translation) || !std::isfinite(p.yaw_degrees) || !std::isfinite(p.scale) ||
        !(p.scale > 0)) {
        finding("a model placement with a non-finite number or scale <= 0 was accepted");
    }
}

void check_light(const sv::SceneLight &l) {
    if (l.placed_automatically) return;
    if (!finite3(l.position) || !finite3(l.direction) || !std::isfinite(l.range) || l.range < 0) {
        finding("a light with a non-finite number or a negative range was accepted: " +
                l.describe());
    }
    if (l.kind != sv::LightKind::point) {
        const double len = std::sqrt(l.direction.x * l.direction.x + l.direction.y * l.direction.y +
                                     l.direction.z * l.direction.z);
        if (!(std::fabs(len - 1) < 1e-9))
            finding("a light direction that is not unit: " + l.describe());
    }
    if (l.kind == sv::LightKind::spot &&
        !(l.inner_degrees >= 0 && l.inner_degrees <= l.outer_degrees && l.outer_degrees < 90)) {
        finding("a spot with cone angles outside 0 <= inner <= outer < 90: " + l.describe());
    }
}

void check_camera(const sv::Camera &c) {
    if (!finite3(c.eye) || !finite3(c.target) || !finite3(c.up) ||
        !std::isfinite(c.fov_y_degrees) || !std::isfinite(c.near_distance)) {
        finding("a camera with a non-finite number was accepted");
    }
}

void check_size(int w, int h) {
    if (w < 1 || h < 1 || w > sv::render::kMaxFrameSide || h > sv::render::kMaxFrameSide ||
        (int64_t)w * h > sv::render::kMaxFramePixels) {
        finding("a frame size outside the limits was accepted: " + std::to_string(w) + "x" +
                std::to_string(h));
    }
}

void check_render(const svcli::RenderArgs &r) {
    for (const auto &m : r.models) check_placement(m);
    for (const auto &l : r.lights) check_light(l);
    if (r.has_camera) check_camera(r.camera);
    check_size(r.width, r.height);
    if (r.threads < 0 || r.threads > 256) finding("--threads outside 0..256 accepted");
}

void check_scene(const svcli::SceneArgs &s) {
    for (const auto &m : s.seq.adds) check_placement(m);
    for (const auto &l : s.seq.lights) check_light(l);
    if (s.seq.has_camera) check_camera(s.seq.camera);
    check_size(s.width, s.height);
    if (s.frames < 0 || s.frames > 10000) finding("--frames outside 1..10000 accepted");
    if (s.has_time && (s.frames || !std::isfinite(s.time_from) || !std::isfinite(s.time_to) ||
                       !(s.time_to >= s.time_from))) {
        finding("a --time range that is not FROM <= TO (finite), or with --frames, was accepted");
    }
    if (!(s.fps > 0 && s.fps <= 10000)) finding("--fps outside (0, 10000] accepted");
    if (s.threads < 0 || s.threads > 256) finding("--threads outside 0..256 accepted");
}

/* What the script reader promises of an accepted script: frames from 0
 * to 10^8 in order, drag points within 0..65535 and a button of 1 or 3,
 * wheel notches within +-1000, a key or file name that is not empty. */
void check_script(const std::vector<svcli::ScriptEvent> &events) {
    long last = 0;
    for (const svcli::ScriptEvent &e : events) {
        if (e.frame < last || e.frame > 100000000) finding("script events out of frame order");
        last = e.frame;
        if (e.kind == svcli::ScriptEvent::drag &&
            ((e.button != 1 && e.button != 3) || e.x0 < 0 || e.y0 < 0 || e.x1 < 0 || e.y1 < 0 ||
             e.x0 > 65535 || e.y0 > 65535 || e.x1 > 65535 || e.y1 > 65535)) {
            finding("a drag outside its ranges was accepted");
        }
        if (e.kind == svcli::ScriptEvent::wheel && (e.amount < -1000 || e.amount > 1000))
            finding("a wheel outside -1000..1000 was accepted");
        if ((e.kind == svcli::ScriptEvent::key || e.kind == svcli::ScriptEvent::snap) &&
            e.text.empty())
            finding("a key or snap without its name was accepted");
    }
}

} // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size) {
    if (size == 0) return 0;
    const int which = data[0] % 8;
    const std::string rest((const char *)data + 1, size - 1);
    std::vector<std::string> args{which == 1 ? "scene" : which == 6 ? "view" : "render"};
    for (std::size_t start = 0; start <= rest.size() && args.size() <= kMaxArgs;) {
        const std::size_t nul = rest.find('\0', start);
        const std::size_t end = nul == std::string::npos ? rest.size() : nul;
        args.push_back(rest.substr(start, end - start));
        if (nul == std::string::npos) break;
        start = nul + 1;
    }
    std::vector<char *> argv;
    for (std::string &a : args) argv.push_back(a.data());
    argv.push_back(nullptr);
    const int argc = (int)args.size();
    try {
        bool help = false;
        switch (which) {
        /* --help ends the parse at once (and the program only prints the
         * usage): what was parsed before it is not checked. */
        case 0: {
            const svcli::RenderArgs r = svcli::parse_render_args(argc, argv.data(), help);
            if (!help) check_render(r);
            break;
        }
        case 1: {
            const svcli::SceneArgs s = svcli::parse_scene_args(argc, argv.data(), help);
            if (!help) check_scene(s);
            break;
        }
        case 2: check_light(sv::parse_light(rest)); break;
        case 3: check_camera(sv::parse_camera(rest)); break;
        case 4: check_placement(sv::parse_model_placement(rest)); break;
        case 6: {
            const svcli::ViewArgs v = svcli::parse_view_args(argc, argv.data(), help);
            if (!help) check_scene(v.scene);
            break;
        }
        case 7: {
            std::vector<svcli::ScriptEvent> events;
            try {
                events = svcli::parse_view_script(rest, "fuzz.script");
            } catch (const std::runtime_error &e) {
                check_message(e.what(), "a script refusal");
            }
            check_script(events);
            break;
        }
        default: {
            int w = 0, h = 0;
            svcli::parse_frame_size(rest, w, h);
            check_size(w, h);
        }
        }
    } catch (const svcli::UsageError &e) {
        check_message(e.message, "a usage error");
    } catch (const sv::SceneError &e) {
        check_message(e.what(), "a scene error");
    } catch (const std::exception &e) {
        finding(std::string("an undocumented exception: ") + sv::printable_text(e.what()));
    }
    return 0;
}
