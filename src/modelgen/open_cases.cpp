// The generated open meshes of open_cases.h.
//
// Copyright (C) 2026 the shadowvol authors. LGPL-2.1-or-later.
#include "open_cases.h"

#include <cmath>

namespace svgen {

/* An axis-aligned box from LO to HI, outward faces, optionally without
 * its top (+y) face. */
void add_box(Soup &s, double x0, double y0, double z0, double x1, double y1, double z1,
             bool with_top) {
    uint32_t v[8];
    for (int i = 0; i < 8; i++) v[i] = s.vertex(i & 1 ? x1 : x0, i & 2 ? y1 : y0, i & 4 ? z1 : z0);
    s.quad(v[0], v[1], v[5], v[4]); /* bottom, -y */
    if (with_top) s.quad(v[2], v[6], v[7], v[3]);
    s.quad(v[0], v[4], v[6], v[2]); /* -x */
    s.quad(v[1], v[3], v[7], v[5]); /* +x */
    s.quad(v[0], v[2], v[3], v[1]); /* -z */
    s.quad(v[4], v[5], v[7], v[6]); /* +z */
}

std::vector<Soup> open_cases() {
    std::vector<Soup> out;
    {
        Soup s{"one triangle"};
        s.tri(s.vertex(-0.5, 1, 0.5), s.vertex(0.5, 1, 0.5), s.vertex(0, 1, -0.5));
        out.push_back(s);
    }
    {
        /* A plane tilted towards the camera: lit from above on its front,
         * its shadow on the ground, the lights on either side of it. */
        Soup s{"tilted plane"};
        s.quad(s.vertex(-0.6, 0.7, 0.4), s.vertex(0.6, 0.7, 0.4), s.vertex(0.6, 1.3, -0.4),
               s.vertex(-0.6, 1.3, -0.4));
        out.push_back(s);
    }
    {
        /* Open at its bottom, upside down: the lit top casts nothing under
         * the paper's rule, and nothing dark lies under it. */
        Soup s{"open box"};
        add_box(s, -0.5, 0.5, -0.5, 0.5, 1.2, 0.5, true);
        s.idx.erase(s.idx.begin(), s.idx.begin() + 6); /* the bottom quad */
        out.push_back(s);
    }
    {
        /* Castle Game Engine's case: a cylinder open at one end (here its
         * bottom, so that the light from above meets the closed end). */
        Soup s{"cylinder open at one end"};
        constexpr int kSides = 16;
        const uint32_t centre = s.vertex(0, 1.4, 0);
        std::vector<uint32_t> lo, hi;
        for (int i = 0; i < kSides; i++) {
            const double a = 2 * M_PI * i / kSides;
            lo.push_back(s.vertex(0.5 * std::cos(a), 0.4, -0.5 * std::sin(a)));
            hi.push_back(s.vertex(0.5 * std::cos(a), 1.4, -0.5 * std::sin(a)));
        }
        for (int i = 0; i < kSides; i++) {
            const int j = (i + 1) % kSides;
            s.quad(lo[(std::size_t)i], lo[(std::size_t)j], hi[(std::size_t)j], hi[(std::size_t)i]);
            s.tri(centre, hi[(std::size_t)i], hi[(std::size_t)j]); /* top, +y */
        }
        out.push_back(s);
    }
    {
        Soup s{"two overlapping shells"};
        s.quad(s.vertex(-0.6, 0.8, 0.3), s.vertex(0.4, 0.8, 0.3), s.vertex(0.4, 0.8, -0.5),
               s.vertex(-0.6, 0.8, -0.5));
        s.quad(s.vertex(-0.3, 1.3, 0.5), s.vertex(0.7, 1.3, 0.5), s.vertex(0.7, 1.3, -0.3),
               s.vertex(-0.3, 1.3, -0.3));
        out.push_back(s);
    }
    for (int k : {3, 4}) {
        /* K fins around one edge along z at (0, 1). */
        Soup s{std::to_string(k) + " triangles on one edge"};
        const uint32_t a = s.vertex(0, 1, 0.5), b = s.vertex(0, 1, -0.5);
        for (int i = 0; i < k; i++) {
            const double ang = 0.3 + 2 * M_PI * i / k;
            s.tri(a, b, s.vertex(0.6 * std::cos(ang), 1 + 0.6 * std::sin(ang), 0));
        }
        out.push_back(s);
    }
    {
        /* Two triangles run their shared edge the same way: one faces up,
         * one down. */
        Soup s{"inconsistently wound edge"};
        const uint32_t a = s.vertex(-0.5, 1, 0.5), b = s.vertex(0.5, 1, -0.5);
        s.tri(a, s.vertex(0.5, 1, 0.5), b);
        s.tri(a, b, s.vertex(-0.5, 1.2, -0.5));
        out.push_back(s);
    }
    {
        /* A quad whose edge a-b carries a midpoint m, with the collinear
         * sliver (a, m, b) kept (zero plane) and the fan around m. */
        Soup s{"degenerate sliver"};
        const uint32_t a = s.vertex(-0.5, 1, 0.5), b = s.vertex(0.5, 1, 0.5),
                       c = s.vertex(0.5, 1, -0.5), d = s.vertex(-0.5, 1, -0.5),
                       m = s.vertex(0, 1, 0.5);
        s.tri(a, m, d), s.tri(m, b, c), s.tri(m, c, d), s.tri(a, m, b);
        out.push_back(s);
    }
    return out;
}

} // namespace svgen
