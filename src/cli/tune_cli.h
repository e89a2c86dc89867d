/*
 * shadowvol tune (issue 15): measures every variant of every routine this
 * CPU runs, per size class, and writes the winners to the wisdom file that
 * the planner (include/shadowvol_plan.h) reads.
 *
 * Copyright (C) 2026 the shadowvol authors. LGPL-2.1-or-later.
 */
#ifndef SV_CLI_TUNE_CLI_H
#define SV_CLI_TUNE_CLI_H

#include <cstdio>

namespace svcli {

int tune_main(int argc, char **argv);
void tune_usage(FILE *out);

} // namespace svcli

#endif
