// The character-sized workload of `shadowvol check --bench` and its timed
// calls (routine_bench.h).
//
// Copyright (C) 2026 the shadowvol authors. LGPL-2.1-or-later.
#include "routine_bench.h"

#include <algorithm>
#include <cstring>
#include <vector>

#include "check_inputs.h"
#include "shadowvol_mesh.h"
#include "timer.h"

namespace svcheck {

namespace {

constexpr int kWarmup = 16;
constexpr int kCalls = 301;
constexpr int kBatch = 8;

// lfence; rdtsc; lfence on both sides: the cheapest fence that keeps the
// call inside the region on Intel and on AMD Zen 2 and later (timer.h);
// good enough for checkasm's rough figures, and no CPUID trap under a
// hypervisor.
using Tsc = svbench::TscLfence;

double median(std::vector<double> v) {
    std::sort(v.begin(), v.end());
    return v[v.size() / 2];
}

} // namespace

struct BenchWorkload::Data {
    int numVerts = 0;
    std::vector<Plane> planes;
    Vec4 light{};
    std::vector<Vec4> positions;
    Bounds bounds{};
    Plane lightPlanes[SV_NUM_LIGHT_PLANES]{};
    std::vector<int> indices;
    std::vector<SilEdge> edges;
    std::vector<uint8_t> facing; // numTriangles + 1, the sentinel last
    std::vector<uint8_t> cull;
    // The deforming surfaces' inputs: the positions as 3 floats, a skin
    // of 13 joints with 4 influences, outputs, one-pass segments of 256.
    std::vector<float> pos3, matrices, weights, pos_out;
    std::vector<uint16_t> joints;
    std::vector<Plane> plane_out;
    std::vector<size_t> vertex_end;
    std::vector<int> triangle_end;
    // Seed 002's shadow mesh of the same triangles: three vertices a face
    // with its plane's normal, a point light with a range.
    std::vector<float> extrude_stream;
    // The triangles' clusters, for the planes by clusters.
    sv::PlaneClusters clusters;
    std::vector<Vec4> extrude_out;
    sv_extrude_light extrude_light{};
    // Every array a kernel reads or writes, on a 64-byte boundary.
    GuardedBuffer facing_buf, scratch_facing, indices_buf, out, cull_out;
    double overhead = 0;

    explicit Data(uint64_t seed)
        : facing_buf(kTriangles + 1, 0, 0xA5), scratch_facing(kTriangles + 1, 0, 0xA5),
          indices_buf((size_t)3 * kTriangles * sizeof(int), 0, 0xA5),
          out(sv_shadow_volume_capacity(3 * kTriangles, kTriangles * 3 / 2) * sizeof(int), 0, 0xA5),
          cull_out((size_t)kTriangles / 2 + 2, 0, 0xA5) {
        Rng rng(stream_seed(seed, "bench"));
        numVerts = kTriangles / 2 + 2; // a closed mesh's Euler count
        light = {rng.uniform(-5, 5), rng.uniform(-5, 5), rng.uniform(-5, 5), 1.0f};
        planes.resize(kTriangles);
        for (Plane &p : planes) {
            p = {rng.uniform(-1, 1), rng.uniform(-1, 1), rng.uniform(-1, 1), rng.uniform(-1, 1)};
        }
        positions.resize((size_t)numVerts);
        for (Vec4 &v : positions)
            v = {rng.uniform(-1, 1), rng.uniform(-1, 1), rng.uniform(-1, 1), 1};
        bounds.center = {0, 0, 0, 1};
        bounds.extents = {1, 1, 1, 0};
        // Three planes through the box, three clear of it: half the box
        // tests pass, the per-vertex loop runs for the rest.
        for (int i = 0; i < SV_NUM_LIGHT_PLANES; i++) {
            lightPlanes[i] = {i % 3 == 0 ? 1.0f : 0.0f, i % 3 == 1 ? 1.0f : 0.0f,
                              i % 3 == 2 ? 1.0f : 0.0f, i < 3 ? 0.25f : 4.0f};
        }
        indices.resize((size_t)3 * kTriangles);
        for (int &i : indices) i = (int)rng.below((uint32_t)numVerts);
        edges.resize((size_t)kTriangles * 3 / 2);
        for (SilEdge &e : edges) {
            e = {(int)rng.below(kTriangles), (int)rng.below(kTriangles),
                 2 * (int)rng.below((uint32_t)numVerts), 2 * (int)rng.below((uint32_t)numVerts)};
        }
        facing.resize(kTriangles + 1);
        sv_calculate_facing_c_ref(planes.data(), kTriangles, &light, facing.data());
        cull.resize((size_t)numVerts);
        for (auto &c : cull) c = (uint8_t)(rng.chance(0.2) ? 1u << rng.below(6) : 0);
        std::memcpy(facing_buf.data(), facing.data(), facing.size());
        std::memcpy(indices_buf.data(), indices.data(), indices.size() * sizeof(int));
        for (const Vec4 &v : positions) pos3.insert(pos3.end(), {v.x, v.y, v.z});
        matrices.resize(16 * 13);
        for (float &m : matrices) m = rng.uniform(-1, 1);
        for (int i = 0; i < 4 * numVerts; i++) {
            joints.push_back((uint16_t)rng.below(13));
            weights.push_back((float)rng.unit());
        }
        pos_out.resize(pos3.size());
        plane_out.resize(kTriangles);
        const int segs = sv_skin_planes_schedule(indices.data(), kTriangles, (size_t)numVerts, 256,
                                                 nullptr, nullptr, 0);
        vertex_end.resize((size_t)segs);
        triangle_end.resize((size_t)segs);
        sv_skin_planes_schedule(indices.data(), kTriangles, (size_t)numVerts, 256,
                                vertex_end.data(), triangle_end.data(), segs);
        for (int t = 0; t < kTriangles; t++) {
            for (int c = 0; c < 3; c++) {
                const float *p = &pos3[3 * (size_t)indices[3 * (size_t)t + (size_t)c]];
                const Plane &f = planes[(size_t)t];
                extrude_stream.insert(extrude_stream.end(), {p[0], p[1], p[2], f.a, f.b, f.c});
            }
        }
        extrude_out.resize((size_t)3 * kTriangles);
        clusters = sv::plane_clusters(indices.data(), kTriangles, numVerts);
        extrude_light = {light, 20.0f};
        // The fences' cost: an empty region, timed the same way.
        std::vector<double> t(kCalls);
        for (double &x : t) {
            const uint64_t a = Tsc::begin();
            x = (double)(Tsc::end() - a);
        }
        overhead = median(t);
    }

    // Median ticks of one CALL. Where nothing needs putting back, each
    // timed region holds kBatch calls (a routine of a few dozen ticks is
    // otherwise at the counter's resolution, which a hypervisor may make
    // coarse); TIME_WITH_RESET runs RESET untimed before every single call
    // (inputs a routine modifies in place are put back).
    template <class Call> double time_calls(Call call) {
        std::vector<double> t(kCalls);
        for (int i = 0; i < kWarmup; i++) call();
        for (double &x : t) {
            const uint64_t a = Tsc::begin();
            for (int i = 0; i < kBatch; i++) call();
            x = (double)(Tsc::end() - a);
        }
        return std::max(0.0, (median(t) - overhead) / kBatch);
    }
    template <class Reset, class Call> double time_with_reset(Reset reset, Call call) {
        std::vector<double> t(kCalls);
        for (int i = 0; i < kWarmup; i++) {
            reset();
            call();
        }
        for (double &x : t) {
            reset();
            const uint64_t a = Tsc::begin();
            call();
            x = (double)(Tsc::end() - a);
        }
        return std::max(0.0, median(t) - overhead);
    }
};

BenchWorkload::BenchWorkload(uint64_t seed) : d_(new Data(seed)) {}
BenchWorkload::~BenchWorkload() = default;

double BenchWorkload::ticks(Routine routine, const Kernels &k) {
    Data &d = *d_;
    const int n = kTriangles;
    const int ne = (int)d.edges.size();
    const auto restore_facing = [&] {
        std::memcpy(d.scratch_facing.data(), d.facing.data(), d.facing.size());
    };
    // The result goes to a volatile sink, so no call is optimised away.
    volatile int sink = 0;
    switch (routine) {
    case Routine::calculate_facing:
        return d.time_calls(
            [&] { k.calculate_facing(d.planes.data(), n, &d.light, d.scratch_facing.data()); });
    case Routine::calculate_cull_bits:
        return d.time_calls([&] {
            sink = k.calculate_cull_bits(d.positions.data(), d.numVerts, &d.bounds, d.lightPlanes,
                                         d.cull_out.data());
        });
    case Routine::calculate_facing_count:
        return d.time_calls([&] {
            sink = k.calculate_facing_count(d.planes.data(), n, &d.light, d.scratch_facing.data());
        });
    case Routine::count_facing:
        return d.time_calls([&] { sink = k.kernels.count_facing(d.facing_buf.data(), n); });
    case Routine::count_facing_cull:
        return d.time_with_reset(restore_facing, [&] {
            sink = k.kernels.count_facing_cull(d.scratch_facing.data(), n, d.indices_buf.as<int>(),
                                               d.cull.data());
        });
    case Routine::create_sil_triangles:
        return d.time_calls([&] {
            sink = k.kernels.create_sil_triangles(d.out.as<int>(), d.facing_buf.data(),
                                                  d.edges.data(), ne);
        });
    case Routine::create_cap_triangles:
        return d.time_calls([&] {
            sink = k.kernels.create_cap_triangles(d.out.as<int>(), d.facing_buf.data(),
                                                  d.indices_buf.as<int>(), 3 * n);
        });
    case Routine::create_general_sil_triangles: {
        /* A quick look on the same input: its edges as the paper's class
         * (their bytes are 0 or 1, with the sentinel). */
        sv_general_edges e{};
        e.paper = d.edges.data(), e.numPaper = ne;
        return d.time_calls([&] {
            sink = k.general->create_general_sil_triangles(d.out.as<int>(), d.facing_buf.data(),
                                                           &e);
        });
    }
    case Routine::create_general_cap_triangles:
        /* Bytes 0 or 1: the dark triangles cast, the others nothing. */
        return d.time_calls([&] {
            sink = k.general->create_general_cap_triangles(d.out.as<int>(), d.facing_buf.data(),
                                                           d.indices_buf.as<int>(), 3 * n);
        });
    case Routine::derive_planes:
        return d.time_calls([&] {
            k.planes->derive_planes(d.pos3.data(), d.indices.data(), n, d.plane_out.data());
        });
    case Routine::facing_from_positions:
        return d.time_calls([&] {
            k.planes->facing_from_positions(d.pos3.data(), d.indices.data(), n, &d.light,
                                            d.scratch_facing.data());
        });
    case Routine::skinning:
        return d.time_calls([&] {
            k.skin->fn(d.matrices.data(), d.pos3.data(), d.joints.data(), d.weights.data(), 4,
                       (size_t)d.numVerts, d.pos_out.data());
        });
    case Routine::skin_planes: {
        if (!k.skin_planes) return 0;
        sv_skin_planes_args a{};
        a.joint_matrices = d.matrices.data();
        a.rest = d.pos3.data();
        a.joints = d.joints.data();
        a.weights = d.weights.data();
        a.influences = 4;
        a.num_vertices = (size_t)d.numVerts;
        a.indices = d.indices.data();
        a.num_triangles = n;
        a.segments = (int)d.vertex_end.size();
        a.vertex_end = d.vertex_end.data();
        a.triangle_end = d.triangle_end.data();
        a.out = d.pos_out.data();
        a.planes = d.plane_out.data();
        return d.time_calls([&] { k.skin_planes->fn(&a); });
    }
    case Routine::derive_planes_clustered: {
        const sv_plane_clusters view = d.clusters.view();
        return d.time_calls(
            [&] { k.clustered->derive_planes(d.pos3.data(), &view, d.plane_out.data()); });
    }
    case Routine::extrude:
        return d.time_calls([&] {
            k.extrude->extrude(d.extrude_stream.data(), 3 * n, &d.extrude_light,
                               d.extrude_out.data());
        });
    case Routine::shadow_volume:
    case Routine::shadow_volume_cull: {
        const uint8_t *cull = routine == Routine::shadow_volume_cull ? d.cull.data() : nullptr;
        return d.time_with_reset(restore_facing, [&] {
            sink = sv_create_shadow_volume(&k.kernels, d.out.as<int>(), d.indices_buf.as<int>(),
                                           3 * n, d.edges.data(), ne, d.scratch_facing.data(),
                                           cull);
        });
    }
    case Routine::shadow_volume_for_light: {
        // The plan's one call with the light planes; for a variant without
        // a plan (c_ref, the ratio's reference) the paper's pipeline of its
        // kernels: A, B and its decision, the volume.
        const size_t cap = d.out.size() / sizeof(int);
        if (k.plan) {
            const sv_surface surface = {d.planes.data(),
                                        d.indices_buf.as<int>(),
                                        3 * n,
                                        d.edges.data(),
                                        ne,
                                        d.positions.data(),
                                        d.numVerts,
                                        d.bounds};
            return d.time_calls([&] {
                sink = sv_shadow_volume_for_light(k.plan, &surface, &d.light, d.lightPlanes,
                                                  d.out.as<int>(), cap, d.scratch_facing.data(),
                                                  d.cull_out.data());
            });
        }
        return d.time_calls([&] {
            k.calculate_facing(d.planes.data(), n, &d.light, d.scratch_facing.data());
            const int inside = k.calculate_cull_bits(d.positions.data(), d.numVerts, &d.bounds,
                                                     d.lightPlanes, d.cull_out.data());
            sink = sv_create_shadow_volume(&k.kernels, d.out.as<int>(), d.indices_buf.as<int>(),
                                           3 * n, d.edges.data(), ne, d.scratch_facing.data(),
                                           inside ? nullptr : d.cull_out.data());
        });
    }
    }
    (void)sink;
    return 0;
}

} // namespace svcheck
