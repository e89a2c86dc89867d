/*
 * shadowvol: the proof that a shadow volume is right: closure and the
 * winding-number identity of shadowvol_verify.h (read that header first:
 * it states the identity and why it holds).
 *
 * Everything here is plain double arithmetic on the float positions; none
 * of it shares code with the routines under test, except the reference
 * facing and cull bits (appendices A and B), which decide WHICH triangles
 * cast and are themselves tested against the paper elsewhere.
 *
 * Copyright (C) 2026 the shadowvol authors. LGPL-2.1-or-later.
 */
#include "shadowvol_verify.h"

#include "ray_triangles.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <unordered_map>

namespace sv {

namespace {

/* ---- Small vector algebra in double ------------------------------------ */

Point3 operator-(const Point3 &a, const Point3 &b) { return {a.x - b.x, a.y - b.y, a.z - b.z}; }
Point3 operator+(const Point3 &a, const Point3 &b) { return {a.x + b.x, a.y + b.y, a.z + b.z}; }
Point3 operator*(double s, const Point3 &a) { return {s * a.x, s * a.y, s * a.z}; }
double dot(const Point3 &a, const Point3 &b) { return a.x * b.x + a.y * b.y + a.z * b.z; }
Point3 cross(const Point3 &a, const Point3 &b) {
    return {a.y * b.z - a.z * b.y, a.z * b.x - a.x * b.z, a.x * b.y - a.y * b.x};
}
double length(const Point3 &a) { return std::sqrt(dot(a, a)); }

/* splitmix64: the verifier's own random stream (lights, points, rays). */
uint64_t next_random(uint64_t &state) {
    uint64_t z = (state += 0x9E3779B97F4A7C15ull);
    z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ull;
    z = (z ^ (z >> 27)) * 0x94D049BB133111EBull;
    return z ^ (z >> 31);
}
double unit_random(uint64_t &state) { return (double)(next_random(state) >> 11) * 0x1.0p-53; }
double uniform(uint64_t &state, double lo, double hi) {
    return lo + (hi - lo) * unit_random(state);
}

Point3 random_direction(uint64_t &state) {
    for (;;) {
        Point3 d{uniform(state, -1, 1), uniform(state, -1, 1), uniform(state, -1, 1)};
        double l2 = dot(d, d);
        if (l2 > 1e-4 && l2 <= 1.0) return (1.0 / std::sqrt(l2)) * d;
    }
}

/* Relative tolerance on barycentric coordinates: a crossing this close to
 * a triangle's edge could be counted for the wrong neighbour. */
constexpr double kEdgeEps = 1e-9;

enum class Hit { miss, hit, near_edge, near_start, near_end };

/* Ray P + s*r (r unit), s in (0, s_max], against triangle (a, a+e1, a+e2)
 * (Moller-Trumbore). *det_sign: sign of e1 . (r x e2) = -r . n. */
Hit intersect(const Point3 &p, const Point3 &r, double s_max, double eps_dist, const Point3 &a,
              const Point3 &e1, const Point3 &e2, double *det_out) {
    const Point3 pvec = cross(r, e2);
    const double det = dot(e1, pvec);
    if (det == 0.0) return Hit::miss; /* parallel, or a zero-area triangle */
    const double inv = 1.0 / det;
    const Point3 tvec = p - a;
    const double u = dot(tvec, pvec) * inv;
    if (!(u >= -kEdgeEps && u <= 1.0 + kEdgeEps)) return Hit::miss;
    const Point3 qvec = cross(tvec, e1);
    const double v = dot(r, qvec) * inv;
    if (!(v >= -kEdgeEps && u + v <= 1.0 + kEdgeEps)) return Hit::miss;
    const double s = dot(e2, qvec) * inv;
    if (s < -eps_dist || s > s_max + eps_dist) return Hit::miss;
    *det_out = det;
    if (s <= eps_dist) return Hit::near_start;
    if (s >= s_max - eps_dist) return Hit::near_end;
    if (u <= kEdgeEps || v <= kEdgeEps || u + v >= 1.0 - kEdgeEps) return Hit::near_edge;
    return Hit::hit;
}

Point3 vertex(const PreparedSurface &s, int v) {
    const float *p = &s.positions[3 * (size_t)v];
    return {p[0], p[1], p[2]};
}

struct SurfaceFrame {
    Point3 center;
    double radius; /* half the bounds' diagonal (> 0) */
    Point3 extents;
};

SurfaceFrame frame_of(const PreparedSurface &s) {
    Point3 lo{HUGE_VAL, HUGE_VAL, HUGE_VAL}, hi{-HUGE_VAL, -HUGE_VAL, -HUGE_VAL};
    for (int v = 0; v < s.num_vertices(); v++) {
        Point3 p = vertex(s, v);
        lo = {std::min(lo.x, p.x), std::min(lo.y, p.y), std::min(lo.z, p.z)};
        hi = {std::max(hi.x, p.x), std::max(hi.y, p.y), std::max(hi.z, p.z)};
    }
    if (s.num_vertices() == 0) lo = hi = {0, 0, 0};
    SurfaceFrame f;
    f.center = 0.5 * (lo + hi);
    f.extents = 0.5 * (hi - lo);
    /* No clamp at a "reasonable" size: clamped to 1e-30, a tetrahedron of
     * 1e-45 got lights and sample points 10^15 of its sizes away, beyond
     * double's precision near its features, and a winding-number
     * "mismatch" of the verifier's own making (issue 17). */
    f.radius = std::max(length(f.extents), 1e-300);
    return f;
}

/* A box around C (half sizes H) as six planes pointing into it. */
void box_planes(const Point3 &c, const Point3 &h, Plane p[SV_NUM_LIGHT_PLANES]) {
    const double cc[3] = {c.x, c.y, c.z}, hh[3] = {h.x, h.y, h.z};
    for (int a = 0; a < 3; a++) {
        float n[3] = {0, 0, 0};
        n[a] = 1;
        p[2 * a] = {n[0], n[1], n[2], (float)-(cc[a] - hh[a])};       /* x >= c - h */
        p[2 * a + 1] = {-n[0], -n[1], -n[2], (float)(cc[a] + hh[a])}; /* x <= c + h */
    }
}

/* The casting triangles for light L: facing bytes of appendix A, then (for
 * a culled light) every triangle whose three vertices share a cull bit of
 * appendix B made facing -- computed here without the routines under test.
 * Also returns the cull bits to hand to the variants (NULL: none needed). */
struct FacingInput {
    AlignedVector<uint8_t> facing;  /* numTriangles + 1 bytes, last 1 */
    std::vector<uint8_t> cull_bits; /* per welded vertex */
    bool use_cull_bits = false;
    /* Per triangle, how its prism counts: +1 it casts with the light
     * behind it (the paper's casting triangle; the general rule's byte
     * 0), -1 its reverse casts (the general rule's byte 2: the light in
     * front), 0 it casts nothing (lit under the paper's rule, or culled). */
    std::vector<int8_t> casts;
};

FacingInput facing_input(const PreparedSurface &s, const VerifyLight &l) {
    const int nt = s.num_triangles(), nv = s.num_vertices();
    FacingInput in;
    in.facing.assign((size_t)nt + 1, 1);
    sv_calculate_facing_c_ref(s.planes.data(), nt, &l.light, in.facing.data());
    in.facing[(size_t)nt] = 1;
    in.casts.assign((size_t)nt, 0);
    for (int t = 0; t < nt; t++) in.casts[t] = in.facing[t] ? 0 : 1;
    if (!l.culled) return in;

    const std::vector<Vec4> p4 = positions_vec4(s);
    const Bounds b = surface_bounds(s);
    in.cull_bits.assign((size_t)nv, 0);
    if (sv_calculate_cull_bits_c_ref(p4.data(), nv, &b, l.planes, in.cull_bits.data())) {
        return in; /* the surface is inside the light volume: nothing culled */
    }
    in.use_cull_bits = true;
    for (int t = 0; t < nt; t++) {
        const int *tri = &s.indices[3 * (size_t)t];
        if (in.cull_bits[tri[0]] & in.cull_bits[tri[1]] & in.cull_bits[tri[2]]) in.casts[t] = 0;
    }
    return in;
}

/* Triangles of the mesh in double, for segment crossings, with their
 * (unnormalized) normals. */
struct MeshTriangles {
    RayTriangles tris;
    std::vector<Point3> n;
};

/* Box padding of a triangle set: far above the crossing tolerances, far
 * below any triangle worth skipping. */
double box_pad(double scale) { return 1e-7 * scale; }

MeshTriangles mesh_triangles(const PreparedSurface &s) {
    MeshTriangles m;
    const int nt = s.num_triangles();
    double scale = 0;
    for (int t = 0; t < nt; t++) {
        const int *tri = &s.indices[3 * (size_t)t];
        const Point3 p0 = vertex(s, tri[0]), p1 = vertex(s, tri[1]), p2 = vertex(s, tri[2]);
        m.tris.add(p0, p1, p2);
        m.n.push_back(cross(p1 - p0, p2 - p0));
        for (const Point3 &q : {p0, p1, p2}) {
            scale = std::max({scale, std::fabs(q.x), std::fabs(q.y), std::fabs(q.z)});
        }
    }
    m.tris.build(box_pad(scale));
    return m;
}

/* The right-hand side of the identity at P: sum of s(t) over the casting
 * triangles the segment P -> light crosses; also whether the segment
 * crosses any triangle at all. false when the segment passes too close to
 * an edge or an end lies on a triangle (the point is skipped). */
struct Expected {
    int winding = 0;
    bool crosses_mesh = false;
    int64_t inverted = 0;
    /* A crossed triangle whose float facing byte disagrees with its double
     * orientation (edge-on to the light): the volume is right by the
     * identity, but such a point is left out of the "in shadow iff the
     * segment crosses" check, which assumes exact facing. */
    bool facing_disagrees = false;
};

bool expected_at(const MeshTriangles &m, const FacingInput &in, const Point3 &p,
                 const VerifyLight &l, double eps_dist, Expected *out) {
    Point3 r;
    double s_max;
    if (l.light.w != 0.0f) {
        const Point3 to_light = Point3{l.light.x, l.light.y, l.light.z} - p;
        s_max = length(to_light);
        if (s_max <= eps_dist) return false;
        r = (1.0 / s_max) * to_light;
    } else {
        r = {l.light.x, l.light.y, l.light.z};
        r = (1.0 / length(r)) * r;
        s_max = HUGE_VAL;
    }
    Expected e;
    bool decided = true;
    const RayTriangles &tr = m.tris;
    tr.for_each_candidate(p, r, s_max, [&](uint32_t t) {
        double det;
        const Hit h = intersect(p, r, s_max, eps_dist, tr.a[t], tr.e1[t], tr.e2[t], &det);
        if (h == Hit::miss) return true;
        if (h != Hit::hit) return decided = false;
        e.crosses_mesh = true;
        /* The light behind t's plane: the segment, running towards the
         * light, crosses t from its front to its back, r . n < 0. */
        const bool light_behind = dot(r, m.n[t]) < 0;
        if (light_behind != (in.facing[t] == 0)) e.facing_disagrees = true;
        if (!in.casts[t]) return true;
        if (light_behind == (in.casts[t] > 0)) {
            e.winding += 1;
        } else {
            e.winding -= 1;
            e.inverted++;
        }
        return true;
    });
    if (!decided) return false;
    *out = e;
    return true;
}

/* Inside a closed mesh: its winding number around P is not zero (signed
 * crossings of a random ray). Not the parity of the crossings: real
 * characters are made of closed parts that pass through each other
 * (RobotExpressive's arm), and a point inside two parts has an even
 * number of crossings but is inside the solid all the same. */
enum class Inside { yes, no, undecided };
Inside inside_closed_mesh(const MeshTriangles &m, const Point3 &p, double eps_dist, uint64_t &rng,
                          int64_t *retries) {
    for (int attempt = 0; attempt < 8; attempt++) {
        const Point3 r = random_direction(rng);
        int winding = 0;
        bool clean = true, on_surface = false;
        const RayTriangles &tr = m.tris;
        tr.for_each_candidate(p, r, HUGE_VAL, [&](uint32_t t) {
            double det;
            const Hit h = intersect(p, r, HUGE_VAL, eps_dist, tr.a[t], tr.e1[t], tr.e2[t], &det);
            if (h == Hit::hit)
                winding += det < 0 ? 1 : -1;
            else if (h == Hit::near_start)
                return !(on_surface = true);
            else if (h != Hit::miss)
                return clean = false;
            return true;
        });
        if (on_surface) return Inside::undecided;
        if (clean) return winding != 0 ? Inside::yes : Inside::no;
        (*retries)++;
    }
    return Inside::undecided;
}

std::string format_point(const Point3 &p) {
    char buf[128];
    std::snprintf(buf, sizeof buf, "(%.9g, %.9g, %.9g)", p.x, p.y, p.z);
    return buf;
}

/* The volume's vertices: even 2v = v, odd 2v+1 = v pushed away from the
 * light by D. */
std::vector<Point3> volume_vertices(const PreparedSurface &s, const VerifyLight &l, double d) {
    std::vector<Point3> out(2 * (size_t)s.num_vertices());
    const Point3 lp{l.light.x, l.light.y, l.light.z};
    const Point3 dir = (1.0 / std::max(length(lp), 1e-300)) * lp;
    for (int v = 0; v < s.num_vertices(); v++) {
        const Point3 p = vertex(s, v);
        Point3 away;
        if (l.light.w != 0.0f) {
            const Point3 from_light = p - lp;
            const double len = length(from_light);
            /* A vertex exactly at the light has no direction: it extrudes
             * to itself (its quads and caps have zero area). */
            away = len > 0 ? (1.0 / len) * from_light : Point3{0, 0, 0};
        } else {
            away = -1.0 * dir;
        }
        out[2 * (size_t)v] = p;
        out[2 * (size_t)v + 1] = p + d * away;
    }
    return out;
}

} // namespace

/* ---- Closure ------------------------------------------------------------ */

ClosureResult check_closure(const int *shadowIndices, int numIndices, int numVertices) {
    ClosureResult r;
    char buf[200];
    if (numIndices < 0 || numIndices % 3 != 0) {
        r.closed = false;
        std::snprintf(buf, sizeof buf, "%d indices: not a whole number of triangles", numIndices);
        r.problem = buf;
        return r;
    }
    const int64_t limit = 2 * (int64_t)numVertices;
    /* Undirected key (lo, hi) -> (uses lo->hi) - (uses hi->lo); all zero
     * when the volume is closed and consistently wound. */
    std::unordered_map<uint64_t, int64_t> balance;
    balance.reserve((size_t)numIndices);
    for (int i = 0; i < numIndices; i += 3) {
        for (int k = 0; k < 3; k++) {
            const int a = shadowIndices[i + k], b = shadowIndices[i + (k + 1) % 3];
            if (a < 0 || a >= limit) {
                r.closed = false;
                std::snprintf(buf, sizeof buf, "index %d at position %d is outside [0, %lld)", a,
                              i + k, (long long)limit);
                r.problem = buf;
                return r;
            }
            const uint32_t lo = (uint32_t)std::min(a, b), hi = (uint32_t)std::max(a, b);
            balance[((uint64_t)lo << 32) | hi] += (a < b) ? 1 : -1;
        }
    }
    for (const auto &kv : balance) {
        if (kv.second != 0) {
            r.closed = false;
            const int lo = (int)(kv.first >> 32), hi = (int)(kv.first & 0xFFFFFFFFu);
            std::snprintf(buf, sizeof buf,
                          "edge %d->%d is used %lld more time(s) than %d->%d: the volume is open",
                          kv.second > 0 ? lo : hi, kv.second > 0 ? hi : lo,
                          (long long)std::llabs(kv.second), kv.second > 0 ? hi : lo,
                          kv.second > 0 ? lo : hi);
            r.problem = buf;
            return r;
        }
    }
    return r;
}

/* ---- Winding numbers ---------------------------------------------------- */

WindingVolume::WindingVolume(const std::vector<Point3> &vertices, const int *indices, int n) {
    double scale = 0;
    for (const Point3 &v : vertices) {
        scale = std::max({scale, std::fabs(v.x), std::fabs(v.y), std::fabs(v.z)});
    }
    eps_dist_ = 1e-12 * scale;
    auto tris = std::make_shared<RayTriangles>();
    for (int i = 0; i + 2 < n; i += 3) {
        tris->add(vertices[(size_t)indices[i]], vertices[(size_t)indices[i + 1]],
                  vertices[(size_t)indices[i + 2]]);
    }
    tris->build(box_pad(scale));
    tris_ = std::move(tris);
}

std::size_t WindingVolume::triangles() const { return tris_->size(); }

WindingVolume::Status WindingVolume::winding(const Point3 &p, uint64_t &seed_state, int *out,
                                             int64_t *retries) const {
    const RayTriangles &tr = *tris_;
    for (int attempt = 0; attempt < 8; attempt++) {
        const Point3 r = random_direction(seed_state);
        int w = 0;
        bool clean = true, on_boundary = false;
        tr.for_each_candidate(p, r, HUGE_VAL, [&](uint32_t t) {
            double det;
            const Hit h = intersect(p, r, HUGE_VAL, eps_dist_, tr.a[t], tr.e1[t], tr.e2[t], &det);
            if (h == Hit::miss) return true;
            if (h == Hit::near_start) return !(on_boundary = true);
            if (h != Hit::hit) return clean = false;
            /* det = -r . n: leaving through a triangle whose normal points
             * along the ray counts +1. */
            w += det < 0 ? 1 : -1;
            return true;
        });
        if (on_boundary) return Status::on_boundary;
        if (clean) {
            *out = w;
            return Status::ok;
        }
        if (retries) (*retries)++;
    }
    return Status::undecided;
}

/* ---- Lights ------------------------------------------------------------- */

std::string VerifyLight::describe() const {
    char buf[400];
    if (light.w != 0.0f) {
        int n = std::snprintf(buf, sizeof buf, "point light at (%.9g, %.9g, %.9g)", light.x,
                              light.y, light.z);
        if (culled) {
            /* planes 0/1, 2/3, 4/5 bound x, y, z (see box_planes) */
            std::snprintf(buf + n, sizeof buf - (size_t)n,
                          " culled to the box x [%.9g, %.9g] y [%.9g, %.9g] z [%.9g, %.9g]",
                          -planes[0].d, planes[1].d, -planes[2].d, planes[3].d, -planes[4].d,
                          planes[5].d);
        }
    } else {
        std::snprintf(buf, sizeof buf, "directional light towards (%.9g, %.9g, %.9g)", light.x,
                      light.y, light.z);
    }
    return buf;
}

std::vector<VerifyLight> make_verify_lights(const PreparedSurface &s, int count, uint64_t seed) {
    const SurfaceFrame f = frame_of(s);
    uint64_t rng = seed ^ 0x5EED11647u;
    std::vector<VerifyLight> lights;
    const int points = (count + 1) / 2;
    for (int i = 0; i < count; i++) {
        VerifyLight l;
        if (i < points) {
            const bool close = (i % 4 == 3);
            const double dist = close ? uniform(rng, 0.3, 1.2) : uniform(rng, 1.5, 4.0);
            const Point3 p = f.center + (dist * f.radius) * random_direction(rng);
            l.light = {(float)p.x, (float)p.y, (float)p.z, 1.0f};
            l.culled = (i % 2 == 1);
            if (l.culled) {
                /* A box around the light whose faces on the mesh's side
                 * pass within half a radius of its center: they cut it. */
                const Point3 to_center = f.center - p;
                auto half = [&](double gap) {
                    return std::max(std::fabs(gap) + f.radius * uniform(rng, -0.5, 0.5),
                                    0.1 * f.radius);
                };
                const Point3 h{half(to_center.x), half(to_center.y), half(to_center.z)};
                box_planes(p, h, l.planes);
            }
        } else {
            const Point3 d = random_direction(rng);
            l.light = {(float)d.x, (float)d.y, (float)d.z, 0.0f};
        }
        lights.push_back(l);
    }
    return lights;
}

std::vector<const sv_variant *> supported_variants() {
    int n = 0;
    const sv_variant *all = sv_variants(&n);
    std::vector<const sv_variant *> out;
    for (int i = 0; i < n; i++) {
        if ((all[i].isa & sv_cpu_isa()) == all[i].isa) out.push_back(&all[i]);
    }
    return out;
}

void InSpaceCounts::add(const InSpaceCounts &o) {
    points += o.points;
    in_shadow += o.in_shadow;
    lit += o.lit;
    inside_mesh += o.inside_mesh;
    crossing_checked += o.crossing_checked;
    skipped += o.skipped;
    ray_retries += o.ray_retries;
    inverted_prisms += o.inverted_prisms;
}

/* ---- One light ---------------------------------------------------------- */

namespace {

/* A sample point: half uniform in the bounds grown by half, half just
 * behind (mostly) or in front of a random point of a random triangle, as
 * seen from the light -- where shadow boundaries are. */
Point3 sample_point(const PreparedSurface &s, const SurfaceFrame &f, const VerifyLight &l,
                    const std::vector<int> &casting, uint64_t &rng) {
    if (s.num_triangles() == 0 || unit_random(rng) < 0.5) {
        const double pad = 0.05 * f.radius;
        return {f.center.x + (1.5 * f.extents.x + pad) * uniform(rng, -1, 1),
                f.center.y + (1.5 * f.extents.y + pad) * uniform(rng, -1, 1),
                f.center.z + (1.5 * f.extents.z + pad) * uniform(rng, -1, 1)};
    }
    /* Half of these near a casting triangle: where the volume is, even
     * when a light box culls most of the mesh. */
    const int t = !casting.empty() && unit_random(rng) < 0.5
                      ? casting[(size_t)(next_random(rng) % casting.size())]
                      : (int)(next_random(rng) % (uint64_t)s.num_triangles());
    const int *tri = &s.indices[3 * (size_t)t];
    double u = unit_random(rng), v = unit_random(rng);
    if (u + v > 1) u = 1 - u, v = 1 - v;
    const Point3 p0 = vertex(s, tri[0]);
    const Point3 x = p0 + u * (vertex(s, tri[1]) - p0) + v * (vertex(s, tri[2]) - p0);
    Point3 away;
    const Point3 lp{l.light.x, l.light.y, l.light.z};
    if (l.light.w != 0.0f) {
        away = x - lp;
        const double len = length(away);
        away = len > 0 ? (1.0 / len) * away : Point3{1, 0, 0};
    } else {
        away = (-1.0 / length(lp)) * lp;
    }
    const double offset = f.radius * std::pow(10.0, uniform(rng, -3, 0));
    return x + (unit_random(rng) < 0.8 ? offset : -offset) * away;
}

} // namespace

namespace {

/* The index lists of the variants, each checked closed (within its
 * capacity, nothing written past it), the equal ones merged. */
struct BuiltVolumes {
    std::vector<AlignedVector<int>> lists;
    std::vector<std::string> names; /* the variants that built each list */
};

/* Adds LIST, built by variant NAME (N indices returned into CAPACITY ints
 * plus one sentinel -7), to V; false with RES's failure when it is out of
 * bounds or not closed. */
bool add_volume(BuiltVolumes &v, AlignedVector<int> list, int n, std::size_t capacity,
                const char *name, int num_vertices, const VerifyLight &l, LightResult &res) {
    res.variants_checked++;
    if (n < 0 || (size_t)n > capacity || list[capacity] != -7) {
        res.ok = false;
        res.failure = std::string("variant ") + name + ", " + l.describe() + ": returned " +
                      std::to_string(n) + " indices for a capacity of " + std::to_string(capacity) +
                      " (or wrote past it)";
        return false;
    }
    list.resize((size_t)n);
    const ClosureResult c = check_closure(list.data(), n, num_vertices);
    if (!c.closed) {
        res.ok = false;
        res.failure = std::string("variant ") + name + ", " + l.describe() +
                      ": not closed: " + c.problem;
        return false;
    }
    for (size_t k = 0; k < v.lists.size(); k++) {
        if (v.lists[k] == list) {
            v.names[k] += std::string(", ") + name;
            return true;
        }
    }
    v.lists.push_back(std::move(list));
    v.names.emplace_back(name);
    return true;
}

/* The in-space half of the proof: at random points, every distinct list's
 * winding number against the signed count of IN's casting triangles the
 * segment to the light crosses. CLOSED_MESH: the paper's rule on a closed
 * mesh, also "in shadow iff the segment crosses" outside the solid;
 * GENERAL: the general rule, where that holds at every point (every
 * crossing counts +1). */
void check_in_space(const PreparedSurface &s, const VerifyLight &l, const FacingInput &in,
                    const BuiltVolumes &built, bool closed_mesh, bool general,
                    const VerifyOptions &options, uint64_t seed, LightResult &res) {
    const int nt = s.num_triangles();
    const SurfaceFrame f = frame_of(s);
    res.distinct_volumes = (int)built.lists.size();
    if (built.lists.empty()) return;
    if (!(f.radius >= kVerifyMinRadius && f.radius <= kVerifyMaxRadius)) {
        char buf[200];
        std::snprintf(buf, sizeof buf,
                      "the surface's radius %.3g is outside the range verify decides in space "
                      "[%.0e, %.0e] (closure was checked)",
                      f.radius, kVerifyMinRadius, kVerifyMaxRadius);
        res.undecided = true;
        res.undecided_reason = buf;
        return;
    }

    const MeshTriangles mesh = mesh_triangles(s);
    const double extrusion = options.extrusion_radii * f.radius;
    const std::vector<Point3> verts = volume_vertices(s, l, extrusion);
    std::vector<WindingVolume> volumes;
    for (const auto &d : built.lists) {
        volumes.emplace_back(verts, d.data(), (int)d.size());
        res.volume_triangles += (int64_t)volumes.back().triangles();
    }
    const double light_reach = l.light.w != 0.0f
                                   ? length(Point3{l.light.x, l.light.y, l.light.z} - f.center)
                                   : 0.0;
    const double eps_dist = 1e-9 * (f.radius + light_reach);

    std::vector<int> casting;
    for (int t = 0; t < nt; t++) {
        if (in.casts[t]) casting.push_back(t);
    }
    uint64_t rng = seed;
    InSpaceCounts &c = res.counts;
    for (int i = 0; i < options.points_per_light; i++) {
        const Point3 p = sample_point(s, f, l, casting, rng);
        Expected e;
        if (!expected_at(mesh, in, p, l, eps_dist, &e)) {
            c.skipped++;
            continue;
        }
        Inside inside = Inside::no;
        if (closed_mesh) {
            inside = inside_closed_mesh(mesh, p, eps_dist, rng, &c.ray_retries);
            if (inside == Inside::undecided) {
                c.skipped++;
                continue;
            }
        }
        int got_first = 0;
        bool skipped = false;
        for (size_t k = 0; k < volumes.size(); k++) {
            int w = 0;
            const WindingVolume::Status st = volumes[k].winding(p, rng, &w, &c.ray_retries);
            if (st != WindingVolume::Status::ok) {
                skipped = true;
                break;
            }
            if (w != e.winding) {
                char buf[300];
                std::snprintf(buf, sizeof buf,
                              ": point %s has winding number %d in the shadow volume, "
                              "expected %d (casting triangles crossed by its %s, "
                              "%lld of them with the light on the wrong side)",
                              format_point(p).c_str(), w, e.winding,
                              l.light.w != 0.0f ? "segment to the light" : "ray towards the light",
                              (long long)e.inverted);
                res.ok = false;
                res.failure = "variant(s) " + built.names[k] + ", " + l.describe() + buf;
                return;
            }
            got_first = w;
        }
        if (skipped) {
            c.skipped++;
            continue;
        }
        c.points++;
        c.inverted_prisms += e.inverted;
        (got_first != 0 ? c.in_shadow : c.lit)++;
        if (inside == Inside::yes) {
            c.inside_mesh++;
        } else if ((closed_mesh || general) && !l.culled && !e.facing_disagrees) {
            c.crossing_checked++;
            if ((got_first != 0) != e.crosses_mesh) {
                res.ok = false;
                res.failure = "variant(s) " + built.names[0] + ", " + l.describe() + ": point " +
                              format_point(p) + (general ? "" : " outside the closed mesh") +
                              " is " + (got_first != 0 ? "in shadow" : "lit") + " but its " +
                              (l.light.w != 0.0f ? "segment to" : "ray towards") + " the light " +
                              (e.crosses_mesh ? "crosses" : "does not cross") + " the mesh";
                return;
            }
        }
    }
    const int64_t tried = c.points + c.skipped;
    if (tried > 0 && (double)c.skipped > options.max_skipped_fraction * (double)tried) {
        /* Not a failure: no point contradicted the identity; too many could
         * not be decided (degenerate, collinear or coincident triangles, or
         * features far below the surface's size). */
        char pct[32];
        std::snprintf(pct, sizeof pct, "%g%%", 100.0 * options.max_skipped_fraction);
        res.undecided = true;
        res.undecided_reason = l.describe() + ": " + std::to_string(c.skipped) + " of " +
                               std::to_string(tried) +
                               " points were too close to a boundary to decide (more than " + pct +
                               "; degenerate, collinear or coincident triangles, or "
                               "features far below the surface's size)";
    }
}

} // namespace

LightResult verify_light(const PreparedSurface &s, const VerifyLight &l,
                         const std::vector<const sv_variant *> &variants,
                         const VerifyOptions &options, uint64_t seed) {
    LightResult res;
    const int nt = s.num_triangles(), nv = s.num_vertices();
    const FacingInput in = facing_input(s, l);
    const size_t capacity = sv_shadow_volume_capacity(s.num_indices(), s.num_sil_edges());
    const PrepareReport &rep = s.report;
    const bool closed_mesh = rep.boundary_edges == 0 && rep.non_manifold_edges == 0 &&
                             rep.same_direction_edges == 0 && nt > 0;

    for (int t = 0; t < nt; t++) {
        res.casting_triangles += in.casts[t];
        res.culled_triangles += (in.facing[t] == 0 && !in.casts[t]);
    }

    /* Build every variant's volume; check each closed; keep distinct lists. */
    BuiltVolumes built;
    for (const sv_variant *var : variants) {
        AlignedVector<uint8_t> facing = in.facing; /* the routines modify it */
        AlignedVector<int> out(capacity + 1, -7);  /* one sentinel past the end */
        const int n =
            nt == 0 ? 0
                    : sv_create_shadow_volume(var, out.data(), s.indices.data(), s.num_indices(),
                                              s.sil_edges.data(), s.num_sil_edges(), facing.data(),
                                              in.use_cull_bits ? in.cull_bits.data() : nullptr);
        if (!add_volume(built, std::move(out), n, capacity, var->name, nv, l, res)) return res;
    }
    check_in_space(s, l, in, built, closed_mesh, false, options, seed, res);
    return res;
}

LightResult verify_general_light(const PreparedSurface &s, const GeneralEdgeTable &table,
                                 const VerifyLight &l,
                                 const std::vector<const sv_general_variant *> &variants,
                                 const VerifyOptions &options, uint64_t seed) {
    LightResult res;
    const int nt = s.num_triangles(), nv = s.num_vertices();
    FacingInput in = facing_input(s, l);
    /* The general bytes (shadowvol.h), from the same reference facing and
     * cull bits: 0 casts V_t, 2 its reverse casts, 1 nothing. */
    AlignedVector<uint8_t> general((size_t)nt + 1, SV_GENERAL_NONE);
    const int unculled = sv_general_facing_from_calculated(general.data(), in.facing.data(),
                                                           table.lit_byte.data(), nt);
    res.casting_triangles = in.use_cull_bits
                                ? sv_general_cull_c_ref(general.data(), nt, s.indices.data(),
                                                        in.cull_bits.data())
                                : unculled;
    res.culled_triangles = unculled - res.casting_triangles;
    for (int t = 0; t < nt; t++) {
        const uint8_t b = general[(size_t)t];
        in.casts[(size_t)t] = (int8_t)(b == SV_GENERAL_DARK ? 1 : b == SV_GENERAL_LIT ? -1 : 0);
    }
    const sv_general_edges edges = table.view();
    const size_t sil_capacity = table.sil_capacity();
    const size_t capacity = sil_capacity + 2 * (size_t)s.num_indices();
    BuiltVolumes built;
    for (const sv_general_variant *var : variants) {
        /* The silhouette quads, then the caps after them: the volume the
         * stencil pass draws in z-fail, which must close. */
        AlignedVector<int> out(capacity + 1, -7);
        const int sil = var->create_general_sil_triangles(out.data(), general.data(), &edges);
        int n = sil;
        if (sil >= 0 && (size_t)sil <= sil_capacity)
            n += var->create_general_cap_triangles(out.data() + sil, general.data(),
                                                   s.indices.data(), s.num_indices());
        if (!add_volume(built, std::move(out), n, capacity, var->name, nv, l, res)) return res;
    }
    /* "In shadow iff the segment crosses" holds where every triangle
     * takes the general rule (a closed shell under the paper's rule holds
     * it only outside its solid). */
    const bool all_general = std::all_of(table.lit_byte.begin(), table.lit_byte.end(),
                                         [](uint8_t b) { return b == SV_GENERAL_LIT; });
    check_in_space(s, l, in, built, false, all_general, options, seed, res);
    return res;
}

std::vector<const sv_general_variant *> supported_general_variants() {
    std::vector<const sv_general_variant *> out;
    int count = 0;
    const sv_general_variant *all = sv_general_variants(&count);
    for (int i = 0; i < count; i++)
        if ((all[i].isa & ~sv_cpu_isa()) == 0) out.push_back(&all[i]);
    return out;
}

} // namespace sv
