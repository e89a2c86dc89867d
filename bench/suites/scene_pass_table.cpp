/*
 * The table of passes of `shadowvol bench --scene` (scene_pass_table.h).
 *
 * Like for like: every method renders the same frames at the same thread
 * count, each (frame, method, threads) RUNS times after one warm-up frame,
 * and the minimum of the pass's wall time is kept; a row's figure is the
 * mean of those minima over the frames. Each row keeps one FrameScratch
 * through its frames, as a sequence does (src/cli/scene_cli.cpp): what a
 * method keeps from frame to frame (hier and db: the receivers' triangles
 * grouped, keyed by their index lists) is kept here too. The check of the same run: each
 * light's stencil of every frame equals brute force's at that thread count
 * byte for byte (and brute force's on every core equals its own on one).
 *
 * Copyright (C) 2026 the shadowvol authors. LGPL-2.1-or-later.
 */
#include "scene_pass_table.h"

#include <algorithm>
#include <limits>
#include <memory>

#include "frame.h"
#include "json_writer.h"

namespace svbench {
namespace {

using sv::render::Frame;
using sv::render::RenderOptions;
using sv::render::StencilMethod;

constexpr StencilMethod kMethods[] = {StencilMethod::brute_force, StencilMethod::depth_bounds,
                                      StencilMethod::hierarchical, StencilMethod::automatic};

/* What one render of a frame gives the table: per pass its wall ms. */
struct PassTiming {
    double stencil_ms = 0;
};

PassTiming pass_timing(const Frame &f) {
    PassTiming t;
    for (const auto &lf : f.lights) t.stencil_ms += 1e3 * lf.seconds_stencil;
    return t;
}

/* Seed 004's Table 1 accounting (section 6 and 5; Aila and
 * Akenine-Moeller 2004), as a model counted from the frame, not a change
 * of the bytes the pass writes:
 *  - stencil in the shadow pass: 8-bit stencil, read and written where a
 *    pixel is updated per pixel (hier: in its boundary tiles; a tile
 *    updated wholesale changes its S_min/S_max on chip, no external
 *    bytes);
 *  - Z in the shadow pass: 32-bit depth read where a pixel is tested per
 *    pixel, halved by the seed's assumed lossless Z compression (its
 *    z_min/z_max on chip);
 *  - stencil in the lighting pass: one byte per pixel that shows a
 *    surface, per light; hier only in tiles whose S_min != S_max (the
 *    boundary tiles of the combined shadow, section 4.1.2), elsewhere the
 *    on-chip S_min decides;
 *  - PSV buffer: each 64-byte line of it a volume touches read into the
 *    on-chip cache and written back once (StencilPassResult::psv_lines;
 *    reuse across volumes not counted, so at most what a 2 KB cache
 *    costs);
 *  - delay stream: each drawn volume triangle written and read back as
 *    one new 12-byte position (the seed's history compression keeps
 *    positions only and drops repeated vertices: about one new vertex a
 *    triangle in a mesh).
 * Not modelled: the FS buffer's skipping of tiles already in full shadow
 * (hier here walks them, to keep brute force's bytes: its figures are
 * upper bounds of the seed's), and brute force's z_min/z_max culling (our
 * bf tests every covered pixel). */
struct Bandwidth {
    double stencil_shadow = 0, z_shadow = 0, stencil_lighting = 0, psv = 0, delay = 0;
};
Bandwidth bandwidth_model(const Frame &f, bool hier, int tile) {
    Bandwidth b;
    const int w = f.width, h = f.height;
    for (const auto &lf : f.lights) {
        b.stencil_shadow += 2.0 * (double)lf.stencil_counters.pixels_written;
        b.z_shadow += 0.5 * 4.0 * (double)lf.stencil_counters.pixels_tested;
        if (hier) {
            b.psv += 2.0 * 64.0 * (double)lf.stencil_psv_lines;
            const int64_t triangles = lf.drawn_indices / 3;
            b.delay += 2.0 * 12.0 * (double)triangles;
        }
        if (lf.stencil.size() != (std::size_t)w * (std::size_t)h) continue;
        const int side = hier ? tile : 1;
        for (int y0 = 0; y0 < h; y0 += side) {
            for (int x0 = 0; x0 < w; x0 += side) {
                uint8_t lo = 255, hi = 0;
                uint64_t shown = 0;
                for (int y = y0; y < std::min(h, y0 + side); y++) {
                    for (int x = x0; x < std::min(w, x0 + side); x++) {
                        const std::size_t i = (std::size_t)y * (std::size_t)w + (std::size_t)x;
                        lo = std::min(lo, lf.stencil[i]);
                        hi = std::max(hi, lf.stencil[i]);
                        shown += f.target.ids[i] >= 0;
                    }
                }
                if (!hier || lo != hi) b.stencil_lighting += (double)shown;
            }
        }
    }
    return b;
}

std::vector<std::vector<uint8_t>> stencils(const Frame &f) {
    std::vector<std::vector<uint8_t>> s;
    for (const auto &lf : f.lights) s.push_back(lf.stencil);
    return s;
}

} // namespace

int PassTable::failed() const {
    int n = 0;
    for (const PassRow &r : rows) n += r.frames_equal != r.frames;
    return n;
}

PassTable run_pass_table(ScenePreset &preset, const PassTableOptions &o) {
    PassTable t;
    t.scene = preset.describe();
    t.width = o.width;
    t.height = o.height;
    const int default_tile = o.stencil_tile ? o.stencil_tile : sv::render::kDefaultStencilTile;
    std::vector<int> thread_counts = {1};
    if (o.threads_all > 1) thread_counts.push_back(o.threads_all);
    /* Per thread count: bf first (the reference of the rows after it), db,
     * hier at the default tile; then, on 1 thread, hier at the other tile
     * sizes (the tile-size measurement). */
    for (int threads : thread_counts) {
        for (StencilMethod m : kMethods) {
            PassRow r;
            r.pass = "stencil";
            r.method = sv::render::stencil_method_name(m);
            r.tile = m == StencilMethod::hierarchical || m == StencilMethod::automatic
                         ? default_tile
                         : 0;
            r.threads = threads;
            r.frames = o.frames;
            r.runs = o.runs;
            t.rows.push_back(r);
        }
    }
    for (int tile : {4, 8, 16, 32}) {
        if (tile == default_tile || !o.tile_rows) continue;
        PassRow r;
        r.pass = "stencil";
        r.method = "hier";
        r.tile = tile;
        r.threads = 1;
        r.frames = o.frames;
        r.runs = o.runs;
        t.rows.push_back(r);
    }
    auto options = [&](const PassRow &r) {
        RenderOptions ro;
        ro.width = o.width;
        ro.height = o.height;
        sv::render::stencil_method_by_name(r.method, ro.stencil);
        ro.threads = r.threads;
        if (r.tile) ro.stencil_tile = r.tile;
        return ro;
    };
    std::vector<std::unique_ptr<sv::render::FrameScratch>> scratch;
    for (std::size_t i = 0; i < t.rows.size(); i++)
        scratch.push_back(std::make_unique<sv::render::FrameScratch>());
    auto render = [&](const sv::Scene &scene, std::size_t row) {
        RenderOptions ro = options(t.rows[row]);
        ro.scratch = scratch[row].get();
        return sv::render::render_frame(scene, ro);
    };
    /* Warm-up: one frame of each configuration, not timed. */
    {
        const sv::Scene &scene = preset.at(0);
        for (std::size_t i = 0; i < t.rows.size(); i++) (void)render(scene, i);
    }
    for (int k = 0; k < o.frames; k++) {
        const sv::Scene &scene = preset.at(k);
        t.lights = (int)scene.lights.size();
        std::vector<std::vector<uint8_t>> bf_one_thread, bf;
        int bf_threads = 0;
        for (std::size_t row = 0; row < t.rows.size(); row++) {
            PassRow &r = t.rows[row];
            double best = std::numeric_limits<double>::infinity();
            std::vector<std::vector<uint8_t>> mine;
            for (int run = 0; run < o.runs; run++) {
                const Frame f = render(scene, row);
                best = std::min(best, pass_timing(f).stencil_ms);
                if (run == 0) {
                    mine = stencils(f);
                    uint64_t px = 0, tris = 0;
                    for (const auto &lf : f.lights) {
                        px += lf.stencil_counters.pixels_tested;
                        tris += (uint64_t)lf.drawn_indices / 3;
                    }
                    r.pixels_per_frame += px;
                    r.volume_triangles += tris;
                    const Bandwidth bw = bandwidth_model(f, r.method == "hier", r.tile);
                    r.bw_stencil_shadow += bw.stencil_shadow;
                    r.bw_z_shadow += bw.z_shadow;
                    r.bw_stencil_lighting += bw.stencil_lighting;
                    r.bw_psv += bw.psv;
                    r.bw_delay += bw.delay;
                }
            }
            r.ms_per_frame += best;
            if (r.method == "bf") {
                bf = mine;
                bf_threads = r.threads;
                if (r.threads == 1) bf_one_thread = mine;
                r.frames_equal += mine == bf_one_thread;
            } else {
                r.frames_equal += mine == (r.threads == bf_threads ? bf : bf_one_thread);
            }
        }
    }
    for (PassRow &r : t.rows) {
        r.ms_per_frame /= std::max(1, o.frames);
        r.pixels_per_frame /= (uint64_t)std::max(1, o.frames);
        r.volume_triangles /= (uint64_t)std::max(1, o.frames);
        for (double *v : {&r.bw_stencil_shadow, &r.bw_z_shadow, &r.bw_stencil_lighting, &r.bw_psv,
                          &r.bw_delay}) {
            *v /= std::max(1, o.frames);
        }
    }
    return t;
}

void print_pass_table(FILE *out, const PassTable &t) {
    std::fprintf(out, "%s\n%dx%d, %d light(s), %d frame(s) 1/8 s apart, min of %d run(s) each\n",
                 t.scene.c_str(), t.width, t.height, t.lights,
                 t.rows.empty() ? 0 : t.rows[0].frames, t.rows.empty() ? 0 : t.rows[0].runs);
    std::fprintf(out, "%-8s %-6s %4s %7s %10s %8s %14s %8s %12s %6s\n", "pass", "method", "tile",
                 "threads", "ms/frame", "bf/this", "pixels tested", "bf/this", "volume tris",
                 "=bf");
    for (const PassRow &r : t.rows) {
        const PassRow *bf = nullptr;
        for (const PassRow &b : t.rows) {
            if (b.pass == r.pass && b.threads == r.threads && b.method == "bf" && !bf) bf = &b;
        }
        const double time_ratio = bf && r.ms_per_frame > 0 ? bf->ms_per_frame / r.ms_per_frame : 0;
        const double px_ratio = bf && r.pixels_per_frame
                                    ? (double)bf->pixels_per_frame / (double)r.pixels_per_frame
                                    : 0;
        const std::string tile = r.tile ? std::to_string(r.tile) : "-";
        std::fprintf(out, "%-8s %-6s %4s %7d %10.3f %8.2f %14llu %8.2f %12llu %6s\n",
                     r.pass.c_str(), r.method.c_str(), tile.c_str(), r.threads, r.ms_per_frame,
                     time_ratio, (unsigned long long)r.pixels_per_frame, px_ratio,
                     (unsigned long long)r.volume_triangles,
                     r.frames_equal == r.frames ? "yes" : "NO");
    }
    std::fprintf(out, "(=bf: every light's stencil of every frame equals bf's at that thread "
                      "count, byte for byte; bf's rows: equal to bf on 1 thread; tile: hier's "
                      "tile side)\n");
}

void print_bandwidth_table(FILE *out, const PassTable &t) {
    std::fprintf(out, "\nbandwidth per frame, MB (seed 004's Table 1 accounting, a model counted "
                      "from the pass: docs/RENDERING.md)\n");
    std::fprintf(out, "%-6s %4s %10s %10s %10s %8s %8s %10s %8s\n", "method", "tile", "stencil",
                 "Z", "lighting", "PSV", "delay", "total", "bf/this");
    const PassRow *bf = nullptr;
    for (const PassRow &r : t.rows) {
        if (r.method == "bf" && r.threads == 1 && !bf) bf = &r;
    }
    for (const PassRow &r : t.rows) {
        if (r.threads != 1) continue;
        const std::string tile = r.tile ? std::to_string(r.tile) : "-";
        const double ratio = bf && r.bw_total() > 0 ? bf->bw_total() / r.bw_total() : 0;
        std::fprintf(out, "%-6s %4s %10.3f %10.3f %10.3f %8.3f %8.3f %10.3f %8.2f\n",
                     r.method.c_str(), tile.c_str(), r.bw_stencil_shadow * 1e-6,
                     r.bw_z_shadow * 1e-6, r.bw_stencil_lighting * 1e-6, r.bw_psv * 1e-6,
                     r.bw_delay * 1e-6, r.bw_total() * 1e-6, ratio);
    }
}

void pass_table_json(JsonWriter &j, const PassTable &t) {
    j.begin_object();
    j.key("scene"), j.value(t.scene);
    j.key("width"), j.value(t.width);
    j.key("height"), j.value(t.height);
    j.key("lights"), j.value(t.lights);
    j.key("rows");
    j.begin_array();
    for (const PassRow &r : t.rows) {
        j.begin_object(true);
        j.key("pass"), j.value(r.pass);
        j.key("method"), j.value(r.method);
        j.key("threads"), j.value(r.threads);
        if (r.tile) j.key("tile"), j.value(r.tile);
        j.key("ms_per_frame"), j.value(r.ms_per_frame);
        j.key("pixels_tested_per_frame"), j.value((unsigned long long)r.pixels_per_frame);
        j.key("volume_triangles_per_frame"), j.value((unsigned long long)r.volume_triangles);
        j.key("bw_stencil_shadow"), j.value(r.bw_stencil_shadow);
        j.key("bw_z_shadow"), j.value(r.bw_z_shadow);
        j.key("bw_stencil_lighting"), j.value(r.bw_stencil_lighting);
        j.key("bw_psv"), j.value(r.bw_psv);
        j.key("bw_delay"), j.value(r.bw_delay);
        j.key("bw_total"), j.value(r.bw_total());
        j.key("frames"), j.value(r.frames);
        j.key("runs"), j.value(r.runs);
        j.key("frames_equal_to_bf"), j.value(r.frames_equal);
        j.end_object();
    }
    j.end_array();
    j.end_object();
}

} // namespace svbench
