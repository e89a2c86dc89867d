/*
 * shadowvol render (issue 12): see render_cli.cpp.
 *
 * Copyright (C) 2026 the shadowvol authors. LGPL-2.1-or-later.
 */
#ifndef SV_CLI_RENDER_CLI_H
#define SV_CLI_RENDER_CLI_H

#include <cstdio>

namespace svcli {

int render_main(int argc, char **argv);
void render_usage(FILE *out);

} // namespace svcli

#endif
