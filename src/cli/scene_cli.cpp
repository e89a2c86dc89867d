/*
 * shadowvol scene (issue 13): a glTF scene in time, frame by frame, with
 * only what each frame requires (frame.h's Shortcuts), proved against the
 * full frame (every surface, no culling, both caps, z-fail) pixel for
 * pixel and against the ray-cast truth, with a table per frame of what
 * was built, reused and skipped and what each stage cost.
 *
 * Exit status: 0 done; 1 a frame that differs from the full one where the
 * light reaches, or a stencil mismatch against the truth off a shadow
 * boundary; 2 bad arguments; 3 a file that cannot be loaded.
 *
 * Copyright (C) 2026 the shadowvol authors. LGPL-2.1-or-later.
 */
#include "scene_cli.h"
#include "scene_args.h"
#include "scene_open.h"
#include "scene_skinned_normals.h"

#include <tbb/info.h>
#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <memory>
#include <string>
#include <vector>

#include "cli_args.h"
#include "extruded_volumes.h"
#include "frame.h"
#include "images.h"
#include "json_writer.h"
#include "render_cli.h"
#include "scene_options.h"
#include "sequence.h"
#include "shadowvol_gltf.h"
#include "timer.h"
#include "truth.h"
#include "webp_writer.h"

#ifndef SV_DEMO_SCENE
#define SV_DEMO_SCENE "models/demo_scene.glb"
#endif

namespace svcli {
namespace {

constexpr int kExitMismatch = 1, kExitUsage = 2; /* 3 (a file): open_scene */

double ms(uint64_t ticks, double hz) { return hz > 0 ? 1e3 * (double)ticks / hz : 0; }
double kt(uint64_t ticks) { return (double)ticks / 1000.0; }

/* What a frame cost and decided, summed over its lights. */
struct FrameRow {
    int index = 0;
    double time = 0;
    sv::PoseStats pose;
    int volumes_built = 0, reused = 0, out_of_reach = 0, out_of_view = 0, culled = 0, zfail = 0,
        dark_caps_dropped = 0;
    int64_t indices_built = 0, indices_drawn = 0, full_indices = -1;
    uint64_t ticks_facing = 0, ticks_culling = 0, ticks_volume = 0, ticks_depth = 0,
             ticks_stencil = 0, ticks_shading = 0, ticks_frame = 0, ticks_full_frame = 0;
    uint64_t stencil_pixels = 0, full_stencil_pixels = 0;
    bool compared = false;
    sv::render::FrameDifference diff;
    bool truth_done = false;
    uint64_t truth_mismatches = 0, truth_off_boundary = 0, truth_compared = 0;
    uint64_t primary_checked = 0, primary_disagreements = 0; /* truth.h */
    /* --skinned-normals: shadow pixels that differ from the recomputed
     * normals' frame where the light reaches. */
    uint64_t skinned_differ = 0;
};

void sum_lights(const sv::render::Frame &f, FrameRow &r) {
    for (const sv::render::LightFrame &lf : f.lights) {
        r.volumes_built += lf.built;
        r.reused += lf.reused;
        r.out_of_reach += lf.out_of_reach;
        r.out_of_view += lf.out_of_view;
        r.culled += lf.culled;
        r.zfail += lf.zfail_volumes;
        for (const auto &d : lf.decisions) r.dark_caps_dropped += d.dark_cap_dropped;
        r.indices_built += lf.built_indices;
        r.indices_drawn += lf.drawn_indices;
        r.ticks_facing += lf.ticks_facing;
        r.ticks_culling += lf.ticks_culling;
        r.ticks_volume += lf.ticks_volume;
        r.ticks_stencil += lf.ticks_stencil;
        r.stencil_pixels += lf.stencil_counters.pixels_tested;
    }
    r.ticks_depth = f.ticks_depth;
    r.ticks_shading = f.ticks_shading;
    r.ticks_frame = f.ticks_total;
}

/* Indices the full frame built that the shortcuts did not, per shortcut:
 * each (light, surface) pair's difference goes to the first of its
 * decisions that applies, in the order they are made (reach, view, reuse,
 * culling, z-pass without caps, the directional dark cap). */
enum Saving {
    kSavedReach,
    kSavedView,
    kSavedReuse,
    kSavedCulling,
    kSavedCaps,
    kSavedDarkCap,
    kSavings
};
const char *const kSavingNames[kSavings] = {"1 light reach",          "2 view reach",
                                            "6 static reuse",         "3 culling",
                                            "4 caps for z-fail only", "5 directional dark cap"};
struct Savings {
    int64_t indices[kSavings] = {};
    int decisions[kSavings] = {};
};

void attribute_savings(const sv::render::Frame &fast, const sv::render::Frame &full, Savings &s) {
    for (std::size_t li = 0; li < fast.lights.size(); li++) {
        const auto &a = fast.lights[li].decisions, &b = full.lights[li].decisions;
        for (std::size_t si = 0; si < a.size() && si < b.size(); si++) {
            const int64_t diff = b[si].indices_built - a[si].indices_built;
            using sv::render::VolumeFate;
            int k;
            if (a[si].fate == VolumeFate::out_of_reach)
                k = kSavedReach;
            else if (a[si].fate == VolumeFate::out_of_view)
                k = kSavedView;
            else if (a[si].fate == VolumeFate::reused)
                k = kSavedReuse;
            else if (a[si].cull_bits)
                k = kSavedCulling;
            else if (a[si].indices_drawn > 0 && !a[si].zfail)
                k = kSavedCaps;
            else if (a[si].dark_cap_dropped)
                k = kSavedDarkCap;
            else
                continue;
            s.indices[k] += diff;
            s.decisions[k]++;
        }
    }
}

/* A box-filtered copy of IMAGE, FACTOR times smaller. */
sv::render::Image shrink(const std::vector<uint8_t> &rgb, int w, int h, int factor) {
    sv::render::Image out(std::max(1, w / factor), std::max(1, h / factor));
    for (int y = 0; y < out.height; y++) {
        for (int x = 0; x < out.width; x++) {
            for (int c = 0; c < 3; c++) {
                int sum = 0, n = 0;
                for (int j = 0; j < factor; j++) {
                    for (int i = 0; i < factor; i++) {
                        const int sx = x * factor + i, sy = y * factor + j;
                        if (sx >= w || sy >= h) continue;
                        sum += rgb[((std::size_t)sy * w + sx) * 3 + c];
                        n++;
                    }
                }
                out.at(x, y)[c] = (uint8_t)((sum + n / 2) / std::max(n, 1));
            }
        }
    }
    return out;
}

/* Frames in rows of at most four, with a 4-pixel gap. */
sv::render::Image contact_sheet(const std::vector<sv::render::Image> &tiles) {
    if (tiles.empty()) return {};
    const int cols = std::min<int>(4, (int)tiles.size());
    const int rows = ((int)tiles.size() + cols - 1) / cols;
    const int tw = tiles[0].width, th = tiles[0].height, gap = 4;
    sv::render::Image sheet(cols * tw + (cols - 1) * gap, rows * th + (rows - 1) * gap);
    std::fill(sheet.rgb.begin(), sheet.rgb.end(), 24);
    for (std::size_t k = 0; k < tiles.size(); k++) {
        const int ox = (int)(k % cols) * (tw + gap), oy = (int)(k / cols) * (th + gap);
        for (int y = 0; y < th; y++) {
            std::memcpy(sheet.at(ox, oy + y), &tiles[k].rgb[(std::size_t)y * tw * 3],
                        (std::size_t)tw * 3);
        }
    }
    return sheet;
}

} // namespace

void scene_usage(FILE *out) {
    std::fprintf(
        out,
        "usage: shadowvol scene [FILE[@x,y,z[,yaw[,scale]]][:A]] [--add FILE[@...][:A]]\n"
        "                       [--animation A]\n"
        "                       [--frames N | --time FROM:TO] [--fps F] [--threads T] [--full]\n"
        "                       [--size WxH] [--mode zpass|zfail|auto]\n"
        "                       [--stencil bf|db|hier|auto] [--stencil-tile N]\n"
        "                       [--caster-rule auto|closed|general]\n"
        "                       [--ground-hints use|ignore] [--volume silhouette|extrude]\n"
        "                       [--stencil-op saturate|wrap] [--extrude-to range|infinity]\n"
        "                       [--skinned-normals WAY] [--out DIR] [--json FILE]\n"
        "                       [--webp FILE]\n"
        "\n"
        "Plays a glTF scene in time: its node animation, skins (posed on the CPU), its\n"
        "KHR_lights_punctual lights and its camera, frame by frame. Each frame builds only\n"
        "what it requires: no volume for a surface out of a light's range or cone, or\n"
        "whose shadow cannot reach the view; the culling routine only where the surface\n"
        "straddles the light volume; caps only for z-fail; no dark cap for a directional\n"
        "light; a static surface's volume reused until it or its light moves. Every\n"
        "frame is checked against the full frame (every surface, no culling, both caps,\n"
        "z-fail: the shaded image byte for byte, the shadow mask wherever the light\n"
        "reaches) and against the ray-cast truth. Writes DIR/frame_NNN.png and\n"
        "DIR/contact.png. With no FILE: the project's demo scene (%s).\n"
        "\n"
        "scene:\n"
        "  --add FILE[@x,y,z[,yaw_degrees[,scale]]][:A]  another glTF file, playing its\n"
        "                    animation A (a name or an index; default: its first)\n"
        "  --animation A     the scene file's animation, by name or index (default: its\n"
        "                    first); FILE:A says the same\n"
        "                    A is the text after the last ':'; a file name that holds a ':'\n"
        "                    is written with a ':' after it (a:b.glb: plays its first),\n"
        "                    one that holds a '@' with a placement (a@b.glb@0,0,0)\n"
        "  --ground          a ground plane under everything\n"
        "  --light L         a light besides the file's (the syntax of shadowvol render);\n"
        "                    a file without lights gets point, spot and directional auto lights\n"
        "  --camera C        instead of the file's first camera (else: framed from the front)\n"
        "time:\n"
        "  --frames N        N frames from the animation's start, 1/F s apart (default:\n"
        "                    8, or 1 for a still scene)\n"
        "  --time FROM:TO    every frame 1/F s apart from FROM to TO (seconds; clamped to\n"
        "                    the animation's range, as glTF says)\n"
        "  --fps F           frames per second (default 8)\n"
        "frame:\n"
        "  --size WxH        default 640x512\n"
        "  --threads T       worker threads (default: every core); the same bytes at any T\n"
        "  --stencil S       how the stencil pass fills: bf (brute force, the reference),\n"
        "                    db (depth bounds), hier (tiles, seed 004) or auto (bf or\n"
        "                    hier per light); the same bytes by each. Default: the\n"
        "                    wisdom file's (shadowvol tune), else auto\n"
        "  --stencil-tile N  hier's tile side: 4, 8 (the seed's), 16 or 32 (default: the\n"
        "                    wisdom file's, else 32)\n"
        "  --mode M          zpass, zfail or auto (default: z-fail only where the near\n"
        "                    plane may be in shadow)\n"
        "  --caster-rule R   auto (default: closed shells the paper's volume, open or\n"
        "                    non-manifold shells the general rule, exact for any caster),\n"
        "                    closed (the paper's everywhere) or general (docs/CASTERS.md)\n"
        "  --ground-hints H  use (default: under auto, a surface declared ground, the\n"
        "                    --ground quad or a glTF extras \"shadowvol_ground\", keeps\n"
        "                    the paper's rule) or ignore (its shells decide)\n"
        "  --general-build B direct (default) or two-sided: how the general rule's\n"
        "                    volumes are built; the same stencil\n"
        "%s"
        "  --full            render with no shortcut at all (what the check compares with)\n"
        "  --no-check        skip the full frame beside each frame\n"
        "  --no-truth        skip the ray-cast truth\n"
        "  --skinning K      c_ref, sse2, avx2, avx512 (default: the best this CPU runs)\n"
        "  --skinned-normals WAY  with --volume extrude: the skinned surfaces' face normals\n"
        "                    straightforward (skinned per vertex: the seed's Figure 4),\n"
        "                    face-weights, recomputed (the default's) or neighbours (the\n"
        "                    neighbour fix); each frame is drawn again with the recomputed\n"
        "                    ones and the shadow pixels that differ are counted (the truth\n"
        "                    judges the artifact too; docs/EXTRUSION.md)\n"
        "  --out DIR         where the PNGs go (default shadowvol-scene)\n"
        "  --json FILE       the report as JSON (schema shadowvol-scene/1; - for stdout)\n"
        "  --webp FILE       the frames also as an animated WebP a browser plays, looping,\n"
        "                    1/F s a frame; lossless: each frame the PNG's bytes%s\n"
        "\n"
        "Exit status: 0 done; 1 a frame differs from the full frame where the light reaches,\n"
        "or disagrees with the truth off a shadow boundary; 2 bad arguments; 3 a file\n"
        "that cannot be loaded.\n",
        SV_DEMO_SCENE, volume_options_help(),
        webp_available() ? "" : "\n                    (not in this build: no libwebp)");
}

int scene_main(int argc, char **argv) {
    SceneArgs args;
    try {
        bool help = false;
        args = parse_scene_args(argc, argv, help);
        if (help) {
            scene_usage(stdout);
            return 0;
        }
    } catch (const UsageError &e) {
        std::fprintf(stderr, "shadowvol scene: %s\nTry 'shadowvol scene --help'.\n",
                     e.message.c_str());
        return kExitUsage;
    } catch (const sv::SceneError &e) {
        std::fprintf(stderr, "shadowvol scene: %s\n", e.what());
        return kExitUsage;
    }
    if (!args.webp_path.empty() && !webp_available()) {
        std::fprintf(stderr,
                     "shadowvol scene: --webp %s: this shadowvol was built without libwebp "
                     "(Debian's libwebp-dev; cmake -DSV_WEBP=ON finds it)\n",
                     args.webp_path.c_str());
        return kExitUsage;
    }
    int open_status = 0;
    const std::unique_ptr<sv::SceneSequence> seq = open_scene("scene", args, open_status);
    if (!seq) return open_status;

    /* The frames' times. */
    std::vector<double> times;
    if (args.has_time) {
        const int n = (int)std::floor((args.time_to - args.time_from) * args.fps + 1e-9) + 1;
        if (n > 10000) {
            std::fprintf(stderr,
                         "shadowvol scene: --time at --fps %g makes %d frames (at most 10000)\n",
                         args.fps, n);
            return kExitUsage;
        }
        for (int k = 0; k < n; k++) times.push_back(args.time_from + k / args.fps);
    } else {
        const int n = args.frames ? args.frames : (seq->animated() ? 8 : 1);
        for (int k = 0; k < n; k++) times.push_back(seq->start() + k / args.fps);
    }
    if (!make_dir(args.out_dir)) {
        std::fprintf(stderr, "shadowvol scene: --out %s: cannot create the folder\n",
                     args.out_dir.c_str());
        return kExitUsage;
    }
    const int threads = args.threads ? args.threads : tbb::info::default_concurrency();
    const double hz = svbench::estimate_tsc_hz(0.05);
    const sv::Scene &scene = seq->scene();

    std::printf("scene: %s\n", args.seq.file.c_str());
    for (const std::string &d : seq->describe()) std::printf("  %s\n", d.c_str());
    std::printf("  %zu surface(s), %lld triangles, %zu light(s):\n", scene.surfaces.size(),
                (long long)scene.triangles(), scene.lights.size());
    for (std::size_t li = 0; li < scene.lights.size(); li++) {
        std::printf("    %zu %s\n", li, scene.lights[li].describe().c_str());
    }
    std::printf("frames: %zu at %g fps from %.3f s; %dx%d; %d thread(s); %s; TSC %.3f GHz\n",
                times.size(), args.fps, times.front(), args.width, args.height, threads,
                args.full ? "no shortcuts (--full)" : "shortcuts on", hz / 1e9);
    std::printf("ticks in thousands (kt): skin and planes per frame; facing, culling, volume: work "
                "summed over "
                "threads; depth, stencil, shading, frame: wall\n\n");
    std::printf("%5s %7s %5s | %5s %5s %5s %5s %4s %5s | %9s %9s %9s | %7s %7s %7s %7s %7s %7s %8s "
                "%8s %8s | %9s | %5s %6s\n",
                "frame", "time", "moved", "built", "reuse", "reach", "view", "cull", "zfail",
                "idx.built", "idx.drawn", "idx.full", "skin", "planes", "facing", "culling",
                "volume", "depth", "stencil", "shading", "frame", "st.pixels", "=full", "truth");

    sv::render::RenderOptions fast;
    fast.width = args.width;
    fast.height = args.height;
    fast.threads = threads;
    args.stencil.apply(fast);
    fast.mode = args.mode;
    fast.caster_rule = args.caster_rule;
    fast.ground_hints = args.ground_hints;
    fast.general_build = args.general_build;
    apply_volume_args(args.volume, fast);
    sv::render::VolumeCache cache;
    fast.cache = &cache;
    sv::render::FrameScratch scratch; /* the frames' buffers, kept from frame to frame */
    fast.scratch = &scratch;
    if (args.full) fast.shortcuts = sv::render::Shortcuts::none();
    /* --skinned-normals: the skinned surfaces' normals that way, each
     * frame drawn again with the recomputed ones (the default's: the
     * per-frame planes) to count the shadow pixels that differ. */
    std::unique_ptr<SceneSkinnedNormals> skinned;
    if (!args.skinned_normals.empty()) {
        sv::SkinnedNormals way = sv::SkinnedNormals::recomputed;
        sv::skinned_normals_by_option(args.skinned_normals, way);
        skinned = std::make_unique<SceneSkinnedNormals>(*seq, way);
    }
    sv::render::RenderOptions full = fast;
    full.shortcuts = sv::render::Shortcuts::none();
    full.mode = sv::render::ModeChoice::automatic; /* with no shortcut: z-fail, both caps */
    full.cache = nullptr;

    std::vector<FrameRow> rows;
    Savings saved;
    std::vector<std::string> truth_notes;
    std::vector<sv::render::Image> tiles;
    std::unique_ptr<WebpAnimation> webp;
    try {
        if (!args.webp_path.empty())
            webp = std::make_unique<WebpAnimation>(args.width, args.height, args.fps);
    } catch (const std::exception &e) {
        std::fprintf(stderr, "shadowvol scene: --webp %s: %s\n", args.webp_path.c_str(), e.what());
        return kExitUsage;
    }
    const int factor = std::max(1, (args.width + 319) / 320);
    bool failed = false;
    /* Progress on stderr when it is a terminal (a log gets the table only). */
    const bool progress = isatty(2);
    for (std::size_t k = 0; k < times.size(); k++) {
        if (progress)
            std::fprintf(stderr, "\rshadowvol scene: frame %zu of %zu", k + 1, times.size());
        FrameRow r;
        r.index = (int)k;
        r.time = times[k];
        sv::render::Frame f;
        try {
            r.pose = seq->set_time(times[k]);
            sv::validate_scene(seq->scene());
            if (skinned) {
                skinned->apply(fast);
                skinned->apply(full);
            }
            f = sv::render::render_frame(scene, fast);
            if (skinned) {
                sv::render::RenderOptions recomputed = fast;
                recomputed.shadow_mesh_hook = nullptr;
                recomputed.extrude_program = nullptr;
                recomputed.cache = nullptr;
                recomputed.scratch = nullptr;
                r.skinned_differ = sv::render::compare_frames(scene, f,
                                                              sv::render::render_frame(scene,
                                                                                       recomputed))
                                       .mask_in_reach;
            }
        } catch (const sv::SceneError &e) {
            std::fprintf(stderr, "\nshadowvol scene: frame %zu (%.3f s): %s\n", k, times[k],
                         e.what());
            return kExitUsage;
        } catch (const std::bad_alloc &) {
            std::fprintf(stderr, "\nshadowvol scene: out of memory for a %dx%d frame\n", args.width,
                         args.height);
            return kExitUsage;
        }
        sum_lights(f, r);
        if (args.check && !args.full) {
            const sv::render::Frame g = sv::render::render_frame(scene, full);
            r.compared = true;
            r.diff = sv::render::compare_frames(scene, f, g);
            r.full_indices = 0;
            for (const auto &lf : g.lights) {
                r.full_indices += lf.built_indices;
                r.full_stencil_pixels += lf.stencil_counters.pixels_tested;
            }
            r.ticks_full_frame = g.ticks_total;
            if (!r.diff.identical()) failed = true;
            attribute_savings(f, g, saved);
        }
        if (args.truth) {
            const sv::render::TruthCaster caster(scene);
            r.truth_done = true;
            for (std::size_t li = 0; li < f.lights.size(); li++) {
                const sv::render::Truth t = caster.cast(f, (int)li, threads);
                const sv::render::Comparison c = caster.compare(f, (int)li, t);
                r.truth_mismatches += c.mismatches;
                r.truth_off_boundary += c.off_boundary_mismatches;
                r.truth_compared += c.compared;
                r.primary_checked += c.primary_checked;
                r.primary_disagreements += c.primary_disagreements;
                if (c.off_boundary_mismatches) {
                    const int p = c.first_off_boundary.empty() ? -1 : c.first_off_boundary[0];
                    char line[200];
                    std::snprintf(
                        line, sizeof line,
                        "frame %zu, light %zu: %llu stencil pixels disagree with the truth off a "
                        "shadow boundary, the first at (%d, %d)",
                        k, li, (unsigned long long)c.off_boundary_mismatches,
                        p < 0 ? -1 : p % args.width, p < 0 ? -1 : p / args.width);
                    truth_notes.push_back(line);
                    /* The picture of the disagreement, to look at. */
                    char tname[64];
                    std::snprintf(tname, sizeof tname, "/truth_%03zu_light%zu.png", k, li);
                    try {
                        sv::render::write_png(args.out_dir + tname,
                                              sv::render::truth_image(t, f.lights[li].stencil,
                                                                      f.width, f.height));
                        truth_notes.back() += std::string(" (") + args.out_dir + tname + ")";
                    } catch (const std::exception &) {
                    }
                }
            }
            if (r.truth_off_boundary) failed = true;
        }
        char name[64];
        std::snprintf(name, sizeof name, "/frame_%03zu.png", k);
        sv::render::Image img(args.width, args.height);
        img.rgb = f.rgb;
        try {
            sv::render::write_png(args.out_dir + name, img);
            if (webp) webp->add(f.rgb);
        } catch (const std::exception &e) {
            std::fprintf(stderr, "\nshadowvol scene: %s\n", e.what());
            return kExitUsage;
        }
        tiles.push_back(shrink(f.rgb, args.width, args.height, factor));
        if (progress) std::fprintf(stderr, "\r");
        std::printf("%5zu %7.3f %5d | %5d %5d %5d %5d %4d %5d | %9lld %9lld %9s | %7.1f %7.1f "
                    "%7.1f %7.1f %7.1f %7.1f %8.1f %8.1f %8.1f | %9llu | %5s %6s\n",
                    k, r.time, r.pose.surfaces_moved, r.volumes_built, r.reused, r.out_of_reach,
                    r.out_of_view, r.culled, r.zfail, (long long)r.indices_built,
                    (long long)r.indices_drawn,
                    r.compared ? std::to_string(r.full_indices).c_str() : "-",
                    kt(r.pose.ticks_skinning), kt(r.pose.ticks_planes), kt(r.ticks_facing),
                    kt(r.ticks_culling), kt(r.ticks_volume), kt(r.ticks_depth), kt(r.ticks_stencil),
                    kt(r.ticks_shading), kt(r.ticks_frame), (unsigned long long)r.stencil_pixels,
                    !r.compared          ? "-"
                    : r.diff.identical() ? "yes"
                                         : "NO",
                    !r.truth_done          ? "-"
                    : r.truth_off_boundary ? "FAIL"
                                           : "ok");
        std::fflush(stdout);
        rows.push_back(r);
    }
    if (progress) std::fprintf(stderr, "\n");
    try {
        sv::render::write_png(args.out_dir + "/contact.png", contact_sheet(tiles));
        if (webp) webp->write(args.webp_path);
    } catch (const std::exception &e) {
        std::fprintf(stderr, "shadowvol scene: %s\n", e.what());
        return kExitUsage;
    }

    /* Totals, and what the shortcuts saved against the full frames. */
    FrameRow t;
    uint64_t full_ticks = 0, full_pixels = 0;
    int64_t full_indices = 0;
    for (const FrameRow &r : rows) {
        t.volumes_built += r.volumes_built, t.reused += r.reused, t.out_of_reach += r.out_of_reach;
        t.out_of_view += r.out_of_view, t.culled += r.culled, t.zfail += r.zfail;
        t.dark_caps_dropped += r.dark_caps_dropped;
        t.indices_built += r.indices_built, t.indices_drawn += r.indices_drawn;
        t.pose.ticks_skinning += r.pose.ticks_skinning, t.pose.ticks_planes += r.pose.ticks_planes;
        t.pose.ticks_skin_planes += r.pose.ticks_skin_planes;
        t.pose.planes_derived += r.pose.planes_derived;
        t.ticks_facing += r.ticks_facing, t.ticks_culling += r.ticks_culling,
            t.ticks_volume += r.ticks_volume;
        t.ticks_depth += r.ticks_depth, t.ticks_stencil += r.ticks_stencil,
            t.ticks_shading += r.ticks_shading;
        t.ticks_frame += r.ticks_frame, t.stencil_pixels += r.stencil_pixels;
        full_ticks += r.ticks_full_frame, full_pixels += r.full_stencil_pixels,
            full_indices += r.full_indices;
        t.truth_mismatches += r.truth_mismatches, t.truth_off_boundary += r.truth_off_boundary;
        t.primary_checked += r.primary_checked, t.primary_disagreements += r.primary_disagreements;
    }
    const double n = (double)rows.size();
    std::printf("\ntotals over %zu frame(s): %d volumes built, %d reused, %d skipped out of reach, "
                "%d out of view; "
                "culling ran on %d; %d drawn in z-fail; %d dark caps dropped\n",
                rows.size(), t.volumes_built, t.reused, t.out_of_reach, t.out_of_view, t.culled,
                t.zfail, t.dark_caps_dropped);
    std::printf(
        "per frame: %.2f ms (%.1f kt), skinning %.1f kt, planes %.1f kt, skinning and "
        "planes in one pass %.1f kt (%.2f ticks per triangle for planes, or for both in one "
        "pass, over "
        "%lld triangles)\n",
        ms(t.ticks_frame, hz) / n, kt(t.ticks_frame) / n, kt(t.pose.ticks_skinning) / n,
        kt(t.pose.ticks_planes) / n, kt(t.pose.ticks_skin_planes) / n,
        t.pose.planes_derived ? (double)(t.pose.ticks_planes + t.pose.ticks_skin_planes) /
                                    (double)t.pose.planes_derived
                              : 0.0,
        (long long)t.pose.planes_derived);
    if (skinned) {
        uint64_t total = 0, worst = 0;
        std::size_t worst_frame = 0;
        for (const FrameRow &r : rows) {
            total += r.skinned_differ;
            if (r.skinned_differ > worst)
                worst = r.skinned_differ, worst_frame = (std::size_t)r.index;
        }
        std::printf("skinned normals %s: %llu shadow pixels differ from the recomputed normals' "
                    "where the light reaches, over %zu frame(s) and every light (the worst frame "
                    "%zu: %llu)\n",
                    args.skinned_normals.c_str(), (unsigned long long)total, rows.size(),
                    worst_frame, (unsigned long long)worst);
    }
    if (args.check && !args.full) {
        bool all_same = true;
        for (const FrameRow &r : rows) all_same &= r.diff.identical();
        std::printf(
            "against the full frames: indices built %lld against %lld (%.1f%%), stencil pixels "
            "%llu "
            "against %llu (%.1f%%), frame %.2f ms against %.2f ms (%.2fx faster); pictures %s\n",
            (long long)t.indices_built, (long long)full_indices,
            full_indices ? 100.0 * (double)t.indices_built / (double)full_indices : 0.0,
            (unsigned long long)t.stencil_pixels, (unsigned long long)full_pixels,
            full_pixels ? 100.0 * (double)t.stencil_pixels / (double)full_pixels : 0.0,
            ms(t.ticks_frame, hz) / n, ms(full_ticks, hz) / n,
            t.ticks_frame ? (double)full_ticks / (double)t.ticks_frame : 0.0,
            all_same ? "identical (shaded bytes, and the shadow mask wherever the light reaches)"
                     : "DIFFERENT");
        std::printf("what each shortcut saved (indices the full frames built and these did not, "
                    "each (light, "
                    "surface) pair's\nto the first decision that applies):\n");
        for (int k = 0; k < kSavings; k++) {
            std::printf("  %-24s %6d decisions %12lld indices (%.1f%% of the full frames')\n",
                        kSavingNames[k], saved.decisions[k], (long long)saved.indices[k],
                        full_indices ? 100.0 * (double)saved.indices[k] / (double)full_indices
                                     : 0.0);
        }
        for (const FrameRow &r : rows) {
            if (r.diff.identical()) continue;
            std::printf("  frame %d: %llu shaded bytes differ (first at pixel %llu), %llu mask "
                        "pixels in reach "
                        "(first at %llu)\n",
                        r.index, (unsigned long long)r.diff.rgb_bytes,
                        (unsigned long long)r.diff.first_rgb,
                        (unsigned long long)r.diff.mask_in_reach,
                        (unsigned long long)r.diff.first_mask);
        }
    }
    if (args.truth) {
        std::printf("truth: %llu mismatches, all on shadow boundaries: %s; the depth pass's "
                    "visible triangle checked by the truth's own camera rays at %llu pixels: %llu "
                    "disagree\n",
                    (unsigned long long)t.truth_mismatches, t.truth_off_boundary ? "NO" : "yes",
                    (unsigned long long)t.primary_checked,
                    (unsigned long long)t.primary_disagreements);
        for (const std::string &n : truth_notes) std::printf("  %s\n", n.c_str());
    }
    std::printf("images: %s/frame_000.png .. frame_%03zu.png, contact.png%s%s\n",
                args.out_dir.c_str(), rows.size() - 1, webp ? "; animation: " : "",
                webp ? args.webp_path.c_str() : "");

    if (!args.json_path.empty()) {
        svbench::JsonWriter j;
        j.begin_object();
        j.key("schema"), j.value("shadowvol-scene/1");
        j.key("file"), j.value(args.seq.file);
        j.key("animation"), j.value(seq->animation_name());
        j.key("width"), j.value(args.width);
        j.key("height"), j.value(args.height);
        j.key("threads"), j.value(threads);
        j.key("shortcuts"), j.value(!args.full);
        j.key("stencil"), j.value(sv::render::stencil_method_name(args.stencil.method));
        j.key("mode"), j.value(sv::render::mode_name(args.mode));
        j.key("caster_rule"), j.value(sv::caster_rule_name(args.caster_rule));
        j.key("ground_hints"), j.value(args.ground_hints);
        j.key("general_build"), j.value(sv::general_build_name(args.general_build));
        j.key("volume"), j.value(sv::render::volume_source_name(fast.volume));
        j.key("stencil_saturate"), j.value(fast.stencil_saturate);
        j.key("extrude_to_infinity"), j.value(fast.extrude_to_infinity);
        j.key("skinned_normals");
        skinned ? j.value(args.skinned_normals) : j.null();
        j.key("tsc_hz"), j.value(hz);
        j.key("surfaces"), j.value((long long)scene.surfaces.size());
        j.key("triangles"), j.value((long long)scene.triangles());
        j.key("lights");
        j.begin_array();
        for (const sv::SceneLight &l : scene.lights) j.value(l.describe());
        j.end_array();
        j.key("frames");
        j.begin_array();
        for (const FrameRow &r : rows) {
            j.begin_object(true);
            j.key("index"), j.value(r.index);
            j.key("time"), j.value(r.time);
            j.key("surfaces_moved"), j.value(r.pose.surfaces_moved);
            j.key("lights_moved"), j.value(r.pose.lights_moved);
            j.key("volumes_built"), j.value(r.volumes_built);
            j.key("volumes_reused"), j.value(r.reused);
            j.key("skipped_out_of_reach"), j.value(r.out_of_reach);
            j.key("skipped_out_of_view"), j.value(r.out_of_view);
            j.key("culled"), j.value(r.culled);
            j.key("zfail"), j.value(r.zfail);
            j.key("dark_caps_dropped"), j.value(r.dark_caps_dropped);
            j.key("indices_built"), j.value((long long)r.indices_built);
            j.key("indices_drawn"), j.value((long long)r.indices_drawn);
            j.key("full_indices"), r.compared ? j.value((long long)r.full_indices) : j.null();
            if (skinned)
                j.key("skinned_pixels_differ"), j.value((unsigned long long)r.skinned_differ);
            j.key("ticks");
            j.begin_object(true);
            j.key("skinning"), j.value((unsigned long long)r.pose.ticks_skinning);
            j.key("planes"), j.value((unsigned long long)r.pose.ticks_planes);
            j.key("skin_planes"), j.value((unsigned long long)r.pose.ticks_skin_planes);
            j.key("facing"), j.value((unsigned long long)r.ticks_facing);
            j.key("culling"), j.value((unsigned long long)r.ticks_culling);
            j.key("volume"), j.value((unsigned long long)r.ticks_volume);
            j.key("depth"), j.value((unsigned long long)r.ticks_depth);
            j.key("stencil"), j.value((unsigned long long)r.ticks_stencil);
            j.key("shading"), j.value((unsigned long long)r.ticks_shading);
            j.key("frame"), j.value((unsigned long long)r.ticks_frame);
            j.key("full_frame"),
                r.compared ? j.value((unsigned long long)r.ticks_full_frame) : j.null();
            j.end_object();
            j.key("planes_derived"), j.value((long long)r.pose.planes_derived);
            j.key("stencil_pixels"), j.value((unsigned long long)r.stencil_pixels);
            j.key("identical_to_full"), r.compared ? j.value(r.diff.identical()) : j.null();
            j.key("differing_bytes"),
                r.compared ? j.value((unsigned long long)r.diff.rgb_bytes) : j.null();
            j.key("truth_off_boundary"),
                r.truth_done ? j.value((unsigned long long)r.truth_off_boundary) : j.null();
            j.end_object();
        }
        j.end_array();
        if (args.check && !args.full) {
            j.key("saved");
            j.begin_array();
            for (int k = 0; k < kSavings; k++) {
                j.begin_object(true);
                j.key("shortcut"), j.value(kSavingNames[k]);
                j.key("decisions"), j.value(saved.decisions[k]);
                j.key("indices"), j.value((long long)saved.indices[k]);
                j.end_object();
            }
            j.end_array();
        }
        j.key("passed"), j.value(!failed);
        j.end_object();
        FILE *fj = args.json_path == "-" ? stdout : std::fopen(args.json_path.c_str(), "w");
        if (!fj) {
            std::fprintf(stderr, "shadowvol scene: --json %s: cannot write\n",
                         args.json_path.c_str());
            return kExitUsage;
        }
        const std::string &doc = j.str();
        if (std::fwrite(doc.data(), 1, doc.size(), fj) != doc.size() ||
            (fj != stdout && std::fclose(fj) != 0)) {
            std::fprintf(stderr, "shadowvol scene: --json %s: cannot write\n",
                         args.json_path.c_str());
            return kExitUsage;
        }
    }
    std::printf("%s\n",
                failed ? "FAILED: a frame differs from the full frame where the light reaches, or "
                         "from the truth "
                         "off a shadow boundary"
                : args.check && !args.full && args.truth
                    ? "PASSED: every frame equals the full frame and agrees with the truth"
                : args.check && !args.full
                    ? "PASSED: every frame equals the full frame (truth not cast)"
                : args.truth
                    ? "PASSED: every frame agrees with the truth (not compared with a full frame)"
                    : "done (nothing checked: --no-check/--full and --no-truth)");
    return failed ? kExitMismatch : 0;
}

} // namespace svcli
