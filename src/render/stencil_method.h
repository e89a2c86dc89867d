/*
 * How the stencil pass fills each light's stencil (stencil_pass.h), chosen
 * per frame (RenderOptions::stencil, the CLI's --stencil): every method
 * must leave the same stencil bytes as the brute-force one, the reference.
 *
 * Copyright (C) 2026 the shadowvol authors. LGPL-2.1-or-later.
 */
#ifndef SV_RENDER_STENCIL_METHOD_H
#define SV_RENDER_STENCIL_METHOD_H

#include <string>

namespace sv::render {

enum class StencilMethod {
    /* "bf", brute force: every volume triangle set up and walked row by
     * row over every pixel it covers (the reference). */
    brute_force,
};

/* The method's name on the command line and in the JSON report. */
const char *stencil_method_name(StencilMethod m);
/* NAME -> METHOD; false (METHOD untouched) for a name no method has. */
bool stencil_method_by_name(const std::string &name, StencilMethod &method);
/* The names, "bf" or "bf, ..." (for usage messages). */
std::string stencil_method_names();

} // namespace sv::render

#endif
