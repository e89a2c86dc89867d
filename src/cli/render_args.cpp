/*
 * Copyright (C) 2026 the shadowvol authors. LGPL-2.1-or-later.
 */
#include "render_args.h"

#include <string>

#include "cli_args.h"
#include "scene_options.h"

namespace svcli {

void parse_frame_size(const std::string &text, int &width, int &height) {
    const std::size_t x = text.find('x');
    auto num = [&](const std::string &t) -> long long {
        if (t.empty() || t.size() > 9 || t.find_first_not_of("0123456789") != std::string::npos)
            return -1;
        return std::stoll(t);
    };
    const long long a = x == std::string::npos ? -1 : num(text.substr(0, x));
    const long long b = x == std::string::npos ? -1 : num(text.substr(x + 1));
    if (a < 1 || b < 1 || a > sv::render::kMaxFrameSide || b > sv::render::kMaxFrameSide ||
        a * b > sv::render::kMaxFramePixels) {
        usage_error("--size needs WxH with 1 <= W, H <= " +
                    std::to_string(sv::render::kMaxFrameSide) + " (not '" + quoted(text) + "')");
    }
    width = (int)a, height = (int)b;
}

bool parse_scene_content_option(ArgReader &a, std::vector<sv::ModelPlacement> &adds, bool &ground,
                                std::vector<sv::SceneLight> &lights, sv::Camera &camera,
                                bool &has_camera) {
    if (a.is("--add")) {
        adds.push_back(sv::parse_model_placement(a.value()));
    } else if (a.is_flag("--ground")) {
        ground = true;
    } else if (a.is("--light")) {
        lights.push_back(sv::parse_light(a.value()));
    } else if (a.is("--camera")) {
        camera = sv::parse_camera(a.value());
        has_camera = true;
    } else {
        return false;
    }
    return true;
}

bool parse_render_pass_option(ArgReader &a, StencilArgs &stencil) {
    if (a.is("--stencil")) {
        const std::string m = a.value();
        if (!sv::render::stencil_method_by_name(m, stencil.method)) {
            usage_error("--stencil needs " + sv::render::stencil_method_names() + ", not '" +
                        quoted(m) + "'");
        }
        stencil.method_given = true;
        stencil.source = "option";
    } else if (a.is("--stencil-tile")) {
        const std::string t = a.value();
        const int side = t == "4" ? 4 : t == "8" ? 8 : t == "16" ? 16 : t == "32" ? 32 : 0;
        if (!sv::render::valid_stencil_tile(side))
            usage_error("--stencil-tile needs 4, 8, 16 or 32, not '" + quoted(t) + "'");
        stencil.tile = side;
        stencil.tile_given = true;
    } else {
        return false;
    }
    return true;
}

bool parse_caster_rule_option(ArgReader &a, sv::CasterRule &rule) {
    if (!a.is("--caster-rule")) return false;
    const std::string r = a.value();
    if (!sv::caster_rule_by_name(r, rule))
        usage_error("--caster-rule needs auto, closed or general, not '" + quoted(r) + "'");
    return true;
}

bool parse_ground_hints_option(ArgReader &a, bool &use) {
    if (!a.is("--ground-hints")) return false;
    const std::string h = a.value();
    if (h != "use" && h != "ignore")
        usage_error("--ground-hints needs use or ignore, not '" + quoted(h) + "'");
    use = h == "use";
    return true;
}

bool parse_general_build_option(ArgReader &a, sv::GeneralBuild &build) {
    if (!a.is("--general-build")) return false;
    const std::string b = a.value();
    if (!sv::general_build_by_name(b, build))
        usage_error("--general-build needs two-sided or direct, not '" + quoted(b) + "'");
    return true;
}

bool parse_mode_option(ArgReader &a, sv::render::ModeChoice &mode) {
    if (!a.is("--mode")) return false;
    const std::string m = a.value();
    if (m == "zpass")
        mode = sv::render::ModeChoice::zpass;
    else if (m == "zfail")
        mode = sv::render::ModeChoice::zfail;
    else if (m == "auto")
        mode = sv::render::ModeChoice::automatic;
    else
        usage_error("--mode needs zpass, zfail or auto, not '" + quoted(m) + "'");
    return true;
}

RenderArgs parse_render_args(int argc, char **argv, bool &help) {
    RenderArgs r;
    ArgReader a(argc, argv);
    while (a.next()) {
        if (a.is_flag("--help") || a.is_flag("-h")) {
            help = true;
            return r;
        } else if (parse_scene_content_option(a, r.models, r.ground, r.lights, r.camera,
                                              r.has_camera) ||
                   parse_render_pass_option(a, r.stencil) ||
                   parse_caster_rule_option(a, r.caster_rule) ||
                   parse_ground_hints_option(a, r.ground_hints) ||
                   parse_general_build_option(a, r.general_build) || parse_mode_option(a, r.mode) ||
                   parse_volume_option(a, r.volume)) {
            /* the options scene shares: --add, --ground, --light, --camera; --stencil;
             * --caster-rule; --ground-hints; --general-build; --mode */
        } else if (a.is("--size")) {
            parse_frame_size(a.value(), r.width, r.height);
        } else if (a.is("--out")) {
            r.out_dir = a.value();
        } else if (a.is("--json")) {
            r.json_path = a.value();
        } else if (a.is("--kernels")) {
            r.kernels = a.value();
        } else if (a.is("--variant")) {
            r.variant = a.value();
        } else if (a.is_flag("--no-truth")) {
            r.truth = false;
        } else if (a.is_flag("--no-gl")) {
            r.gl = false;
        } else if (a.is("--threads")) {
            r.threads = (int)a.integer(1, 256);
        } else {
            usage_error("unknown option '" + quoted(a.arg()) + "'");
        }
    }
    for (const sv::ModelPlacement &m : r.models) {
        if (!m.animation.empty()) {
            usage_error("--add " + quoted(m.path) + ":" + quoted(m.animation) +
                        ": render draws the files at rest; an animation is shadowvol scene's (a "
                        "file name with a ':' is written with a ':' after it)");
        }
    }
    return r;
}

} // namespace svcli
