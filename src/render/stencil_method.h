/*
 * How the stencil pass fills each light's stencil (stencil_pass.h), chosen
 * per frame (RenderOptions::stencil, the CLI's --stencil): every method
 * must leave the same stencil bytes as the brute-force one, the reference.
 *
 * Copyright (C) 2026 the shadowvol authors. LGPL-2.1-or-later.
 */
#ifndef SV_RENDER_STENCIL_METHOD_H
#define SV_RENDER_STENCIL_METHOD_H

#include <cstdint>
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
    /* "auto": per light, bf or hier, chosen after the set-up both share
     * from the light's counts (StencilRule), never by timing. */
    automatic,
};

/* What a light's stencil pass has to do, counted after the set-up every
 * method shares (stencil_auto.cpp), over its volume pieces that cover a
 * pixel centre (triangles after clipping to the view, degenerate ones
 * dropped). */
struct StencilLoad {
    uint64_t pieces = 0;
    double area = 0;         /* the pieces' areas in pixels: about the pixels bf tests */
    uint64_t rows = 0;       /* the pieces' pixel rows: bf's row set-ups */
    uint64_t cap_pieces = 0; /* pieces of caps (triangles of the surface's own vertices
                                or of the extruded ones alone) */
    double area_per_piece() const { return pieces ? area / (double)pieces : 0.0; }
};

/* The automatic method's rule: hier for a light whose pieces cover at
 * least HIER_FROM_AREA_PER_PIECE pixels each on average, bf below. Why
 * this count: bf's cost is per pixel it tests (and per row), hier's per
 * piece (set-up, open edges and caps, classification per tile) plus the
 * boundary tiles' pixels, so small pieces (a terrain's, a dense mesh's
 * z-fail caps) favour bf and large ones (silhouette slivers hundreds of
 * rows tall) favour hier. Measured, never tuned by hand:
 * `shadowvol bench --stencil-rule` times both on every light of the
 * bench's scenes and the render table's models, and picks the threshold
 * with the least total time (docs/results/stencil_rule/: the lights that
 * bf won had 41-58 pixels per piece, those hier won 73 and more);
 * `shadowvol tune` measures it for this CPU into the wisdom file
 * (src/plan/stencil_choices.cpp). This default is the bench's result,
 * taken where no wisdom says otherwise. 0 sends every light to hier,
 * infinity every light to bf (the tests cover both through auto). */
constexpr double kDefaultHierFromAreaPerPiece = 65;
struct StencilRule {
    double hier_from_area_per_piece = kDefaultHierFromAreaPerPiece;
    bool choose_hier(const StencilLoad &load) const {
        return load.pieces > 0 && load.area_per_piece() >= hier_from_area_per_piece;
    }
};

/* Deliberately wrong versions of the hierarchical method's tests, for the
 * tests that show the equality with brute force catches them (as
 * ShortcutFaults, frame.h). Never set outside tests. */
struct StencilFaults {
    bool tile_box_test_too_tight = false; /* the plane's depth at the tile's centre only */
    bool sample_outside_tile = false;     /* the tile's sample point in the next tile */
    /* The receiver's caps by coverage (z-fail): the tiles where they meet
     * the rest of the volume not made boundary tiles; each covered span
     * one pixel short. */
    bool cap_edges_not_boundary = false;
    bool cap_spans_short = false;
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
