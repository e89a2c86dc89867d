/*
 * Copyright (C) 2026 the shadowvol authors. LGPL-2.1-or-later.
 */
#include "synthetic_workload.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <string>
#include <utility>
#include <vector>

#include "rng.h"
#include "shadowvol_mesh.h"

namespace svbench {

namespace {

/* The paper's character (section 8): 1344 triangles, 2016 SilEdges. */
constexpr int kGridU = 24; /* quads around the ring */
constexpr int kGridV = 28; /* quads around the tube */
constexpr double kMajorRadius = 1.0;
constexpr double kMinorRadius = 0.4;
/* The paper's targets need a few thousand swaps per pattern; ratios that
 * cannot be reached stop here (about a second) with a message. */
constexpr long kMaxSwapsPerPattern = 20L * 1000 * 1000;

/* Cuts away 25% of the triangles: strips beyond x = +-1.1 and y = 1.1 and
 * -1.2, and the band of the tube's underside below z = -0.385. The top
 * plane z = 0.395 has only the ring of topmost vertices (z = 0.4) outside
 * it, so bit 5 is set on vertices but never culls a triangle on its own. No
 * vertex lies within 1e-3 of a plane (checked), so the bits do not depend
 * on the last bit of a libm sin or cos. */
constexpr LightBox kLightBox = {-1.1f, 1.1f, -1.2f, 1.1f, -0.385f, 0.395f};

[[noreturn]] void fail(const std::string &what) {
    throw std::logic_error("synthetic workload: " + what);
}

void require(bool ok, const std::string &what) {
    if (!ok) {
        fail(what);
    }
}

/* The torus, prepared like any model (welding changes nothing: every grid
 * position is distinct; triangle order and winding are kept). */
sv::PreparedSurface torus() {
    const int U = kGridU, V = kGridV;
    auto vert = [](int i, int j) { return (i % kGridU) * kGridV + (j % kGridV); };
    const double twoPi = 6.283185307179586476925286766559;

    std::vector<float> xyz((size_t)(U * V) * 3);
    for (int i = 0; i < U; i++) {
        for (int j = 0; j < V; j++) {
            const double th = twoPi * i / U, ph = twoPi * j / V;
            const double rr = kMajorRadius + kMinorRadius * std::cos(ph);
            float *p = &xyz[(size_t)vert(i, j) * 3];
            p[0] = (float)(rr * std::cos(th));
            p[1] = (float)(rr * std::sin(th));
            p[2] = (float)(kMinorRadius * std::sin(ph));
        }
    }
    /* Quad (i, j): a = (i, j), b = (i+1, j), c = (i+1, j+1), d = (i, j+1).
     * b - a runs along the ring, d - a around the tube, and their cross
     * product points out of the tube: (a, b, c) and (a, c, d) are counter-
     * clockwise seen from outside (checked below). */
    std::vector<uint32_t> idx;
    for (int i = 0; i < U; i++) {
        for (int j = 0; j < V; j++) {
            const int a = vert(i, j), b = vert(i + 1, j), c = vert(i + 1, j + 1),
                      d = vert(i, j + 1);
            for (int x : {a, b, c, a, c, d}) {
                idx.push_back((uint32_t)x);
            }
        }
    }
    sv::PreparedSurface s = sv::prepare_surface(xyz.data(), xyz.size() / 3, idx.data(), idx.size());
    require(s.num_triangles() == 1344 && s.num_sil_edges() == 2016 && s.num_vertices() == U * V &&
                s.report.dangling_sil_edges == 0 && s.report.manifold_edges == 2016,
            "expected a closed mesh of 1344 triangles and 2016 SilEdges");
    require(std::equal(idx.begin(), idx.end(), s.indices.begin(),
                       [](uint32_t a, int b) { return (int)a == b; }),
            "preparation changed the triangles");

    /* Outward winding: the normal of every triangle points away from the
     * tube's centre line. */
    for (int t = 0; t < s.num_triangles(); t++) {
        const Plane &pl = s.planes[(size_t)t];
        double centroid[3] = {0, 0, 0};
        for (int c = 0; c < 3; c++) {
            for (int k = 0; k < 3; k++) {
                centroid[k] += s.positions[3 * (size_t)s.indices[3 * (size_t)t + c] + k] / 3.0;
            }
        }
        const double len = std::hypot(centroid[0], centroid[1]);
        const double out = pl.a * (centroid[0] - centroid[0] / len * kMajorRadius) +
                           pl.b * (centroid[1] - centroid[1] / len * kMajorRadius) +
                           pl.c * centroid[2];
        require(out > 0, "triangle " + std::to_string(t) + " is not wound counter-clockwise");
    }
    return s;
}

/* Cull bits of the fixed box; every pattern gets a copy. */
void cull_bits(const Workload &w, Light &l) {
    l.box = kLightBox;
    light_box_planes(l.box, l.planes);
    l.cullBits = AlignedArray<uint8_t>((size_t)w.numVerts);
    l.cullInside = sv_calculate_cull_bits_c_ref(w.positions.data(), w.numVerts, &w.bounds, l.planes,
                                                l.cullBits.data()) != 0;
    require(!l.cullInside, "the light box holds the whole torus");
}

/* No vertex within 1e-3 of a box plane (see kLightBox). */
void check_box_margin(const Workload &w) {
    const LightBox &b = kLightBox;
    float nearest = 1e30f;
    for (int v = 0; v < w.numVerts; v++) {
        const Vec4 &p = w.positions[(size_t)v];
        for (float d :
             {p.x - b.xmin, p.x - b.xmax, p.y - b.ymin, p.y - b.ymax, p.z - b.zmin, p.z - b.zmax}) {
            nearest = std::min(nearest, std::fabs(d));
        }
    }
    require(nearest > 1e-3f, "a vertex lies on a light-box plane");
}

void make_pattern(const Workload &w, const std::vector<std::array<int, 3>> &triEdges,
                  int targetFacing, int targetSilhouette, Rng rng, Light &l) {
    const int n = w.numTriangles;
    l.facing = AlignedArray<uint8_t>((size_t)n + 1);
    uint8_t *f = l.facing.data();
    f[n] = 1;

    /* A random split: a Fisher-Yates shuffle, the first part facing. */
    std::vector<int> order((size_t)n);
    for (int t = 0; t < n; t++) {
        order[(size_t)t] = t;
    }
    for (int t = n - 1; t > 0; t--) {
        std::swap(order[(size_t)t], order[rng.below((uint32_t)t + 1)]);
    }
    std::vector<int> on(order.begin(), order.begin() + targetFacing);
    std::vector<int> off(order.begin() + targetFacing, order.end());
    for (int t : on) {
        f[t] = 1;
    }

    auto isSil = [&](int e) {
        const SilEdge &s = w.silEdges[(size_t)e];
        return f[s.p1] != f[s.p2];
    };
    int sil = 0;
    for (int e = 0; e < w.numSilEdges; e++) {
        sil += isSil(e);
    }
    /* Flips triangle t; returns how the silhouette count changed. */
    auto flip = [&](int t) {
        f[t] ^= 1;
        int d = 0;
        for (int e : triEdges[(size_t)t]) {
            d += isSil(e) ? 1 : -1;
        }
        return d;
    };

    long swaps = 0;
    while (sil != targetSilhouette) {
        if (on.empty() || off.empty() || ++swaps > kMaxSwapsPerPattern) {
            throw WorkloadError("synthetic workload: no facing pattern with " +
                                std::to_string(targetFacing) + " facing triangles and " +
                                std::to_string(targetSilhouette) +
                                " silhouette edges was found; choose other ratios");
        }
        const uint32_t ia = rng.below((uint32_t)on.size()), ib = rng.below((uint32_t)off.size());
        const int a = on[ia], b = off[ib];
        int d = flip(a);
        d += flip(b);
        if (std::abs(sil + d - targetSilhouette) > std::abs(sil - targetSilhouette)) {
            flip(b);
            flip(a);
        } else {
            sil += d;
            on[ia] = b;
            off[ib] = a;
        }
    }
}

} // namespace

Workload make_synthetic_workload(uint64_t seed, int numPatterns, double facingRatio,
                                 double silhouetteRatio) {
    require(numPatterns >= 1, "need at least one facing pattern");
    Workload w = workload_from_surface(
        torus(), "synthetic",
        "torus of " + std::to_string(kGridU) + " x " + std::to_string(kGridV) +
            " quads, facing patterns generated to the target ratios (not lit)");
    w.surfaces = 1;
    check_box_margin(w);

    std::vector<std::array<int, 3>> triEdges((size_t)w.numTriangles, {-1, -1, -1});
    for (int e = 0; e < w.numSilEdges; e++) {
        const SilEdge &s = w.silEdges[(size_t)e];
        for (int t : {s.p1, s.p2}) {
            auto &te = triEdges[(size_t)t];
            *std::find(te.begin(), te.end(), -1) = e;
        }
    }

    const int targetFacing = (int)std::lround(facingRatio * w.numTriangles);
    /* The silhouette count has the parity of the facing count (see the
     * header): take the count of that parity nearest the ratio. */
    const double want = silhouetteRatio * w.numSilEdges;
    int targetSil = (int)std::lround(want);
    if ((targetSil - targetFacing) % 2 != 0) {
        targetSil = std::fabs(targetSil + 1 - want) <= std::fabs(targetSil - 1 - want)
                        ? targetSil + 1
                        : targetSil - 1;
    }

    w.origin.lit = false;
    w.origin.targetFacing = facingRatio;
    w.origin.targetSilhouette = silhouetteRatio;
    w.origin.seed = seed;

    /* One generator per pattern, seeded from a master stream, so pattern k
     * is the same whatever the number of patterns asked for. */
    Rng master{seed};
    w.lights.resize((size_t)numPatterns);
    for (Light &l : w.lights) {
        make_pattern(w, triEdges, targetFacing, targetSil, Rng{master.next()}, l);
        cull_bits(w, l);
        count_light(w, l);
        require(l.numFacing == targetFacing && l.numSilhouette == targetSil,
                "facing pattern off its ratios");
    }
    w.numMoving = numPatterns;
    w.fixedLight = 0;
    w.origin.targetCulled = light_ratio(w, w.lights[0], Ratio::culled);
    return w;
}

} // namespace svbench
