/*
 * shadowvol tune: per size class, every runnable variant of each routine
 * timed on the planner's generated mesh, or with MODEL on the model's own
 * largest surface of each class it has (every call checked against
 * c_ref), a table of the timings with the winner and the static choice
 * marked, then the winners saved as this CPU's section of the wisdom file.
 *
 * Why a model: the generated character stands in for "a mesh of this
 * size", but the ranking of the silhouette and cap kernels moves with the
 * share of SilEdges on the silhouette and of triangles facing away
 * (docs/BENCHMARK.md): a terrain, a character and a CAD part of one size
 * can want different kernels.
 *
 * Exit status: 0 done; 1 a variant disagreed with c_ref (nothing saved);
 * 2 bad arguments; 3 the wisdom file could not be written (or read, when
 * it exists and is not a wisdom file), or the model could not be loaded
 * or prepared, or has no surface in the classes asked for.
 *
 * Copyright (C) 2026 the shadowvol authors. LGPL-2.1-or-later.
 */
#include "tune_cli.h"

#include <algorithm>
#include <cstdio>
#include <map>
#include <string>
#include <vector>

#include "cli_args.h"
#include "model_load.h"
#include "render_args.h"
#include "shadowvol_anim.h"
#include "shadowvol_mesh.h"
#include "shadowvol_plan.h"
#include "stencil_method.h"
#include "stencil_rule.h"

namespace svcli {

void tune_usage(FILE *out) {
    std::fprintf(
        out,
        "usage: shadowvol tune [MODEL.glb|MODEL.gltf] [--class N]... [--wisdom FILE] [--dry-run]\n"
        "                      [--stencil-size WxH] [--stencil-quick | --no-stencil]\n"
        "  Times every variant of every routine this CPU runs on a mesh of each size\n"
        "  class (0: under 4096 triangles, 1: under 65536, 2: under 524288, 3: larger),\n"
        "  checks every call against c_ref, and saves the fastest per routine and class\n"
        "  as this CPU's plans (sv_plan_for reads them; see docs/BENCHMARK.md).\n"
        "  Without MODEL a class is measured on the generated character at %d, %d,\n"
        "  %d and %d triangles; with MODEL on the model's largest surface in each\n"
        "  class it has (its own shape and silhouette share), and only those classes.\n"
        "  Then, per class, the deforming pass of skinned surfaces (skinning kernel,\n"
        "  planes variant, and one pass or two) on a generated skinned height field.\n"
        "  Last, the stencil pass's method (what render, scene and view use without\n"
        "  --stencil): auto, its threshold fitted as bench --stencil-rule fits it (every\n"
        "  light of the simple, knights and demo presets and of the render table's\n"
        "  models, bf against hier on 1 thread, 1 frame, the minimum of 2 runs).\n"
        "  --class N       measure class N only (repeatable; default: all four, or\n"
        "                  those of MODEL's surfaces)\n"
        "  --wisdom FILE   the wisdom file (default: $SV_WISDOM, else\n"
        "                  $XDG_CACHE_HOME/shadowvol/wisdom, else ~/.cache/shadowvol/wisdom)\n"
        "  --dry-run       measure and print, save nothing\n"
        "  --stencil-size WxH  the stencil measurement's frame (default 1280x1024)\n"
        "  --stencil-quick the stencil measurement on the simple preset and the bundled\n"
        "                  character only (a rough threshold: for checking the tuning\n"
        "                  itself, as the tests and the sanitizer build do)\n"
        "  --no-stencil    leave the stencil method out (the wisdom file keeps its line)\n"
        "exit status: 0 done, 1 a variant disagreed with c_ref, 2 bad arguments,\n"
        "3 the wisdom file could not be written, or MODEL could not be loaded or has\n"
        "no surface in the classes asked for\n",
        sv_size_class_triangles(0), sv_size_class_triangles(1), sv_size_class_triangles(2),
        sv_size_class_triangles(3));
}

namespace {

/* A prepared surface as the planner measures it (positions as Vec4, in
 * POSITIONS, which must outlive the view). */
sv_surface view_of(const sv::PreparedSurface &p, const std::vector<Vec4> &positions) {
    return sv_surface{p.planes.data(),   p.indices.data(), p.num_indices(),  p.sil_edges.data(),
                      p.num_sil_edges(), positions.data(), p.num_vertices(), sv::surface_bounds(p)};
}

/* The timings of class C, a line per routine and variant, the plan's
 * choice and the static choice marked. */
void print_class(int c, const std::string &measuredOn, const std::vector<sv_plan_timing> &t) {
    const sv_plan *p = sv_plan_for(sv_size_class_triangles(c), SV_PLAN_ESTIMATE);
    std::printf("\nclass %d (%s)\n", c, measuredOn.c_str());
    std::printf("%-22s %-14s %12s %10s  %s\n", "routine", "variant", "ticks", "vs static", "");
    for (int r = 0; r < SV_NUM_ROUTINES; r++) {
        const char *stat = sv_static_variant_name((sv_routine)r);
        double stat_ticks = 0;
        for (const sv_plan_timing &x : t) {
            if (x.routine == r && std::string(x.variant) == stat) stat_ticks = x.ticks;
        }
        for (const sv_plan_timing &x : t) {
            if (x.routine != r) continue;
            const bool chosen = std::string(x.variant) == p->variant[r];
            const bool is_static = std::string(x.variant) == stat;
            std::printf("%-22s %-14s %12.0f %9.2fx  %s%s\n", sv_routine_name((sv_routine)r),
                        x.variant, x.ticks, x.ticks > 0 ? stat_ticks / x.ticks : 0.0,
                        chosen ? "<- planned" : "",
                        is_static ? (chosen ? ", static" : "(static)") : "");
        }
    }
}

/* The deforming pass of class C (skinning, planes, one pass): every
 * kernel's ticks per triangle, the choices marked. Returns false when a
 * kernel disagreed with the C references. */
bool tune_deform(int c) {
    std::vector<sv::DeformTiming> t;
    try {
        t = sv::measure_deform_plan(c);
    } catch (const std::exception &e) {
        std::fprintf(stderr,
                     "shadowvol tune: class %d: %s; nothing saved (a bug: please report it)\n", c,
                     e.what());
        return false;
    }
    std::printf("\nclass %d, deforming surfaces (a skinned height field of about %d triangles; "
                "ticks per triangle)\n",
                c, sv_size_class_triangles(c));
    for (const sv::DeformTiming &x : t) {
        sv_deform_choice ch;
        const bool chosen = sv_deform_choice_for(c, x.routine, &ch) == 1 &&
                            (x.variant == ch.variant ||
                             (x.variant == "two_passes" && std::string(ch.variant) == "none"));
        std::printf("%-24s %-16s %10.2f  %s\n", sv_deform_routine_name(x.routine),
                    x.variant.c_str(), x.ticks_per_triangle, chosen ? "<- planned" : "");
    }
    return true;
}

/* The stencil pass's method (stencil_rule.h): auto at the fitted
 * threshold, recorded for sv_wisdom_save. Returns false when hier's
 * stencil differed from bf's on a light, or a scene did not load. */
bool tune_stencil(int width, int height, bool quick) {
    svbench::SeedCommand cmd;
    cmd.sharedModels = SV_SHARED_MODELS_DIR;
    svbench::StencilRuleOptions o;
    o.models = svbench::render_table_models(cmd);
    if (quick) { /* the smallest preset and the bundled character (the table's first) */
        o.presets = {"simple"};
        o.models.resize(1);
    }
    o.width = width, o.height = height;
    o.frames = 1, o.runs = 2;
    std::vector<svbench::StencilRuleSample> samples;
    try {
        samples = svbench::sample_stencil_rule(cmd, o);
    } catch (const std::exception &e) {
        std::fprintf(stderr, "shadowvol tune: the stencil measurement: %s; nothing saved\n",
                     e.what());
        return false;
    }
    for (const svbench::StencilRuleSample &s : samples) {
        if (!s.equal) {
            std::fprintf(stderr,
                         "shadowvol tune: %s, light %d: hier's stencil differs from bf's; "
                         "nothing saved (a bug: please report it)\n",
                         s.scene.c_str(), s.light);
            return false;
        }
    }
    const svbench::StencilRuleFit fit = svbench::fit_stencil_rule(samples);
    std::printf("\nstencil pass (%dx%d, %d lights, 1 thread; ms in all): bf %.2f, hier %.2f, "
                "each light's faster %.2f\n",
                width, height, fit.lights, fit.total_bf, fit.total_hier, fit.total_best);
    std::printf("stencil   auto, hier from %.1f pixels of area per piece: %.2f ms  <- planned\n",
                fit.threshold, fit.total_rule);
    sv_stencil_choice_set("auto", sv::render::kDefaultStencilTile, fit.threshold);
    return true;
}

} // namespace

int tune_main(int argc, char **argv) {
    std::vector<int> classes;
    std::string path, model;
    bool dry = false, stencil = true, stencil_quick = false;
    int stencil_width = 1280, stencil_height = 1024;
    try {
        ArgReader a(argc, argv);
        while (a.next()) {
            if (a.is_flag("--help") || a.is_flag("-h")) {
                tune_usage(stdout);
                return 0;
            } else if (a.is("--class")) {
                classes.push_back((int)a.integer(0, SV_NUM_SIZE_CLASSES - 1));
            } else if (a.is("--wisdom")) {
                path = a.value();
                if (path.empty()) usage_error("--wisdom needs a file name");
            } else if (a.is_flag("--dry-run")) {
                dry = true;
            } else if (a.is("--stencil-size")) {
                parse_frame_size(a.value(), stencil_width, stencil_height);
            } else if (a.is_flag("--no-stencil")) {
                stencil = false;
            } else if (a.is_flag("--stencil-quick")) {
                stencil_quick = true;
            } else if (!a.arg().empty() && a.arg()[0] != '-' && model.empty()) {
                model = a.arg();
            } else {
                usage_error("unknown argument '" + quoted(a.arg()) + "'");
            }
        }
    } catch (const UsageError &e) {
        std::fprintf(stderr, "shadowvol tune: %s\nTry 'shadowvol tune --help'.\n",
                     e.message.c_str());
        return 2;
    }
    /* With a model: per class, its largest surface there. */
    LoadedModel loaded;
    std::vector<const Surface *> on(SV_NUM_SIZE_CLASSES, nullptr);
    if (!model.empty()) {
        if (!load_model("tune", model, "", -1, &loaded)) return 3;
        for (const Surface &s : loaded.surfaces) {
            if (s.prepared.num_triangles() == 0) continue; /* nothing to time */
            const int c = sv_size_class(s.prepared.num_triangles());
            if (!on[(size_t)c] ||
                s.prepared.num_triangles() > on[(size_t)c]->prepared.num_triangles()) {
                on[(size_t)c] = &s;
            }
        }
        if (classes.empty()) {
            for (int c = 0; c < SV_NUM_SIZE_CLASSES; c++) {
                if (on[(size_t)c]) classes.push_back(c);
            }
        }
        for (int c : classes) {
            if (!on[(size_t)c]) {
                std::fprintf(stderr, "shadowvol tune: %s has no surface in class %d\n",
                             model.c_str(), c);
                return 3;
            }
        }
        if (classes.empty()) {
            std::fprintf(stderr, "shadowvol tune: %s has no triangles\n", model.c_str());
            return 3;
        }
    }
    if (classes.empty()) {
        for (int c = 0; c < SV_NUM_SIZE_CLASSES; c++) classes.push_back(c);
    }
    char buf[1024];
    if (path.empty()) path = sv_wisdom_default_path(buf, sizeof buf);
    if (path.empty() && !dry) {
        std::fprintf(stderr,
                     "shadowvol tune: no wisdom file (set SV_WISDOM or HOME, or give --wisdom)\n");
        return 3;
    }
    char key[256];
    std::printf("cpu       %s\n", sv_cpu_model_key(key, sizeof key));
    std::printf(
        "unit      median TSC ticks per call, 8 moving lights, each call checked against c_ref\n");
    for (int c : classes) {
        std::vector<sv_plan_timing> t(256);
        std::string measuredOn;
        int n;
        if (const Surface *s = on[(size_t)c]) {
            const std::vector<Vec4> positions = sv::positions_vec4(s->prepared);
            const sv_surface v = view_of(s->prepared, positions);
            n = sv_plan_measure_surface(&v, t.data(), (int)t.size());
            measuredOn = model + ", surface " + s->source.name + ": " +
                         std::to_string(s->prepared.num_triangles()) + " triangles";
        } else {
            n = sv_plan_measure(c, t.data(), (int)t.size());
            measuredOn = "the generated character, " + std::to_string(sv_size_class_triangles(c)) +
                         " triangles";
        }
        if (n == -2) { /* a prepared surface always meets the contracts */
            std::fprintf(stderr,
                         "shadowvol tune: class %d: the surface breaks a contract (a bug: "
                         "please report it)\n",
                         c);
            return 1;
        }
        if (n < 0) {
            std::fprintf(stderr,
                         "shadowvol tune: class %d: a variant's result differed from c_ref's; "
                         "nothing saved (a bug: please report it)\n",
                         c);
            return 1;
        }
        t.resize((size_t)std::min(n, (int)t.size()));
        print_class(c, measuredOn, t);
        if (!tune_deform(c)) return 1;
    }
    if (stencil && !tune_stencil(stencil_width, stencil_height, stencil_quick)) return 1;
    if (dry) {
        std::printf("\n--dry-run: nothing saved\n");
        return 0;
    }
    if (sv_wisdom_save(path.c_str()) != 0) {
        std::fprintf(stderr, "shadowvol tune: cannot write the wisdom file %s\n",
                     quoted(path).c_str());
        return 3;
    }
    std::printf("\nsaved     %s (this CPU's section; other CPUs' kept)\n", path.c_str());
    return 0;
}

} // namespace svcli
