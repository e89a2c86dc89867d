/*
 * The automatic stencil method ("auto"): per light, brute force or the
 * hierarchical method, chosen from what the light's set-up counted and
 * never by timing during a render. bf and hier set a light's volumes up
 * the same way (volume_pieces.h's first half: the paper's vertex program,
 * clipping, the rasteriser's set-up per triangle), so the set-up is done
 * once, its pieces and their area counted (StencilLoad), and the light goes on as bf (the pieces binned to bands
 * and walked per pixel) or as hier (open edges, caps, classification per
 * tile, the boundary tiles walked) by StencilPassInputs::rule
 * (stencil_method.h says why that count and where its constant comes
 * from). Both are exact, so the stencil is brute force's byte for byte
 * whichever is chosen.
 *
 * Copyright (C) 2026 the shadowvol authors. LGPL-2.1-or-later.
 */
#include <cmath>
#include <utility>

#include "frame_math.h"
#include "pass_bins.h"
#include "stencil_pass.h"
#include "volume_pieces.h"

namespace sv::render {

using namespace detail;

namespace {

StencilLoad count_load(const StencilPassInputs &in, const PieceSetup &setup) {
    StencilLoad load;
    for (std::size_t c = 0; c < setup.chunk_out.size(); c++) {
        const PieceSetup::ChunkOut &o = setup.chunk_out[c];
        const Volume &vol = (*in.volumes)[(std::size_t)setup.chunks[c].volume];
        for (std::size_t i = 0; i < o.pieces.size(); i++) {
            const raster::SetupTriangle &p = o.pieces[i];
            if (p.x_first > p.x_last || p.y_first > p.y_last) continue; /* covers no centre */
            load.pieces++;
            load.rows += (uint64_t)(p.y_last - p.y_first + 1);
            /* Edge e runs (ex, ey) = (step_y, -step_x) / 256 in 1/256 pixel. */
            const double ex0 = (double)p.step_y[0], ey0 = -(double)p.step_x[0];
            const double ex1 = (double)p.step_y[1], ey1 = -(double)p.step_x[1];
            load.area += std::fabs(ex0 * ey1 - ey0 * ex1) / (2.0 * 65536.0 * 65536.0);
            const int *ix = &vol.indices[3 * (std::size_t)o.triangle[i]];
            const int parity = ix[0] & 1;
            load.cap_pieces += (ix[1] & 1) == parity && (ix[2] & 1) == parity;
        }
    }
    return load;
}

/* bf from the shared set-up: each chunk's pieces that cover a pixel
 * centre (the set-up kept the others for hier's classification; bf's own
 * set-up drops them) binned to bands, then bf's walk. */
void brute_force_from(const StencilPassInputs &in, PieceSetup &&setup, StencilPassResult &result) {
    const std::vector<Volume> &volumes = *in.volumes;
    const int height = in.target->height;
    BinnedTriangles bt;
    bt.clear_chunks(setup.chunks.size());
    parallel((int)setup.chunks.size(), [&](int c) {
        std::vector<raster::SetupTriangle> &out = bt.chunks[(std::size_t)c];
        for (const raster::SetupTriangle &p : setup.chunk_out[(std::size_t)c].pieces) {
            if (p.x_first <= p.x_last && p.y_first <= p.y_last) out.push_back(p);
        }
        bt.bin_chunk((std::size_t)c, height);
    });
    for (std::size_t c = 0; c < setup.chunks.size(); c++) {
        result.counters.add(setup.chunk_out[c].counters);
        bt.chunk_mode.push_back(volumes[(std::size_t)setup.chunks[c].volume].zfail
                                    ? raster::StencilMode::zfail
                                    : raster::StencilMode::zpass);
    }
    brute_force_walk(in, bt, result);
    result.ran = StencilMethod::brute_force;
}

} // namespace

StencilPassResult stencil_pass_automatic(const StencilPassInputs &in) {
    check_stencil_tile(in.tile); /* the tile hier would use: refused whichever runs */
    StencilPassResult result;
    const int width = in.target->width, height = in.target->height;
    result.stencil.assign((std::size_t)width * height, 0); /* the clear: not the pass's time */
    const double t0 = now_seconds();
    const uint64_t k0 = ticks();
    PieceSetup setup = set_up_pieces(in);
    result.load = count_load(in, setup);
    if (in.rule.choose_hier(result.load))
        hierarchical_stencil(in, std::move(setup), result);
    else
        brute_force_from(in, std::move(setup), result);
    result.ticks = ticks() - k0;
    result.seconds = now_seconds() - t0;
    return result;
}

} // namespace sv::render
