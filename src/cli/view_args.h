/*
 * The command line of `shadowvol view` (issue 30), parsed with nothing
 * opened: scene's options where they mean the same thing (read by
 * scene_args.h's SharedSceneOptions, not a copy), and the view's own.
 *
 * Copyright (C) 2026 the shadowvol authors. LGPL-2.1-or-later.
 */
#ifndef SV_CLI_VIEW_ARGS_H
#define SV_CLI_VIEW_ARGS_H

#include <string>

#include "scene_args.h"

namespace svcli {

struct ViewArgs {
    /* The options shared with scene; the rest of SceneArgs stays at its
     * defaults (scene's frames, output and checks mean nothing here). */
    SceneArgs scene;
    std::string script; /* --script FILE (view_script.h) */
    bool hud = true;    /* --no-hud: the on-screen line starts off (H) */
};

/* argv[1..] of `shadowvol view`. --help / -h sets HELP and returns at
 * once. Throws UsageError or sv::SceneError, as parse_scene_args. */
ViewArgs parse_view_args(int argc, char **argv, bool &help);

} // namespace svcli

#endif
