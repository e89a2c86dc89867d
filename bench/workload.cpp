/*
 * Copyright (C) 2026 the shadowvol authors. LGPL-2.1-or-later.
 */
#include "workload.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <map>
#include <stdexcept>
#include <string>
#include <utility>

namespace svbench {

namespace {

/* The paper's character (section 8): 1344 triangles, 2016 SilEdges. */
constexpr int kGridU = 24; /* quads around the ring */
constexpr int kGridV = 28; /* quads around the tube */
constexpr double kMajorRadius = 1.0;
constexpr double kMinorRadius = 0.4;
constexpr double kFacingRatio = 0.5;     /* the paper's 50% */
constexpr double kSilhouetteRatio = 0.2; /* the paper's 20% */
constexpr long kMaxSwapsPerPattern = 50L * 1000 * 1000;

/* Cuts away 25% of the triangles: strips beyond x = +-1.1 and y = 1.1 and
 * -1.2, and the band of the tube's underside below z = -0.385. The top
 * plane z = 0.395 has only the ring of topmost vertices (z = 0.4) outside
 * it, so bit 5 is set on vertices but never culls a triangle on its own. No
 * vertex lies within 1e-3 of a plane (checked), so the bits do not depend
 * on the last bit of a libm sin or cos. */
constexpr LightBox kLightBox = {-1.1f, 1.1f, -1.2f, 1.1f, -0.385f, 0.395f};

[[noreturn]] void fail(const std::string &what) {
    throw std::logic_error("workload: " + what);
}

void require(bool ok, const std::string &what) {
    if (!ok) {
        fail(what);
    }
}

/* SplitMix64 (Steele, Lea, Flood 2014): small, seedable with any value,
 * the same sequence on every compiler. */
struct Rng {
    uint64_t s;
    uint64_t next() {
        uint64_t z = (s += 0x9e3779b97f4a7c15ull);
        z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ull;
        z = (z ^ (z >> 27)) * 0x94d049bb133111ebull;
        return z ^ (z >> 31);
    }
    /* Uniform in [0, n) for n < 2^32 (multiply-shift; the bias is below
     * 2^-32 and the same everywhere). */
    uint32_t below(uint32_t n) { return (uint32_t)(((next() >> 32) * n) >> 32); }
};

void build_mesh(Workload &w, std::vector<std::array<int, 3>> &triEdges) {
    const int U = kGridU, V = kGridV;
    w.gridU = U;
    w.gridV = V;
    w.numVerts = U * V;
    w.numTriangles = 2 * U * V;
    w.numIndices = 3 * w.numTriangles;

    auto vert = [](int i, int j) { return (i % kGridU) * kGridV + (j % kGridV); };
    const double twoPi = 6.283185307179586476925286766559;

    w.xyz.assign((size_t)w.numVerts * 3, 0.0f);
    for (int i = 0; i < U; i++) {
        for (int j = 0; j < V; j++) {
            double th = twoPi * i / U, ph = twoPi * j / V;
            double rr = kMajorRadius + kMinorRadius * std::cos(ph);
            float *p = &w.xyz[(size_t)vert(i, j) * 3];
            p[0] = (float)(rr * std::cos(th));
            p[1] = (float)(rr * std::sin(th));
            p[2] = (float)(kMinorRadius * std::sin(ph));
        }
    }

    /* Quad (i, j): a = (i, j), b = (i+1, j), c = (i+1, j+1), d = (i, j+1).
     * b - a runs along the ring, d - a around the tube, and their cross
     * product points out of the tube: (a, b, c) and (a, c, d) are counter-
     * clockwise seen from outside (checked below). */
    w.indices = AlignedArray<int>((size_t)w.numIndices);
    int k = 0;
    for (int i = 0; i < U; i++) {
        for (int j = 0; j < V; j++) {
            int a = vert(i, j), b = vert(i + 1, j), c = vert(i + 1, j + 1), d = vert(i, j + 1);
            const int t[6] = {a, b, c, a, c, d};
            for (int x : t) {
                w.indices[(size_t)k++] = x;
            }
        }
    }

    /* Outward winding: the normal of every triangle points away from the
     * tube's centre line. */
    for (int t = 0; t < w.numTriangles; t++) {
        const float *p[3];
        for (int c = 0; c < 3; c++) {
            p[c] = &w.xyz[(size_t)w.indices[(size_t)(3 * t + c)] * 3];
        }
        double e1[3], e2[3], n[3], centroid[3], axis[3];
        for (int c = 0; c < 3; c++) {
            e1[c] = (double)p[1][c] - p[0][c];
            e2[c] = (double)p[2][c] - p[0][c];
            centroid[c] = ((double)p[0][c] + p[1][c] + p[2][c]) / 3;
        }
        n[0] = e1[1] * e2[2] - e1[2] * e2[1];
        n[1] = e1[2] * e2[0] - e1[0] * e2[2];
        n[2] = e1[0] * e2[1] - e1[1] * e2[0];
        double len = std::sqrt(centroid[0] * centroid[0] + centroid[1] * centroid[1]);
        axis[0] = centroid[0] / len * kMajorRadius;
        axis[1] = centroid[1] / len * kMajorRadius;
        axis[2] = 0;
        double dot = 0;
        for (int c = 0; c < 3; c++) {
            dot += n[c] * (centroid[c] - axis[c]);
        }
        require(dot > 0, "triangle " + std::to_string(t) + " is not wound counter-clockwise");
    }

    /* SilEdges, the paper's convention: v1 -> v2 runs counter-clockwise in
     * p1 and clockwise in p2; vertex numbers doubled. The first triangle
     * that meets an edge is p1 (the edge runs v1 -> v2 in its winding), the
     * second must run it v2 -> v1 and becomes p2. */
    std::map<std::pair<int, int>, int> edgeOf;
    std::vector<SilEdge> edges;
    std::vector<int> users;
    triEdges.assign((size_t)w.numTriangles, {-1, -1, -1});
    for (int t = 0; t < w.numTriangles; t++) {
        for (int c = 0; c < 3; c++) {
            int from = w.indices[(size_t)(3 * t + c)];
            int to = w.indices[(size_t)(3 * t + (c + 1) % 3)];
            auto key = std::make_pair(std::min(from, to), std::max(from, to));
            auto it = edgeOf.find(key);
            if (it == edgeOf.end()) {
                edgeOf.emplace(key, (int)edges.size());
                triEdges[(size_t)t][(size_t)c] = (int)edges.size();
                edges.push_back(SilEdge{t, -1, 2 * from, 2 * to});
                users.push_back(1);
            } else {
                SilEdge &e = edges[(size_t)it->second];
                users[(size_t)it->second]++;
                require(users[(size_t)it->second] == 2,
                        "an edge is shared by more than two triangles");
                require(e.v1 == 2 * to && e.v2 == 2 * from,
                        "two triangles wind a shared edge the same way");
                e.p2 = t;
                triEdges[(size_t)t][(size_t)c] = it->second;
            }
        }
    }
    for (size_t e = 0; e < edges.size(); e++) {
        require(users[e] == 2, "an edge is used by one triangle only: the mesh is not closed");
    }
    require((int)edges.size() == 3 * w.numTriangles / 2 && edges.size() == 2016 &&
                w.numTriangles == 1344,
            "expected the paper's 1344 triangles and 2016 SilEdges, got " +
                std::to_string(w.numTriangles) + " and " + std::to_string(edges.size()));
    w.numSilEdges = (int)edges.size();
    w.silEdges = AlignedArray<SilEdge>(edges.size());
    std::copy(edges.begin(), edges.end(), w.silEdges.data());
}

void build_cull_bits(Workload &w) {
    const LightBox &b = kLightBox;
    w.box = b;
    w.cullBits = AlignedArray<uint8_t>((size_t)w.numVerts);
    float nearest = 1e30f;
    for (int v = 0; v < w.numVerts; v++) {
        const float x = w.xyz[(size_t)v * 3], y = w.xyz[(size_t)v * 3 + 1],
                    z = w.xyz[(size_t)v * 3 + 2];
        unsigned bits = (unsigned)(x < b.xmin) | (unsigned)(x > b.xmax) << 1 |
                        (unsigned)(y < b.ymin) << 2 | (unsigned)(y > b.ymax) << 3 |
                        (unsigned)(z < b.zmin) << 4 | (unsigned)(z > b.zmax) << 5;
        w.cullBits[(size_t)v] = (uint8_t)bits;
        for (float d : {x - b.xmin, x - b.xmax, y - b.ymin, y - b.ymax, z - b.zmin, z - b.zmax}) {
            nearest = std::min(nearest, std::fabs(d));
        }
    }
    require(nearest > 1e-3f, "a vertex lies on a light-box plane");
    w.numCulled = 0;
    for (int t = 0; t < w.numTriangles; t++) {
        const int *i = &w.indices[(size_t)(3 * t)];
        if (w.cullBits[(size_t)i[0]] & w.cullBits[(size_t)i[1]] & w.cullBits[(size_t)i[2]]) {
            w.numCulled++;
        }
    }
}

FacingPattern make_pattern(const Workload &w, const std::vector<std::array<int, 3>> &triEdges,
                           Rng rng) {
    const int n = w.numTriangles;
    FacingPattern p;
    p.facing = AlignedArray<uint8_t>((size_t)n + 1);
    uint8_t *f = p.facing.data();
    f[n] = 1;

    /* A random split: a Fisher-Yates shuffle, the first half facing. */
    std::vector<int> order((size_t)n);
    for (int t = 0; t < n; t++) {
        order[(size_t)t] = t;
    }
    for (int t = n - 1; t > 0; t--) {
        std::swap(order[(size_t)t], order[rng.below((uint32_t)t + 1)]);
    }
    std::vector<int> on(order.begin(), order.begin() + w.targetFacing);
    std::vector<int> off(order.begin() + w.targetFacing, order.end());
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

    const int target = w.targetSilhouette;
    while (sil != target) {
        require(++p.swaps <= kMaxSwapsPerPattern, "facing pattern did not converge");
        uint32_t ia = rng.below((uint32_t)on.size()), ib = rng.below((uint32_t)off.size());
        int a = on[ia], b = off[ib];
        int d = flip(a);
        d += flip(b);
        if (std::abs(sil + d - target) > std::abs(sil - target)) {
            flip(b);
            flip(a);
        } else {
            sil += d;
            on[ia] = b;
            off[ib] = a;
        }
    }

    p.numFacing = 0;
    for (int t = 0; t < n; t++) {
        require(f[t] <= 1, "facing byte out of range");
        p.numFacing += f[t];
    }
    int check = 0;
    for (int e = 0; e < w.numSilEdges; e++) {
        check += isSil(e);
    }
    require(p.numFacing == w.targetFacing && check == target && f[n] == 1,
            "facing pattern off its ratios");
    p.numSilhouette = check;
    return p;
}

} // namespace

Workload make_workload(uint64_t seed, int numPatterns) {
    require(numPatterns >= 1, "need at least one facing pattern");
    Workload w;
    w.seed = seed;
    std::vector<std::array<int, 3>> triEdges;
    build_mesh(w, triEdges);
    build_cull_bits(w);

    w.targetFacing = (int)std::lround(kFacingRatio * w.numTriangles);
    /* The silhouette count has the parity of the facing count (see
     * workload.h): take the count of that parity nearest the ratio. */
    const double want = kSilhouetteRatio * w.numSilEdges;
    int target = (int)std::lround(want);
    if ((target - w.targetFacing) % 2 != 0) {
        target =
            std::fabs(target + 1 - want) <= std::fabs(target - 1 - want) ? target + 1 : target - 1;
    }
    w.targetSilhouette = target;

    /* One generator per pattern, seeded from a master stream, so pattern k
     * is the same whatever the number of patterns asked for. */
    Rng master{seed};
    w.patterns.reserve((size_t)numPatterns);
    for (int k = 0; k < numPatterns; k++) {
        w.patterns.push_back(make_pattern(w, triEdges, Rng{master.next()}));
    }
    return w;
}

} // namespace svbench
