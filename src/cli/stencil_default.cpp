/*
 * take_stencil_default (render_args.h): the stencil method render, scene
 * and view draw with when the command line does not say, from the
 * planner's stencil choice (include/shadowvol_plan.h).
 *
 * Copyright (C) 2026 the shadowvol authors. LGPL-2.1-or-later.
 */
#include "render_args.h"
#include "shadowvol_plan.h"

namespace svcli {

void take_stencil_default(StencilArgs &s) {
    sv_stencil_choice c;
    if (sv_stencil_choice_for(&c) != 1) return; /* auto at its offline threshold */
    sv::render::StencilMethod m = sv::render::StencilMethod::automatic;
    /* The planner checked the name against the same four. */
    if (!sv::render::stencil_method_by_name(c.method, m)) return;
    if (!s.method_given) {
        s.method = m;
        s.source = c.source;
    }
    if (!s.tile_given) s.tile = c.tile;
    s.rule.hier_from_area_per_piece = c.hier_from_area_per_piece;
}

} // namespace svcli
