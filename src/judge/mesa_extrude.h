/*
 * The GLSL judge of seed 002's vertex program (issue 31): the same program
 * as shadowvol_extrude.h emulates on the CPU, written as a GLSL vertex
 * shader and run by Mesa's llvmpipe (OSMesa, a GL 4.5 core context as the
 * Mesa judge makes it), its outputs read back by transform feedback.
 *
 * The shader follows the seed's sequence (sub, dp3, rsq, mul, dp3, slt;
 * rcp, sub, max, mad) as GLSL says it: `inversesqrt` for rsq, which GLSL
 * does not round correctly (GLSL 4.50, section 4.7.1: 2 ULP), and no
 * `precise`, so llvmpipe may fuse a product and a sum (the mad) as a GPU
 * would. Where the CPU emulation's sqrt-then-divide and this differ is what
 * tests/unit/test_mesa_extrude.cpp measures.
 *
 * Copyright (C) 2026 the shadowvol authors. LGPL-2.1-or-later.
 */
#ifndef SV_GLJUDGE_MESA_EXTRUDE_H
#define SV_GLJUDGE_MESA_EXTRUDE_H

#include <string>
#include <vector>

#include "shadowvol_extrude.h"

namespace sv::gl {

/* STREAM's N vertices (SV_EXTRUDE_STREAM_FLOATS floats each) through the
 * seed's program in GLSL under LIGHT, into OUT (N of them; x, y, z, w as
 * sv_extrude_c_ref writes them). False, with *WHY_NOT, when no GL context
 * can be made (no OSMesa in this build, or none at run time); a GL error
 * once a context exists throws std::runtime_error. *RENDERER, where given,
 * gets GL_RENDERER and GL_VERSION. */
bool mesa_extrude(const float *stream, int n, const sv_extrude_light &light, std::vector<Vec4> &out,
                  std::string *why_not, std::string *renderer = nullptr);

/* Whether this build has OSMesa (then no context is a failure, not a
 * reason to skip). */
bool mesa_extrude_available_at_build();

} // namespace sv::gl

#endif
