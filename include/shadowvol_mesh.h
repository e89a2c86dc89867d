/*
 * shadowvol: per-surface preparation (C++). Turns a triangle soup of float
 * positions and 32-bit indices into what the routines of shadowvol.h take:
 * welded vertices, triangle indices without degenerate triangles, SilEdges
 * with the paper's convention, one plane per triangle (for
 * sv_calculate_facing_c_ref), and the double-length shadow vertex buffer.
 * Done once per surface (again only when its positions change).
 *
 * Copyright (C) 2026 the shadowvol authors. LGPL-2.1-or-later.
 */
#ifndef SHADOWVOL_MESH_H
#define SHADOWVOL_MESH_H

#include "shadowvol.h"
#include "shadowvol_planes.h"

#include <cstddef>
#include <cstdint>
#include <new>
#include <stdexcept>
#include <vector>

namespace sv {

/* std::allocator with 64-byte alignment: the arrays below satisfy every
 * variant's alignment needs (sv_variant::align_*), and SIMD loads of them
 * never straddle a cache line. */
template <class T> struct AlignedAllocator {
    using value_type = T;
    static constexpr std::size_t kAlign = 64;
    AlignedAllocator() noexcept = default;
    template <class U> AlignedAllocator(const AlignedAllocator<U> &) noexcept {}
    T *allocate(std::size_t n) {
        if (n > std::size_t(-1) / sizeof(T)) throw std::bad_array_new_length();
        return static_cast<T *>(::operator new(n * sizeof(T), std::align_val_t(kAlign)));
    }
    void deallocate(T *p, std::size_t) noexcept { ::operator delete(p, std::align_val_t(kAlign)); }
    template <class U> bool operator==(const AlignedAllocator<U> &) const noexcept { return true; }
    template <class U> bool operator!=(const AlignedAllocator<U> &) const noexcept { return false; }
};
template <class T> using AlignedVector = std::vector<T, AlignedAllocator<T>>;

/* What preparation found. "Uses" of an edge are its directed occurrences
 * a->b in the kept triangles (three per triangle). */
struct PrepareReport {
    int64_t vertices_in = 0;        /* input vertices */
    int64_t triangles_in = 0;       /* input triangles (num_indices / 3) */
    int64_t degenerate_dropped = 0; /* two or three welded indices equal */
    int64_t triangles = 0;          /* kept: triangles_in - degenerate_dropped */
    int64_t welded_vertices = 0;    /* distinct positions (all input vertices, used or not) */
    int64_t zero_normal_triangles =
        0;                      /* kept, but the cross product is exactly 0: plane (0,0,0,0) */
    int64_t edges = 0;          /* distinct undirected edges of kept triangles */
    int64_t boundary_edges = 0; /* used by exactly one triangle */
    int64_t manifold_edges = 0; /* used twice, in opposite directions */
    int64_t same_direction_edges = 0; /* used twice, both in the same direction */
    int64_t non_manifold_edges = 0;   /* used by more than two triangles */
    int64_t sil_edges = 0;            /* SilEdges built (regular + dangling) */
    int64_t dangling_sil_edges = 0;   /* SilEdges with p2 = numTriangles */
};

/* A prepared surface. All int arrays are ready for the C routines: vertex
 * numbers < 2^30, counts fit an int, and the volume's output capacity
 * sv_shadow_volume_capacity(num_indices(), num_sil_edges()) fits an int. */
struct PreparedSurface {
    /* Welded positions, xyz per vertex (3 * num_vertices() floats). Vertex
     * w is numbered in order of the first input vertex with its position;
     * -0.0 is stored as +0.0. */
    std::vector<float> positions;
    /* remap[i]: the welded vertex of input vertex i (vertices_in entries). */
    std::vector<int> remap;
    /* Kept triangles on welded vertices, 3 ints each, input order and
     * winding preserved. 64-byte aligned. */
    AlignedVector<int> indices;
    /* triangle_source[t]: the input triangle that kept triangle t came from. */
    std::vector<int> triangle_source;
    /* The paper's SilEdges (section 3): v1 -> v2 is in the winding of
     * triangle p1 and v2 -> v1 in p2; v1, v2 are welded vertex numbers
     * times two; dangling edges have p2 = num_triangles(). Every directed
     * use of an edge by a kept triangle is in exactly one SilEdge (see
     * prepare_surface). Sorted by p1, then by p1's corner. */
    std::vector<SilEdge> sil_edges;
    /* planes[t]: the plane of kept triangle t (see triangle_plane).
     * 64-byte aligned. */
    AlignedVector<Plane> planes;
    PrepareReport report;

    int num_vertices() const { return (int)(positions.size() / 3); }
    int num_triangles() const { return (int)(indices.size() / 3); }
    int num_indices() const { return (int)indices.size(); }
    int num_sil_edges() const { return (int)sil_edges.size(); }
};

/* Malformed input: the message names the problem (and the vertex or
 * triangle). */
class PrepareError : public std::runtime_error {
public:
    using std::runtime_error::runtime_error;
};

/* Prepares one surface.
 *   positions    3 * num_vertices floats (x, y, z); every one finite.
 *   indices      num_indices (a multiple of 3) vertex numbers, each
 *                < num_vertices. Any count: no 16-bit limits.
 * Welding: two input vertices weld when their x, y and z are bitwise equal
 * after mapping -0.0 to +0.0 (exact position; no tolerance). O(n log n).
 * Degenerate triangles (two or three welded indices equal) are dropped and
 * counted; a triangle of three distinct but collinear positions is kept
 * (dropping it would open the mesh) with the zero plane.
 * SilEdges: for each undirected edge, its directed uses are paired: each
 * use a->b with an unpaired opposite use b->a, in the order of their
 * triangles (first with first), giving a regular SilEdge whose p1 is the
 * earlier triangle. Every use left unpaired (boundary edges, the extra
 * uses of non-manifold edges, both uses of an edge used twice in the same
 * direction) becomes its own dangling SilEdge (p2 = num_triangles). This
 * keeps every shadow volume closed, for ANY facing bytes (so for every
 * light, with or without cull bits): see the proof in src/mesh/mesh_prep.cpp.
 * An empty mesh (no triangles, or all degenerate) is valid: no indices, no
 * SilEdges, no planes.
 * Throws PrepareError on: a NULL array with a non-zero count, num_indices %
 * 3 != 0, an index >= num_vertices, a NaN or infinite coordinate, more
 * than INT_MAX input vertices, 2^30 or more welded vertices, or a mesh so
 * large that its shadow-volume capacity does not fit an int. */
PreparedSurface prepare_surface(const float *positions, std::size_t num_vertices,
                                const uint32_t *indices, std::size_t num_indices);

/* The plane of triangle (p0, p1, p2), counter-clockwise seen from its
 * front, computed in double and rounded to float once at the end:
 *   e1 = p1 - p0, e2 = p2 - p0                      (double)
 *   n  = e1 x e2 = (e1.y*e2.z - e1.z*e2.y,
 *                   e1.z*e2.x - e1.x*e2.z,
 *                   e1.x*e2.y - e1.y*e2.x)
 *   len = sqrt(n.x*n.x + n.y*n.y + n.z*n.z)
 *   n  /= len;  d = -(n.x*p0.x + n.y*p0.y + n.z*p0.z)
 *   plane = ((float)n.x, (float)n.y, (float)n.z, (float)d)
 * (double keeps slivers whose float cross product would underflow.) When
 * the cross product is exactly zero (collinear points) the plane is
 * (0, 0, 0, 0): sv_calculate_facing_c_ref gives it facing 0 for every light
 * (0 > 0 is false), so the triangle always casts; its caps have zero area
 * and the volume stays closed (closure holds for any facing). */
Plane triangle_plane(const float p0[3], const float p1[3], const float p2[3]);

/* The welded positions as (x, y, z, 1), one per vertex: what appendix B
 * (sv_calculate_cull_bits_*) and sv_surface read. */
std::vector<Vec4> positions_vec4(const PreparedSurface &s);

/* The double-length shadow vertex buffer (section 3): for welded vertex v,
 * element 2v = (x, y, z, 1) and 2v + 1 = (x, y, z, 0). The same buffer
 * serves every light when a vertex program subtracts the light origin from
 * the odd vertices. */
AlignedVector<Vec4> shadow_vertices(const PreparedSurface &s);

/* The CPU variant, for hardware without vertex programs: one buffer per
 * light. Even vertices as above; odd vertex 2v + 1 =
 *   (x*light.w - light.x, y*light.w - light.y, z*light.w - light.z, 0),
 * i.e. the paper's (x,y,z) - light origin for a point light (w = 1), and
 * the direction away from a directional light (w = 0, light.xyz pointing
 * towards the light) for every vertex. out: 2 * num_vertices() elements. */
void shadow_vertices_for_light(const PreparedSurface &s, const Vec4 &light, Vec4 *out);
AlignedVector<Vec4> shadow_vertices_for_light(const PreparedSurface &s, const Vec4 &light);

/* Bounds of the welded vertices for sv_calculate_cull_bits_c_ref: center
 * and extents rounded so that center +- extents contains every vertex
 * (extents rounded up). An empty surface gives zero bounds. */
Bounds surface_bounds(const PreparedSurface &s);

/* The triangles of an index list grouped for the clustered plane kernels
 * (include/shadowvol_planes.h, "Planes by clusters"): owning storage, and
 * view() for the kernels. Built once per index list; the planes of every
 * frame then come from the clusters and that frame's positions. */
struct PlaneClusters {
    std::vector<int> vertex_begin, group_begin;
    std::vector<uint32_t> vertex_offsets, plane_offsets;
    std::vector<uint8_t> corners;
    int num_clusters() const { return (int)group_begin.size() - 1; }
    sv_plane_clusters view() const;
};

/* Greedy clusters, grown over shared vertices: a cluster starts at the
 * first triangle not yet in one and takes, again and again, the triangle
 * sharing the most corners with it (ties: the first met), while the
 * cluster stays within SV_PLANE_CLUSTER_VERTICES vertices. Deterministic.
 * Throws PrepareError when an index is negative or not below NUM_VERTICES,
 * for a negative count, or for more vertices or triangles than the 32-bit
 * offsets reach (include/shadowvol_planes.h). No triangles: no clusters. */
PlaneClusters plane_clusters(const int *indices, int num_triangles, int num_vertices);

} // namespace sv

#endif /* SHADOWVOL_MESH_H */
