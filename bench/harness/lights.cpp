/*
 * Copyright (C) 2026 the shadowvol authors. LGPL-2.1-or-later.
 */
#include "lights.h"

#include <algorithm>
#include <cmath>
#include <vector>

#include "rng.h"

namespace svbench {

namespace {

constexpr double kNearest = 1.0; /* light distances, in bounding-sphere radii */
constexpr double kFarthest = 16.0;
constexpr double kDirectionalBoxDistance = 4.0; /* radii, see lights.h */
constexpr int kBisections = 32;                 /* of the box's half size: 2^-32 of the range */
constexpr long kSearchWork = 1L << 25;          /* candidates x (triangles + edges) */
constexpr int kMinCandidates = 256;
constexpr int kMaxCandidates = 4096;

double bounding_radius(const Workload &w) {
    const Vec4 &e = w.bounds.extents;
    const double r = std::sqrt((double)e.x * e.x + (double)e.y * e.y + (double)e.z * e.z);
    return r > 0 ? r : 1.0; /* a mesh of one point: any scale will do */
}

/* A direction uniform on the sphere (rejection from the cube). */
void random_direction(Rng &rng, double d[3]) {
    for (;;) {
        double len2 = 0;
        for (int k = 0; k < 3; k++) {
            d[k] = 2 * rng.unit() - 1;
            len2 += d[k] * d[k];
        }
        if (len2 > 1e-6 && len2 <= 1) {
            const double len = std::sqrt(len2);
            for (int k = 0; k < 3; k++) {
                d[k] /= len;
            }
            return;
        }
    }
}

int count_facing_bytes(const uint8_t *f, int n) {
    int c = 0;
    for (int t = 0; t < n; t++) {
        c += f[t];
    }
    return c;
}

int count_silhouette(const Workload &w, const uint8_t *f) {
    int c = 0;
    for (int e = 0; e < w.numSilEdges; e++) {
        const SilEdge &s = w.silEdges[(size_t)e];
        c += f[s.p1] != f[s.p2];
    }
    return c;
}

/* The distance from the targets in the (facing, silhouette) plane. */
double score(const LightTargets &t, double facing, double silhouette) {
    return std::hypot(facing - t.facing, silhouette - t.silhouette);
}

/* The cube of half size H around C, its planes and cull bits in L; returns
 * the triangles it culls. */
int cull_with_box(const Workload &w, const double c[3], double h, Light &l) {
    l.box = LightBox{(float)(c[0] - h), (float)(c[0] + h), (float)(c[1] - h),
                     (float)(c[1] + h), (float)(c[2] - h), (float)(c[2] + h)};
    light_box_planes(l.box, l.planes);
    l.cullInside = sv_calculate_cull_bits_c_ref(w.positions.data(), w.numVerts, &w.bounds, l.planes,
                                                l.cullBits.data()) != 0;
    if (l.cullInside) { /* not written: nothing is outside */
        std::fill_n(l.cullBits.data(), w.numVerts, (uint8_t)0);
        return 0;
    }
    int culled = 0;
    const uint8_t *b = l.cullBits.data();
    for (int t = 0; t < w.numTriangles; t++) {
        const int *i = &w.indices[3 * (size_t)t];
        culled += (b[i[0]] & b[i[1]] & b[i[2]]) != 0;
    }
    return culled;
}

/* The light volume of L (see lights.h): the culled count never rises as
 * the cube grows, so bisection on the half size finds the step nearest the
 * target. */
void choose_light_box(const Workload &w, const LightTargets &t, double r, Light &l) {
    double c[3] = {l.position.x, l.position.y, l.position.z};
    if (l.position.w == 0) {
        const double len = std::sqrt(c[0] * c[0] + c[1] * c[1] + c[2] * c[2]);
        const double centre[3] = {w.bounds.center.x, w.bounds.center.y, w.bounds.center.z};
        for (int k = 0; k < 3; k++) {
            c[k] = centre[k] + c[k] / len * kDirectionalBoxDistance * r;
        }
    }
    /* Large enough to hold every vertex. */
    double hi = 0;
    const Bounds &b = w.bounds;
    const double lo3[3] = {(double)b.center.x - b.extents.x, (double)b.center.y - b.extents.y,
                           (double)b.center.z - b.extents.z};
    const double hi3[3] = {(double)b.center.x + b.extents.x, (double)b.center.y + b.extents.y,
                           (double)b.center.z + b.extents.z};
    for (int k = 0; k < 3; k++) {
        hi = std::max({hi, std::fabs(lo3[k] - c[k]), std::fabs(hi3[k] - c[k])});
    }
    hi = hi * 1.001 + 1e-6;
    double lo = 0;
    const int target = (int)std::lround(t.culled * w.numTriangles);
    l.cullBits = AlignedArray<uint8_t>((size_t)w.numVerts);
    for (int i = 0; i < kBisections; i++) {
        const double mid = 0.5 * (lo + hi);
        if (cull_with_box(w, c, mid, l) > target) {
            lo = mid;
        } else {
            hi = mid;
        }
    }
    const int atLo = cull_with_box(w, c, lo, l);
    const int atHi = cull_with_box(w, c, hi, l); /* leaves hi's box in l */
    if (std::abs(atLo - target) < std::abs(atHi - target)) {
        cull_with_box(w, c, lo, l);
    }
}

/* L's facing (App. A's reference C), light box and counts. */
void light_up(const Workload &w, const LightTargets &t, double r, Light &l) {
    l.facing = AlignedArray<uint8_t>((size_t)w.numTriangles + 1);
    sv_calculate_facing_c_ref(w.planes.data(), w.numTriangles, &l.position, l.facing.data());
    choose_light_box(w, t, r, l);
    count_light(w, l);
    l.score = score(t, light_ratio(w, l, Ratio::facing), light_ratio(w, l, Ratio::silhouette));
}

} // namespace

int light_candidates(int numTriangles, int numSilEdges) {
    const long work = std::max(1L, (long)numTriangles + numSilEdges);
    return (int)std::clamp(kSearchWork / work, (long)kMinCandidates, (long)kMaxCandidates);
}

void place_lights(Workload &w, const LightTargets &targets, int count, uint64_t seed,
                  const Vec4 *fixed) {
    const double r = bounding_radius(w);
    const double centre[3] = {w.bounds.center.x, w.bounds.center.y, w.bounds.center.z};
    const int candidates = std::max(count, light_candidates(w.numTriangles, w.numSilEdges));

    struct Candidate {
        Vec4 position;
        double score;
        int index;
    };
    std::vector<Candidate> all;
    all.reserve((size_t)candidates);
    AlignedArray<uint8_t> facing((size_t)w.numTriangles + 1);
    Rng rng{seed};
    for (int k = 0; k < candidates; k++) {
        double d[3];
        random_direction(rng, d);
        const double dist = r * kNearest * std::pow(kFarthest / kNearest, rng.unit());
        const Vec4 p{(float)(centre[0] + d[0] * dist), (float)(centre[1] + d[1] * dist),
                     (float)(centre[2] + d[2] * dist), 1.0f};
        sv_calculate_facing_c_ref(w.planes.data(), w.numTriangles, &p, facing.data());
        const double f = w.numTriangles
                             ? (double)count_facing_bytes(facing.data(), w.numTriangles) /
                                   w.numTriangles
                             : 0.0;
        const double s = w.numSilEdges ? (double)count_silhouette(w, facing.data()) / w.numSilEdges
                                       : 0.0;
        all.push_back(Candidate{p, score(targets, f, s), k});
    }
    std::partial_sort(all.begin(), all.begin() + count, all.end(),
                      [](const Candidate &a, const Candidate &b) {
                          return a.score < b.score || (a.score == b.score && a.index < b.index);
                      });

    w.lights.clear();
    w.lights.resize((size_t)count + (fixed ? 1 : 0));
    for (int i = 0; i < count; i++) {
        w.lights[(size_t)i].position = all[(size_t)i].position;
    }
    if (fixed) {
        w.lights.back().position = *fixed;
    }
    for (Light &l : w.lights) {
        light_up(w, targets, r, l);
    }
    w.numMoving = count;
    w.fixedLight = fixed ? count : 0;
    w.origin.lit = true;
    w.origin.targetFacing = targets.facing;
    w.origin.targetSilhouette = targets.silhouette;
    w.origin.targetCulled = targets.culled;
    w.origin.seed = seed;
    w.origin.candidates = candidates;
    w.origin.fixedGiven = fixed != nullptr;
}

} // namespace svbench
