/*
 * What every fuzz target of tests/fuzz reports a finding with, and the
 * check every message the program prints must pass (issue 17): bounded,
 * printable UTF-8.
 *
 * Copyright (C) 2026 the shadowvol authors. LGPL-2.1-or-later.
 */
#ifndef SV_FUZZ_SUPPORT_H
#define SV_FUZZ_SUPPORT_H

#include <cstdio>
#include <cstdlib>
#include <string>

#include "shadowvol_gltf.h"

namespace svfuzz {

[[noreturn]] inline void finding(const std::string &what) {
    std::fprintf(stderr, "FUZZ FINDING: %s\n", what.c_str());
    std::fflush(stderr);
    std::abort();
}

/* Messages: at most a few kGltfMaxQuotedBytes, printable UTF-8. */
inline void check_message(const std::string &m, const char *what) {
    if (m.size() > 16 * sv::kGltfMaxQuotedBytes) {
        finding(std::string(what) + " of " + std::to_string(m.size()) + " bytes");
    }
    if (sv::printable_text(m, m.size()) != m) {
        finding(std::string(what) + " is not printable UTF-8: " + sv::printable_text(m));
    }
}

} // namespace svfuzz

#endif
