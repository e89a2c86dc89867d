/*
 * `shadowvol bench --frame` (issue 29): the whole shadowed frame, pass by
 * pass, beside its floor and beside Mesa's llvmpipe drawing the same frame.
 *
 * The scene plays its animation with the camera orbiting its target and
 * its first point or spot light circling it, a step every frame, so no
 * view-dependent work and nothing of the moving light carries over from
 * one frame to the next. Each frame is drawn RUNS times after the scene is
 * posed, and each pass's minimum kept (the volume pass: its first
 * drawing, before its volumes are cached); Mesa draws the same frame
 * (mesa_frame.h) the same number of times after a warm-up, on as many
 * threads (LP_NUM_THREADS, which llvmpipe reads once per process: run one
 * process per thread count, as tools/frame_table.sh does).
 *
 * Floors: the bytes each pass must touch at the memory rate measured in
 * the same run (memory_rate.h): the depth pass clears depth and ids and
 * reads and writes what its counters count; each light's stencil pass
 * clears its stencil and reads the depth and reads and writes the stencil
 * its counters count; the lighting pass reads the ids and every light's
 * stencil and writes the colour.
 *
 * The checks of the same run: our RUNS drawings of a frame are the same
 * bytes, and Mesa's picture agrees with ours within kFrameTolerance but
 * where the two rasterisers' edges meet (frame_vs_mesa.h).
 *
 * Copyright (C) 2026 the shadowvol authors. LGPL-2.1-or-later.
 */
#include "frame_bench.h"

#include <tbb/info.h>
#include <x86intrin.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <memory>
#include <stdexcept>
#include <string>
#include <vector>

#include "frame.h"
#include "frame_vs_mesa.h"
#include "images.h"
#include "json_writer.h"
#include "memory_rate.h"
#include "scene_presets.h"
#include "workload.h"

#ifndef SV_DEMO_SCENE
#define SV_DEMO_SCENE "models/demo_scene.glb"
#endif
#ifndef SV_MODELS_DIR
#define SV_MODELS_DIR "models"
#endif

namespace svbench {
namespace {

using sv::render::Frame;
using sv::render::RenderOptions;

constexpr double kPi = 3.14159265358979323846;
constexpr double kStepDegrees = 7.5; /* the camera's orbit per frame; the light's is half */

/* P turned by ANGLE radians about the vertical axis through C. */
sv::Vec3d turn(const sv::Vec3d &p, const sv::Vec3d &c, double angle) {
    const double x = p.x - c.x, z = p.z - c.z, cs = std::cos(angle), sn = std::sin(angle);
    return {c.x + cs * x + sn * z, p.y, c.z - sn * x + cs * z};
}
sv::Vec3d turn_direction(const sv::Vec3d &d, double angle) { return turn(d, {0, 0, 0}, angle); }

/* The passes of one frame, ms; the minimum over the runs, each pass its own. */
struct PassTimes {
    double pose = 0, volumes = 0, depth = 0, stencil = 0, lighting = 0;
    double other = 0; /* render_frame's wall time outside the passes: the target's clear, copies */
    double frame = 0;
};

/* Bytes a pass must touch (read, written). */
struct Bytes {
    double read = 0, written = 0;
    double ms(const MemoryRate &m) const {
        return 1e3 * (read / m.read_bytes_per_second + written / m.write_bytes_per_second);
    }
};

struct Floors {
    Bytes depth, stencil, lighting;
};

Floors floors_of(const Frame &f) {
    Floors fl;
    const double px = (double)f.width * f.height;
    const auto &d = f.depth_counters;
    fl.depth.read = (double)d.depth_bytes_read;
    fl.depth.written = 8 * px + (double)d.depth_bytes_written + 4.0 * (double)d.pixels_written;
    for (const auto &lf : f.lights) {
        const auto &c = lf.stencil_counters;
        fl.stencil.read += (double)c.depth_bytes_read + (double)c.stencil_bytes_read;
        fl.stencil.written += px + (double)c.stencil_bytes_written;
    }
    fl.lighting.read = (4.0 + (double)f.lights.size()) * px;
    fl.lighting.written = 3 * px;
    return fl;
}

double ms_of(uint64_t ticks, double hz) { return 1e3 * (double)ticks / hz; }

} // namespace

FrameTable measure_frame_table(const SeedCommand &cmd, const FrameBenchOptions &fo, double hz) {
    FrameTable t;
    t.preset = fo.preset.empty() ? "demo" : fo.preset;
    t.width = fo.width, t.height = fo.height;
    t.threads = fo.threads > 0 ? fo.threads : tbb::info::default_concurrency();
    t.frames = std::max(fo.frames, 1), t.runs = std::max(fo.runs, 1);
    std::unique_ptr<ScenePreset> preset = open_bench_preset(cmd, t.preset,
                                                            (double)fo.width / fo.height);
    t.scene = preset->describe();
    const sv::Scene &first = preset->at(0);
    const sv::Camera base_camera = first.camera;
    for (std::size_t i = 0; i < first.lights.size(); i++) {
        if (first.lights[i].kind != sv::LightKind::directional) {
            t.moving_light = (int)i;
            break;
        }
    }
    t.hz = hz;
    t.divider = measure_divider_rate(5);
    t.rate = measure_memory_rate(t.threads, (std::size_t)64 << 20, 3);

    /* One volume cache and one set of frame buffers for the whole run, as
     * an interactive program keeps them: what depends on neither the view
     * nor a moving light (the static surfaces' volumes of the lights that
     * stand still, the casters' preparation) is built once. The volume
     * pass is timed in the first drawing of each frame only (the later
     * ones find its volumes cached); the other passes take their minimum. */
    sv::render::VolumeCache cache;
    sv::render::FrameScratch scratch;
    RenderOptions o;
    o.width = fo.width, o.height = fo.height;
    o.threads = t.threads;
    t.stencil = fo.stencil;
    t.stencil_source = fo.stencil_source;
    t.stencil_tile = fo.stencil_tile;
    t.hier_from_area_per_piece = fo.hier_from_area_per_piece;
    if (!sv::render::stencil_method_by_name(fo.stencil, o.stencil)) {
        throw std::invalid_argument("--stencil " + fo.stencil);
    }
    o.stencil_tile = fo.stencil_tile;
    o.stencil_rule.hier_from_area_per_piece = fo.hier_from_area_per_piece;
    o.cache = &cache;
    o.scratch = &scratch;
    std::vector<PassTimes> ours((std::size_t)t.frames);
    std::vector<double> first_wall((std::size_t)t.frames);
    std::vector<Floors> floors;
    Frame last;
    sv::Scene scene;
    /* Frame 0 is the warm-up: it builds what the cache keeps (an
     * interactive program does so while loading) and is not timed. The
     * timed frames are 1 .. FRAMES. */
    for (int k = 0; k <= t.frames; k++) {
        const uint64_t p0 = __rdtsc();
        const sv::Scene &posed = preset->at(k);
        const double pose_ms = 1e3 * (double)(__rdtsc() - p0) / hz;
        scene = posed; /* a copy to move the camera and the light in (not timed) */
        const double angle = k * kStepDegrees * kPi / 180.0;
        scene.camera.eye = turn(base_camera.eye, base_camera.target, angle);
        if (t.moving_light >= 0) {
            sv::SceneLight &l = scene.lights[(std::size_t)t.moving_light];
            l.position = turn(l.position, base_camera.target, angle / 2);
            l.direction = turn_direction(l.direction, angle / 2);
        }
        if (k == 0) {
            (void)sv::render::render_frame(scene, o);
            continue;
        }
        PassTimes &best = ours[(std::size_t)k - 1];
        std::vector<uint8_t> first_rgb;
        bool same = true;
        for (int r = 0; r < t.runs; r++) {
            Frame f = sv::render::render_frame(scene, o);
            PassTimes p;
            p.volumes = ms_of(f.ticks_jobs, hz);
            p.depth = ms_of(f.ticks_depth, hz);
            for (const auto &lf : f.lights) p.stencil += ms_of(lf.ticks_stencil, hz);
            p.lighting = ms_of(f.ticks_shading, hz);
            p.other = std::max(0.0, ms_of(f.ticks_total, hz) -
                                        (p.volumes + p.depth + p.stencil + p.lighting));
            if (r == 0) {
                best = PassTimes{pose_ms, p.volumes, p.depth, p.stencil, p.lighting, p.other, 0};
                first_wall[(std::size_t)k - 1] = ms_of(f.ticks_total, hz) + pose_ms;
                first_rgb = f.rgb;
            } else {
                best.depth = std::min(best.depth, p.depth);
                best.stencil = std::min(best.stencil, p.stencil);
                best.lighting = std::min(best.lighting, p.lighting);
                best.other = std::min(best.other, p.other);
                same = same && f.rgb == first_rgb;
            }
            if (r == t.runs - 1) last = std::move(f);
        }
        best.frame = best.pose + best.volumes + best.depth + best.stencil + best.lighting +
                     best.other;
        t.same_runs += same;
        floors.push_back(floors_of(last));
        FrameTable::Work &w = t.work;
        w.depth_triangles += (double)last.depth_counters.triangles / t.frames;
        w.depth_rows += (double)last.depth_counters.rows / t.frames;
        w.depth_pixels += (double)last.depth_counters.pixels_tested / t.frames;
        for (const auto &lf : last.lights) {
            w.stencil_triangles += (double)lf.stencil_counters.triangles / t.frames;
            w.stencil_rows += (double)lf.stencil_counters.rows / t.frames;
            w.stencil_pixels += (double)lf.stencil_counters.pixels_tested / t.frames;
        }
        w.pixels = (double)last.width * last.height;
        w.divider_lanes += (double)last.shading_divider_lanes / t.frames;
        w.visible_pixels += (double)std::count_if(last.target.ids.begin(), last.target.ids.end(),
                                                  [](int32_t id) { return id >= 0; }) /
                            t.frames;
        w.lights = (double)last.lights.size();
        if (fo.mesa && t.mesa_note.empty()) {
            sv::render::MesaFrameComparison m =
                sv::render::compare_frame_with_mesa(scene, last, o.ambient, t.threads, t.runs,
                                                    &t.mesa_note);
            if (m.ran) {
                if (t.mesa_renderer.empty()) {
                    t.mesa_renderer = m.renderer;
                    t.lp_num_threads = m.lp_num_threads;
                }
                t.compared += m.compared, t.equal += m.equal, t.on_edge += m.on_edge;
                t.other += m.other, t.stencil_other += m.stencil_other;
                t.mesa.push_back(m);
            }
        }
    }
    t.mesa_wanted = fo.mesa;
    t.last_rgb = last.rgb;
    if (!t.mesa.empty()) t.last_mesa_rgb = t.mesa.back().mesa_rgb;

    /* The rows: each pass's mean over the frames of its minimum. */
    auto mean = [&](double PassTimes::*field) {
        double sum = 0;
        for (const PassTimes &p : ours) sum += p.*field;
        return sum / t.frames;
    };
    auto mean_floor = [&](Bytes Floors::*field) {
        double sum = 0;
        for (const Floors &f : floors) sum += (f.*field).ms(t.rate);
        return sum / t.frames;
    };
    auto mean_mesa = [&](double sv::render::MesaFrameComparison::*field) {
        double sum = 0;
        for (const auto &m : t.mesa) sum += 1e3 * (m.*field);
        return t.mesa.empty() ? -1.0 : sum / (double)t.mesa.size();
    };
    using M = sv::render::MesaFrameComparison;
    t.rows = {
        {"pose, skin, planes", mean(&PassTimes::pose), -1, -1},
        {"volumes", mean(&PassTimes::volumes), -1, -1},
        {"depth", mean(&PassTimes::depth), mean_floor(&Floors::depth),
         mean_mesa(&M::depth_seconds)},
        {"stencil", mean(&PassTimes::stencil), mean_floor(&Floors::stencil),
         mean_mesa(&M::stencil_seconds)},
        {"lighting", mean(&PassTimes::lighting), mean_floor(&Floors::lighting),
         mean_mesa(&M::lighting_seconds)},
        {"clear, copies", mean(&PassTimes::other), -1, -1},
        {"frame", mean(&PassTimes::frame),
         mean_floor(&Floors::depth) + mean_floor(&Floors::stencil) + mean_floor(&Floors::lighting),
         mean_mesa(&M::total_seconds)},
    };
    for (double w : first_wall) t.first_drawing_wall_ms += w / t.frames;
    return t;
}

void print_frame_table(FILE *out, const FrameTable &t) {
    std::fprintf(out,
                 "the whole frame: %s, %d frames 1/8 s apart after a warm-up frame, %dx%d, %d "
                 "thread(s) on both sides, each frame drawn %d time(s) (the minimum kept); the "
                 "camera orbits %.1f deg and light %d %.2f deg a frame; our stencil pass: %s "
                 "(%s; tile %d, auto's hier from %.1f pixels a piece)\n",
                 t.scene.c_str(), t.frames, t.width, t.height, t.threads, t.runs, kStepDegrees,
                 t.moving_light, kStepDegrees / 2, t.stencil.c_str(), t.stencil_source.c_str(),
                 t.stencil_tile, t.hier_from_area_per_piece);
    std::fprintf(out, "memory: %.1f GB/s read, %.1f GB/s write (%d thread(s), best of %d)\n",
                 t.rate.read_bytes_per_second / 1e9, t.rate.write_bytes_per_second / 1e9,
                 t.rate.threads, t.rate.runs);
    std::fprintf(out, "%-20s %10s %10s %8s %10s %8s\n", "pass", "ours ms", "floor ms", "/floor",
                 "Mesa ms", "Mesa/us");
    for (const FrameTable::Row &r : t.rows) {
        std::fprintf(out, "%-20s %10.2f ", r.name, r.ours);
        if (r.floor >= 0) {
            std::fprintf(out, "%10.2f %8.1f ", r.floor, r.ours / r.floor);
        } else {
            std::fprintf(out, "%10s %8s ", "-", "-");
        }
        if (r.mesa > 0) {
            std::fprintf(out, "%10.2f %8.2f\n", r.mesa, r.mesa / r.ours);
        } else {
            std::fprintf(out, "%10s %8s\n", "-", "-");
        }
    }
    /* A pass's ms (-1: no such row), and its ticks per unit of work. */
    auto pass_ms = [&](const char *pass) {
        for (const FrameTable::Row &r : t.rows) {
            if (std::string(r.name) == pass) return r.ours;
        }
        return -1.0;
    };
    auto per = [&](const char *pass, double units) {
        const double ms = pass_ms(pass);
        return ms >= 0 && units > 0 ? ms * 1e-3 * t.hz / units : -1.0;
    };
    const FrameTable::Work &w = t.work;
    std::fprintf(out,
                 "work a frame: depth %.0f triangles, %.2f M rows, %.2f M pixels tested (%.0f "
                 "ticks a triangle); stencil %.0f volume triangles, %.2f M rows, %.2f M pixels "
                 "tested (%.1f ticks a row); lighting %.2f M pixels x %.0f light(s) (%.1f ticks a "
                 "pixel and light)\n",
                 w.depth_triangles, w.depth_rows / 1e6, w.depth_pixels / 1e6,
                 per("depth", w.depth_triangles), w.stencil_triangles, w.stencil_rows / 1e6,
                 w.stencil_pixels / 1e6, per("stencil", w.stencil_rows), w.pixels / 1e6, w.lights,
                 per("lighting", w.pixels * std::max(w.lights, 1.0)));
    /* The lighting pass's exact double arithmetic: a square root and two
     * divides per lane of a point or spot light the kernel computed, a
     * divide per visible pixel; at the divider's rate, on each thread. */
    const DividerRate &dv = t.divider;
    const double divider_ms = (w.divider_lanes *
                                   (dv.sqrt_ticks_per_lane + 2 * dv.div_ticks_per_lane) +
                               w.visible_pixels * dv.div_ticks_per_lane) /
                              t.hz * 1e3;
    const double lighting_ms = pass_ms("lighting");
    std::fprintf(out,
                 "lighting's divider: %.2f M lanes through a light's square root and 2 divides, "
                 "%.2f M visible pixels' ray divide; at this core's rate (divide %.2f, square root "
                 "%.2f ticks a lane in %d-lane vectors, best of %d) %.2f ms on one thread, %.2f "
                 "on %d: the pass takes %.1fx that\n",
                 w.divider_lanes / 1e6, w.visible_pixels / 1e6, dv.div_ticks_per_lane,
                 dv.sqrt_ticks_per_lane, dv.lanes, dv.runs, divider_ms, divider_ms / t.threads,
                 t.threads, divider_ms > 0 ? lighting_ms / (divider_ms / t.threads) : 0.0);
    std::fprintf(out,
                 "(frame: the sum of the rows; the first drawing's wall time with posing: "
                 "%.2f ms. Mesa's frame without a wait between passes, its passes with one; its "
                 "volumes are given, not built)\n",
                 t.first_drawing_wall_ms);
    std::fprintf(out, "check: %d of %d frames the same bytes in each of the %d run(s)%s\n",
                 t.same_runs, t.frames, t.runs, t.same_runs == t.frames ? "" : " -- FAILED");
    if (!t.mesa.empty()) {
        std::fprintf(out,
                     "check: Mesa (%s, LP_NUM_THREADS %d): %llu pixels compared, %llu within %d "
                     "levels, %llu on an edge, %llu other; stencils: %llu other%s\n",
                     t.mesa_renderer.c_str(), t.lp_num_threads, (unsigned long long)t.compared,
                     (unsigned long long)t.equal, sv::render::kFrameTolerance,
                     (unsigned long long)t.on_edge, (unsigned long long)t.other,
                     (unsigned long long)t.stencil_other,
                     t.other == 0 && t.stencil_other == 0 ? "" : " -- FAILED");
        for (const auto &m : t.mesa) {
            for (const std::string &w : m.first_other)
                std::fprintf(out, "  other: %s\n", w.c_str());
        }
    } else if (t.mesa_wanted) {
        std::fprintf(out, "NOTE: %s\n", t.mesa_note.c_str());
    }
}

void frame_table_json(JsonWriter &j, const FrameTable &t) {
    j.begin_object();
    j.key("preset"), j.value(t.preset);
    j.key("width"), j.value(t.width);
    j.key("height"), j.value(t.height);
    j.key("threads"), j.value(t.threads);
    j.key("stencil"), j.value(t.stencil);
    j.key("stencil_source"), j.value(t.stencil_source);
    j.key("stencil_tile"), j.value(t.stencil_tile);
    j.key("stencil_hier_from_area_per_piece");
    if (std::isfinite(t.hier_from_area_per_piece))
        j.value(t.hier_from_area_per_piece);
    else
        j.value("infinity");
    j.key("frames"), j.value(t.frames);
    j.key("runs_per_frame"), j.value(t.runs);
    j.key("first_drawing_wall_ms"), j.value(t.first_drawing_wall_ms);
    j.key("memory_read_gbps"), j.value(t.rate.read_bytes_per_second / 1e9);
    j.key("memory_write_gbps"), j.value(t.rate.write_bytes_per_second / 1e9);
    j.key("passes");
    j.begin_array();
    for (const FrameTable::Row &r : t.rows) {
        j.begin_object(true);
        j.key("pass"), j.value(r.name);
        j.key("ours_ms"), j.value(r.ours);
        if (r.floor >= 0) j.key("floor_ms"), j.value(r.floor);
        if (r.mesa > 0) j.key("mesa_ms"), j.value(r.mesa);
        j.end_object();
    }
    j.end_array();
    j.key("work_per_frame");
    j.begin_object(true);
    j.key("depth_triangles"), j.value(t.work.depth_triangles);
    j.key("depth_rows"), j.value(t.work.depth_rows);
    j.key("depth_pixels_tested"), j.value(t.work.depth_pixels);
    j.key("stencil_triangles"), j.value(t.work.stencil_triangles);
    j.key("stencil_rows"), j.value(t.work.stencil_rows);
    j.key("stencil_pixels_tested"), j.value(t.work.stencil_pixels);
    j.key("pixels"), j.value(t.work.pixels);
    j.key("lights"), j.value(t.work.lights);
    j.key("visible_pixels"), j.value(t.work.visible_pixels);
    j.key("divider_lanes"), j.value(t.work.divider_lanes);
    j.end_object();
    j.key("tsc_hz"), j.value(t.hz);
    j.key("divider");
    j.begin_object(true);
    j.key("div_ticks_per_lane"), j.value(t.divider.div_ticks_per_lane);
    j.key("sqrt_ticks_per_lane"), j.value(t.divider.sqrt_ticks_per_lane);
    j.key("lanes"), j.value(t.divider.lanes);
    j.key("runs"), j.value(t.divider.runs);
    j.end_object();
    j.key("mesa");
    if (t.mesa.empty()) {
        j.null();
    } else {
        j.begin_object();
        j.key("renderer"), j.value(t.mesa_renderer);
        j.key("lp_num_threads"), j.value(t.lp_num_threads);
        j.key("runs_per_frame"), j.value(t.mesa[0].runs);
        j.key("compared"), j.value((unsigned long long)t.compared);
        j.key("equal"), j.value((unsigned long long)t.equal);
        j.key("on_edge"), j.value((unsigned long long)t.on_edge);
        j.key("other"), j.value((unsigned long long)t.other);
        j.key("stencil_other"), j.value((unsigned long long)t.stencil_other);
        j.end_object();
    }
    j.key("same_bytes_every_run"), j.value(t.same_runs == t.frames);
    j.key("ok"), j.value(t.failed() == 0);
    j.end_object();
}

int run_frame_bench(const SeedCommand &cmd, const FrameBenchOptions &fo) {
    return run_seed_frame(cmd, "frame", [&](FILE *out, std::string *doc) {
        const SeedTimer timer = make_seed_timer(cmd.timer, cmd.quick);
        print_seed_header(out, "shadowvol bench --frame: the whole frame, pass by pass", timer, -1,
                          "each frame drawn the times below by us and by Mesa, each pass's "
                          "minimum kept; every drawing's bytes compared");
        const FrameTable t = measure_frame_table(cmd, fo, timer.tscHz);
        print_frame_table(out, t);
        if (!fo.out_dir.empty()) {
            sv::render::Image image(t.width, t.height);
            image.rgb = t.last_rgb;
            sv::render::write_png(fo.out_dir + "/frame_ours.png", image);
            if (!t.last_mesa_rgb.empty()) {
                image.rgb = t.last_mesa_rgb;
                sv::render::write_png(fo.out_dir + "/frame_mesa.png", image);
            }
            std::fprintf(out, "images: %s/frame_ours.png%s\n", fo.out_dir.c_str(),
                         t.last_mesa_rgb.empty() ? "" : ", frame_mesa.png");
        }
        JsonWriter j;
        j.begin_object();
        seed_json_header(j, "shadowvol-frame-bench/1", timer);
        j.key("frame");
        frame_table_json(j, t);
        j.end_object();
        *doc = j.str();
        return t.failed();
    });
}

} // namespace svbench
