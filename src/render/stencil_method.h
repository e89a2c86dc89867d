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
    /* "db", depth bounds: brute force behind a per-volume depth-bounds
     * test (seed 004's DB), bounds from the volume's drawn pieces. */
    depth_bounds,
    /* "hier", hierarchical (seed 004, Aila and Akenine-Moeller 2004):
     * tiles classified per volume against their depth range; only the
     * tiles a volume's surface crosses are walked per pixel. */
    hierarchical,
};

/* Deliberately wrong versions of the hierarchical method's tests, for the
 * tests that show the equality with brute force catches them (as
 * ShortcutFaults, frame.h). Never set outside tests. */
struct StencilFaults {
    bool tile_box_test_too_tight = false; /* the plane's depth at the tile's centre only */
    bool sample_outside_tile = false;     /* the tile's sample point in the next tile */
};

/* The hierarchical method's tile side in pixels (4, 8, 16 or 32). The
 * default is the side `shadowvol bench --scene` measured fastest on each
 * of its presets (docs/RENDERING.md, "Tile size"): bigger tiles test more
 * pixels per pixel-walked tile but classify four or sixteen times fewer
 * tiles, and classification is what a tile costs on a CPU. Measured by
 * the bench, never during a render. */
constexpr int kDefaultStencilTile = 32;
bool valid_stencil_tile(int side);

/* The method's name on the command line and in the JSON report. */
const char *stencil_method_name(StencilMethod m);
/* NAME -> METHOD; false (METHOD untouched) for a name no method has. */
bool stencil_method_by_name(const std::string &name, StencilMethod &method);
/* The names, "bf" or "bf, ..." (for usage messages). */
std::string stencil_method_names();

} // namespace sv::render

#endif
