/*
 * Dispatch by measurement (include/shadowvol_plan.h): the plans, how a
 * class is measured, and where a plan comes from.
 *
 * Measuring a class: a generated height-field mesh of the class's size
 * (a grid with bumps, so facing comes in coherent regions as on a real
 * surface), prepared by sv::prepare_surface, lit by 8 point lights that
 * move over it (and a light box around each for the cull bits). Every
 * runnable variant of each routine is called on every light in turn, in
 * rounds; each call's result is compared with c_ref's on the same light
 * (a plan is never built from a variant that computes something else);
 * the figure is the median over rounds of the per-call rdtsc time. The
 * rounds shrink with the class so that a class takes roughly the same
 * wall time.
 *
 * Copyright (C) 2026 the shadowvol authors. LGPL-2.1-or-later.
 */
#include "shadowvol_plan.h"

#include <x86intrin.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <climits>
#include <cstring>
#include <deque>
#include <mutex>
#include <string>
#include <vector>

#include "plan_internal.h"
#include "model_gen.h"
#include "shadowvol_mesh.h"

namespace {

const char *const kRoutineNames[SV_NUM_ROUTINES] = {
    "calculate_facing",  "calculate_cull_bits",  "count_facing",
    "count_facing_cull", "create_sil_triangles", "create_cap_triangles"};

constexpr int kClassLimit[SV_NUM_SIZE_CLASSES - 1] = {4096, 65536, 524288};
/* The generated character subdivided n x n (1344 n^2 triangles), n = 1, 4,
 * 12, 27. Class 0 is measured on the 1344-triangle character itself, not
 * at the class's middle: a mesh that small has under 1024 vertices, where
 * the VBMI CountFacingCull keeps the whole cull-bit table in registers;
 * measured at 2048 triangles (its fallback path) it lost to avx2, and the
 * plan then made the paper's character slower than the static choice. */
constexpr int kClassTriangles[SV_NUM_SIZE_CLASSES] = {1344, 21504, 193536, 979776};
/* A measured variant displaces the static choice only when it is faster by
 * more than this: the timings of two kernels within a few percent of each
 * other swap from run to run, and a plan that follows the noise picks a
 * kernel that is slower on the user's mesh as often as faster. */
constexpr double kStaticMargin = 1.03;
constexpr int kLights = 8;

bool runs(unsigned isa) { return (isa & sv_cpu_isa()) == isa; }

/* ---- The plans ----------------------------------------------------------- */

/* Plans are immutable once made and never freed (a few hundred bytes
 * each, a handful per process): a pointer sv_plan_for returned stays valid
 * and unchanged while another thread installs a newer plan. */
struct State {
    std::mutex lock;
    std::deque<sv_plan> arena;
    std::array<const sv_plan *, SV_NUM_SIZE_CLASSES> plan{};
    std::array<int, SV_NUM_SIZE_CLASSES> kind{}; /* 0 none yet, 1 built-in, 2 wisdom, 3 measured */
};
State &state() {
    static State s;
    return s;
}

} // namespace

namespace svplan {

bool variant_runs_routine(const char *name, sv_routine r) {
    if (!name) return false;
    if (r == SV_ROUTINE_CALCULATE_FACING || r == SV_ROUTINE_CALCULATE_CULL_BITS) {
        const sv_facing_variant *f = sv_facing_variant_by_name(name);
        return f && runs(f->isa);
    }
    const sv_variant *v = sv_variant_by_name(name);
    return v && runs(v->isa);
}

sv_plan make_plan(int sizeClass, const char *source, const char *const names[SV_NUM_ROUTINES],
                  const double ticks[SV_NUM_ROUTINES]) {
    sv_plan p{};
    p.size_class = sizeClass;
    p.source = source;
    const sv_facing_variant *fallback_f = sv_best_facing_variant();
    const sv_variant *fallback_v = sv_best_variant();
    for (int r = 0; r < SV_NUM_ROUTINES; r++) {
        const bool ok = variant_runs_routine(names[r], (sv_routine)r);
        const bool facing_table = r <= SV_ROUTINE_CALCULATE_CULL_BITS;
        p.variant[r] = ok ? (facing_table ? sv_facing_variant_by_name(names[r])->name
                                          : sv_variant_by_name(names[r])->name)
                          : (facing_table ? fallback_f->name : fallback_v->name);
        p.ticks[r] = ticks ? ticks[r] : 0;
    }
    const sv_facing_variant *fa = sv_facing_variant_by_name(p.variant[SV_ROUTINE_CALCULATE_FACING]);
    const sv_facing_variant *fb = sv_facing_variant_by_name(p.variant[SV_ROUTINE_CALCULATE_CULL_BITS]);
    p.calculate_facing = fa->calculate_facing;
    p.calculate_facing_count = fa->calculate_facing_count;
    p.calculate_cull_bits = fb->calculate_cull_bits;
    const sv_variant *c = sv_variant_by_name(p.variant[SV_ROUTINE_COUNT_FACING]);
    const sv_variant *d = sv_variant_by_name(p.variant[SV_ROUTINE_COUNT_FACING_CULL]);
    const sv_variant *e = sv_variant_by_name(p.variant[SV_ROUTINE_CREATE_SIL_TRIANGLES]);
    const sv_variant *f = sv_variant_by_name(p.variant[SV_ROUTINE_CREATE_CAP_TRIANGLES]);
    sv_variant &k = p.kernels;
    k.name = "planned";
    k.isa = c->isa | d->isa | e->isa | f->isa;
    k.count_facing = c->count_facing;
    k.count_facing_cull = d->count_facing_cull;
    k.create_sil_triangles = e->create_sil_triangles;
    k.create_cap_triangles = f->create_cap_triangles;
    /* CountFacing reads facing; CountFacingCull writes it (sse2_paper has
     * no alignment need there); Sil and Cap write the output; Cap reads
     * the indices. */
    k.align_facing = c->align_facing;
    k.align_indices = f->align_indices;
    k.align_shadow_indices = std::max(e->align_shadow_indices, f->align_shadow_indices);
    return p;
}

void install(int sizeClass, const sv_plan &p, int kind) {
    State &s = state();
    std::lock_guard<std::mutex> g(s.lock);
    if (kind >= s.kind[(size_t)sizeClass]) {
        s.arena.push_back(p);
        s.plan[(size_t)sizeClass] = &s.arena.back();
        s.kind[(size_t)sizeClass] = kind;
    }
}

bool measured(int sizeClass, sv_plan *out) {
    State &s = state();
    std::lock_guard<std::mutex> g(s.lock);
    if (s.kind[(size_t)sizeClass] != 3) return false;
    *out = *s.plan[(size_t)sizeClass];
    return true;
}

} // namespace svplan

/* ---- Measuring ----------------------------------------------------------- */

namespace {

struct Mesh {
    sv::PreparedSurface s;
    std::vector<Vec4> positions4;
    Bounds bounds{};
    std::array<Vec4, kLights> lights{};
    std::array<std::array<Plane, SV_NUM_LIGHT_PLANES>, kLights> boxes{};
};

/* The mesh a class is measured on: the project's generated character
 * (tools/generate_models, the paper's 1344-triangle stand-in), each quad
 * subdivided n x n to the class's size, lit from around it. A height field
 * lit from low above was used first: its facing regions are large and
 * only a few percent of its SilEdges lie on the silhouette, where the
 * AVX2 silhouette and cap kernels (scalar, branchy) win, and the plans
 * made from it were 10-30% slower than the static choice on the
 * character and the real models (scaling run, AMD Zen 5). */
/* The lights and light boxes of M, from its bounds (set here). */
void light_mesh(Mesh &m) {
    m.positions4.resize((size_t)m.s.num_vertices());
    for (int i = 0; i < m.s.num_vertices(); i++) {
        m.positions4[(size_t)i] = {m.s.positions[3 * (size_t)i], m.s.positions[3 * (size_t)i + 1],
                                   m.s.positions[3 * (size_t)i + 2], 1};
    }
    m.bounds = sv::surface_bounds(m.s);
    const Vec4 c = m.bounds.center, e = m.bounds.extents;
    /* A flat surface (a ground plane) has a zero extent: the ring of
     * lights is sized by the largest one, and a degenerate surface of one
     * point still gets lights apart from it. */
    const float r = std::max(1e-3f, std::max(e.x, std::max(e.y, e.z)));
    for (int l = 0; l < kLights; l++) {
        /* Point lights on a ring around the character, at several heights:
         * about half the triangles face each (a closed mesh lit from
         * outside), with silhouettes across arms, legs and head. */
        const double t2 = 6.2832 * (l + 0.5) / kLights;
        const float dx = (float)std::cos(t2), dz = (float)std::sin(t2);
        const float dy = (float)(0.6 * std::sin(3.0 * t2));
        const Vec4 light{c.x + 2.0f * r * dx, c.y + r * dy, c.z + 2.0f * r * dz, 1};
        m.lights[(size_t)l] = light;
        /* The light box: a cube of side 1.6 r centred between the mesh
         * centre and the light, planes pointing in: it holds part of the
         * mesh, so the culling path runs with triangles on both sides. */
        const float bx = c.x + 0.6f * r * dx, by = c.y + 0.6f * r * dy, bz = c.z + 0.6f * r * dz;
        const float h = 0.8f * r;
        m.boxes[(size_t)l] = {Plane{1, 0, 0, -(bx - h)}, Plane{-1, 0, 0, bx + h},
                              Plane{0, 1, 0, -(by - h)}, Plane{0, -1, 0, by + h},
                              Plane{0, 0, 1, -(bz - h)}, Plane{0, 0, -1, bz + h}};
    }
}

Mesh make_mesh(int triangles) {
    const int n = std::max(1, (int)std::lround(std::sqrt((double)triangles / 1344.0)));
    const svgen::TriMesh t = svgen::build_character(n);
    Mesh m;
    m.s = sv::prepare_surface(t.positions.data(), t.num_vertices(), t.indices.data(),
                              t.indices.size());
    light_mesh(m);
    return m;
}

/* The caller's surface, copied (the kernels' alignment is then the
 * planner's to give, whatever the caller's arrays have). Its own bounds
 * are replaced by the positions' (the same box, or a tighter one). */
Mesh copy_mesh(const sv_surface &v) {
    Mesh m;
    const int nt = v.numIndices / 3;
    m.s.indices.assign(v.indices, v.indices + v.numIndices);
    m.s.planes.assign(v.planes, v.planes + nt);
    m.s.sil_edges.assign(v.silEdges, v.silEdges + v.numSilEdges);
    m.s.positions.resize(3 * (size_t)v.numVerts);
    for (int i = 0; i < v.numVerts; i++) {
        m.s.positions[3 * (size_t)i] = v.positions[i].x;
        m.s.positions[3 * (size_t)i + 1] = v.positions[i].y;
        m.s.positions[3 * (size_t)i + 2] = v.positions[i].z;
    }
    light_mesh(m);
    return m;
}

inline uint64_t ticks_now() {
    _mm_lfence();
    const uint64_t t = __rdtsc();
    _mm_lfence();
    return t;
}

/* What one light's reference results are, for the checks. */
struct Reference {
    std::vector<uint8_t> facing, cull, culled_facing;
    int cull_inside = 0;
    int count = 0, count_cull = 0;
    std::vector<int> sil, cap;
};

struct Measurer {
    const Mesh &m;
    int rounds;
    std::vector<Reference> ref;
    std::vector<uint8_t> facing;
    sv::AlignedVector<uint8_t> facing_aligned;
    std::vector<uint8_t> cull;
    sv::AlignedVector<int> out;
    bool failed = false;

    explicit Measurer(const Mesh &mesh, int r) : m(mesh), rounds(r) {
        const size_t nt = (size_t)m.s.num_triangles();
        facing_aligned.resize(nt + 16);
        cull.resize((size_t)m.s.num_vertices());
        out.resize(sv_shadow_volume_capacity(m.s.num_indices(), m.s.num_sil_edges()) + 16);
        ref.resize(kLights);
        for (int l = 0; l < kLights; l++) {
            Reference &x = ref[(size_t)l];
            x.facing.resize(nt + 1);
            sv_calculate_facing_c_ref(m.s.planes.data(), (int)nt, &m.lights[(size_t)l],
                                      x.facing.data());
            x.cull.resize((size_t)m.s.num_vertices());
            x.cull_inside = sv_calculate_cull_bits_c_ref(m.positions4.data(), m.s.num_vertices(),
                                                         &m.bounds, m.boxes[(size_t)l].data(),
                                                         x.cull.data());
            if (x.cull_inside) std::fill(x.cull.begin(), x.cull.end(), 0);
            x.count = sv_count_facing_c_ref(x.facing.data(), (int)nt);
            x.culled_facing = x.facing;
            x.count_cull = sv_count_facing_cull_c_ref(x.culled_facing.data(), (int)nt,
                                                      m.s.indices.data(), x.cull.data());
            x.sil.resize(6 * (size_t)m.s.num_sil_edges() + 1);
            x.sil.resize((size_t)sv_create_sil_triangles_c_ref(
                x.sil.data(), x.facing.data(), m.s.sil_edges.data(), m.s.num_sil_edges()));
            x.cap.resize(2 * (size_t)m.s.num_indices() + 1);
            x.cap.resize((size_t)sv_create_cap_triangles_c_ref(x.cap.data(), x.facing.data(),
                                                               m.s.indices.data(),
                                                               m.s.num_indices()));
        }
    }

    /* Median over rounds of one call, one light per call in turn. PREPARE
     * sets the call's input up outside the timed region; CALL returns
     * whether its result matched c_ref's. */
    template <class Prepare, class Call> double time(const Prepare &prepare, const Call &call) {
        std::vector<double> per_call;
        per_call.reserve((size_t)rounds * kLights);
        for (int round = 0; round < rounds; round++) {
            for (int l = 0; l < kLights; l++) {
                prepare(l);
                const uint64_t t0 = ticks_now();
                const bool ok = call(l);
                const uint64_t t1 = ticks_now();
                if (!ok) failed = true;
                per_call.push_back((double)(t1 - t0));
            }
        }
        std::nth_element(per_call.begin(), per_call.begin() + (long)per_call.size() / 2,
                         per_call.end());
        return per_call[per_call.size() / 2];
    }

    double facing_variant(const sv_facing_variant &f) {
        const int nt = m.s.num_triangles();
        return time([](int) {},
                    [&](int l) {
                        f.calculate_facing(m.s.planes.data(), nt, &m.lights[(size_t)l],
                                           facing_aligned.data());
                        return std::memcmp(facing_aligned.data(), ref[(size_t)l].facing.data(),
                                           (size_t)nt + 1) == 0;
                    });
    }
    double cull_variant(const sv_facing_variant &f) {
        const int nv = m.s.num_vertices();
        return time([](int) {},
                    [&](int l) {
                        const int inside = f.calculate_cull_bits(m.positions4.data(), nv, &m.bounds,
                                                                 m.boxes[(size_t)l].data(),
                                                                 cull.data());
                        const Reference &x = ref[(size_t)l];
                        return inside == x.cull_inside &&
                               (inside || std::memcmp(cull.data(), x.cull.data(), (size_t)nv) == 0);
                    });
    }
    double kernel(const sv_variant &v, sv_routine r) {
        const int nt = m.s.num_triangles();
        uint8_t *fa = facing_aligned.data();
        switch (r) {
        case SV_ROUTINE_COUNT_FACING:
            return time([&](int l) { std::memcpy(fa, ref[(size_t)l].facing.data(), (size_t)nt + 1); },
                        [&](int l) { return v.count_facing(fa, nt) == ref[(size_t)l].count; });
        case SV_ROUTINE_COUNT_FACING_CULL:
            return time([&](int l) { std::memcpy(fa, ref[(size_t)l].facing.data(), (size_t)nt + 1); },
                        [&](int l) {
                            const Reference &x = ref[(size_t)l];
                            return v.count_facing_cull(fa, nt, m.s.indices.data(), x.cull.data()) ==
                                       x.count_cull &&
                                   std::memcmp(fa, x.culled_facing.data(), (size_t)nt) == 0;
                        });
        case SV_ROUTINE_CREATE_SIL_TRIANGLES:
            return time([](int) {},
                        [&](int l) {
                            const Reference &x = ref[(size_t)l];
                            const int n = v.create_sil_triangles(out.data(), x.facing.data(),
                                                                 m.s.sil_edges.data(),
                                                                 m.s.num_sil_edges());
                            return n == (int)x.sil.size() &&
                                   std::memcmp(out.data(), x.sil.data(), sizeof(int) * x.sil.size()) == 0;
                        });
        case SV_ROUTINE_CREATE_CAP_TRIANGLES:
            return time([&](int l) { std::memcpy(fa, ref[(size_t)l].facing.data(), (size_t)nt + 1); },
                        [&](int l) {
                            const Reference &x = ref[(size_t)l];
                            const int n = v.create_cap_triangles(out.data(), fa, m.s.indices.data(),
                                                                 m.s.num_indices());
                            return n == (int)x.cap.size() &&
                                   std::memcmp(out.data(), x.cap.data(), sizeof(int) * x.cap.size()) == 0;
                        });
        default: return 0;
        }
    }
};

} // namespace

extern "C" {

const char *sv_routine_name(sv_routine r) {
    return (int)r >= 0 && r < SV_NUM_ROUTINES ? kRoutineNames[r] : nullptr;
}

int sv_size_class(int numTriangles) {
    int c = 0;
    while (c < SV_NUM_SIZE_CLASSES - 1 && numTriangles >= kClassLimit[c]) c++;
    return c;
}

int sv_size_class_triangles(int sizeClass) {
    return sizeClass >= 0 && sizeClass < SV_NUM_SIZE_CLASSES ? kClassTriangles[sizeClass] : 0;
}

} // extern "C"

namespace {

/* Every runnable variant of every routine timed on M, the winners (the
 * static choice kept within the margin) installed as SIZECLASS's measured
 * plan. As sv_plan_measure returns. */
int measure_mesh(const Mesh &m, int sizeClass, sv_plan_timing *timings, int maxTimings) {
    /* About the same work per class: 1 M triangle-calls per variant. */
    const int rounds = std::max(3, std::min(61, (1 << 20) / (kLights * m.s.num_triangles())));
    Measurer meas(m, rounds);
    const char *best[SV_NUM_ROUTINES] = {};
    double best_ticks[SV_NUM_ROUTINES];
    int taken = 0;
    double static_ticks[SV_NUM_ROUTINES] = {};
    auto record = [&](sv_routine r, const char *name, double t) {
        if (timings && taken < maxTimings) timings[taken] = {sizeClass, r, name, t};
        taken++;
        if (std::strcmp(name, sv_static_variant_name(r)) == 0) static_ticks[r] = t;
        if (!best[r] || t < best_ticks[r]) best[r] = name, best_ticks[r] = t;
    };
    int nf = 0;
    const sv_facing_variant *fv = sv_facing_variants(&nf);
    for (int i = 0; i < nf; i++) {
        if (!runs(fv[i].isa)) continue;
        record(SV_ROUTINE_CALCULATE_FACING, fv[i].name, meas.facing_variant(fv[i]));
        record(SV_ROUTINE_CALCULATE_CULL_BITS, fv[i].name, meas.cull_variant(fv[i]));
    }
    int nv = 0;
    const sv_variant *v = sv_variants(&nv);
    for (int i = 0; i < nv; i++) {
        if (!runs(v[i].isa)) continue;
        for (int r = SV_ROUTINE_COUNT_FACING; r < SV_NUM_ROUTINES; r++) {
            record((sv_routine)r, v[i].name, meas.kernel(v[i], (sv_routine)r));
        }
    }
    if (meas.failed) return -1;
    /* The static choice stays unless beaten by more than the margin. */
    for (int r = 0; r < SV_NUM_ROUTINES; r++) {
        const double t = static_ticks[r];
        if (best[r] && t > 0 && t <= best_ticks[r] * kStaticMargin) {
            best[r] = sv_static_variant_name((sv_routine)r), best_ticks[r] = t;
        }
    }
    svplan::install(sizeClass, svplan::make_plan(sizeClass, "measured", best, best_ticks), 3);
    return taken;
}

} // namespace

extern "C" {

int sv_plan_measure(int sizeClass, sv_plan_timing *timings, int maxTimings) {
    if (sizeClass < 0 || sizeClass >= SV_NUM_SIZE_CLASSES) return -1;
    return measure_mesh(make_mesh(kClassTriangles[sizeClass]), sizeClass, timings, maxTimings);
}

int sv_plan_measure_surface(const sv_surface *surface, sv_plan_timing *timings, int maxTimings) {
    /* The contracts of sv_shadow_volume_for_light (minus alignment, which
     * the copy gives), checked before anything else is read: a surface
     * the kernels cannot take makes no plan, and non-finite planes or
     * positions would make the variants' comparisons with c_ref, not the
     * variants, decide the result. */
    constexpr int kBadSurface = -2;
    if (!surface) return kBadSurface;
    const sv_surface &v = *surface;
    if (v.numIndices < 3 || v.numIndices % 3 != 0 || v.numSilEdges < 0 || v.numVerts <= 0 ||
        v.numVerts > (1 << 30) || 6ll * v.numSilEdges + 2ll * v.numIndices > INT_MAX ||
        !v.planes || !v.indices || !v.positions || (v.numSilEdges > 0 && !v.silEdges)) {
        return kBadSurface;
    }
    const int nt = v.numIndices / 3;
    for (int i = 0; i < v.numIndices; i++) {
        if (v.indices[i] < 0 || v.indices[i] >= v.numVerts) return kBadSurface;
    }
    for (int e = 0; e < v.numSilEdges; e++) {
        const SilEdge &x = v.silEdges[e];
        if (x.p1 < 0 || x.p1 > nt || x.p2 < 0 || x.p2 > nt || x.v1 < 0 || x.v2 < 0 ||
            (x.v1 & 1) || (x.v2 & 1) || x.v1 / 2 >= v.numVerts || x.v2 / 2 >= v.numVerts) {
            return kBadSurface;
        }
    }
    for (int t = 0; t < nt; t++) {
        const Plane &q = v.planes[t];
        if (!std::isfinite(q.a) || !std::isfinite(q.b) || !std::isfinite(q.c) || !std::isfinite(q.d)) {
            return kBadSurface;
        }
    }
    for (int i = 0; i < v.numVerts; i++) {
        const Vec4 &q = v.positions[i];
        if (!std::isfinite(q.x) || !std::isfinite(q.y) || !std::isfinite(q.z)) return kBadSurface;
    }
    return measure_mesh(copy_mesh(v), sv_size_class(nt), timings, maxTimings);
}

const char *sv_static_variant_name(sv_routine r) {
    if ((int)r < 0 || r >= SV_NUM_ROUTINES) return nullptr;
    return r <= SV_ROUTINE_CALCULATE_CULL_BITS ? sv_best_facing_variant()->name
                                               : sv_best_variant()->name;
}

const sv_plan *sv_plan_for(int numTriangles, unsigned flags) {
    const int c = sv_size_class(numTriangles);
    State &s = state();
    int kind;
    {
        std::lock_guard<std::mutex> g(s.lock);
        kind = s.kind[(size_t)c];
        /* A plan made before the ISA limit was lowered (sv_set_isa_limit)
         * may name kernels the limit no longer allows: start the class
         * again. */
        const sv_plan *p = s.plan[(size_t)c];
        if (kind && !(runs(p->kernels.isa) &&
                      svplan::variant_runs_routine(p->variant[SV_ROUTINE_CALCULATE_FACING],
                                                   SV_ROUTINE_CALCULATE_FACING) &&
                      svplan::variant_runs_routine(p->variant[SV_ROUTINE_CALCULATE_CULL_BITS],
                                                   SV_ROUTINE_CALCULATE_CULL_BITS))) {
            s.kind[(size_t)c] = kind = 0;
        }
    }
    if (kind < 2 && (flags & SV_PLAN_MEASURE)) {
        if (sv_plan_measure(c, nullptr, 0) >= 0) kind = 3;
    }
    if (kind == 0) {
        svplan::install(c, svplan::builtin_plan(c), 1);
    }
    std::lock_guard<std::mutex> g(s.lock);
    return s.plan[(size_t)c];
}

void sv_plan_reset(void) {
    State &s = state();
    std::lock_guard<std::mutex> g(s.lock);
    s.kind.fill(0);
}

} // extern "C"
