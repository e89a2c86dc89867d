/*
 * The Mesa judge in a build without OSMesa (pkg-config found no osmesa):
 * no context can be made, and the caller is told why, so a renderer or a
 * test can print the reason and go on without the comparison.
 *
 * Copyright (C) 2026 the shadowvol authors. LGPL-2.1-or-later.
 */
#include "mesa_stencil.h"

namespace sv::gl {

std::unique_ptr<MesaContext> MesaContext::create(int, int, int, std::string *why_not) {
    if (why_not) *why_not = "built without OSMesa: install libosmesa6-dev";
    return nullptr;
}

bool mesa_available_at_build() { return false; }

} // namespace sv::gl
