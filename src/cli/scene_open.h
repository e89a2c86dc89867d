/*
 * The scene that `shadowvol scene` and `shadowvol view` play, opened from
 * their shared options (scene_args.h) in one place: the demo scene when no
 * FILE is given, the --skinning kernel by name, the frame's aspect, the
 * files loaded and posed at their first frame, the loader's notes printed.
 *
 * Copyright (C) 2026 the shadowvol authors. LGPL-2.1-or-later.
 */
#ifndef SV_CLI_SCENE_OPEN_H
#define SV_CLI_SCENE_OPEN_H

#include <memory>

#include "scene_args.h"
#include "sequence.h"

namespace svcli {

/* The sequence of ARGS (whose seq.file, seq.skinning and seq.aspect it
 * fills in). On failure prints "shadowvol COMMAND: the reason" on stderr
 * and returns nullptr with EXIT_STATUS 2 (bad arguments: a skinning
 * kernel, a placement, a light) or 3 (a file that cannot be loaded). */
std::unique_ptr<sv::SceneSequence> open_scene(const char *command, SceneArgs &args,
                                              int &exit_status);

} // namespace svcli

#endif
