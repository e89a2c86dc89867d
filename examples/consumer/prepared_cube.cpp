/* An installed-package consumer in C++: prepares a cube with
 * sv::prepare_surface (welding 24 corner copies to 8 vertices), then builds
 * its shadow volume for a point light with the best variant this CPU runs
 * and checks what a closed cube's volume must be: 8 vertices, 12 triangles,
 * 18 edges; with the light above the top face only, 2 triangles face it,
 * the silhouette is the top face's 4 edges (2 triangles each) and the other
 * 10 triangles each give a near and a far cap triangle (include/shadowvol.h):
 * 4 * 6 + 10 * 2 * 3 = 84 indices. Exit 0 when so.
 * LGPL-2.1-or-later. */
#include <cstdio>
#include <vector>

#include "shadowvol_mesh.h"

int main() {
    std::vector<float> p;
    std::vector<uint32_t> idx;
    // Six faces, each with its own four corners (so welding has work).
    const int faces[6][4][3] = {{{0, 0, 0}, {0, 1, 0}, {1, 1, 0}, {1, 0, 0}},
                                {{0, 0, 1}, {1, 0, 1}, {1, 1, 1}, {0, 1, 1}},
                                {{0, 0, 0}, {1, 0, 0}, {1, 0, 1}, {0, 0, 1}},
                                {{0, 1, 0}, {0, 1, 1}, {1, 1, 1}, {1, 1, 0}},
                                {{0, 0, 0}, {0, 0, 1}, {0, 1, 1}, {0, 1, 0}},
                                {{1, 0, 0}, {1, 1, 0}, {1, 1, 1}, {1, 0, 1}}};
    for (const auto &f : faces) {
        const uint32_t base = (uint32_t)(p.size() / 3);
        for (const auto &c : f)
            for (int k = 0; k < 3; k++) p.push_back((float)c[k]);
        for (uint32_t t : {0u, 1u, 2u, 0u, 2u, 3u}) idx.push_back(base + t);
    }
    const sv::PreparedSurface s = sv::prepare_surface(p.data(), p.size() / 3, idx.data(),
                                                      idx.size());
    if (s.num_vertices() != 8 || s.num_triangles() != 12 || s.num_sil_edges() != 18) {
        std::fprintf(stderr,
                     "prepare_surface: %d vertices, %d triangles, %d edges (want 8, 12, 18)\n",
                     s.num_vertices(), s.num_triangles(), s.num_sil_edges());
        return 1;
    }
    const Vec4 light = {0.5f, 0.5f, 5.0f, 1.0f}; // above the z = 1 face only
    sv::AlignedVector<uint8_t> facing(s.num_triangles() + 1);
    sv_calculate_facing_c_ref(s.planes.data(), s.num_triangles(), &light, facing.data());
    sv::AlignedVector<int> out(sv_shadow_volume_capacity(s.num_indices(), s.num_sil_edges()));
    const sv_variant *v = sv_best_variant();
    const int n = sv_create_shadow_volume_checked(v, out.data(), (int)out.size(), s.indices.data(),
                                                  s.num_indices(), s.num_triangles(),
                                                  s.sil_edges.data(), s.num_sil_edges(),
                                                  facing.data(), nullptr);
    if (n != 84) {
        std::fprintf(stderr, "%s: %d indices (%s), want 84\n", v->name, n,
                     n < 0 ? sv_status_string(n) : "wrong count");
        return 1;
    }
    std::printf("%s: cube volume of %d indices from the installed package\n", v->name, n);
    return 0;
}
