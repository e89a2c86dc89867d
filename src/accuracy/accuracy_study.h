/*
 * The accuracy study behind `shadowvol accuracy`: for every facing variant
 * (accuracy_variants.h), every model and every light placement, how often
 * its facing byte differs from the exact one, how many silhouette edges
 * that moves, how often it flickers when the light jitters, and what it
 * costs in TSC ticks per triangle under a moving light. Every facing byte
 * computed is also checked against the variant's contract; a broken
 * contract is a failure of the run.
 *
 * Definitions (per model and placement, summed over its lights L and the
 * model's surfaces; exact = sv_calculate_facing_exact's bytes):
 *   misclassified      triangles t with facing_V[t] != exact[t]
 *   silhouette_exact   SilEdges e with exact[e.p1] != exact[e.p2]
 *   silhouette_changed SilEdges whose silhouette status differs between
 *                      V and exact (added or lost); its fraction is over
 *                      silhouette_exact
 *   uncertain          triangles with |D| <= B_V, the variant's error bound
 *                      (the band where the bound promises nothing)
 *   flicker            triangles whose byte changes when the light returns
 *                      from a jittered position L' (|L' - L| = 1e-6 of its
 *                      distance from the model's center, or 1e-6 rad for a
 *                      directional light) to L, in the frames L, L', L;
 *                      eps_bias with hysteresis from the second frame on
 *                      (previous = the frame before's bytes), the others
 *                      stateless. The exact variant's flicker is the
 *                      geometry's own: planes the light really crosses.
 *   ticks_per_triangle TSC ticks of one call over the model (every surface)
 *                      divided by its triangles: median (and min) over
 *                      timed regions rotating through the placement's
 *                      lights, the median of back-to-back empty regions
 *                      subtracted; several lights per region for models
 *                      too small for the TSC's resolution.
 *
 * Copyright (C) 2026 the shadowvol authors. LGPL-2.1-or-later.
 */
#ifndef SV_ACCURACY_STUDY_H
#define SV_ACCURACY_STUDY_H

#include <cstdint>
#include <functional>
#include <memory>
#include <stdexcept>
#include <string>
#include <vector>

#include "accuracy_variants.h"

namespace sv {
namespace acc {

/* One surface of a model, with what the study needs of each triangle. */
struct StudySurface {
    std::string name;
    PreparedSurface prepared;
    SurfaceData data; /* points into prepared: a StudySurface never moves */
    std::vector<TriangleErrorModel> error_models;
    std::vector<double> normal_length; /* |n| from the exact cross product */
};

struct StudyModel {
    std::string path, name; /* name: the file name */
    std::vector<std::unique_ptr<StudySurface>> surfaces;
    float center[3] = {0, 0, 0};
    float extents[3] = {0, 0, 0}; /* half sizes of the axis-aligned bounds */
    double radius = 0;            /* |extents| */
    int64_t triangles = 0, sil_edges = 0;
    /* FNV-1a of the prepared surfaces' positions and indices: the lights
     * are drawn from it and the seed, so a .gltf and a .glb of the same
     * geometry (or the same file under another name) give the same table. */
    uint64_t content_hash = 0;
};

class StudyError : public std::runtime_error {
public:
    using std::runtime_error::runtime_error;
};

/* Loads a glTF model (every mesh instance, sv::load_gltf) and prepares its
 * surfaces; throws StudyError naming the file and the problem. */
std::unique_ptr<StudyModel> load_study_model(const std::string &path);

/* The default models: the bundled character (models/character_1344.glb)
 * and, unless BUNDLED_ONLY, every .glb in SV_SHARED_MODELS_DIR sorted by
 * name. note says what was found; it starts with "NOTE:" when the shared
 * folder is missing or empty. */
struct DefaultModels {
    std::vector<std::string> paths;
    std::string shared_dir;
    bool shared_found = false;
    std::string note;
};
DefaultModels default_models(bool bundled_only);

/* The light placements, nearest first. */
struct Placement {
    const char *name; /* graze, hair, inside, 2r, ..., 1e6r, dir, axis */
    bool directional;
    double radii; /* point lights at a fixed distance: it, in radii */
    const char *summary;
};
const std::vector<Placement> &placements();
const Placement *placement_by_name(const std::string &name);

/* A placement's lights for one model, and their jittered twins. */
struct LightSet {
    const Placement *placement = nullptr;
    std::vector<Vec4> lights, jittered;
    double mean_distance_radii = 0; /* point lights: from the model's center */
    double height_radii = 0;        /* graze, hair: above the chosen triangle's plane */
};
/* hair: 2^-20 radii above the centroid of a random triangle, along its
 * double normal; graze: the same 2^-40 radii above (the float light ends
 * within about an ulp of the plane, on either side); inside: uniform in the bounds; Nr: N radii from the
 * center in a uniform random direction; dir: uniform random directions
 * (w = 0); axis: +-x, +-y, +-z (w = 0). COUNT lights (axis: 6), rounded to
 * float, drawn from SEED. */
LightSet make_lights(const StudyModel &m, const Placement &p, int count, uint64_t seed);

struct StudyOptions {
    int lights = 32;       /* per placement */
    int timing_rounds = 3; /* timed passes over the lights */
    bool timing = true;
    uint64_t seed = 1;
    std::vector<const Variant *> variants;             /* empty: every runnable one */
    std::vector<const Placement *> placements;         /* empty: all */
    std::function<void(const std::string &)> progress; /* may be empty */
};

struct StudyRow {
    const Variant *variant = nullptr;
    const StudyModel *model = nullptr;
    const Placement *placement = nullptr;
    double mean_distance_radii = 0, height_radii = 0;
    int lights = 0;
    int64_t triangles = 0; /* of the model: per light */
    int64_t tests = 0;     /* triangles x lights */
    int64_t misclassified = 0;
    int64_t silhouette_exact = 0, silhouette_changed = 0;
    int64_t uncertain = 0;
    int64_t flicker = 0;
    int64_t exact_stage = 0; /* exact variants: triangles the filter left */
    int64_t violations = 0;  /* contract broken (also listed in failures) */
    bool timed = false;
    double ticks_median = 0, ticks_min = 0; /* per triangle */
};

struct StudyResult {
    std::vector<StudyRow> rows;
    std::vector<std::string> failures; /* the first few broken contracts */
    int64_t failure_count = 0;
    std::string timer; /* the rdtsc fencing used */
    double tsc_hz = 0;
    int pinned_cpu = -1;
};

StudyResult run_study(const std::vector<const StudyModel *> &models, const StudyOptions &o);

} // namespace acc
} // namespace sv

#endif
