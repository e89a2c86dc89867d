/*
 * The GLSL judge of seed 002's program without OSMesa (mesa_extrude.h):
 * it says why it cannot run.
 *
 * Copyright (C) 2026 the shadowvol authors. LGPL-2.1-or-later.
 */
#include "mesa_extrude.h"

namespace sv::gl {

bool mesa_extrude(const float *, int, const sv_extrude_light &, std::vector<Vec4> &,
                  std::string *why_not, std::string *) {
    if (why_not) *why_not = "built without OSMesa: install libosmesa6-dev";
    return false;
}

bool mesa_extrude_available_at_build() { return false; }

} // namespace sv::gl
