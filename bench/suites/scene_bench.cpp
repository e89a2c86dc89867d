/*
 * `shadowvol bench --scene` (issue 13): the demo scene frame by frame,
 * with only what each frame requires and with everything (--full), on one
 * thread and on every core, as ratios measured in the same run; what each
 * shortcut saves when it alone is switched off; and the culling decision
 * (appendix B's routine only where a surface straddles the light volume)
 * timed on both sides for the paper's two cases: the big terrain under a
 * small spot light (a car's headlight: culling pays) and the character
 * inside the large lamp (culling would cull nothing: skipping it pays).
 *
 * Every figure comes with the check of the same run: each frame with the
 * shortcuts equals its full frame (the shaded bytes, and the shadow mask
 * wherever the light reaches), and the frames on every core equal those
 * on one thread byte for byte.
 *
 * Copyright (C) 2026 the shadowvol authors. LGPL-2.1-or-later.
 */
#include "scene_bench.h"

#include <tbb/info.h>
#include <x86intrin.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <memory>
#include <string>
#include <vector>

#include "frame.h"
#include "frame_bench.h"
#include "json_writer.h"
#include "shadowvol_gltf.h"
#include "shadowvol_mesh.h"
#include "workload.h"
#include "scene_pass_table.h"
#include "scene_presets.h"
#include "seed_bench.h"
#include "sequence.h"
#include "shadowvol_casters.h"

#ifndef SV_DEMO_SCENE
#define SV_DEMO_SCENE "models/demo_scene.glb"
#endif

namespace svbench {
namespace {

using sv::render::Frame;
using sv::render::RenderOptions;
using sv::render::Shortcuts;

/* A run of the demo scene's frames under one configuration. */
struct Run {
    std::string name;
    Shortcuts shortcuts;
    int threads = 1;
    std::vector<double> ms; /* per frame: pose + render */
    std::vector<std::vector<uint8_t>> rgb;
    int64_t indices_built = 0;
    uint64_t stencil_pixels = 0;
    sv::CasterRule rule = sv::CasterRule::automatic; /* set after the braces above */
    double median_ms() const {
        std::vector<double> v = ms;
        std::sort(v.begin(), v.end());
        return v.empty() ? 0 : v[v.size() / 2];
    }
};

/* Plays FRAMES frames 1/8 s apart from the start (a fresh cache), keeping
 * the pictures; FULL, when given, gets the full frame of each for the
 * proof (not timed). */
void play(const sv::SequenceOptions &so, int frames, int width, int height, double hz, Run &run,
          std::vector<sv::render::FrameDifference> *proof) {
    sv::SceneSequence seq(so);
    sv::render::VolumeCache cache;
    RenderOptions o;
    o.width = width, o.height = height;
    o.threads = run.threads;
    o.shortcuts = run.shortcuts;
    o.caster_rule = run.rule;
    o.cache = &cache;
    RenderOptions full = o;
    full.shortcuts = Shortcuts::none();
    full.cache = nullptr;
    for (int k = 0; k < frames; k++) {
        const uint64_t k0 = __rdtsc();
        seq.set_time(seq.start() + k / 8.0);
        Frame f = sv::render::render_frame(seq.scene(), o);
        run.ms.push_back(1e3 * (double)(__rdtsc() - k0) / hz);
        for (const auto &lf : f.lights) {
            run.indices_built += lf.built_indices;
            run.stencil_pixels += lf.stencil_counters.pixels_tested;
        }
        if (proof) {
            const Frame g = sv::render::render_frame(seq.scene(), full);
            proof->push_back(sv::render::compare_frames(seq.scene(), f, g));
        }
        run.rgb.push_back(std::move(f.rgb));
    }
}

/* One surface under one light, its volume built and drawn again and
 * again: the work of the (facing, culling, volume) job and the stencil
 * pass, the minimum over REPEATS frames. */
struct CullSide {
    bool culled = false;
    uint64_t job_ticks = 0, stencil_ticks = 0;
    int64_t indices = 0;
    uint64_t pixels = 0;
    std::vector<uint8_t> rgb;
};
CullSide cull_side(const sv::Scene &scene, int width, int height, const Shortcuts &sc,
                   int repeats) {
    CullSide best;
    for (int r = 0; r < repeats; r++) {
        RenderOptions o;
        o.width = width, o.height = height;
        o.shortcuts = sc;
        o.shortcuts.reuse_static = false;
        const Frame f = sv::render::render_frame(scene, o);
        const auto &lf = f.lights[0];
        const uint64_t job = lf.ticks_facing + lf.ticks_culling + lf.ticks_volume;
        if (r == 0 || job + lf.ticks_stencil < best.job_ticks + best.stencil_ticks) {
            best.job_ticks = job;
            best.stencil_ticks = lf.ticks_stencil;
        }
        best.culled = lf.culled > 0;
        best.indices = lf.drawn_indices;
        best.pixels = lf.stencil_counters.pixels_tested;
        best.rgb = f.rgb;
    }
    return best;
}

int find_surface(const sv::Scene &s, const std::string &suffix) {
    for (std::size_t i = 0; i < s.surfaces.size(); i++) {
        const std::string &n = s.surfaces[i].name;
        if (n.size() >= suffix.size() &&
            n.compare(n.size() - suffix.size(), suffix.size(), suffix) == 0) {
            return (int)i;
        }
    }
    return -1;
}

/* The table of passes (scene_pass_table.h) of preset NAME at WIDTH x
 * HEIGHT. */
PassTable pass_table(const SeedCommand &cmd, const std::string &name, int width, int height) {
    std::unique_ptr<ScenePreset> preset = open_bench_preset(cmd, name, (double)width / height);
    PassTableOptions po;
    po.width = width;
    po.height = height;
    po.frames = cmd.quick ? 2 : 4;
    po.runs = cmd.quick ? 2 : 3;
    po.threads_all = tbb::info::default_concurrency();
    return run_pass_table(*preset, po);
}

/* --preset / --size: the table of passes alone. */
int run_preset_passes(const SeedCommand &cmd) {
    return run_seed_frame(cmd, "scene", [&](FILE *out, std::string *doc) {
        const SeedTimer timer = make_seed_timer(cmd.timer, cmd.quick);
        const std::string name = cmd.scenePreset.empty() ? "demo" : cmd.scenePreset;
        const int width = cmd.sceneWidth ? cmd.sceneWidth : cmd.quick ? 320 : 640;
        const int height = cmd.sceneHeight ? cmd.sceneHeight : cmd.quick ? 256 : 512;
        print_seed_header(out, "shadowvol bench --scene: the passes of a scene, per method", timer,
                          -1,
                          "each (frame, method, thread count) drawn the runs below after a "
                          "warm-up frame, the minimum kept; every stencil compared with bf's");
        const PassTable t = pass_table(cmd, name, width, height);
        print_pass_table(out, t);
        print_bandwidth_table(out, t);
        /* The whole frame, pass by pass, beside its floor and Mesa's same
         * frame (issue 29; frame_bench.h), on every core. */
        FrameBenchOptions fo;
        fo.preset = name;
        fo.width = width, fo.height = height;
        fo.frames = cmd.quick ? 1 : 4;
        fo.runs = cmd.quick ? 1 : 3;
        std::fprintf(out, "\n");
        const FrameTable frame = measure_frame_table(cmd, fo, timer.tscHz);
        print_frame_table(out, frame);
        JsonWriter j;
        j.begin_object();
        seed_json_header(j, "shadowvol-scene-bench/1", timer);
        j.key("preset"), j.value(name);
        j.key("passes");
        pass_table_json(j, t);
        j.key("frame");
        frame_table_json(j, frame);
        j.end_object();
        *doc = j.str();
        return t.failed() + frame.failed();
    });
}

} // namespace

int run_scene_bench(const SeedCommand &cmd) {
    if (!cmd.scenePreset.empty() || cmd.sceneWidth) return run_preset_passes(cmd);
    return run_seed_frame(cmd, "scene", [&](FILE *out, std::string *doc) {
        const SeedTimer timer = make_seed_timer(cmd.timer, cmd.quick);
        const double hz = timer.tscHz;
        const int frames = cmd.quick ? 4 : 8, width = cmd.quick ? 320 : 640,
                  height = cmd.quick ? 256 : 512;
        const int cores = tbb::info::default_concurrency();
        sv::SequenceOptions so;
        so.file = SV_DEMO_SCENE;
        so.aspect = (double)width / height;
        int failed = 0;
        print_seed_header(
            out, "shadowvol bench --scene: the demo scene per frame, and the culling decision",
            timer, -1);
        std::fprintf(
            out, "scene: %s, %d frames 1/8 s apart from the walk's start, %dx%d, %d core(s)\n\n",
            so.file.c_str(), frames, width, height, cores);

        /* 1. Per frame: shortcuts and full, 1 thread and every core. */
        std::vector<Run> runs(4);
        runs[0] = {"shortcuts", Shortcuts{}, 1, {}, {}, 0, 0};
        runs[1] = {"full", Shortcuts::none(), 1, {}, {}, 0, 0};
        runs[2] = {"shortcuts", Shortcuts{}, cores, {}, {}, 0, 0};
        runs[3] = {"full", Shortcuts::none(), cores, {}, {}, 0, 0};
        sv::CasterRule rule = sv::CasterRule::automatic;
        if (!sv::caster_rule_by_name(cmd.casterRule, rule))
            throw std::runtime_error("--caster-rule " + cmd.casterRule + ": no such rule");
        for (Run &r : runs) r.rule = rule;
        std::vector<sv::render::FrameDifference> proof;
        for (std::size_t i = 0; i < runs.size(); i++) {
            play(so, frames, width, height, hz, runs[i], i == 0 ? &proof : nullptr);
        }
        int same_as_full = 0, same_threads = 0;
        for (int k = 0; k < frames; k++) {
            same_as_full += proof[(std::size_t)k].identical();
            same_threads += runs[0].rgb[(std::size_t)k] == runs[2].rgb[(std::size_t)k] &&
                            runs[1].rgb[(std::size_t)k] == runs[3].rgb[(std::size_t)k];
        }
        const bool ok_frames = same_as_full == frames && same_threads == frames;
        failed += !ok_frames;
        std::fprintf(out, "%-10s %8s %10s %12s %14s\n", "frame", "threads", "ms/frame", "indices",
                     "stencil px");
        for (const Run &r : runs) {
            std::fprintf(out, "%-10s %8d %10.2f %12lld %14llu\n", r.name.c_str(), r.threads,
                         r.median_ms(), (long long)r.indices_built / frames,
                         (unsigned long long)r.stencil_pixels / frames);
        }
        const double save1 = runs[1].median_ms() / runs[0].median_ms();
        const double saveN = runs[3].median_ms() / runs[2].median_ms();
        const double scale_short = runs[0].median_ms() / runs[2].median_ms();
        const double scale_full = runs[1].median_ms() / runs[3].median_ms();
        std::fprintf(out,
                     "full / shortcuts: %.2fx on 1 thread, %.2fx on %d; 1 thread / %d: %.2fx with "
                     "shortcuts, "
                     "%.2fx full\ncheck: %d of %d frames equal their full frame, %d of %d the same "
                     "bytes on 1 and %d "
                     "threads%s\n\n",
                     save1, saveN, cores, cores, scale_short, scale_full, same_as_full, frames,
                     same_threads, frames, cores, ok_frames ? "" : "  FAILED");

        /* 2. Each shortcut alone switched off (every core). */
        struct Ablation {
            const char *name;
            bool Shortcuts::*flag;
            Run run;
        };
        std::vector<Ablation> ab = {{"light reach", &Shortcuts::light_reach, {}},
                                    {"view reach", &Shortcuts::view_reach, {}},
                                    {"culling test", &Shortcuts::cull_straddling, {}},
                                    {"caps for z-fail only", &Shortcuts::zpass_when_safe, {}},
                                    {"directional dark cap",
                                     &Shortcuts::no_directional_dark_cap,
                                     {}},
                                    {"static reuse", &Shortcuts::reuse_static, {}}};
        std::fprintf(out, "%-22s %10s %10s %12s %14s %8s\n", "without", "ms/frame", "+ms",
                     "indices", "stencil px", "=all");
        for (Ablation &a : ab) {
            a.run.name = a.name;
            a.run.shortcuts = Shortcuts{};
            a.run.shortcuts.*a.flag = false;
            a.run.threads = cores;
            a.run.rule = rule;
            play(so, frames, width, height, hz, a.run, nullptr);
            bool same = true;
            for (int k = 0; k < frames; k++)
                same &= a.run.rgb[(std::size_t)k] == runs[2].rgb[(std::size_t)k];
            failed += !same;
            std::fprintf(out, "%-22s %10.2f %+10.2f %12lld %14llu %8s\n", a.name, a.run.median_ms(),
                         a.run.median_ms() - runs[2].median_ms(),
                         (long long)a.run.indices_built / frames,
                         (unsigned long long)a.run.stencil_pixels / frames, same ? "yes" : "NO");
        }
        std::fprintf(
            out,
            "(each row: every shortcut but that one; +ms is what the shortcut saves per frame, "
            "=all: the same pictures as with all)\n\n");

        /* 2b. The caster rule (issue 27, docs/CASTERS.md): the paper's
         * volume everywhere against auto, where the open surfaces (the
         * terrain, the ground) take the general rule. The same pictures
         * here (nothing open stands between a lit point and a light in the
         * demo), the cost in indices, stencil pixels and time. */
        std::fprintf(out, "%-22s %10s %12s %14s %8s\n", "caster rule", "ms/frame", "indices",
                     "stencil px", "=closed");
        std::vector<Run> rule_runs(2);
        const sv::CasterRule rules[2] = {sv::CasterRule::closed, sv::CasterRule::automatic};
        for (int i = 0; i < 2; i++) {
            Run &r = rule_runs[(std::size_t)i];
            r.name = sv::caster_rule_name(rules[i]);
            r.threads = cores;
            r.rule = rules[i];
            play(so, frames, width, height, hz, r, nullptr);
        }
        for (const Run &r : rule_runs) {
            const bool same = r.rgb == rule_runs[0].rgb;
            std::fprintf(out, "%-22s %10.2f %12lld %14llu %8s\n", r.name.c_str(), r.median_ms(),
                         (long long)r.indices_built / frames,
                         (unsigned long long)r.stencil_pixels / frames, same ? "yes" : "no");
        }
        std::fprintf(out,
                     "(every shortcut, every core; auto / closed: %.2fx the time, %.2fx the "
                     "indices, %.2fx the stencil pixels)\n\n",
                     rule_runs[1].median_ms() / rule_runs[0].median_ms(),
                     (double)rule_runs[1].indices_built /
                         (double)std::max<int64_t>(1, rule_runs[0].indices_built),
                     (double)rule_runs[1].stencil_pixels /
                         (double)std::max<uint64_t>(1, rule_runs[0].stencil_pixels));

        /* 3. The culling decision on both sides. */
        sv::SceneSequence seq(so);
        const sv::Scene &demo = seq.scene();
        struct Case {
            const char *what;
            int surface, light;
            CullSide by_test, other;
            bool straddles;
        };
        const int terrain = find_surface(demo, "terrain @ terrain"),
                  character = find_surface(demo, "character @ character");
        int headlight = -1, lamp = -1;
        for (std::size_t li = 0; li < demo.lights.size(); li++) {
            if (demo.lights[li].kind == sv::LightKind::spot && headlight < 0) headlight = (int)li;
            if (demo.lights[li].kind == sv::LightKind::point && lamp < 0) lamp = (int)li;
        }
        if (terrain < 0 || character < 0 || headlight < 0 || lamp < 0) {
            throw std::runtime_error(
                so.file + ": not the demo scene (no terrain, character, spot and point light)");
        }
        std::vector<Case> cases = {{"terrain under a headlight", terrain, headlight, {}, {}, false},
                                   {"character inside the lamp", character, lamp, {}, {}, false}};
        std::fprintf(out,
                     "%-26s %9s %10s | %-8s %10s %10s %10s %10s | %-8s %10s %10s %10s %10s | %s\n",
                     "culling decision", "triangles", "box", "test", "job kt", "stencil kt",
                     "indices", "pixels", "other", "job kt", "stencil kt", "indices", "pixels",
                     "cheaper");
        const int repeats = cmd.quick ? 3 : 7;
        for (Case &c : cases) {
            sv::Scene one;
            one.surfaces = {demo.surfaces[(std::size_t)c.surface]};
            one.lights = {demo.lights[(std::size_t)c.light]};
            one.camera = demo.camera;
            Plane planes[SV_NUM_LIGHT_PLANES];
            sv::render::light_volume_planes(one.lights[0], planes);
            c.straddles = sv::render::classify_box(planes, one.surfaces[0].lo,
                                                   one.surfaces[0].hi) !=
                          sv::render::BoxSide::inside;
            Shortcuts test;
            test.view_reach = false; /* the volume is wanted even if out of view */
            Shortcuts other = test;
            if (c.straddles) {
                other.cull_straddling = false; /* the other side: no culling */
            } else {
                other.cull_always = true; /* the other side: the routine anyway */
            }
            c.by_test = cull_side(one, width, height, test, repeats);
            c.other = cull_side(one, width, height, other, repeats);
            const bool same = c.by_test.rgb == c.other.rgb;
            /* The same volume drawn (culling culled nothing): the same
             * stencil work, so only the job tells them apart (the stencil
             * pass's ticks there differ by noise only). */
            const bool same_volume = c.by_test.indices == c.other.indices &&
                                     c.by_test.pixels == c.other.pixels;
            const uint64_t a = c.by_test.job_ticks + (same_volume ? 0 : c.by_test.stencil_ticks),
                           b = c.other.job_ticks + (same_volume ? 0 : c.other.stencil_ticks);
            const bool test_cheaper = a <= b;
            failed += !same;
            std::fprintf(out,
                         "%-26s %9d %10s | %-8s %10.1f %10.1f %10lld %10llu | %-8s %10.1f %10.1f "
                         "%10lld %10llu | %s%s\n",
                         c.what, one.surfaces[0].prepared.num_triangles(),
                         c.straddles ? "straddles" : "inside",
                         c.by_test.culled ? "cull" : "no cull", (double)c.by_test.job_ticks / 1e3,
                         (double)c.by_test.stencil_ticks / 1e3, (long long)c.by_test.indices,
                         (unsigned long long)c.by_test.pixels, c.other.culled ? "cull" : "no cull",
                         (double)c.other.job_ticks / 1e3, (double)c.other.stencil_ticks / 1e3,
                         (long long)c.other.indices, (unsigned long long)c.other.pixels,
                         test_cheaper ? "the test's side" : "the other side",
                         same ? "" : "  (pictures differ: FAILED)");
        }
        std::fprintf(
            out,
            "(one surface, one light, min of %d frames: job = facing + culling + volume, then the "
            "stencil pass; where both sides draw the same volume only the job is compared)\n",
            repeats);

        /* 4. The passes per stencil method (issue 28). */
        std::fprintf(out, "\n");
        const PassTable passes = pass_table(cmd, "demo", width, height);
        print_pass_table(out, passes);
        failed += passes.failed();

        JsonWriter j;
        j.begin_object();
        seed_json_header(j, "shadowvol-scene-bench/1", timer);
        j.key("scene"), j.value(so.file);
        j.key("passes");
        pass_table_json(j, passes);
        j.key("frames"), j.value(frames);
        j.key("width"), j.value(width);
        j.key("height"), j.value(height);
        j.key("cores"), j.value(cores);
        j.key("runs");
        j.begin_array();
        for (const Run &r : runs) {
            j.begin_object(true);
            j.key("config"), j.value(r.name);
            j.key("threads"), j.value(r.threads);
            j.key("median_ms"), j.value(r.median_ms());
            j.key("indices_per_frame"), j.value((long long)r.indices_built / frames);
            j.key("stencil_pixels_per_frame"),
                j.value((unsigned long long)r.stencil_pixels / frames);
            j.end_object();
        }
        j.end_array();
        j.key("caster_rule"), j.value(cmd.casterRule);
        j.key("caster_rules");
        j.begin_array();
        for (const Run &r : rule_runs) {
            j.begin_object(true);
            j.key("rule"), j.value(r.name);
            j.key("threads"), j.value(r.threads);
            j.key("median_ms"), j.value(r.median_ms());
            j.key("indices_per_frame"), j.value((long long)r.indices_built / frames);
            j.key("stencil_pixels_per_frame"),
                j.value((unsigned long long)r.stencil_pixels / frames);
            j.end_object();
        }
        j.end_array();
        j.key("frames_equal_to_full"), j.value(same_as_full);
        j.key("frames_equal_across_threads"), j.value(same_threads);
        j.key("without");
        j.begin_array();
        for (const Ablation &a : ab) {
            j.begin_object(true);
            j.key("shortcut"), j.value(a.name);
            j.key("median_ms"), j.value(a.run.median_ms());
            j.key("indices_per_frame"), j.value((long long)a.run.indices_built / frames);
            j.end_object();
        }
        j.end_array();
        j.key("culling");
        j.begin_array();
        for (const Case &c : cases) {
            j.begin_object(true);
            j.key("case"), j.value(c.what);
            j.key("straddles"), j.value(c.straddles);
            j.key("test_culls"), j.value(c.by_test.culled);
            j.key("test_ticks"),
                j.value((unsigned long long)c.by_test.job_ticks + c.by_test.stencil_ticks);
            j.key("other_ticks"),
                j.value((unsigned long long)c.other.job_ticks + c.other.stencil_ticks);
            j.end_object();
        }
        j.end_array();
        j.end_object();
        *doc = j.str();
        return failed;
    });
}

} // namespace svbench
