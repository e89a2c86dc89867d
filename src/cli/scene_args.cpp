/*
 * Copyright (C) 2026 the shadowvol authors. LGPL-2.1-or-later.
 */
#include "scene_args.h"

#include <string>
#include <vector>

#include "cli_args.h"
#include "render_args.h"
#include "scene_options.h"
#include "skinned_normals.h"

namespace svcli {
namespace {

double parse_number(const std::string &text, const std::string &what) {
    const std::vector<double> v = sv::parse_numbers(text, what);
    if (v.size() != 1) usage_error(what + " needs one number, not '" + quoted(text) + "'");
    return v[0];
}

} // namespace

bool SharedSceneOptions::read(ArgReader &a, SceneArgs &r) {
    if (parse_scene_content_option(a, r.seq.adds, r.seq.ground, r.seq.lights, r.seq.camera,
                                   r.seq.has_camera) ||
        parse_render_pass_option(a, r.stencil) || parse_caster_rule_option(a, r.caster_rule) ||
        parse_ground_hints_option(a, r.ground_hints) ||
        parse_general_build_option(a, r.general_build) || parse_mode_option(a, r.mode) ||
        parse_volume_option(a, r.volume)) {
        /* the options render shares too: --add, --ground, --light, --camera; --stencil;
         * --caster-rule; --ground-hints; --general-build; --mode */
    } else if (a.is("--animation")) {
        r.seq.animation = a.value();
        if (r.seq.animation.empty()) usage_error("--animation needs a name or an index");
    } else if (a.is("--fps")) {
        r.fps = parse_number(a.value(), "--fps");
        if (!(r.fps > 0 && r.fps <= 10000))
            usage_error("--fps needs a number above 0 and at most 10000");
    } else if (a.is("--threads")) {
        r.threads = (int)a.integer(1, 256);
    } else if (a.is_flag("--full")) {
        r.full = true;
    } else if (a.is("--size")) {
        parse_frame_size(a.value(), r.width, r.height);
    } else if (a.is("--skinning")) {
        r.skinning = a.value();
    } else if (a.arg().rfind('-', 0) == 0) {
        return false; /* the caller's, or unknown */
    } else if (r.seq.file.empty()) {
        const sv::ModelPlacement m = sv::parse_model_placement(a.arg());
        r.seq.file = m.path;
        r.seq.placement = m.placement;
        file_animation_ = m.animation;
    } else {
        usage_error("one scene file only (add more with --add): '" + quoted(a.arg()) + "'");
    }
    return true;
}

void SharedSceneOptions::finish(SceneArgs &r) const {
    if (file_animation_.empty()) return;
    if (!r.seq.animation.empty()) {
        usage_error(quoted(r.seq.file) + ": its animation is given twice (FILE:" +
                    quoted(file_animation_) + " and --animation)");
    }
    r.seq.animation = file_animation_;
}

SceneArgs parse_scene_args(int argc, char **argv, bool &help) {
    SceneArgs r;
    SharedSceneOptions shared;
    ArgReader a(argc, argv);
    while (a.next()) {
        if (a.is_flag("--help") || a.is_flag("-h")) {
            help = true;
            return r;
        } else if (shared.read(a, r)) {
            /* FILE, the scene, the frame's passes, the clock's rate, threads, size */
        } else if (a.is("--frames")) {
            r.frames = (int)a.integer(1, 10000);
        } else if (a.is("--time")) {
            const std::string t = a.value();
            const std::size_t c = t.find(':');
            if (c == std::string::npos)
                usage_error("--time needs FROM:TO in seconds, not '" + quoted(t) + "'");
            r.time_from = parse_number(t.substr(0, c), "--time");
            r.time_to = parse_number(t.substr(c + 1), "--time");
            if (!(r.time_to >= r.time_from))
                usage_error("--time " + quoted(t) + ": TO must not be before FROM");
            r.has_time = true;
        } else if (a.is_flag("--no-check")) {
            r.check = false;
        } else if (a.is_flag("--no-truth")) {
            r.truth = false;
        } else if (a.is("--skinned-normals")) {
            r.skinned_normals = a.value();
            sv::SkinnedNormals way;
            if (!sv::skinned_normals_by_option(r.skinned_normals, way)) {
                usage_error("--skinned-normals needs straightforward, face-weights, recomputed "
                            "or neighbours, not '" +
                            quoted(r.skinned_normals) + "'");
            }
        } else if (a.is("--out")) {
            r.out_dir = a.value();
        } else if (a.is("--json")) {
            r.json_path = a.value();
        } else if (a.is("--webp")) {
            r.webp_path = a.value();
            if (r.webp_path.empty()) usage_error("--webp needs a file name");
        } else {
            usage_error("unknown option '" + quoted(a.arg()) + "'");
        }
    }
    if (r.has_time && r.frames) usage_error("--frames and --time exclude each other");
    if (!r.skinned_normals.empty() && r.volume.volume != sv::render::VolumeSource::extrude)
        usage_error("--skinned-normals needs --volume extrude (the seed's shadow meshes)");
    shared.finish(r);
    return r;
}

} // namespace svcli
