/*
 * shadowvol view (issue 30): see view_cli.cpp.
 *
 * Copyright (C) 2026 the shadowvol authors. LGPL-2.1-or-later.
 */
#ifndef SV_CLI_VIEW_CLI_H
#define SV_CLI_VIEW_CLI_H

#include <cstdio>

namespace svcli {

int view_main(int argc, char **argv);
void view_usage(FILE *out);

} // namespace svcli

#endif
