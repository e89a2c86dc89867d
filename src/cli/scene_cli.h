/*
 * shadowvol scene (issue 13): see scene_cli.cpp.
 *
 * Copyright (C) 2026 the shadowvol authors. LGPL-2.1-or-later.
 */
#ifndef SV_CLI_SCENE_CLI_H
#define SV_CLI_SCENE_CLI_H

#include <cstdio>

namespace svcli {

int scene_main(int argc, char **argv);
void scene_usage(FILE *out);

} // namespace svcli

#endif
