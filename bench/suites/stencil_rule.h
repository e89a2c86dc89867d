/*
 * The automatic stencil method's rule, measured (issue 28): every light of
 * a spread of scenes (the bench's presets, and the render table's models
 * in both modes) drawn by bf and by hier through the automatic method
 * (its rule forced each way, so both time the same shared set-up), the
 * light's load counted (StencilLoad: pieces, their area), and the
 * threshold of area per piece (pixels) chosen that makes
 * the least total stencil time over the lights. `shadowvol bench
 * --stencil-rule` prints the lights and the fit; `shadowvol tune` fits it
 * for this CPU into the wisdom file.
 *
 * Copyright (C) 2026 the shadowvol authors. LGPL-2.1-or-later.
 */
#ifndef SV_BENCH_STENCIL_RULE_H
#define SV_BENCH_STENCIL_RULE_H

#include <cstdio>
#include <string>
#include <vector>

#include "seed_bench.h"
#include "stencil_method.h"

namespace svbench {

struct StencilRuleSample {
    std::string scene;
    int frame = 0, light = 0;
    sv::render::StencilLoad load;
    double bf_ms = 0, hier_ms = 0; /* the minimum over the runs */
    bool equal = true;             /* hier's stencil equals bf's */
};

struct StencilRuleFit {
    double threshold = sv::render::kDefaultHierFromAreaPerPiece; /* area per piece, pixels */
    /* Summed over the lights, ms: every light by bf, by hier, by the rule
     * at THRESHOLD, and each by the faster of the two (the best any rule
     * on any count could do). */
    double total_bf = 0, total_hier = 0, total_rule = 0, total_best = 0;
    int lights = 0;
};

struct StencilRuleOptions {
    std::vector<std::string> presets = {"simple", "knights", "demo"};
    /* glTF files drawn as the render table draws them (render_table_models). */
    std::vector<std::string> models;
    int width = 1280, height = 1024;
    int frames = 3, runs = 3;
    int threads = 1;
    int tile = sv::render::kDefaultStencilTile;
};

/* Every light of every preset's frames (throws WorkloadError for a
 * preset that does not load). */
std::vector<StencilRuleSample> sample_stencil_rule(const SeedCommand &cmd,
                                                   const StencilRuleOptions &o);
/* The render table's models (tools/render_models.sh): the bundled
 * character, then ../shared/models' glTF files (none where it is absent). */
std::vector<std::string> render_table_models(const SeedCommand &cmd);
/* The threshold with the least total time: the candidates are the
 * lights' own areas per piece (a light at the threshold takes hier), 0
 * and infinity; a tie keeps the smallest total of the chosen method's
 * distance from each light's best; the threshold returned is the midpoint
 * (geometric) between the chosen candidate and the next lower light, so
 * it is not on any measured light. */
StencilRuleFit fit_stencil_rule(const std::vector<StencilRuleSample> &samples);

/* `shadowvol bench --stencil-rule [--size WxH] [--preset P] [--quick]
 * [--json FILE]`. */
int run_stencil_rule_bench(const SeedCommand &cmd);

} // namespace svbench

#endif
