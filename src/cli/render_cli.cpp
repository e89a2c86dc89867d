/*
 * shadowvol render (issue 12): a scene of glTF surfaces, lights and a
 * camera; its shadow volumes drawn into the project's stencil; the shaded
 * picture; and both judges: ray-cast truth at every pixel and Mesa's
 * OpenGL stencil fed the very same index lists.
 *
 * Exit status: 0 done; 1 a stencil mismatch against the truth off a
 * shadow boundary (or a GL difference off every volume edge and depth
 * tie); 2 bad arguments; 3 a model that cannot be loaded.
 *
 * Copyright (C) 2026 the shadowvol authors. LGPL-2.1-or-later.
 */
#include "render_cli.h"
#include "render_args.h"

#include <sys/stat.h>

#include <cerrno>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <string>
#include <thread>
#include <vector>

#include "cli_args.h"
#include "extruded_volumes.h"
#include "frame.h"
#include "fnv1a.h"
#include "gl_compare.h"
#include "images.h"
#include "json_writer.h"
#include "scene_options.h"
#include "shadowvol_gltf.h"
#include "shadowvol_plan.h"
#include "timer.h"
#include "truth.h"

#ifndef SV_MODELS_DIR
#define SV_MODELS_DIR "models"
#endif

namespace svcli {
namespace {

constexpr int kExitMismatch = 1, kExitUsage = 2, kExitBadModel = 3;

double ms(uint64_t ticks, double hz) { return hz > 0 ? 1e3 * (double)ticks / hz : 0; }

/* FNV-1a 64 over the list as little-endian int32s, in order, as 16 hex
 * digits: a fingerprint of the exact index list the library returned, so
 * tools/pin_bytes.sh can pin the volumes apart from the pictures (a volume
 * may change while the pixels stay the same, and the reverse). */
std::string indices_fnv1a64(const int *indices, std::size_t n) {
    /* (x86 keeps an int32 as its little-endian bytes.) */
    const uint64_t h = sv::fnv1a64(indices, n * sizeof *indices);
    char hex[17];
    std::snprintf(hex, sizeof hex, "%016llx", (unsigned long long)h);
    return hex;
}

} // namespace

bool make_dir(const std::string &d) {
    if (mkdir(d.c_str(), 0777) == 0 || errno == EEXIST) {
        struct stat st;
        return stat(d.c_str(), &st) == 0 && S_ISDIR(st.st_mode);
    }
    return false;
}

void counters_json(svbench::JsonWriter &j, const sv::raster::PassCounters &c) {
    j.begin_object(true);
    j.key("triangles"), j.value((unsigned long long)c.triangles);
    j.key("clipped"), j.value((unsigned long long)c.triangles_clipped);
    j.key("outside"), j.value((unsigned long long)c.triangles_outside);
    j.key("degenerate"), j.value((unsigned long long)c.triangles_degenerate);
    j.key("pixels_tested"), j.value((unsigned long long)c.pixels_tested);
    j.key("pixels_written"), j.value((unsigned long long)c.pixels_written);
    j.key("depth_bytes_read"), j.value((unsigned long long)c.depth_bytes_read);
    j.key("depth_bytes_written"), j.value((unsigned long long)c.depth_bytes_written);
    j.key("stencil_bytes_read"), j.value((unsigned long long)c.stencil_bytes_read);
    j.key("stencil_bytes_written"), j.value((unsigned long long)c.stencil_bytes_written);
    j.end_object();
}

void render_usage(FILE *out) {
    std::fprintf(
        out,
        "usage: shadowvol render [scene options] [--size WxH] [--mode zpass|zfail|auto]\n"
        "                        [--stencil bf|db|hier|auto] [--stencil-tile N]\n"
        "                        [--caster-rule auto|closed|general] [--ground-hints use|ignore]\n"
        "                        [--volume silhouette|extrude] [--stencil-op saturate|wrap]\n"
        "                        [--extrude-to range|infinity]\n"
        "                        [--out DIR] [--json FILE] [--no-truth] [--no-gl]\n"
        "\n"
        "Renders a scene with the paper's shadow volumes in the project's own stencil\n"
        "rasteriser, and checks every pixel against ray-cast truth and against Mesa's\n"
        "OpenGL (llvmpipe) fed the same index lists. Writes DIR/shaded.png,\n"
        "DIR/stencil.png (one panel per light), DIR/truth.png and DIR/gl_diff.png.\n"
        "With no scene options: the bundled character on a ground plane.\n"
        "\n"
        "scene:\n"
        "  --add FILE[@x,y,z[,yaw_degrees[,scale]]]   a glTF model, placed (repeatable);\n"
        "                                a file name that holds a ':' is written with a ':'\n"
        "                                after it (FILE:ANIMATION is shadowvol scene's)\n"
        "  --ground                      a ground plane under the models\n"
        "  --light point:x,y,z[,range]   a point light (repeatable, any kind)\n"
        "  --light spot:x,y,z,dx,dy,dz,inner_deg,outer_deg\n"
        "  --light dir:x,y,z             a directional light travelling along (x,y,z)\n"
        "  --light point:auto | spot:auto | dir:auto   placed around the models\n"
        "  --camera eye=x,y,z,target=x,y,z[,fov=deg][,near=d][,up=x,y,z]\n"
        "                                default: framed from the front and above;\n"
        "                                without near=, one fitted to the scene's distance\n"
        "  (no light: a point light and a directional light whose shadows fall on the\n"
        "  ground in view; a light's intensity makes it give irradiance 1 at the\n"
        "  scene's centre)\n"
        "\n"
        "frame:\n"
        "  --size WxH        default 1280x1024; at most %d per side\n"
        "  --mode M          zpass (silhouettes only), zfail (with caps), or auto\n"
        "                    (default: z-fail for a volume only where the camera's near\n"
        "                    rectangle may lie inside it)\n"
        "  --stencil S       how the stencil pass fills: bf (brute force: every volume\n"
        "                    triangle walked per pixel; the reference), db (behind\n"
        "                    per-volume depth bounds), hier (tiles classified per volume,\n"
        "                    seed 004) or auto (bf or hier per light, by its volume\n"
        "                    pieces' mean area: docs/RENDERING.md); all leave the same\n"
        "                    bytes. Default: the wisdom file's (shadowvol tune), else auto\n"
        "  --stencil-tile N  hier's tile side: 4, 8 (the seed's), 16 or 32 (default: the\n"
        "                    wisdom file's, else 32)\n"
        "  --caster-rule R   auto (default: closed shells the paper's volume, open or\n"
        "                    non-manifold shells the general rule, exact for any caster),\n"
        "                    closed (the paper's everywhere) or general (docs/CASTERS.md)\n"
        "  --ground-hints H  use (default: under auto, a surface declared ground, the\n"
        "                    --ground quad or a glTF extras \"shadowvol_ground\", keeps\n"
        "                    the paper's rule) or ignore (its shells decide)\n"
        "  --general-build B how the general rule's volumes are built: direct (default:\n"
        "                    the general kernels) or two-sided (the paper's kernels on\n"
        "                    the shells and their reverses); the same stencil\n"
        "%s"
        "  --kernels K       the rasteriser's row kernels: c, avx2, avx512 (default: best)\n"
        "  --variant NAME    the library's volume kernels (default: best)\n"
        "  --no-truth        skip the ray-cast truth\n"
        "  --no-gl           skip the Mesa comparison\n"
        "  --threads N       threads for the frame's passes and the truth's rays\n"
        "                    (default: every core; the pictures are the same at any N)\n"
        "  --out DIR         where the PNGs go (default shadowvol-render)\n"
        "  --json FILE       the report as JSON (schema shadowvol-render/1; - for stdout)\n"
        "\n"
        "Exit status: 0 done; 1 a mismatch against the truth off a shadow boundary, or a\n"
        "difference from Mesa off every volume edge and depth tie; 2 bad arguments;\n"
        "3 a model could not be loaded.\n",
        sv::render::kMaxFrameSide, volume_options_help());
}

int render_main(int argc, char **argv) {
    RenderArgs args;
    try {
        bool help = false;
        args = parse_render_args(argc, argv, help);
        if (help) {
            render_usage(stdout);
            return 0;
        }
    } catch (const UsageError &e) {
        std::fprintf(stderr, "shadowvol render: %s\nTry 'shadowvol render --help'.\n",
                     e.message.c_str());
        return kExitUsage;
    } catch (const sv::SceneError &e) {
        std::fprintf(stderr, "shadowvol render: %s\n", e.what());
        return kExitUsage;
    }
    const sv::raster::RowKernels *kernels = nullptr;
    if (!args.kernels.empty()) {
        kernels = sv::raster::row_kernels_by_name(args.kernels.c_str());
        if (!kernels || (kernels->isa & sv_cpu_isa()) != kernels->isa) {
            std::fprintf(stderr, "shadowvol render: --kernels %s: %s\n", args.kernels.c_str(),
                         kernels ? "this CPU (or SV_ISA) does not run it"
                                 : "unknown (c, avx2, avx512)");
            return kExitUsage;
        }
    }
    const sv_variant *variant = nullptr;
    if (!args.variant.empty()) {
        variant = sv_variant_by_name(args.variant.c_str());
        if (!variant || (variant->isa & sv_cpu_isa()) != variant->isa) {
            std::fprintf(stderr, "shadowvol render: --variant %s: %s\n", args.variant.c_str(),
                         variant ? "this CPU (or SV_ISA) does not run it" : "unknown variant");
            return kExitUsage;
        }
    }
    const bool bundled = args.models.empty();
    if (bundled) {
        args.models.push_back({std::string(SV_MODELS_DIR) + "/character_1344.glb", {}, {}});
        args.ground = true;
    }

    sv::Scene scene;
    for (const sv::ModelPlacement &m : args.models) {
        try {
            sv::add_model(scene, m.path, m.placement);
        } catch (const sv::GltfError &e) {
            std::fprintf(stderr, "shadowvol render: %s\n", e.what());
            return kExitBadModel;
        } catch (const sv::PrepareError &e) {
            std::fprintf(stderr, "shadowvol render: %s: %s\n", m.path.c_str(), e.what());
            return kExitBadModel;
        } catch (const sv::SceneError &e) {
            std::fprintf(stderr, "shadowvol render: %s\n", e.what());
            return kExitUsage;
        }
    }
    if (scene.triangles() == 0) {
        std::fprintf(stderr, "shadowvol render: the models have no triangles to render\n");
        return kExitBadModel;
    }
    if (args.ground) sv::add_ground(scene);
    const double aspect = (double)args.width / args.height;
    scene.camera = args.has_camera ? args.camera : sv::frame_camera(scene, aspect);
    if (scene.camera.near_distance == 0)
        scene.camera.near_distance = sv::fitting_near_distance(scene, scene.camera);
    scene.lights = args.lights.empty() ? sv::default_lights(scene) : args.lights;
    for (sv::SceneLight &l : scene.lights) {
        if (l.placed_automatically) l = sv::auto_light(scene, l.kind);
    }
    for (sv::SceneLight &l : scene.lights) sv::default_intensity(scene, l);
    try {
        sv::validate_scene(scene);
    } catch (const sv::SceneError &e) {
        std::fprintf(stderr, "shadowvol render: %s\n", e.what());
        return kExitUsage;
    }
    for (const std::string &n : scene.notes) std::fprintf(stderr, "note: %s\n", n.c_str());

    const uint64_t bytes = sv::render::frame_bytes(args.width, args.height,
                                                   (int)scene.lights.size());
    std::fprintf(
        stderr, "shadowvol render: %dx%d, %zu light(s), %lld triangles; the frame needs %.1f MiB\n",
        args.width, args.height, scene.lights.size(), (long long)scene.triangles(),
        (double)bytes / (1 << 20));
    if (!make_dir(args.out_dir)) {
        std::fprintf(stderr, "shadowvol render: --out %s: cannot create the folder\n",
                     args.out_dir.c_str());
        return kExitUsage;
    }

    sv::render::RenderOptions opt;
    opt.width = args.width;
    opt.height = args.height;
    opt.mode = args.mode;
    /* The stencil method `shadowvol tune` measured for this CPU where
     * --stencil does not say (render_args.h); the same bytes by each. */
    char wisdom[1024];
    sv_wisdom_load(sv_wisdom_default_path(wisdom, sizeof wisdom));
    svcli::take_stencil_default(args.stencil);
    args.stencil.apply(opt);
    opt.caster_rule = args.caster_rule;
    opt.ground_hints = args.ground_hints;
    opt.general_build = args.general_build;
    apply_volume_args(args.volume, opt);
    opt.kernels = kernels;
    opt.variant = variant;
    opt.threads = args.threads; /* 0: every core; the same bytes at any count */
    /* Kept from the first drawing to the second (below), as a sequence of
     * frames keeps it: the second is warm as Mesa's second is. */
    sv::render::FrameScratch scratch;
    opt.scratch = &scratch;
    sv::render::Frame frame;
    try {
        frame = sv::render::render_frame(scene, opt);
    } catch (const std::bad_alloc &) {
        std::fprintf(stderr, "shadowvol render: out of memory for a %dx%d frame\n", args.width,
                     args.height);
        return kExitUsage;
    }
    const double hz = svbench::estimate_tsc_hz(0.05);
    const int threads = args.threads ? args.threads
                                     : (int)std::max(1u, std::thread::hardware_concurrency());

    /* The judges. */
    std::vector<sv::render::Truth> truths;
    std::vector<sv::render::Comparison> cmps;
    if (args.truth) {
        std::fprintf(stderr, "shadowvol render: casting the truth's rays...\n");
        const sv::render::TruthCaster caster(scene);
        for (std::size_t li = 0; li < frame.lights.size(); li++) {
            truths.push_back(caster.cast(frame, (int)li, threads));
            cmps.push_back(caster.compare(frame, (int)li, truths.back()));
        }
    }
    std::vector<sv::render::GlComparison> gls;
    std::string gl_renderer, gl_note;
    int gl_threads = 0;
    if (args.gl) {
        /* Like for like with Mesa's stencil pass (drawn twice, the faster
         * kept, on as many threads as ours): ours drawn once more, warm,
         * each light's faster stencil pass kept (the same bytes: the frame
         * is the first drawing's). */
        sv::render::Frame again;
        try {
            again = sv::render::render_frame(scene, opt);
        } catch (const std::bad_alloc &) {
            again = sv::render::Frame{}; /* the first drawing's times stand */
        }
        for (std::size_t li = 0; li < again.lights.size(); li++) {
            sv::render::LightFrame &lf = frame.lights[li];
            const sv::render::LightFrame &la = again.lights[li];
            if (la.seconds_stencil < lf.seconds_stencil) {
                lf.seconds_stencil = la.seconds_stencil;
                lf.ticks_stencil = la.ticks_stencil;
            }
        }
        std::fprintf(stderr, "shadowvol render: drawing the same volumes with Mesa...\n");
        try {
            gls = sv::render::compare_with_mesa(scene, frame, &gl_renderer, &gl_note, frame.threads,
                                                &gl_threads);
        } catch (const std::exception &e) {
            /* A job the judge refuses or a GL error: say so, and fail. */
            std::fprintf(stderr, "shadowvol render: the Mesa judge failed: %s\n", e.what());
            return kExitMismatch;
        }
        if (!gl_note.empty()) std::fprintf(stderr, "NOTE: %s\n", gl_note.c_str());
    }

    /* Pictures. */
    sv::render::Image shaded(frame.width, frame.height);
    shaded.rgb = frame.rgb;
    std::vector<sv::render::Image> stencil_panels, truth_panels, gl_panels;
    for (std::size_t li = 0; li < frame.lights.size(); li++) {
        stencil_panels.push_back(sv::render::stencil_image(frame.lights[li].stencil, shaded));
        if (li < truths.size()) {
            truth_panels.push_back(sv::render::truth_image(truths[li], frame.lights[li].stencil,
                                                           frame.width, frame.height));
        }
        if (li < gls.size()) gl_panels.push_back(sv::render::difference_image(gls[li].cls, shaded));
    }
    try {
        sv::render::write_png(args.out_dir + "/shaded.png", shaded);
        sv::render::write_png(args.out_dir + "/stencil.png",
                              sv::render::side_by_side(stencil_panels));
        if (!truth_panels.empty()) {
            sv::render::write_png(args.out_dir + "/truth.png",
                                  sv::render::side_by_side(truth_panels));
        }
        if (!gl_panels.empty()) {
            sv::render::write_png(args.out_dir + "/gl_diff.png",
                                  sv::render::side_by_side(gl_panels));
        }
    } catch (const std::exception &e) {
        std::fprintf(stderr, "shadowvol render: %s\n", e.what());
        return kExitUsage;
    }

    /* The report. */
    bool failed = false;
    std::printf("scene: %zu surface(s), %lld triangles, %zu light(s); camera eye (%g, %g, %g) "
                "target (%g, %g, %g) fov %g near %g\n",
                scene.surfaces.size(), (long long)scene.triangles(), scene.lights.size(),
                scene.camera.eye.x, scene.camera.eye.y, scene.camera.eye.z, scene.camera.target.x,
                scene.camera.target.y, scene.camera.target.z, scene.camera.fov_y_degrees,
                scene.camera.near_distance);
    std::printf(
        "frame: %dx%d, mode %s, stencil %s, row kernels %s, volume kernels %s, TSC %.3f GHz\n",
        frame.width, frame.height, sv::render::mode_name(args.mode), frame.stencil_method.c_str(),
        frame.kernels.c_str(), frame.variant.c_str(), hz / 1e9);
    std::printf(
        "depth pass: %llu triangles, %llu pixels tested, %llu written, %.2f ms (%llu ticks)\n",
        (unsigned long long)frame.depth_counters.triangles,
        (unsigned long long)frame.depth_counters.pixels_tested,
        (unsigned long long)frame.depth_counters.pixels_written, ms(frame.ticks_depth, hz),
        (unsigned long long)frame.ticks_depth);
    std::printf("\n%-3s %-46s %4s %5s %8s %8s | %9s %9s %9s %9s | %10s %10s %9s | %8s %8s %8s %6s "
                "%6s | %8s %8s %7s\n",
                "#", "light", "vols", "zfail", "indices", "drawn", "facing", "volume", "stencil",
                "shading", "st.tested", "st.written", "st.bytes", "lit", "shadowed", "boundary",
                "mism", "off", "gl.diff", "gl.other", "gl/own");
    std::printf("%-3s %-46s %4s %5s %8s %8s | %9s %9s %9s %9s | %10s %10s %9s | %8s %8s %8s %6s "
                "%6s | %8s %8s %7s\n",
                "", "", "", "", "", "", "ms", "ms", "ms", "ms", "", "", "r+w", "", "", "", "", "",
                "", "", "x");
    for (std::size_t li = 0; li < frame.lights.size(); li++) {
        const sv::render::LightFrame &lf = frame.lights[li];
        const sv::render::Comparison *c = li < cmps.size() ? &cmps[li] : nullptr;
        const sv::render::GlComparison *g = li < gls.size() ? &gls[li] : nullptr;
        std::string desc = lf.light.describe();
        if (desc.size() > 46) desc = desc.substr(0, 46);
        char truth_cols[128] = "", gl_cols[96] = "";
        if (c) {
            std::snprintf(truth_cols, sizeof truth_cols, "%8llu %8llu %8llu %6llu %6llu",
                          (unsigned long long)c->lit, (unsigned long long)c->shadowed,
                          (unsigned long long)c->boundary, (unsigned long long)c->mismatches,
                          (unsigned long long)c->off_boundary_mismatches);
            failed |= c->off_boundary_mismatches > 0;
        } else {
            std::snprintf(truth_cols, sizeof truth_cols, "%8s %8s %8s %6s %6s", "-", "-", "-", "-",
                          "-");
        }
        if (g) {
            std::snprintf(gl_cols, sizeof gl_cols, "%8llu %8llu %7.2f",
                          (unsigned long long)g->differing, (unsigned long long)g->other,
                          lf.seconds_stencil > 0 ? g->mesa_stencil_seconds / lf.seconds_stencil
                                                 : 0.0);
            failed |= g->other > 0;
        } else {
            std::snprintf(gl_cols, sizeof gl_cols, "%8s %8s %7s", "-", "-", "-");
        }
        std::printf("%-3zu %-46s %4zu %5d %8lld %8lld | %9.3f %9.3f %9.3f %9.3f | %10llu %10llu "
                    "%9llu | %s | %s\n",
                    li, desc.c_str(), lf.volumes.size(), lf.zfail_volumes, (long long)lf.indices,
                    (long long)lf.drawn_indices, ms(lf.ticks_facing, hz), ms(lf.ticks_volume, hz),
                    ms(lf.ticks_stencil, hz), ms(frame.ticks_shading, hz),
                    (unsigned long long)lf.stencil_counters.pixels_tested,
                    (unsigned long long)lf.stencil_counters.pixels_written,
                    (unsigned long long)lf.stencil_counters.stencil_bytes_read +
                        (unsigned long long)lf.stencil_counters.stencil_bytes_written,
                    truth_cols, gl_cols);
    }
    for (std::size_t li = 0; li < frame.lights.size(); li++) {
        const sv::render::LightFrame &lf = frame.lights[li];
        std::printf("ticks %zu: facing %llu, volume %llu, stencil %llu; the frame's depth pass "
                    "%llu, lighting pass %llu\n",
                    li, (unsigned long long)lf.ticks_facing, (unsigned long long)lf.ticks_volume,
                    (unsigned long long)lf.ticks_stencil, (unsigned long long)frame.ticks_depth,
                    (unsigned long long)frame.ticks_shading);
    }
    for (std::size_t li = 0; li < frame.lights.size(); li++) {
        /* What the volume triangles cost set-up (seed 002's degenerate
         * quads are submitted and rejected there as zero-area). */
        const sv::render::LightFrame &lf = frame.lights[li];
        const sv::raster::PassCounters &c = lf.stencil_counters;
        std::printf("volume set-up %zu (%s volumes, stencil %s): %llu triangles submitted, %llu "
                    "zero-area after snapping, %llu clipped, %llu outside the view; %llu pixels "
                    "tested, %llu written; seed 002's extrusion %llu ticks\n",
                    li, sv::render::volume_source_name(opt.volume),
                    opt.stencil_saturate ? "saturating" : "wrap-around",
                    (unsigned long long)c.triangles, (unsigned long long)c.triangles_degenerate,
                    (unsigned long long)c.triangles_clipped,
                    (unsigned long long)c.triangles_outside, (unsigned long long)c.pixels_tested,
                    (unsigned long long)c.pixels_written, (unsigned long long)lf.ticks_extrude);
    }
    for (std::size_t li = 0; li < truths.size(); li++) {
        std::printf(
            "truth %zu: %llu rays in %.2f s (%.2f M rays/s, %d threads, BVH of src/verify)\n", li,
            (unsigned long long)truths[li].rays, truths[li].seconds,
            truths[li].seconds > 0 ? (double)truths[li].rays / truths[li].seconds / 1e6 : 0.0,
            threads);
        std::printf("truth %zu: the depth pass's visible triangle checked by the truth's own "
                    "camera rays at %llu pixels: %llu disagree\n",
                    li, (unsigned long long)cmps[li].primary_checked,
                    (unsigned long long)cmps[li].primary_disagreements);
        for (int p : cmps[li].first_off_boundary) {
            std::printf("  off-boundary mismatch at pixel (%d, %d): stencil %u\n", p % frame.width,
                        p / frame.width, frame.lights[li].stencil[(std::size_t)p]);
        }
    }
    if (!gls.empty()) {
        std::printf("mesa: %s; LP_NUM_THREADS %d, ours %d thread(s); each stencil pass the "
                    "faster of two drawings\n",
                    gl_renderer.c_str(), gl_threads, frame.threads);
        for (std::size_t li = 0; li < gls.size(); li++) {
            const sv::render::GlComparison &g = gls[li];
            std::printf("gl %zu: %llu pixels differ (%.6f%%): %llu on a volume triangle's edge "
                        "(within %.4f px), %llu at a depth tie, %llu other; "
                        "Mesa's stencil pass %.2f ms against ours %.2f ms (Mesa / ours = %.2f)\n",
                        li, (unsigned long long)g.differing,
                        100.0 * (double)g.differing / ((double)frame.width * frame.height),
                        (unsigned long long)g.on_edge, g.max_edge_distance,
                        (unsigned long long)g.depth_tie, (unsigned long long)g.other,
                        1e3 * g.mesa_stencil_seconds, 1e3 * frame.lights[li].seconds_stencil,
                        frame.lights[li].seconds_stencil > 0
                            ? g.mesa_stencil_seconds / frame.lights[li].seconds_stencil
                            : 0.0);
            for (const std::string &o : g.first_other)
                std::printf("  gl %zu other: %s\n", li, o.c_str());
        }
    }
    std::printf("images: %s/shaded.png stencil.png%s%s\n", args.out_dir.c_str(),
                truth_panels.empty() ? "" : " truth.png", gl_panels.empty() ? "" : " gl_diff.png");

    if (!args.json_path.empty()) {
        svbench::JsonWriter j;
        j.begin_object();
        j.key("schema"), j.value("shadowvol-render/1");
        j.key("width"), j.value(frame.width);
        j.key("height"), j.value(frame.height);
        j.key("mode"), j.value(sv::render::mode_name(args.mode));
        j.key("caster_rule"), j.value(sv::caster_rule_name(args.caster_rule));
        j.key("ground_hints"), j.value(args.ground_hints);
        j.key("volume"), j.value(sv::render::volume_source_name(opt.volume));
        j.key("stencil_saturate"), j.value(opt.stencil_saturate);
        j.key("extrude_to_infinity"), j.value(opt.extrude_to_infinity);
        j.key("general_build"), j.value(sv::general_build_name(args.general_build));
        j.key("stencil"), j.value(frame.stencil_method);
        /* Where the method came from: --stencil ("option"), the wisdom
         * file ("wisdom"), or the built-in default ("default": auto). */
        j.key("stencil_source"), j.value(args.stencil.source);
        j.key("stencil_tile"), j.value(args.stencil.tile);
        j.key("stencil_hier_from_area_per_piece"),
            j.value(args.stencil.rule.hier_from_area_per_piece);
        j.key("row_kernels"), j.value(frame.kernels);
        j.key("volume_kernels"), j.value(frame.variant);
        j.key("tsc_hz"), j.value(hz);
        j.key("surfaces");
        j.begin_array();
        for (const sv::SceneSurface &s : scene.surfaces) {
            j.begin_object(true);
            j.key("name"), j.value(s.name);
            j.key("triangles"), j.value(s.prepared.num_triangles());
            j.key("vertices"), j.value(s.prepared.num_vertices());
            j.key("ground"), j.value(s.ground);
            j.key("declared_ground"), j.value(s.declared_ground);
            j.end_object();
        }
        j.end_array();
        j.key("lighting_pass_ticks"), j.value((unsigned long long)frame.ticks_shading);
        j.key("depth_pass");
        j.begin_object();
        j.key("ticks"), j.value((unsigned long long)frame.ticks_depth);
        j.key("counters");
        counters_json(j, frame.depth_counters);
        j.end_object();
        j.key("lights");
        j.begin_array();
        for (std::size_t li = 0; li < frame.lights.size(); li++) {
            const sv::render::LightFrame &lf = frame.lights[li];
            j.begin_object();
            j.key("light"), j.value(lf.light.describe());
            j.key("volumes"), j.value((int)lf.volumes.size());
            j.key("zfail_volumes"), j.value(lf.zfail_volumes);
            j.key("indices"), j.value((long long)lf.indices);
            j.key("drawn_indices"), j.value((long long)lf.drawn_indices);
            j.key("ticks");
            j.begin_object(true);
            j.key("facing"), j.value((unsigned long long)lf.ticks_facing);
            j.key("volume"), j.value((unsigned long long)lf.ticks_volume);
            j.key("stencil"), j.value((unsigned long long)lf.ticks_stencil);
            j.key("extrude"), j.value((unsigned long long)lf.ticks_extrude);
            j.end_object();
            /* The method that ran (auto: the one it chose, by the load). */
            j.key("stencil_method"), j.value(sv::render::stencil_method_name(lf.stencil_ran));
            if (frame.stencil_method == "auto") {
                j.key("stencil_load");
                j.begin_object(true);
                j.key("pieces"), j.value((unsigned long long)lf.stencil_load.pieces);
                j.key("area"), j.value(lf.stencil_load.area);
                j.key("cap_pieces"), j.value((unsigned long long)lf.stencil_load.cap_pieces);
                j.end_object();
            }
            j.key("stencil_counters");
            counters_json(j, lf.stencil_counters);
            /* One row per volume (a surface that casts), with its light's
             * number so each row stands alone for grep. */
            j.key("index_lists");
            j.begin_array();
            for (const sv::render::Volume &v : lf.volumes) {
                j.begin_object(true);
                j.key("light"), j.value((int)li);
                j.key("surface"), j.value(v.surface);
                j.key("zfail"), j.value(v.zfail);
                j.key("indices"), j.value((long long)v.indices.size());
                j.key("silhouette_indices"), j.value(v.silhouette_indices);
                j.key("indices_fnv1a64"),
                    j.value(indices_fnv1a64(v.indices.data(), v.indices.size()));
                j.end_object();
            }
            j.end_array();
            if (li < cmps.size()) {
                const sv::render::Comparison &c = cmps[li];
                j.key("truth");
                j.begin_object(true);
                j.key("compared"), j.value((unsigned long long)c.compared);
                j.key("lit"), j.value((unsigned long long)c.lit);
                j.key("shadowed"), j.value((unsigned long long)c.shadowed);
                j.key("boundary"), j.value((unsigned long long)c.boundary);
                j.key("mismatches"), j.value((unsigned long long)c.mismatches);
                j.key("off_boundary_mismatches"),
                    j.value((unsigned long long)c.off_boundary_mismatches);
                j.key("primary_rays_checked"), j.value((unsigned long long)c.primary_checked);
                j.key("primary_rays_disagree"),
                    j.value((unsigned long long)c.primary_disagreements);
                j.key("rays"), j.value((unsigned long long)truths[li].rays);
                j.key("seconds"), j.value(truths[li].seconds);
                j.end_object();
            } else {
                j.key("truth"), j.null();
            }
            if (li < gls.size()) {
                const sv::render::GlComparison &g = gls[li];
                j.key("gl");
                j.begin_object(true);
                j.key("differing"), j.value((unsigned long long)g.differing);
                j.key("on_edge"), j.value((unsigned long long)g.on_edge);
                j.key("max_edge_distance"), j.value(g.max_edge_distance);
                j.key("depth_tie"), j.value((unsigned long long)g.depth_tie);
                j.key("other"), j.value((unsigned long long)g.other);
                j.key("mesa_stencil_seconds"), j.value(g.mesa_stencil_seconds);
                j.key("own_stencil_seconds"), j.value(lf.seconds_stencil);
                j.end_object();
            } else {
                j.key("gl"), j.null();
            }
            j.end_object();
        }
        j.end_array();
        j.key("gl_renderer"), j.value(gl_renderer);
        j.key("gl_lp_num_threads"), j.value(gl_threads);
        j.key("threads"), j.value(frame.threads);
        j.key("notes");
        j.begin_array();
        for (const std::string &n : scene.notes) j.value(n);
        if (!gl_note.empty()) j.value(gl_note);
        j.end_array();
        j.key("passed"), j.value(!failed);
        j.end_object();
        const std::string &doc = j.str();
        FILE *f = args.json_path == "-" ? stdout : std::fopen(args.json_path.c_str(), "w");
        if (!f || std::fwrite(doc.data(), 1, doc.size(), f) != doc.size() ||
            (f != stdout && std::fclose(f) != 0)) {
            std::fprintf(stderr, "shadowvol render: --json %s: cannot write\n",
                         args.json_path.c_str());
            return kExitUsage;
        }
    }
    if (failed) {
        std::printf("FAILED: a stencil pixel disagrees with the truth off a shadow boundary, or "
                    "with Mesa off every edge and depth tie\n");
        return kExitMismatch;
    }
    std::printf("PASSED: every mismatch against the truth lies on a shadow boundary%s\n",
                gls.empty() ? "" : "; every difference from Mesa on a volume edge or a depth tie");
    return 0;
}

} // namespace svcli
