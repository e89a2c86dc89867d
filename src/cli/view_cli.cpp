/*
 * shadowvol view (issue 30): the scene of `shadowvol scene` played in a
 * window, drawn by the same render_frame (frame.h) with the same options,
 * so that a frame on the screen is the bytes scene writes for the same
 * camera, lights and time. The loop: the script's input for this frame,
 * SDL's events, the clock, the pose, the frame, the overlays and the
 * on-screen line, the window; then the script's reads of this frame.
 *
 * Exit status: 0 done; 2 bad arguments (a bad --script too); 3 a file that
 * cannot be loaded; 5 no window (no display, or a build without SDL2).
 *
 * Copyright (C) 2026 the shadowvol authors. LGPL-2.1-or-later.
 */
#include "view_cli.h"

#include <tbb/info.h>

#include <chrono>
#include <cmath>
#include <cstdio>
#include <memory>
#include <string>
#include <vector>

#include "cli_args.h"
#include "frame.h"
#include "images.h"
#include "scene_open.h"
#include "sequence.h"
#include "shadowvol_gltf.h"
#include "timer.h"
#include "view_args.h"
#include "view_controls.h"
#include "view_font.h"
#include "view_overlays.h"
#include "view_script.h"
#include "view_window.h"

#ifndef SV_DEMO_SCENE
#define SV_DEMO_SCENE "models/demo_scene.glb"
#endif

namespace svcli {
namespace {

constexpr int kExitUsage = 2, kExitNoWindow = 5; /* 3 (a file): open_scene */
constexpr int64_t kMaxWireframeEdges = 300000;

double ms(uint64_t ticks, double hz) { return hz > 0 ? 1e3 * (double)ticks / hz : 0; }

/* The state line of --script's print and the P key: the frame, its time,
 * the switches, the camera, the lights and what the frame decided. */
std::string state_line(long frame, double time, const ViewControls &controls,
                       const sv::Scene &scene, const sv::render::Frame &f) {
    int built = 0, reused = 0, zfail = 0, out_of_reach = 0, out_of_view = 0, culled = 0;
    long long drawn = 0;
    unsigned long long stencil_pixels = 0;
    for (const sv::render::LightFrame &lf : f.lights) {
        built += lf.built, reused += lf.reused, zfail += lf.zfail_volumes;
        out_of_reach += lf.out_of_reach, out_of_view += lf.out_of_view, culled += lf.culled;
        drawn += lf.drawn_indices;
        stencil_pixels += lf.stencil_counters.pixels_tested;
    }
    char buf[512];
    std::snprintf(buf, sizeof buf,
                  "frame %ld time %.17g | %s | built %d reused %d reach %d view %d culled %d "
                  "zfail %d drawn %lld stencil_pixels %llu stencil_method %s | camera ",
                  frame, time, controls.switches_text().c_str(), built, reused, out_of_reach,
                  out_of_view, culled, zfail, drawn, stencil_pixels, f.stencil_method.c_str());
    std::string line = buf + ViewControls::camera_text(scene.camera);
    for (std::size_t li = 0; li < scene.lights.size(); li++)
        line += " | light " + std::to_string(li) + " " + scene.lights[li].describe();
    return line;
}

/* The on-screen line: frames per second, each pass's milliseconds, the
 * switches that change how the frame is drawn, the time. */
std::string hud_line(double fps, double time, const sv::render::Frame &f, double hz,
                     const ViewSwitches &s) {
    double stencil = 0;
    for (const sv::render::LightFrame &lf : f.lights) stencil += lf.seconds_stencil * 1e3;
    char buf[256];
    std::snprintf(buf, sizeof buf,
                  "%.1f fps | depth %.1f volumes %.1f stencil %.1f shading %.1f frame %.1f ms | "
                  "%s %s %s | t %.2f%s",
                  fps, f.seconds_depth * 1e3, ms(f.ticks_jobs, hz), stencil,
                  ms(f.ticks_shading, hz), ms(f.ticks_total, hz), sv::render::mode_name(s.mode),
                  sv::render::stencil_method_name(s.stencil), sv::caster_rule_name(s.caster_rule),
                  time, s.paused ? " paused" : "");
    return buf;
}

} // namespace

void view_usage(FILE *out) {
    std::fprintf(out,
                 "usage: shadowvol view [FILE[@x,y,z[,yaw[,scale]]][:A]] [--add FILE[@...][:A]]\n"
                 "                      [--animation A] [--ground] [--light L] [--camera C]\n"
                 "                      [--fps F] [--size WxH] [--threads T] [--full]\n"
                 "                      [--mode zpass|zfail|auto] [--stencil bf|db|hier|auto]\n"
                 "                      [--stencil-tile N] [--caster-rule auto|closed|general]\n"
                 "                      [--ground-hints use|ignore] [--general-build B]\n"
                 "                      [--skinning K] [--no-hud] [--script FILE]\n"
                 "\n"
                 "Plays a glTF scene in a window (SDL2): the scene of shadowvol scene, drawn by\n"
                 "the same frame, so that what the window shows is the bytes scene writes for the\n"
                 "same camera, lights and time. With no FILE: the project's demo scene (%s).\n"
                 "The options above are shadowvol scene's (see shadowvol scene --help); --fps is\n"
                 "the animation's clock under --script (one frame per frame drawn), else the\n"
                 "time follows the wall clock.\n"
                 "\n"
                 "  --no-hud          start with the on-screen line off (H shows it)\n"
                 "  --script FILE     key and mouse events keyed to frame numbers, one a line:\n"
                 "                      FRAME key NAME | drag left|right X0 Y0 X1 Y1 | wheel N |\n"
                 "                      snap FILE | print | quit\n"
                 "                    snap writes the window as the X server holds it (PNG);\n"
                 "                    print writes the state line; the view closes after the\n"
                 "                    script's last frame\n"
                 "\n"
                 "mouse: left button orbits the camera, the wheel zooms, the right button drags\n"
                 "       the picked light\n"
                 "keys:  W A S D Q E move the camera; R the scene's camera again\n"
                 "       L pick the next light (or none); Space pause; . one frame on, paused\n"
                 "       M mode (zpass, zfail, auto); T stencil pass (bf, db, hier, auto);\n"
                 "       C caster rule (auto, closed, general); 1-6 each shortcut off and on\n"
                 "       (1 light reach, 2 view reach, 3 culling where straddling, 4 z-pass\n"
                 "       when safe, 5 no directional dark cap, 6 static reuse)\n"
                 "       H the on-screen line (fps, each pass's ms); O stencil counts;\n"
                 "       B boundary tiles (hier); V volumes as wireframe (of the picked light,\n"
                 "       else light 0); P print the state line; Escape quit\n"
                 "\n"
                 "Exit status: 0 done; 2 bad arguments or a bad script; 3 a file that cannot be\n"
                 "loaded; 5 no window: no display (DISPLAY unset, or no X server there), or a\n"
                 "build without SDL2.\n",
                 SV_DEMO_SCENE);
}

int view_main(int argc, char **argv) {
    ViewArgs args;
    try {
        bool help = false;
        args = parse_view_args(argc, argv, help);
        if (help) {
            view_usage(stdout);
            return 0;
        }
    } catch (const UsageError &e) {
        std::fprintf(stderr, "shadowvol view: %s\nTry 'shadowvol view --help'.\n",
                     e.message.c_str());
        return kExitUsage;
    } catch (const sv::SceneError &e) {
        std::fprintf(stderr, "shadowvol view: %s\n", e.what());
        return kExitUsage;
    }
    SceneArgs &sa = args.scene;
    std::vector<ScriptEvent> script;
    if (!args.script.empty()) {
        try {
            script = read_view_script(args.script);
        } catch (const std::exception &e) {
            std::fprintf(stderr, "shadowvol view: %s\n", e.what());
            return kExitUsage;
        }
    }
    int open_status = 0;
    const std::unique_ptr<sv::SceneSequence> seq = open_scene("view", sa, open_status);
    if (!seq) return open_status;

    std::unique_ptr<ViewWindow> window;
    try {
        window = std::make_unique<ViewWindow>("shadowvol view: " + sa.seq.file, sa.width,
                                              sa.height);
    } catch (const NoWindow &e) {
        std::fprintf(stderr, "shadowvol view: %s\n", e.what());
        return kExitNoWindow;
    }

    ViewSwitches start;
    start.mode = sa.mode;
    start.stencil = sa.stencil.method;
    start.caster_rule = sa.caster_rule;
    if (sa.full) start.shortcuts = sv::render::Shortcuts::none();
    start.hud = args.hud;
    ViewControls controls(start, sa.height);

    sv::render::RenderOptions options;
    options.width = sa.width;
    options.height = sa.height;
    options.threads = sa.threads ? sa.threads : tbb::info::default_concurrency();
    options.stencil_tile = sa.stencil.tile;
    options.stencil_rule = sa.stencil.rule;
    options.ground_hints = sa.ground_hints;
    options.general_build = sa.general_build;
    sv::render::VolumeCache cache;
    sv::render::FrameScratch scratch;
    options.cache = &cache;
    options.scratch = &scratch;
    const double hz = svbench::estimate_tsc_hz(0.02);

    const bool scripted = !args.script.empty();
    const long last_frame = script.empty() ? -1 : script.back().frame;
    std::size_t next_event = 0;
    long frame_number = 0;
    long clock_frames = 0;     /* under --script: the time is start + clock_frames / fps */
    double clock_seconds = 0;  /* else the wall clock's, paused or not */
    std::string last_switches; /* the cache is cleared when they change */
    double fps = 0;
    auto last = std::chrono::steady_clock::now();
    while (true) {
        try {
            for (std::size_t k = next_event; k < script.size() && script[k].frame == frame_number;
                 k++) {
                if (!script[k].after_frame()) window->push(script[k]);
            }
            window->handle_events(controls);
        } catch (const std::exception &e) {
            std::fprintf(stderr, "shadowvol view: --script %s: %s\n", args.script.c_str(),
                         e.what());
            return kExitUsage;
        }
        if (controls.quit()) break;
        const int steps = controls.take_steps();
        const auto now = std::chrono::steady_clock::now();
        const double dt = std::chrono::duration<double>(now - last).count();
        last = now;
        if (frame_number > 0 && dt > 0) fps = fps == 0 ? 1 / dt : 0.9 * fps + 0.1 / dt;
        if (scripted) {
            clock_frames += steps;
        } else {
            clock_seconds += steps / sa.fps + (controls.switches().paused ? 0 : dt);
        }
        double time = seq->start() + (scripted ? (double)clock_frames / sa.fps : clock_seconds);
        /* Around the animation's range, looping (exact within the first
         * pass, so frame K of a script is scene's frame K). */
        if (seq->animated() && seq->end() > seq->start() && time > seq->end())
            time = seq->start() + std::fmod(time - seq->start(), seq->end() - seq->start());

        const ViewSwitches &sw = controls.switches();
        options.mode = sw.mode;
        options.stencil = sw.stencil;
        options.caster_rule = sw.caster_rule;
        options.shortcuts = sw.shortcuts;
        const std::string switches = controls.switches_text();
        if (switches != last_switches) cache.clear();
        last_switches = switches;
        sv::render::Frame f;
        try {
            seq->set_time(time);
            controls.apply(seq->scene());
            sv::validate_scene(seq->scene());
            f = sv::render::render_frame(seq->scene(), options);
        } catch (const sv::SceneError &e) {
            std::fprintf(stderr, "shadowvol view: frame %ld (%.3f s): %s%s\n", frame_number, time,
                         e.what(), scripted ? "" : " (frame skipped)");
            if (scripted) return kExitUsage;
            /* Live, the next frame's time is another (a pose the validator
             * refuses, such as a light on a triangle's plane, lasts an
             * instant): keep the window going. */
            frame_number++;
            continue;
        } catch (const std::bad_alloc &) {
            std::fprintf(stderr, "shadowvol view: out of memory for a %dx%d frame\n", sa.width,
                         sa.height);
            return kExitUsage;
        }
        sv::render::Image image(sa.width, sa.height);
        image.rgb = f.rgb;
        const int light = controls.shown_light();
        if (sw.overlay_stencil) overlay_stencil_counts(image, f, light);
        if (sw.overlay_tiles) overlay_boundary_tiles(image, f, light, options.stencil_tile);
        if (sw.overlay_wireframe)
            overlay_volume_wireframe(image, f, seq->scene(), light, kMaxWireframeEdges);
        if (sw.hud) {
            const int scale = sa.width >= 1000 ? 2 : 1;
            draw_text(image, 4 * scale, 4 * scale, hud_line(fps, time, f, hz, sw), scale, 255, 255,
                      255);
        }
        try {
            window->show(image);
            for (; next_event < script.size() && script[next_event].frame == frame_number;
                 next_event++) {
                const ScriptEvent &e = script[next_event];
                if (e.kind == ScriptEvent::snap) {
                    sv::render::write_png(e.text, window->read_back());
                } else if (e.kind == ScriptEvent::print) {
                    std::printf("%s\n",
                                state_line(frame_number, time, controls, seq->scene(), f).c_str());
                } else if (e.kind == ScriptEvent::quit) {
                    controls.key("Escape");
                }
            }
        } catch (const std::exception &e) {
            std::fprintf(stderr, "shadowvol view: frame %ld: %s\n", frame_number, e.what());
            return kExitUsage;
        }
        if (controls.print_requested())
            std::printf("%s\n", state_line(frame_number, time, controls, seq->scene(), f).c_str());
        std::fflush(stdout);
        if (controls.quit() || (scripted && frame_number >= last_frame)) break;
        if (scripted && !sw.paused) clock_frames++;
        frame_number++;
    }
    return 0;
}

} // namespace svcli
