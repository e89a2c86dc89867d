/*
 * The automatic stencil method's rule, measured (stencil_rule.h).
 *
 * Like for like: per preset frame, the frame is drawn RUNS times with
 * auto forced to bf and RUNS times forced to hier (after one warm-up
 * frame of each), at the same thread count, each with a FrameScratch kept
 * through the frames as a sequence keeps it; per light the minimum of its
 * stencil pass's wall time is kept. Forcing auto (its threshold at
 * infinity or 0) rather than running bf and hier themselves times what
 * auto runs after it chose: the same shared set-up either way.
 *
 * Copyright (C) 2026 the shadowvol authors. LGPL-2.1-or-later.
 */
#include "stencil_rule.h"

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <limits>
#include <memory>
#include <system_error>

#include "frame.h"
#include "json_writer.h"
#include "scene_options.h"
#include "scene_presets.h"
#include "shadowvol_scene.h"

namespace svbench {
namespace {

using sv::render::Frame;
using sv::render::RenderOptions;
using sv::render::StencilMethod;

double rule_total(const std::vector<StencilRuleSample> &samples, double threshold) {
    double total = 0;
    for (const StencilRuleSample &s : samples)
        total += s.load.area_per_piece() >= threshold && s.load.pieces ? s.hier_ms : s.bf_ms;
    return total;
}

void print_fit(FILE *out, const StencilRuleFit &fit) {
    std::fprintf(out,
                 "\n%d lights. Total stencil ms: bf %.2f, hier %.2f, auto at %.1f pixels of area "
                 "per piece %.2f, each light's faster %.2f\n",
                 fit.lights, fit.total_bf, fit.total_hier, fit.threshold, fit.total_rule,
                 fit.total_best);
}

} // namespace

namespace {

/* [0] auto forced to bf, [1] forced to hier. */
struct ForcedPair {
    RenderOptions ro[2];
    sv::render::FrameScratch scratch[2];
    ForcedPair(const StencilRuleOptions &o, sv::render::ModeChoice mode) {
        for (int k = 0; k < 2; k++) {
            ro[k].width = o.width;
            ro[k].height = o.height;
            ro[k].threads = o.threads;
            ro[k].mode = mode;
            ro[k].stencil = StencilMethod::automatic;
            ro[k].stencil_tile = o.tile;
            ro[k].stencil_rule.hier_from_area_per_piece =
                k == 0 ? std::numeric_limits<double>::infinity() : 0.0;
            ro[k].scratch = &scratch[k];
        }
    }
};

/* Each light of SCENE, drawn RUNS times each way (the pair's scratch warm). */
void sample_frame(const std::string &name, int frame, const sv::Scene &scene, ForcedPair &pair,
                  int runs, std::vector<StencilRuleSample> &samples) {
    const std::size_t first = samples.size();
    std::vector<std::vector<uint8_t>> stencils[2];
    for (int k = 0; k < 2; k++) {
        for (int run = 0; run < runs; run++) {
            const Frame fr = sv::render::render_frame(scene, pair.ro[k]);
            if (k == 0 && run == 0) {
                for (std::size_t l = 0; l < fr.lights.size(); l++) {
                    StencilRuleSample s;
                    s.scene = name;
                    s.frame = frame;
                    s.light = (int)l;
                    s.load = fr.lights[l].stencil_load;
                    s.bf_ms = s.hier_ms = std::numeric_limits<double>::infinity();
                    samples.push_back(s);
                }
            }
            for (std::size_t l = 0; l < fr.lights.size(); l++) {
                StencilRuleSample &s = samples[first + l];
                double &ms = k == 0 ? s.bf_ms : s.hier_ms;
                ms = std::min(ms, 1e3 * fr.lights[l].seconds_stencil);
                if (run == 0) stencils[k].push_back(fr.lights[l].stencil);
            }
        }
    }
    for (std::size_t l = 0; l < stencils[0].size(); l++)
        samples[first + l].equal = stencils[0][l] == stencils[1][l];
}

/* The render table's scene of MODEL (tools/render_models.sh: the model on
 * the ground, the framing camera, a point, a spot and a directional light
 * placed automatically), as `shadowvol render` builds it. */
sv::Scene render_table_scene(const std::string &model, double aspect) {
    sv::Scene scene;
    try {
        sv::add_model(scene, model, {});
    } catch (const std::exception &e) {
        throw WorkloadError(model + ": " + e.what());
    }
    sv::add_ground(scene);
    scene.camera = sv::frame_camera(scene, aspect);
    if (scene.camera.near_distance == 0)
        scene.camera.near_distance = sv::fitting_near_distance(scene, scene.camera);
    for (sv::LightKind kind :
         {sv::LightKind::point, sv::LightKind::spot, sv::LightKind::directional}) {
        scene.lights.push_back(sv::auto_light(scene, kind));
    }
    for (sv::SceneLight &l : scene.lights) sv::default_intensity(scene, l);
    sv::validate_scene(scene);
    return scene;
}

std::string base_name(const std::string &path) {
    std::string n = path.substr(path.find_last_of('/') + 1);
    const std::size_t dot = n.rfind('.');
    return dot == std::string::npos ? n : n.substr(0, dot);
}

} // namespace

std::vector<StencilRuleSample> sample_stencil_rule(const SeedCommand &cmd,
                                                   const StencilRuleOptions &o) {
    std::vector<StencilRuleSample> samples;
    for (const std::string &name : o.presets) {
        std::unique_ptr<ScenePreset> preset = open_bench_preset(cmd, name,
                                                                (double)o.width / o.height);
        ForcedPair pair(o, sv::render::ModeChoice::automatic);
        for (int k = 0; k < 2; k++) (void)sv::render::render_frame(preset->at(0), pair.ro[k]);
        for (int f = 0; f < o.frames; f++)
            sample_frame(name, f, preset->at(f), pair, o.runs, samples);
    }
    for (const std::string &model : o.models) {
        const sv::Scene scene = render_table_scene(model, (double)o.width / o.height);
        for (sv::render::ModeChoice mode :
             {sv::render::ModeChoice::zpass, sv::render::ModeChoice::zfail}) {
            ForcedPair pair(o, mode);
            for (int k = 0; k < 2; k++) (void)sv::render::render_frame(scene, pair.ro[k]);
            sample_frame(base_name(model) +
                             (mode == sv::render::ModeChoice::zpass ? " zpass" : " zfail"),
                         0, scene, pair, o.runs, samples);
        }
    }
    return samples;
}

StencilRuleFit fit_stencil_rule(const std::vector<StencilRuleSample> &samples) {
    StencilRuleFit fit;
    fit.lights = (int)samples.size();
    std::vector<double> candidates = {0.0, std::numeric_limits<double>::infinity()};
    for (const StencilRuleSample &s : samples) {
        fit.total_bf += s.bf_ms;
        fit.total_hier += s.hier_ms;
        fit.total_best += std::min(s.bf_ms, s.hier_ms);
        if (s.load.pieces) candidates.push_back(s.load.area_per_piece());
    }
    std::sort(candidates.begin(), candidates.end());
    candidates.erase(std::unique(candidates.begin(), candidates.end()), candidates.end());
    std::size_t best = 0;
    double best_total = std::numeric_limits<double>::infinity();
    for (std::size_t i = 0; i < candidates.size(); i++) {
        const double total = rule_total(samples, candidates[i]);
        if (total < best_total) best_total = total, best = i;
    }
    /* Every threshold in (candidates[best - 1], candidates[best]] splits
     * the lights the same way: the middle of it (geometric: the counts
     * span decades). */
    double t = candidates[best];
    if (best > 0 && std::isfinite(t)) {
        const double below = candidates[best - 1];
        t = below > 0 ? std::sqrt(below * t) : t / 2;
    } else if (best > 0) {
        t = candidates[best - 1] * 2; /* past every light: all to bf */
    }
    fit.threshold = t;
    fit.total_rule = rule_total(samples, t);
    return fit;
}

std::vector<std::string> render_table_models(const SeedCommand &cmd) {
    std::vector<std::string> models = {std::string(SV_MODELS_DIR) + "/character_1344.glb"};
    std::vector<std::string> shared;
    std::error_code ec;
    for (const auto &e : std::filesystem::directory_iterator(cmd.sharedModels, ec)) {
        if (e.path().extension() == ".glb") shared.push_back(e.path().string());
    }
    std::sort(shared.begin(), shared.end());
    models.insert(models.end(), shared.begin(), shared.end());
    return models;
}

int run_stencil_rule_bench(const SeedCommand &cmd) {
    return run_seed_frame(cmd, "stencil-rule", [&](FILE *out, std::string *doc) {
        const SeedTimer timer = make_seed_timer(cmd.timer, cmd.quick);
        StencilRuleOptions o;
        if (!cmd.scenePreset.empty()) o.presets = {cmd.scenePreset};
        o.models = render_table_models(cmd);
        if (cmd.quick) { /* the bundled character alone of the models (the table's first) */
            o.frames = 1, o.runs = 2, o.width = 320, o.height = 256;
            o.models.resize(1);
        }
        if (cmd.sceneWidth) o.width = cmd.sceneWidth, o.height = cmd.sceneHeight;
        print_seed_header(out, "shadowvol bench --stencil-rule: bf or hier per light", timer, -1,
                          "each light's stencil pass drawn with auto forced to bf and to hier, "
                          "each way the minimum of the runs below after a warm-up frame; every "
                          "light's stencils compared (=bf)");
        std::fprintf(out,
                     "%dx%d, %d thread, tile %d, %d frame%s of %s and the render table's %zu "
                     "models in z-pass and z-fail, minimum of %d runs\n\n",
                     o.width, o.height, o.threads, o.tile, o.frames, o.frames == 1 ? "" : "s",
                     cmd.scenePreset.empty() ? "simple, knights, demo" : cmd.scenePreset.c_str(),
                     o.models.size(), o.runs);
        std::vector<StencilRuleSample> samples = sample_stencil_rule(cmd, o);
        const StencilRuleFit fit = fit_stencil_rule(samples);
        std::vector<std::size_t> order(samples.size());
        for (std::size_t i = 0; i < order.size(); i++) order[i] = i;
        std::stable_sort(order.begin(), order.end(), [&](std::size_t a, std::size_t b) {
            return samples[a].load.area_per_piece() < samples[b].load.area_per_piece();
        });
        std::fprintf(out, "%-22s %5s %5s %9s %12s %9s %6s %9s %9s %6s %5s\n", "scene", "frame",
                     "light", "pieces", "area px", "px/piece", "caps", "bf ms", "hier ms", "auto",
                     "=bf");
        int failed = 0;
        for (std::size_t i : order) {
            const StencilRuleSample &s = samples[i];
            const bool hier = s.load.pieces && s.load.area_per_piece() >= fit.threshold;
            failed += !s.equal;
            std::fprintf(out, "%-22s %5d %5d %9llu %12.0f %9.1f %5.0f%% %9.3f %9.3f %6s %5s\n",
                         s.scene.c_str(), s.frame, s.light, (unsigned long long)s.load.pieces,
                         s.load.area, s.load.area_per_piece(),
                         s.load.pieces ? 100.0 * (double)s.load.cap_pieces / (double)s.load.pieces
                                       : 0.0,
                         s.bf_ms, s.hier_ms, hier ? "hier" : "bf", s.equal ? "yes" : "NO");
        }
        print_fit(out, fit);
        JsonWriter j;
        j.begin_object();
        seed_json_header(j, "shadowvol-stencil-rule/1", timer);
        j.key("width"), j.value(o.width);
        j.key("height"), j.value(o.height);
        j.key("threads"), j.value(o.threads);
        j.key("tile"), j.value(o.tile);
        j.key("frames"), j.value(o.frames);
        j.key("runs"), j.value(o.runs);
        j.key("hier_from_area_per_piece"), j.value(fit.threshold);
        j.key("total_ms");
        j.begin_object(true);
        j.key("bf"), j.value(fit.total_bf);
        j.key("hier"), j.value(fit.total_hier);
        j.key("auto"), j.value(fit.total_rule);
        j.key("best"), j.value(fit.total_best);
        j.end_object();
        j.key("lights");
        j.begin_array();
        for (const StencilRuleSample &s : samples) {
            j.begin_object(true);
            j.key("scene"), j.value(s.scene);
            j.key("frame"), j.value(s.frame);
            j.key("light"), j.value(s.light);
            j.key("pieces"), j.value((unsigned long long)s.load.pieces);
            j.key("area"), j.value(s.load.area);
            j.key("rows"), j.value((unsigned long long)s.load.rows);
            j.key("cap_pieces"), j.value((unsigned long long)s.load.cap_pieces);
            j.key("bf_ms"), j.value(s.bf_ms);
            j.key("hier_ms"), j.value(s.hier_ms);
            j.key("equal"), j.value(s.equal);
            j.end_object();
        }
        j.end_array();
        j.end_object();
        *doc = j.str();
        return failed;
    });
}

} // namespace svbench
