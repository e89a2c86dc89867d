/*
 * A surface's triangles grouped by their lowest vertex, to ask whether a
 * volume's cap is one of the receiver's own triangles (volume_pieces.h;
 * internal to src/render), and the groupings kept from light to light and
 * frame to frame.
 *
 * The grouping reads the surface's index list only (not its positions):
 * a kept grouping is used while that list is the one it was built from,
 * compared whole the first time it is asked for in a frame (the scene
 * does not change within a frame). The demo's terrain: 1.2 MB compared
 * in about 0.15 ms on the project's machine, against about 1 ms to group
 * it again, per light.
 *
 * Copyright (C) 2026 the shadowvol authors. LGPL-2.1-or-later.
 */
#ifndef SV_RENDER_SURFACE_TRIANGLES_H
#define SV_RENDER_SURFACE_TRIANGLES_H

#include <memory>
#include <utility>
#include <vector>

#include "shadowvol_mesh.h"

namespace sv::render::detail {

struct SurfaceTriangles {
    /* Triangles whose lowest vertex is v: others[first[v] .. first[v + 1]),
     * each as its two other vertices in increasing order; a group larger
     * than kScan is sorted. */
    std::vector<int> first;
    std::vector<std::pair<int, int>> others;
    int vertices = 0;
    static constexpr int kScan = 32;
    /* Is (A, B, C), in any order, one of the surface's triangles? */
    bool contains(int a, int b, int c) const;
};

SurfaceTriangles group_surface_triangles(const PreparedSurface &surface);

/* Per surface number, its grouping and the index list it was built from.
 * Sized by the caller before a parallel section (fit); get() for distinct
 * surfaces may then run on different threads.
 * A stale grouping would call a cap the receiver's own (failing its test
 * everywhere) where the surface's list no longer has it; the key's test
 * is tests/unit/test_stencil_methods.cpp (KeptSurfaceTriangles...). */
class SurfaceTrianglesCache {
public:
    /* A new frame (a scene that may have changed): each list is compared
     * again when next asked for. */
    void begin_frame();
    void fit(int surfaces);
    const SurfaceTriangles &get(int surface, const PreparedSurface &p);

private:
    struct Entry {
        bool valid = false;
        bool checked = false;     /* compared (or built) in this frame */
        std::vector<int> indices; /* the key: the list it was built from (and its vertex count) */
        SurfaceTriangles triangles;
    };
    std::vector<Entry> entries_;
};

} // namespace sv::render::detail

#endif
