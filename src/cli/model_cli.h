/*
 * `shadowvol inspect` and `shadowvol verify` (src/cli/model_cli.cpp): the
 * subcommands that take a glTF model.
 *
 * Copyright (C) 2026 the shadowvol authors. LGPL-2.1-or-later.
 */
#ifndef SV_CLI_MODEL_CLI_H
#define SV_CLI_MODEL_CLI_H

#include <cstdio>

namespace svcli {

/* ARGV[0] is the subcommand's name. Return the exit status: 0 done, 1 a
 * check failed, 2 bad arguments, 3 the model could not be loaded. */
int inspect_main(int argc, char **argv);
void inspect_usage(FILE *out);
int verify_main(int argc, char **argv);
void verify_usage(FILE *out);

} // namespace svcli

#endif
