/*
 * The command line of `shadowvol scene`, parsed into SceneArgs with
 * nothing run and no file opened: what scene_cli.cpp acts on, and what
 * tests/fuzz/fuzz_options.cpp feeds hostile arguments.
 *
 * Copyright (C) 2026 the shadowvol authors. LGPL-2.1-or-later.
 */
#ifndef SV_CLI_SCENE_ARGS_H
#define SV_CLI_SCENE_ARGS_H

#include <string>

#include "cli_args.h"
#include "frame.h"
#include "sequence.h"
#include "render_args.h"
#include "stencil_method.h"
#include "volume_args.h"

namespace svcli {

struct SceneArgs {
    sv::SequenceOptions seq;
    int frames = 0; /* 0: the default */
    bool has_time = false;
    double time_from = 0, time_to = 0;
    double fps = 8;
    int threads = 0;     /* 0: every core */
    bool full = false;   /* render with no shortcuts */
    StencilArgs stencil; /* --stencil, --stencil-tile (render_args.h) */
    sv::render::ModeChoice mode = sv::render::ModeChoice::automatic;
    sv::CasterRule caster_rule = sv::CasterRule::automatic;
    bool ground_hints = true;
    VolumeArgs volume; /* --volume, --stencil-op, --extrude-to */
    /* --skinned-normals WAY (scene only, with --volume extrude):
     * scene_skinned_normals.h; empty: the recomputed normals, uncounted. */
    std::string skinned_normals;
    sv::GeneralBuild general_build = sv::render::RenderOptions{}.general_build;
    bool check = true; /* render the full frame beside and compare */
    bool truth = true;
    int width = 640, height = 512;
    std::string out_dir = "shadowvol-scene";
    std::string json_path;
    std::string webp_path; /* --webp: the frames as an animated WebP (issue 30) */
    std::string skinning;
};

/* The options shadowvol scene and shadowvol view share (issue 30: the
 * view takes them where they mean the same thing, through this one
 * reader): the scene file FILE[@...][:ANIMATION], --add, --ground,
 * --light, --camera, --animation, --stencil, --stencil-tile, --mode,
 * --caster-rule, --ground-hints, --general-build, --full, --fps,
 * --threads, --size, --skinning. */
class SharedSceneOptions {
public:
    /* True when A's argument was one of them (read into R); false for
     * another option, left to the caller. Throws as parse_scene_args. */
    bool read(ArgReader &a, SceneArgs &r);
    /* After the last argument: the scene file's FILE:ANIMATION against
     * --animation (both: a usage error). */
    void finish(SceneArgs &r) const;

private:
    std::string file_animation_;
};

/* argv[1..] of `shadowvol scene`. --help / -h sets HELP and returns at
 * once. Throws UsageError (cli_args.h) or sv::SceneError (a malformed
 * --light, --camera, --add or scene file placement) with a message naming
 * the argument. */
SceneArgs parse_scene_args(int argc, char **argv, bool &help);

} // namespace svcli

#endif
