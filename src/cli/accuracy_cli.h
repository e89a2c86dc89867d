/*
 * `shadowvol accuracy` (src/cli/accuracy_cli.cpp): speed against accuracy
 * of the facing decision, per variant, model and light placement.
 *
 * Copyright (C) 2026 the shadowvol authors. LGPL-2.1-or-later.
 */
#ifndef SV_CLI_ACCURACY_CLI_H
#define SV_CLI_ACCURACY_CLI_H

#include <cstdio>

namespace svcli {

/* ARGV[0] is the subcommand's name. Returns the exit status: 0 done, 1 a
 * variant broke its contract, 2 bad arguments, 3 a model could not be
 * loaded (or an output file not written). */
int accuracy_main(int argc, char **argv);
void accuracy_usage(FILE *out);

} // namespace svcli

#endif
