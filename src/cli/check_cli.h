/*
 * shadowvol check (issue 16): the differential and ABI checks of every
 * routine and variant this CPU runs, in the program (checkasm's way), with
 * no GoogleTest or build tree; --bench adds checkasm's cycle counts.
 *
 * Copyright (C) 2026 the shadowvol authors. LGPL-2.1-or-later.
 */
#ifndef SV_CLI_CHECK_CLI_H
#define SV_CLI_CHECK_CLI_H

#include <cstdio>

namespace svcli {

int check_main(int argc, char **argv);
void check_usage(FILE *out);

} // namespace svcli

#endif
