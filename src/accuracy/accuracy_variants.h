/*
 * The facing variants the accuracy study measures, by name, each with its
 * contract: which arithmetic it uses (and so which error bound holds), or
 * which other variant it must equal byte for byte. One table for the study,
 * the command line and the tests, so a variant added here is measured,
 * checked and tested everywhere.
 *
 * Copyright (C) 2026 the shadowvol authors. LGPL-2.1-or-later.
 */
#ifndef SV_ACCURACY_VARIANTS_H
#define SV_ACCURACY_VARIANTS_H

#include <string>
#include <vector>

#include "shadowvol_accuracy.h"
#include "shadowvol_backface.h"

namespace sv {
namespace acc {

/* eps_bias's band (sv_eps_bias_threshold) in the study: a distance of
 * kEpsBiasDistanceRadii model radii and an angle of kEpsBiasAngle radians,
 * about 30 times the reference's relative error bound (a few 1e-7), so the
 * band holds every rounding-uncertain triangle with room to spare. */
constexpr float kEpsBiasDistanceRadii = 1e-5f;
constexpr float kEpsBiasAngle = 1e-5f;

/* One surface with the data of every variant. */
struct SurfaceData {
    const PreparedSurface *surface = nullptr;
    AlignedVector<PlaneD> planes_d;
    AlignedVector<sv_plane16_block> planes16;
    /* seed 001's view culling layouts (shadowvol_backface.h), vertex
     * numbers dropped: the study measures the front-facing decision. */
    AlignedVector<sv_cull_triangle16> cull16;
    AlignedVector<sv_cull_block4> cull_blocks;
    /* eps_bias: the band's distance (model units) and the center it is
     * measured from; the model's, for a model of several surfaces. */
    float eps_distance = 0, eps_angle = kEpsBiasAngle;
    float center[3] = {0, 0, 0};
};
/* planes_d and planes16 of S; eps_distance = kEpsBiasDistanceRadii * radius. */
SurfaceData make_surface_data(const PreparedSurface &s, const float center[3], float radius);

enum class Contract {
    exact,   /* the exact facing, always */
    bounded, /* equal to exact wherever |D| > facing_error_bound(arithmetic) */
    biased,  /* equal to (D > tau') wherever |D - tau'| > the float_planes bound,
                  tau' = +-threshold (eps_bias) */
    same_as  /* byte for byte the variant `same_as` (a SIMD twin) */
};

/* Runs the variant on one surface: facing gets numTriangles + 1 bytes.
 * previous: the last frame's bytes for eps_bias's hysteresis (NULL:
 * stateless; the other variants ignore it). Returns the exact stage's
 * triangle count for the exact variants, else 0. */
using RunFn = int (*)(const SurfaceData &d, const Vec4 &light, const uint8_t *previous,
                      uint8_t *facing);

struct Variant {
    const char *name;
    unsigned isa; /* SV_ISA_* bits sv_cpu_isa() must have */
    Contract contract;
    FacingArithmetic arithmetic; /* bounded and biased: whose bound */
    const char *same_as;         /* Contract::same_as: the definition it equals */
    const char *family;          /* the plot's grouping: c_ref, fma, double, ... */
    const char *summary;         /* one line: what it computes */
    RunFn run;
};

/* Every variant compiled in, definitions before their SIMD twins; those the
 * CPU lacks are included (check isa against sv_cpu_isa()). */
const std::vector<Variant> &variants();
const Variant *variant_by_name(const std::string &name);
bool runnable(const Variant &v);

} // namespace acc
} // namespace sv

#endif
