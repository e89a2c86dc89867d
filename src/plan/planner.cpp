/*
 * Dispatch by measurement (include/shadowvol_plan.h): the plans, how a
 * class is measured, and where a plan comes from.
 *
 * Measuring a class: the generated character subdivided to the class's
 * size (or, sv_plan_measure_surface, the caller's own surface), prepared
 * by sv::prepare_surface, lit by 8 point lights on a ring around it, each
 * with a cube around it that leaves a quarter of the triangles outside
 * (the cull bits). Every runnable variant of each routine is a task; the
 * tasks run in rounds, each task's calls on the 8 lights back to back per
 * round; each call's result is compared with c_ref's on the same light (a
 * plan is never built from a variant that computes something else); a
 * task's figure is the lowest of its round medians. Each class gets at
 * least 5 rounds and about 1 M triangle-calls per task.
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
#include <functional>
#include <mutex>
#include <string>
#include <vector>

#include "plan_internal.h"
#include "../core/contracts_internal.h"
#include "model_gen.h"
#include "shadowvol_mesh.h"

namespace {

const char *const kRoutineNames[SV_NUM_ROUTINES] = {"calculate_facing",     "calculate_cull_bits",
                                                    "count_facing",         "count_facing_cull",
                                                    "create_sil_triangles", "create_cap_triangles"};

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
/* ... and in this many of every 5 rounds (see measure_mesh). */
constexpr int kWinRounds = 4;
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
    const sv_facing_variant *fb = sv_facing_variant_by_name(
        p.variant[SV_ROUTINE_CALCULATE_CULL_BITS]);
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

/* The light box of LIGHT on M: a cube around the light, planes pointing
 * in, its half size bisected so that a quarter of the triangles lie
 * outside it (all three vertices culled), as the benchmark's light
 * volumes are chosen (bench/harness/lights.cpp). The culling kernels' cost
 * depends on how many triangles they cull and in what pattern: a box
 * between the mesh and the light that held part of the mesh was used
 * first, and there c_ref's branchy CountFacingCull tied the avx2 one,
 * which the scaling run then measured 23% faster at 979776 triangles. */
std::array<Plane, SV_NUM_LIGHT_PLANES> light_box(const Mesh &m, const Vec4 &light, float r) {
    auto box = [&](double h) {
        const float x = light.x, y = light.y, z = light.z, hf = (float)h;
        return std::array<Plane, SV_NUM_LIGHT_PLANES>{
            Plane{1, 0, 0, -(x - hf)}, Plane{-1, 0, 0, x + hf},   Plane{0, 1, 0, -(y - hf)},
            Plane{0, -1, 0, y + hf},   Plane{0, 0, 1, -(z - hf)}, Plane{0, 0, -1, z + hf}};
    };
    const int nv = m.s.num_vertices(), nt = m.s.num_triangles();
    std::vector<uint8_t> bits((size_t)nv);
    auto culled = [&](double h) {
        const auto planes = box(h);
        if (sv_calculate_cull_bits_c_ref(m.positions4.data(), nv, &m.bounds, planes.data(),
                                         bits.data())) {
            return 0; /* the whole surface inside */
        }
        int n = 0;
        const int *i = m.s.indices.data();
        for (int t = 0; t < nt; t++, i += 3)
            n += (bits[(size_t)i[0]] & bits[(size_t)i[1]] & bits[(size_t)i[2]]) != 0;
        return n;
    };
    /* The light is 2r from the centre: a half size of 4r holds the mesh. */
    double lo = 0, hi = 4.0 * r;
    const int target = nt / 4;
    for (int k = 0; k < 14; k++) { /* to r / 4096: a few triangles of the target */
        const double mid = 0.5 * (lo + hi);
        (culled(mid) > target ? lo : hi) = mid;
    }
    return box(hi);
}

/* The lights and light boxes of M, from its bounds (set here). */
void light_mesh(Mesh &m) {
    m.positions4 = sv::positions_vec4(m.s);
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
        m.boxes[(size_t)l] = light_box(m, light, r);
    }
}

/* The mesh a class is measured on: the project's generated character
 * (tools/generate_models, the paper's 1344-triangle stand-in), each quad
 * subdivided n x n to the class's size, lit from around it. A height field
 * lit from low above was used first: its facing regions are large and
 * only a few percent of its SilEdges lie on the silhouette, where the
 * AVX2 silhouette and cap kernels (scalar, branchy) win, and the plans
 * made from it were 10-30% slower than the static choice on the
 * character and the real models (scaling run, AMD Zen 5). */
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
            x.sil.resize((size_t)sv_create_sil_triangles_c_ref(x.sil.data(), x.facing.data(),
                                                               m.s.sil_edges.data(),
                                                               m.s.num_sil_edges()));
            x.cap.resize(2 * (size_t)m.s.num_indices() + 1);
            x.cap.resize((size_t)sv_create_cap_triangles_c_ref(x.cap.data(), x.facing.data(),
                                                               m.s.indices.data(),
                                                               m.s.num_indices()));
        }
    }

    /* One (routine, variant) to time: PREPARE sets a call's input up
     * outside the timed region; CALL returns whether its result matched
     * c_ref's. */
    struct Task {
        std::function<void(int)> prepare;
        std::function<bool(int)> call;
        std::vector<double> ticks;
    };
    std::vector<Task> tasks;

    template <class Prepare, class Call> int time(const Prepare &prepare, const Call &call) {
        tasks.push_back(Task{prepare, call, {}});
        return (int)tasks.size() - 1;
    }

    /* Every task's calls, in rounds: per round, each task's calls on the
     * 8 lights back to back (the first warms its code and data, as in a
     * loop over lights), the tasks in an order that rotates per round.
     * Timed one variant after another instead, a shared machine's slow
     * phase (a second or more, seen on KVM guests) lands on whichever
     * variant runs then, and the plan follows it: the class-3 plan once
     * took c_ref's CountFacingCull, 23% slower than avx2's in the same
     * scaling run. In rounds, a phase hits a block of every task and the
     * median over the rounds passes over it. Interleaving single calls
     * was tried too: each call then finds its code and data evicted by
     * the other variants', and a call took up to twice what it takes in
     * a loop, which ranks the kernels by a cost no user loop pays. */
    void run() {
        const size_t n = tasks.size();
        for (Task &t : tasks) t.ticks.reserve((size_t)rounds * kLights);
        for (int round = 0; round < rounds; round++) {
            for (size_t k = 0; k < n; k++) {
                Task &t = tasks[((size_t)round + k) % n];
                for (int l = 0; l < kLights; l++) {
                    t.prepare(l);
                    const uint64_t t0 = ticks_now();
                    const bool ok = t.call(l);
                    const uint64_t t1 = ticks_now();
                    if (!ok) failed = true;
                    t.ticks.push_back((double)(t1 - t0));
                }
            }
        }
    }

    /* Task I's median call in each round, in round order. */
    std::vector<double> round_medians(int i) const {
        const std::vector<double> &v = tasks[(size_t)i].ticks;
        std::vector<double> medians;
        for (size_t r = 0; r + kLights <= v.size(); r += kLights) {
            std::array<double, kLights> round;
            std::copy(v.begin() + (long)r, v.begin() + (long)r + kLights, round.begin());
            std::nth_element(round.begin(), round.begin() + kLights / 2, round.end());
            medians.push_back(round[kLights / 2]);
        }
        return medians;
    }
    /* Task I's figure: the lowest of its round medians (the statistic of
     * the cycle table and the scaling run, whose rows keep their lowest
     * round median): a slow phase over some rounds moves the overall
     * median, not the lowest round. */
    double figure(int i) const {
        const std::vector<double> r = round_medians(i);
        return *std::min_element(r.begin(), r.end());
    }

    int facing_variant(const sv_facing_variant &f) {
        const int nt = m.s.num_triangles();
        return time([](int) {},
                    [=](int l) {
                        f.calculate_facing(m.s.planes.data(), nt, &m.lights[(size_t)l],
                                           facing_aligned.data());
                        return std::memcmp(facing_aligned.data(), ref[(size_t)l].facing.data(),
                                           (size_t)nt + 1) == 0;
                    });
    }
    int cull_variant(const sv_facing_variant &f) {
        const int nv = m.s.num_vertices();
        return time([](int) {},
                    [=](int l) {
                        const int inside = f.calculate_cull_bits(m.positions4.data(), nv, &m.bounds,
                                                                 m.boxes[(size_t)l].data(),
                                                                 cull.data());
                        const Reference &x = ref[(size_t)l];
                        return inside == x.cull_inside &&
                               (inside || std::memcmp(cull.data(), x.cull.data(), (size_t)nv) == 0);
                    });
    }
    int kernel(const sv_variant &v, sv_routine r) {
        const int nt = m.s.num_triangles();
        uint8_t *fa = facing_aligned.data();
        switch (r) {
        case SV_ROUTINE_COUNT_FACING:
            return time(
                [=](int l) { std::memcpy(fa, ref[(size_t)l].facing.data(), (size_t)nt + 1); },
                [=](int l) { return v.count_facing(fa, nt) == ref[(size_t)l].count; });
        case SV_ROUTINE_COUNT_FACING_CULL:
            return time(
                [=](int l) { std::memcpy(fa, ref[(size_t)l].facing.data(), (size_t)nt + 1); },
                [=](int l) {
                    const Reference &x = ref[(size_t)l];
                    return v.count_facing_cull(fa, nt, m.s.indices.data(), x.cull.data()) ==
                               x.count_cull &&
                           std::memcmp(fa, x.culled_facing.data(), (size_t)nt) == 0;
                });
        case SV_ROUTINE_CREATE_SIL_TRIANGLES:
            return time([](int) {},
                        [=](int l) {
                            const Reference &x = ref[(size_t)l];
                            const int n = v.create_sil_triangles(out.data(), x.facing.data(),
                                                                 m.s.sil_edges.data(),
                                                                 m.s.num_sil_edges());
                            return n == (int)x.sil.size() &&
                                   std::memcmp(out.data(), x.sil.data(),
                                               sizeof(int) * x.sil.size()) == 0;
                        });
        case SV_ROUTINE_CREATE_CAP_TRIANGLES:
            return time(
                [=](int l) { std::memcpy(fa, ref[(size_t)l].facing.data(), (size_t)nt + 1); },
                [=](int l) {
                    const Reference &x = ref[(size_t)l];
                    const int n = v.create_cap_triangles(out.data(), fa, m.s.indices.data(),
                                                         m.s.num_indices());
                    return n == (int)x.cap.size() &&
                           std::memcmp(out.data(), x.cap.data(), sizeof(int) * x.cap.size()) == 0;
                });
        default: return -1;
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
    const int rounds = std::max(5, std::min(61, (1 << 20) / (kLights * m.s.num_triangles())));
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
    struct Timed {
        sv_routine routine;
        const char *name;
        int task;
    };
    std::vector<Timed> timed;
    int nf = 0;
    const sv_facing_variant *fv = sv_facing_variants(&nf);
    for (int i = 0; i < nf; i++) {
        if (!runs(fv[i].isa)) continue;
        timed.push_back({SV_ROUTINE_CALCULATE_FACING, fv[i].name, meas.facing_variant(fv[i])});
        timed.push_back({SV_ROUTINE_CALCULATE_CULL_BITS, fv[i].name, meas.cull_variant(fv[i])});
    }
    int nv = 0;
    const sv_variant *v = sv_variants(&nv);
    for (int i = 0; i < nv; i++) {
        if (!runs(v[i].isa)) continue;
        for (int r = SV_ROUTINE_COUNT_FACING; r < SV_NUM_ROUTINES; r++) {
            timed.push_back({(sv_routine)r, v[i].name, meas.kernel(v[i], (sv_routine)r)});
        }
    }
    meas.run();
    if (meas.failed) return -1;
    int task_of[SV_NUM_ROUTINES][2] = {}; /* the best's and the static choice's task */
    for (const Timed &t : timed) {
        record(t.routine, t.name, meas.figure(t.task));
        if (best[t.routine] == t.name) task_of[t.routine][0] = t.task;
        if (std::strcmp(t.name, sv_static_variant_name(t.routine)) == 0)
            task_of[t.routine][1] = t.task;
    }
    /* The static choice stays unless beaten by more than the margin, and
     * beaten round by round: in at least kWinRounds of every 5 rounds the
     * other variant's median is below the static one's of the SAME round
     * by the margin. The two ran in the same round, seconds apart at
     * most, so a paired comparison cancels the machine's slow phases that
     * a lucky lowest round does not (one tune run on a KVM guest took the
     * SSE2 CalculateFacing at class 3, 1.24x "faster" than avx2, which
     * the scaling run then measured slower). */
    for (int r = 0; r < SV_NUM_ROUTINES; r++) {
        const double t = static_ticks[r];
        if (!best[r] || !(t > 0)) continue;
        bool displaces = t > best_ticks[r] * kStaticMargin;
        if (displaces) {
            const std::vector<double> b = meas.round_medians(task_of[r][0]);
            const std::vector<double> st = meas.round_medians(task_of[r][1]);
            size_t wins = 0;
            for (size_t k = 0; k < b.size() && k < st.size(); k++)
                wins += b[k] * kStaticMargin < st[k];
            displaces = 5 * wins >= (size_t)kWinRounds * b.size();
        }
        if (!displaces) best[r] = sv_static_variant_name((sv_routine)r), best_ticks[r] = t;
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
        v.numVerts > (1 << 30) || 6ll * v.numSilEdges + 2ll * v.numIndices > INT_MAX || !v.planes ||
        !v.indices || !v.positions || (v.numSilEdges > 0 && !v.silEdges)) {
        return kBadSurface;
    }
    const int nt = v.numIndices / 3;
    if (sv_check_vertex_indices(v.indices, v.numIndices, v.numVerts) != SV_OK ||
        sv_check_sil_edges(v.silEdges, v.numSilEdges, nt, v.numVerts) != SV_OK) {
        return kBadSurface;
    }
    for (int t = 0; t < nt; t++) {
        const Plane &q = v.planes[t];
        if (!std::isfinite(q.a) || !std::isfinite(q.b) || !std::isfinite(q.c) ||
            !std::isfinite(q.d)) {
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
    svplan::reset_deform_choices();
    svplan::reset_stencil_choice();
    State &s = state();
    std::lock_guard<std::mutex> g(s.lock);
    s.kind.fill(0);
}

} // extern "C"
