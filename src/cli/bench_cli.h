/*
 * `shadowvol bench`: option parsing and usage of the cycle table, as a
 * function the shadowvol program's dispatcher (main.cpp) calls.
 *
 * Copyright (C) 2026 the shadowvol authors. LGPL-2.1-or-later.
 */
#ifndef SV_CLI_BENCH_CLI_H
#define SV_CLI_BENCH_CLI_H

#include <cstdio>

namespace svbench {

/* ARGV[0] is the subcommand's name ("bench"). Returns the exit status: 0
 * done, 1 a row failed its correctness check (or an internal error), 2 bad
 * arguments, 3 a model could not be loaded. */
int bench_main(int argc, char **argv);

/* The --help text. */
void bench_usage(FILE *out);

} // namespace svbench

#endif
