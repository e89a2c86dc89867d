/*
 * The command line of `shadowvol render`, parsed into RenderArgs with
 * nothing run and no file opened: what render_cli.cpp acts on, and what
 * tests/fuzz/fuzz_options.cpp feeds hostile arguments.
 *
 * Copyright (C) 2026 the shadowvol authors. LGPL-2.1-or-later.
 */
#ifndef SV_CLI_RENDER_ARGS_H
#define SV_CLI_RENDER_ARGS_H

#include <string>
#include <vector>

#include "frame.h"
#include "scene_options.h"
#include "volume_args.h"
#include "shadowvol_scene.h"

namespace svcli {

/* --stencil and --stencil-tile as given, and where neither says, the
 * default (take_stencil_default, stencil_default.cpp: the wisdom file's
 * choice, else auto with its offline threshold). */
struct StencilArgs {
    sv::render::StencilMethod method = sv::render::StencilMethod::automatic;
    int tile = sv::render::kDefaultStencilTile; /* hier's (and auto's hier's) tile side */
    sv::render::StencilRule rule;               /* auto's threshold */
    bool method_given = false, tile_given = false;
    const char *source = "default"; /* of the method: "option", "wisdom", "measured", "default" */
    void apply(sv::render::RenderOptions &o) const {
        o.stencil = method;
        o.stencil_tile = tile;
        o.stencil_rule = rule;
    }
};

/* Fills what S's options left open from this process's stencil choice
 * (sv_stencil_choice_for: `shadowvol tune`'s measurement or the wisdom
 * file, which the caller loads first): its method unless --stencil was
 * given, its tile unless --stencil-tile was, its threshold for auto; with
 * no choice, auto at kDefaultHierFromAreaPerPiece. */
void take_stencil_default(StencilArgs &s);

struct RenderArgs {
    std::vector<sv::ModelPlacement> models;
    bool ground = false;
    std::vector<sv::SceneLight> lights;
    bool has_camera = false;
    sv::Camera camera;
    int width = 1280, height = 1024;
    sv::render::ModeChoice mode = sv::render::ModeChoice::automatic;
    StencilArgs stencil; /* --stencil, --stencil-tile */
    sv::CasterRule caster_rule = sv::CasterRule::automatic;
    bool ground_hints = true;
    VolumeArgs volume; /* --volume, --stencil-op, --extrude-to */
    sv::GeneralBuild general_build = sv::render::RenderOptions{}.general_build;
    std::string out_dir = "shadowvol-render";
    std::string json_path;
    std::string kernels, variant;
    bool truth = true, gl = true;
    int threads = 0;
};

/* argv[1..] of `shadowvol render`. --help / -h sets HELP and returns at
 * once. Throws UsageError (cli_args.h) or sv::SceneError (a malformed
 * --light, --camera, --add) with a message naming the argument. */
RenderArgs parse_render_args(int argc, char **argv, bool &help);

class ArgReader;

/* The options render and scene share for what the scene holds: --add,
 * --ground, --light, --camera. Consumes A's value and returns true when A
 * is one of them; false (nothing consumed) otherwise. Throws as the
 * parsers do. */
bool parse_scene_content_option(ArgReader &a, std::vector<sv::ModelPlacement> &adds, bool &ground,
                                std::vector<sv::SceneLight> &lights, sv::Camera &camera,
                                bool &has_camera);

/* The options render and scene share for how the frame's passes run:
 * --stencil METHOD (stencil_method.h), --stencil-tile 4|8|16|32 (hier's
 * tile side). Consumes A's value and returns true when A is one of them;
 * false (nothing consumed) otherwise. Throws UsageError for a value no
 * method or tile side has. */
bool parse_render_pass_option(ArgReader &a, StencilArgs &stencil);

/* --caster-rule auto|closed|general (shadowvol_casters.h), shared by
 * render, scene and bench --scene. As parse_render_pass_option. */
bool parse_caster_rule_option(ArgReader &a, sv::CasterRule &rule);
/* --ground-hints use|ignore: whether a surface declared ground keeps the
 * paper's rule under auto (RenderOptions::ground_hints), shared by render
 * and scene. As parse_render_pass_option. */
bool parse_ground_hints_option(ArgReader &a, bool &use);
/* --general-build two-sided|direct (shadowvol_casters.h): how the general
 * rule's volumes are built, shared by render and scene. As
 * parse_render_pass_option. */
bool parse_general_build_option(ArgReader &a, sv::GeneralBuild &build);

/* --mode zpass|zfail|auto, shared by render and scene. As
 * parse_render_pass_option. */
bool parse_mode_option(ArgReader &a, sv::render::ModeChoice &mode);

/* "WxH" -> width, height, each 1..kMaxFrameSide and at most kMaxFramePixels
 * in all; UsageError otherwise. */
void parse_frame_size(const std::string &text, int &width, int &height);

} // namespace svcli

#endif
