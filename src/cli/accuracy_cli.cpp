/*
 * `shadowvol accuracy`: the speed/accuracy trade of the facing decision
 * (DESIGN.md section 8; issue 7). Runs the study of
 * src/accuracy/accuracy_study.h over the models and prints, per model, the
 * fraction of triangles each variant classifies differently from the exact
 * predicate at each light placement, then a summary per variant; writes the
 * rows as JSON (schema shadowvol-accuracy/1) and the summary as an SVG plot
 * of accuracy against speed.
 *
 * Exit status: 0 done; 1 a variant broke its contract (the first cases are
 * printed); 2 bad arguments; 3 a model could not be loaded, or an output
 * file could not be written.
 *
 * Copyright (C) 2026 the shadowvol authors. LGPL-2.1-or-later.
 */
#include "accuracy_cli.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <map>
#include <memory>
#include <string>
#include <vector>

#include <unistd.h>

#include "svg_scatter.h"
#include "../accuracy/accuracy_study.h"
#include "cli_args.h"
#include "sysinfo.h"

namespace svcli {

namespace {

using sv::acc::Contract;
using sv::acc::StudyRow;

constexpr int kExitCheckFailed = 1;
constexpr int kExitUsage = 2;
constexpr int kExitBadModel = 3;

constexpr int kDefaultLights = 32;
constexpr int kQuickLights = 8;

/* A fraction for the table: "0" when nothing differs, else 3 digits. */
std::string fraction(int64_t num, int64_t den) {
    if (den <= 0) return "-";
    if (num == 0) return "0";
    char buf[32];
    std::snprintf(buf, sizeof buf, "%.2e", (double)num / (double)den);
    return buf;
}

/* JSON number for a fraction (0 when the denominator is 0: nothing to
 * differ). */
std::string json_fraction(int64_t num, int64_t den) {
    char buf[40];
    std::snprintf(buf, sizeof buf, "%.9g", den > 0 ? (double)num / (double)den : 0.0);
    return buf;
}

std::string json_number(double v) {
    if (!std::isfinite(v)) return "null";
    char buf[40];
    std::snprintf(buf, sizeof buf, "%.9g", v);
    return buf;
}

std::string contract_text(const sv::acc::Variant &v) {
    switch (v.contract) {
    case Contract::exact: return "exact";
    case Contract::bounded:
        return std::string("bounded: ") + sv::facing_arithmetic_name(v.arithmetic);
    case Contract::biased: return "biased: threshold +- float_planes bound";
    case Contract::same_as: return std::string("same bytes as ") + v.same_as;
    }
    return "?";
}

/* Sums over rows (one variant). */
struct Totals {
    int64_t tests = 0, mis = 0, sil = 0, sil_changed = 0, uncertain = 0, flicker = 0,
            exact_stage = 0, violations = 0;
    double ticks_weighted = 0, timed_triangles = 0;
    void add(const StudyRow &r) {
        tests += r.tests;
        mis += r.misclassified;
        sil += r.silhouette_exact;
        sil_changed += r.silhouette_changed;
        uncertain += r.uncertain;
        flicker += r.flicker;
        exact_stage += r.exact_stage;
        violations += r.violations;
        if (r.timed) {
            ticks_weighted += r.ticks_median * (double)r.triangles;
            timed_triangles += (double)r.triangles;
        }
    }
    double ticks() const { return timed_triangles > 0 ? ticks_weighted / timed_triangles : 0; }
};

std::string ticks_text(const Totals &t) {
    if (t.timed_triangles <= 0) return "-";
    char buf[32];
    std::snprintf(buf, sizeof buf, "%.2f", t.ticks());
    return buf;
}

bool write_file(const std::string &path, const std::string &text) {
    FILE *f = path == "-" ? stdout : std::fopen(path.c_str(), "w");
    if (!f) return false;
    const bool ok = std::fwrite(text.data(), 1, text.size(), f) == text.size();
    if (f == stdout) return ok && std::fflush(f) == 0;
    return std::fclose(f) == 0 && ok;
}

} // namespace

void accuracy_usage(FILE *out) {
    std::fprintf(
        out,
        "usage: shadowvol accuracy [--model FILE]... [--quick] [--json FILE] [--plot FILE.svg]\n"
        "                          [--lights N] [--seed S] [--variant NAME]...\n"
        "                          [--placement NAME]... [--no-timing]\n"
        "\n"
        "Speed against accuracy of the facing decision (appendix A: plane . light > 0).\n"
        "For every facing variant, model and light placement: the fraction of triangles\n"
        "whose facing byte differs from the exact one (an exact orientation predicate on\n"
        "the welded float positions), the fraction of silhouette edges that changes with\n"
        "it, how often bytes flicker when the light jitters by 1e-6 of its distance, and\n"
        "TSC ticks per triangle under a moving light (rdtsc as in 'shadowvol bench').\n"
        "Every byte is also checked against its variant's contract: SIMD twins equal to\n"
        "their definition, inexact variants equal to the exact facing wherever the\n"
        "light's distance from the plane exceeds their error bound, exact equal to exact.\n"
        "\n"
        "variants:\n");
    for (const sv::acc::Variant &v : sv::acc::variants()) {
        std::fprintf(out, "  %-22s %s\n", v.name, v.summary);
    }
    std::fprintf(out, "light placements (point lights w = 1, directional w = 0):\n");
    for (const sv::acc::Placement &p : sv::acc::placements()) {
        std::fprintf(out, "  %-22s %s\n", p.name, p.summary);
    }
    std::fprintf(
        out,
        "\n"
        "options:\n"
        "  --model FILE      a glTF model (repeatable); default: models/character_1344.glb\n"
        "                    and every .glb in the shared models folder\n"
        "                    (%s)\n"
        "  --quick           the bundled character only (unless --model), %d lights per\n"
        "                    placement, one timed pass: a few seconds\n"
        "  --json FILE       also write the rows as JSON (schema shadowvol-accuracy/1;\n"
        "                    FILE - is stdout, and the tables then go to stderr)\n"
        "  --plot FILE.svg   also write accuracy against speed as an SVG plot\n"
        "  --lights N        lights per placement (default %d; axis always has 6)\n"
        "  --seed S          seed of the lights (default 1)\n"
        "  --variant NAME    only this variant (repeatable)\n"
        "  --placement NAME  only this light placement (repeatable)\n"
        "  --no-timing       skip the timing (accuracy and contracts only)\n"
        "\n"
        "Progress goes to stderr on a terminal. Exit status: 0 done, 1 a variant broke\n"
        "its contract, 2 bad arguments, 3 a model could not be loaded or a file written.\n",
        sv::acc::default_models(false).shared_dir.c_str(), kQuickLights, kDefaultLights);
}

int accuracy_main(int argc, char **argv) {
    std::vector<std::string> model_args;
    std::string json_path, plot_path;
    bool quick = false, timing = true;
    int lights = 0;
    uint64_t seed = 1;
    sv::acc::StudyOptions opt;
    try {
        ArgReader a(argc, argv);
        while (a.next()) {
            if (a.is_flag("-h") || a.is_flag("--help")) {
                accuracy_usage(stdout);
                return 0;
            } else if (a.is("--model")) {
                model_args.push_back(a.value());
            } else if (a.is_flag("--quick")) {
                quick = true;
            } else if (a.is_flag("--no-timing")) {
                timing = false;
            } else if (a.is("--json")) {
                json_path = a.value();
            } else if (a.is("--plot")) {
                plot_path = a.value();
            } else if (a.is("--lights")) {
                lights = (int)a.integer(1, 100000);
            } else if (a.is("--seed")) {
                seed = a.seed();
            } else if (a.is("--variant")) {
                const std::string v = a.value();
                const sv::acc::Variant *var = sv::acc::variant_by_name(v);
                if (!var) {
                    std::string names;
                    for (const sv::acc::Variant &x : sv::acc::variants()) {
                        names += (names.empty() ? "" : ", ") + std::string(x.name);
                    }
                    usage_error("unknown variant '" + quoted(v) + "' (variants: " + names + ")");
                }
                if (!sv::acc::runnable(*var)) {
                    usage_error("variant '" + quoted(v) +
                                "' needs an instruction set this CPU lacks");
                }
                if (std::find(opt.variants.begin(), opt.variants.end(), var) ==
                    opt.variants.end()) {
                    opt.variants.push_back(var);
                }
            } else if (a.is("--placement")) {
                const std::string p = a.value();
                const sv::acc::Placement *pl = sv::acc::placement_by_name(p);
                if (!pl) {
                    std::string names;
                    for (const sv::acc::Placement &x : sv::acc::placements()) {
                        names += (names.empty() ? "" : ", ") + std::string(x.name);
                    }
                    usage_error("unknown placement '" + quoted(p) + "' (placements: " + names +
                                ")");
                }
                if (std::find(opt.placements.begin(), opt.placements.end(), pl) ==
                    opt.placements.end()) {
                    opt.placements.push_back(pl);
                }
            } else if (a.arg().rfind('-', 0) == 0) {
                usage_error("unknown option '" + quoted(a.arg()) + "'");
            } else {
                usage_error("unexpected argument '" + quoted(a.arg()) +
                            "' (models go after --model)");
            }
        }
    } catch (const UsageError &e) {
        std::fprintf(stderr, "shadowvol accuracy: %s\nTry 'shadowvol accuracy --help'.\n",
                     e.message.c_str());
        return kExitUsage;
    }
    opt.lights = lights ? lights : quick ? kQuickLights : kDefaultLights;
    opt.timing_rounds = quick ? 1 : 3;
    opt.timing = timing;
    opt.seed = seed;

    FILE *out = json_path == "-" ? stderr : stdout;
    const auto t_start = std::chrono::steady_clock::now();
    const sv::acc::DefaultModels defaults = sv::acc::default_models(quick);
    std::vector<std::string> paths = model_args.empty() ? defaults.paths : model_args;

    /* Load every model first: a bad one stops the run before any timing. */
    std::vector<std::unique_ptr<sv::acc::StudyModel>> models;
    for (const std::string &p : paths) {
        try {
            models.push_back(sv::acc::load_study_model(p));
        } catch (const sv::acc::StudyError &e) {
            std::fprintf(stderr, "shadowvol accuracy: %s\n", e.what());
            return kExitBadModel;
        } catch (const std::bad_alloc &) {
            std::fprintf(stderr, "shadowvol accuracy: %s: out of memory\n", p.c_str());
            return kExitBadModel;
        }
    }
    std::vector<const sv::acc::StudyModel *> mptr;
    mptr.reserve(models.size());
    for (const auto &m : models) mptr.push_back(m.get());

    const bool progress = isatty(2) != 0;
    if (progress) {
        opt.progress = [](const std::string &what) {
            std::fprintf(stderr, "\r\033[Kaccuracy: %s", what.c_str());
            std::fflush(stderr);
        };
    }
    const sv::acc::StudyResult res = sv::acc::run_study(mptr, opt);
    if (progress) std::fprintf(stderr, "\r\033[K");
    const double seconds =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - t_start).count();

    /* ---- Header ---- */
    std::fprintf(out, "shadowvol accuracy: the facing decision (plane . light > 0), speed "
                      "against accuracy\n");
    std::fprintf(out, "CPU: %s\n", svbench::cpu_model().c_str());
    if (timing) {
        std::fprintf(out,
                     "timer: %s, TSC %.3f GHz, %s; ticks/tri: median over timed regions "
                     "(moving light), per triangle\n",
                     res.timer.c_str(), res.tsc_hz / 1e9,
                     res.pinned_cpu >= 0
                         ? ("pinned to CPU " + std::to_string(res.pinned_cpu)).c_str()
                         : "not pinned");
    }
    if (model_args.empty()) std::fprintf(out, "models: %s\n", defaults.note.c_str());
    std::fprintf(out,
                 "lights: %d per placement (axis: 6), seed %llu; eps_bias band: %g radius + %g "
                 "rad\n",
                 opt.lights, (unsigned long long)seed, (double)sv::acc::kEpsBiasDistanceRadii,
                 (double)sv::acc::kEpsBiasAngle);

    std::vector<const sv::acc::Variant *> vars;
    std::vector<const sv::acc::Placement *> places;
    for (const StudyRow &r : res.rows) {
        if (std::find(vars.begin(), vars.end(), r.variant) == vars.end()) vars.push_back(r.variant);
        if (std::find(places.begin(), places.end(), r.placement) == places.end()) {
            places.push_back(r.placement);
        }
    }

    /* ---- Per model: misclassified fraction by placement ---- */
    for (const auto &m : models) {
        std::fprintf(out,
                     "\n%s: %zu surface%s, %lld triangles, %lld SilEdges, radius %.4g\n"
                     "fraction of triangles whose facing differs from exact, by light placement\n",
                     m->name.c_str(), m->surfaces.size(), m->surfaces.size() == 1 ? "" : "s",
                     (long long)m->triangles, (long long)m->sil_edges, m->radius);
        std::fprintf(out, "%-22s %9s", "variant", "ticks/tri");
        for (const sv::acc::Placement *p : places) std::fprintf(out, " %8s", p->name);
        std::fprintf(out, " %9s %9s\n", "sil.chg", "flicker");
        for (const sv::acc::Variant *v : vars) {
            Totals t;
            std::map<const sv::acc::Placement *, const StudyRow *> by;
            for (const StudyRow &r : res.rows) {
                if (r.model == m.get() && r.variant == v) {
                    t.add(r);
                    by[r.placement] = &r;
                }
            }
            std::fprintf(out, "%-22s %9s", v->name, ticks_text(t).c_str());
            for (const sv::acc::Placement *p : places) {
                const StudyRow *r = by[p];
                std::fprintf(out, " %8s", r ? fraction(r->misclassified, r->tests).c_str() : "-");
            }
            std::fprintf(out, " %9s %9s\n", fraction(t.sil_changed, t.sil).c_str(),
                         fraction(t.flicker, t.tests).c_str());
        }
    }

    /* ---- Summary ---- */
    std::fprintf(out,
                 "\nall models and placements (ticks/tri: triangle-weighted mean; fractions of "
                 "all triangle tests;\nuncertain: |D| within the variant's error bound, where "
                 "its contract promises nothing)\n");
    std::fprintf(out, "%-22s %9s %13s %11s %10s %10s %10s  %s\n", "variant", "ticks/tri",
                 "misclassified", "sil.changed", "uncertain", "flicker", "exact-stg", "contract");
    std::map<const sv::acc::Variant *, Totals> totals;
    for (const StudyRow &r : res.rows) totals[r.variant].add(r);
    for (const sv::acc::Variant *v : vars) {
        const Totals &t = totals[v];
        const bool ex = v->contract == Contract::exact ||
                        (v->contract == Contract::same_as &&
                         sv::acc::variant_by_name(v->same_as)->contract == Contract::exact);
        std::fprintf(out, "%-22s %9s %13s %11s %10s %10s %10s  %s\n", v->name,
                     ticks_text(t).c_str(), fraction(t.mis, t.tests).c_str(),
                     fraction(t.sil_changed, t.sil).c_str(), fraction(t.uncertain, t.tests).c_str(),
                     fraction(t.flicker, t.tests).c_str(),
                     ex ? fraction(t.exact_stage, t.tests).c_str() : "-",
                     contract_text(*v).c_str());
    }
    const bool passed = res.failure_count == 0;
    if (passed) {
        std::fprintf(out, "\nPASSED: every facing byte within its variant's contract (%.1f s).\n",
                     seconds);
    } else {
        std::fprintf(out,
                     "\nFAILED: %lld facing bytes broke their variant's contract; the first:\n",
                     (long long)res.failure_count);
        for (const std::string &f : res.failures) std::fprintf(out, "  %s\n", f.c_str());
        if (out != stderr) {
            std::fprintf(stderr,
                         "shadowvol accuracy: %lld facing bytes broke their variant's "
                         "contract (first: %s)\n",
                         (long long)res.failure_count, res.failures[0].c_str());
        }
    }

    /* ---- Plot ---- */
    if (!plot_path.empty()) {
        std::vector<svplot::ScatterPoint> pts;
        for (const sv::acc::Variant *v : vars) {
            const Totals &t = totals[v];
            pts.push_back({v->name, v->family, t.ticks(),
                           t.tests > 0 ? (double)t.mis / (double)t.tests : 0.0});
        }
        svplot::ScatterText text;
        text.title = "Facing decision: accuracy against speed";
        text.subtitle = std::to_string(models.size()) + " model(s), " +
                        std::to_string(places.size()) + " light placements, " +
                        std::to_string(opt.lights) + " lights each; " + svbench::cpu_model();
        text.x_label = "TSC ticks per triangle (moving light; lower is faster)";
        text.y_label = "fraction of facing bytes that differ from exact";
        text.zero_label = "0";
        text.footnote = "Points on the 0 row agree with the exact predicate on every test.";
        if (!timing) text.footnote += " Timing was off (--no-timing): no speeds.";
        if (!write_file(plot_path, svplot::render_loglog_scatter(pts, text))) {
            std::fprintf(stderr, "shadowvol accuracy: cannot write %s\n", plot_path.c_str());
            return kExitBadModel;
        }
    }

    /* ---- JSON ---- */
    if (!json_path.empty()) {
        std::string j = "{\"schema\": \"shadowvol-accuracy/1\",\n";
        j += " \"cpu\": " + json_string(svbench::cpu_model()) +
             ", \"timer\": " + (timing ? json_string(res.timer) : std::string("null")) +
             ", \"tsc_hz\": " + (timing ? json_number(res.tsc_hz) : "null") +
             ", \"quick\": " + (quick ? "true" : "false") +
             ", \"lights_per_placement\": " + std::to_string(opt.lights) +
             ", \"seed\": " + std::to_string(seed) + ",\n";
        j += " \"shared_models_dir\": " + json_string(defaults.shared_dir) +
             ", \"shared_models_found\": " + (defaults.shared_found ? "true" : "false") + ",\n";
        j += " \"eps_bias\": {\"distance_radii\": " +
             json_number((double)sv::acc::kEpsBiasDistanceRadii) +
             ", \"angle_rad\": " + json_number((double)sv::acc::kEpsBiasAngle) + "},\n";
        j += " \"variants\": [";
        for (std::size_t i = 0; i < vars.size(); i++) {
            const sv::acc::Variant *v = vars[i];
            j += std::string(i ? ",\n  " : "\n  ") + "{\"name\": " + json_string(v->name) +
                 ", \"family\": " + json_string(v->family) +
                 ", \"contract\": " + json_string(contract_text(*v)) +
                 ", \"same_as\": " + (v->same_as ? json_string(v->same_as) : "null") +
                 ", \"summary\": " + json_string(v->summary) + "}";
        }
        j += "],\n \"models\": [";
        for (std::size_t i = 0; i < models.size(); i++) {
            const sv::acc::StudyModel &m = *models[i];
            j += std::string(i ? ",\n  " : "\n  ") + "{\"name\": " + json_string(m.name) +
                 ", \"path\": " + json_string(m.path) +
                 ", \"surfaces\": " + std::to_string(m.surfaces.size()) +
                 ", \"triangles\": " + std::to_string(m.triangles) +
                 ", \"sil_edges\": " + std::to_string(m.sil_edges) +
                 ", \"radius\": " + json_number(m.radius) + "}";
        }
        j += "],\n \"results\": [";
        for (std::size_t i = 0; i < res.rows.size(); i++) {
            const StudyRow &r = res.rows[i];
            const bool ex = r.variant->contract == Contract::exact ||
                            (r.variant->contract == Contract::same_as &&
                             sv::acc::variant_by_name(r.variant->same_as)->contract ==
                                 Contract::exact);
            const bool dir = r.placement->directional;
            const double dist = dir                      ? NAN
                                : r.placement->radii > 0 ? r.placement->radii
                                                         : r.mean_distance_radii;
            j += std::string(i ? ",\n  " : "\n  ") +
                 "{\"variant\": " + json_string(r.variant->name) +
                 ", \"model\": " + json_string(r.model->name) +
                 ", \"light\": {\"kind\": " + (dir ? "\"directional\"" : "\"point\"") +
                 ", \"placement\": " + json_string(r.placement->name) +
                 ", \"distance_radii\": " + json_number(dist) + ", \"height_radii\": " +
                 (r.height_radii > 0 ? json_number(r.height_radii) : "null") +
                 ", \"count\": " + std::to_string(r.lights) + "}" +
                 ", \"triangles\": " + std::to_string(r.triangles) +
                 ", \"tests\": " + std::to_string(r.tests) +
                 ", \"misclassified\": " + std::to_string(r.misclassified) +
                 ", \"misclassified_fraction\": " + json_fraction(r.misclassified, r.tests) +
                 ", \"silhouette_edges\": " + std::to_string(r.silhouette_exact) +
                 ", \"silhouette_changed\": " + std::to_string(r.silhouette_changed) +
                 ", \"silhouette_changed_fraction\": " +
                 json_fraction(r.silhouette_changed, r.silhouette_exact) +
                 ", \"uncertain_fraction\": " + json_fraction(r.uncertain, r.tests) +
                 ", \"flicker_fraction\": " + json_fraction(r.flicker, r.tests) +
                 ", \"exact_stage_fraction\": " +
                 (ex ? json_fraction(r.exact_stage, r.tests) : std::string("null")) +
                 ", \"ticks_per_triangle\": " + (r.timed ? json_number(r.ticks_median) : "null") +
                 ", \"ticks_per_triangle_min\": " + (r.timed ? json_number(r.ticks_min) : "null") +
                 ", \"contract_violations\": " + std::to_string(r.violations) + "}";
        }
        j += "],\n \"passed\": " + std::string(passed ? "true" : "false") + ", \"failures\": [";
        for (std::size_t i = 0; i < res.failures.size(); i++) {
            j += (i ? ", " : "") + json_string(res.failures[i]);
        }
        j += "]}\n";
        if (!write_file(json_path, j)) {
            std::fprintf(stderr, "shadowvol accuracy: cannot write %s\n", json_path.c_str());
            return kExitBadModel;
        }
    }
    return passed ? 0 : kExitCheckFailed;
}

} // namespace svcli
