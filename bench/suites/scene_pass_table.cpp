/*
 * The table of passes of `shadowvol bench --scene` (scene_pass_table.h).
 *
 * Like for like: every method renders the same frames at the same thread
 * count, each (frame, method, threads) RUNS times after one warm-up frame,
 * and the minimum of the pass's wall time is kept; a row's figure is the
 * mean of those minima over the frames. The check of the same run: each
 * light's stencil of every frame equals brute force's at that thread count
 * byte for byte (and brute force's on every core equals its own on one).
 *
 * Copyright (C) 2026 the shadowvol authors. LGPL-2.1-or-later.
 */
#include "scene_pass_table.h"

#include <algorithm>
#include <limits>

#include "frame.h"
#include "json_writer.h"

namespace svbench {
namespace {

using sv::render::Frame;
using sv::render::RenderOptions;
using sv::render::StencilMethod;

constexpr StencilMethod kMethods[] = {StencilMethod::brute_force, StencilMethod::depth_bounds,
                                      StencilMethod::hierarchical};

/* What one render of a frame gives the table: per pass its wall ms. */
struct PassTiming {
    double stencil_ms = 0;
};

PassTiming pass_timing(const Frame &f) {
    PassTiming t;
    for (const auto &lf : f.lights) t.stencil_ms += 1e3 * lf.seconds_stencil;
    return t;
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
            r.tile = m == StencilMethod::hierarchical ? default_tile : 0;
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
    /* Warm-up: one frame of each configuration, not timed. */
    {
        const sv::Scene &scene = preset.at(0);
        for (const PassRow &r : t.rows) (void)sv::render::render_frame(scene, options(r));
    }
    for (int k = 0; k < o.frames; k++) {
        const sv::Scene &scene = preset.at(k);
        t.lights = (int)scene.lights.size();
        std::vector<std::vector<uint8_t>> bf_one_thread, bf;
        int bf_threads = 0;
        for (PassRow &r : t.rows) {
            double best = std::numeric_limits<double>::infinity();
            std::vector<std::vector<uint8_t>> mine;
            for (int run = 0; run < o.runs; run++) {
                const Frame f = sv::render::render_frame(scene, options(r));
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
        j.key("frames"), j.value(r.frames);
        j.key("runs"), j.value(r.runs);
        j.key("frames_equal_to_bf"), j.value(r.frames_equal);
        j.end_object();
    }
    j.end_array();
    j.end_object();
}

} // namespace svbench
