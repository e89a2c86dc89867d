// shadowvol_check: `shadowvol check` as a program of its own, for the
// SV_CORE_ONLY builds (Windows x64, 32-bit x86), which have no `shadowvol`
// (src/cli needs the full build). Same options, output and exit status.
//
// Copyright (C) 2026 the shadowvol authors. LGPL-2.1-or-later.
#include "check_cli.h"

int main(int argc, char **argv) { return svcli::check_main(argc, argv); }
