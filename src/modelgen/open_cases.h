// The generated open meshes of issue 27 (shadows right for any caster):
// one triangle, a tilted plane, an open box, a cylinder open at one end,
// two overlapping shells, three and four triangles on one edge, an edge two
// triangles run the same way, a degenerate sliver. The tests draw them on
// a ground under three lights (tests/support/open_cases.h), and
// `shadowvol bench --casters` times the general rule's builders on them.
//
// Copyright (C) 2026 the shadowvol authors. LGPL-2.1-or-later.
#pragma once

#include <cstdint>
#include <string>
#include <utility>
#include <vector>

namespace svgen {

/* A triangle soup: positions (x, y, z) and triangles. */
struct Soup {
    explicit Soup(std::string n) : name(std::move(n)) {}
    std::string name;
    std::vector<float> pos;
    std::vector<std::uint32_t> idx;
    std::uint32_t vertex(double x, double y, double z) {
        pos.push_back((float)x), pos.push_back((float)y), pos.push_back((float)z);
        return (std::uint32_t)(pos.size() / 3 - 1);
    }
    void tri(std::uint32_t a, std::uint32_t b, std::uint32_t c) {
        idx.insert(idx.end(), {a, b, c});
    }
    /* Quad a b c d, counter-clockwise seen from its front. */
    void quad(std::uint32_t a, std::uint32_t b, std::uint32_t c, std::uint32_t d) {
        tri(a, b, c), tri(a, c, d);
    }
};

/* An axis-aligned box from LO to HI, outward faces, optionally without
 * its top (+y) face. */
void add_box(Soup &s, double x0, double y0, double z0, double x1, double y1, double z1,
             bool with_top);

/* The nine cases, in the order above. */
std::vector<Soup> open_cases();

} // namespace svgen
