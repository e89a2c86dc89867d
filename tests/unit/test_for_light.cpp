// sv_shadow_volume_for_light (one call per light, include/shadowvol_plan.h)
// and the fused CalculateFacing + CountFacing kernels: each against the
// reference pipeline (c_ref's A, B and sv_create_shadow_volume with c_ref),
// byte for byte, on generated open meshes of every size from 0 to 80
// triangles and a few thousand, under point and directional lights, with
// and without a light volume (inside, straddling and outside the surface
// box), at every ISA level this CPU runs, with aligned and misaligned
// buffers.
//
// Copyright (C) 2026 the shadowvol authors. LGPL-2.1-or-later.
#include <gtest/gtest.h>

#include <cstdint>
#include <algorithm>
#include <cstring>
#include <string>
#include <random>
#include <vector>

#include "shadowvol.h"
#include "shadowvol_mesh.h"
#include "shadowvol_plan.h"
#include "test_conditions.h"

namespace {

// A height field of W x H quads, two triangles each, with triangles
// dropped at random (open edges, dangling SilEdges) until TRIANGLES remain.
sv::PreparedSurface height_field(int triangles, std::mt19937 &rng) {
    int w = 1;
    while (2 * w * w < triangles) w++;
    std::uniform_real_distribution<float> height(-0.4f, 0.4f);
    std::vector<float> pos;
    for (int y = 0; y <= w; y++) {
        for (int x = 0; x <= w; x++) {
            pos.push_back((float)x);
            pos.push_back((float)y);
            pos.push_back(height(rng));
        }
    }
    std::vector<uint32_t> idx;
    for (int y = 0; y < w; y++) {
        for (int x = 0; x < w; x++) {
            const uint32_t a = (uint32_t)(y * (w + 1) + x), b = a + 1, c = a + (uint32_t)(w + 1),
                           d = c + 1;
            const uint32_t t[6] = {a, b, d, a, d, c};
            idx.insert(idx.end(), t, t + 6);
        }
    }
    while ((int)idx.size() / 3 > triangles) {
        const size_t t = std::uniform_int_distribution<size_t>(0, idx.size() / 3 - 1)(rng);
        idx.erase(idx.begin() + (long)(3 * t), idx.begin() + (long)(3 * t + 3));
    }
    return sv::prepare_surface(pos.data(), pos.size() / 3, idx.data(), idx.size());
}

struct Mesh {
    sv::PreparedSurface prep;
    std::vector<Vec4> positions;
    sv_surface surface{};
};

Mesh make_mesh(int triangles, std::mt19937 &rng) {
    Mesh m;
    m.prep = height_field(triangles, rng);
    for (int v = 0; v < m.prep.num_vertices(); v++) {
        const float *p = &m.prep.positions[(size_t)3 * v];
        m.positions.push_back(Vec4{p[0], p[1], p[2], 1.0f});
    }
    m.surface.planes = m.prep.planes.data();
    m.surface.indices = m.prep.indices.data();
    m.surface.numIndices = m.prep.num_indices();
    m.surface.silEdges = m.prep.sil_edges.data();
    m.surface.numSilEdges = (int)m.prep.sil_edges.size();
    m.surface.positions = m.positions.data();
    m.surface.numVerts = m.prep.num_vertices();
    m.surface.bounds = sv::surface_bounds(m.prep);
    return m;
}

Vec4 random_light(std::mt19937 &rng) {
    std::uniform_real_distribution<float> u(-3.0f, 12.0f);
    if (rng() % 4 == 0) return Vec4{u(rng) - 4.5f, u(rng) - 4.5f, u(rng), 0.0f};
    return Vec4{u(rng), u(rng), u(rng) * 0.5f, 1.0f};
}

// A light volume: an axis-aligned box (planes pointing inwards) that
// holds the whole surface, part of it, or none of it.
void light_box(const Mesh &m, int kind, std::mt19937 &rng, Plane out[SV_NUM_LIGHT_PLANES]) {
    const Bounds &b = m.surface.bounds;
    float lo[3], hi[3];
    std::uniform_real_distribution<float> u(0.0f, 1.0f);
    for (int a = 0; a < 3; a++) {
        const float c = (&b.center.x)[a], e = (&b.extents.x)[a] + 0.01f;
        if (kind == 0) { // inside: the box test alone decides
            lo[a] = c - 2 * e - 1, hi[a] = c + 2 * e + 1;
        } else if (kind == 1) { // straddling
            lo[a] = c - e * u(rng), hi[a] = c + e * u(rng);
        } else { // outside, beyond one side
            lo[a] = c + 2 * e + 1, hi[a] = c + 3 * e + 2;
        }
    }
    for (int a = 0; a < 3; a++) {
        Plane p{0, 0, 0, 0}, q{0, 0, 0, 0};
        (&p.a)[a] = 1.0f, p.d = -lo[a]; // x >= lo
        (&q.a)[a] = -1.0f, q.d = hi[a]; // x <= hi
        out[2 * a] = p, out[2 * a + 1] = q;
    }
}

// The unfused reference: c_ref's A, B and volume.
int reference_volume(const Mesh &m, const Vec4 &light, const Plane *lightPlanes,
                     std::vector<int> &out) {
    const int nt = m.surface.numIndices / 3;
    std::vector<uint8_t> facing((size_t)nt + 1), cull((size_t)m.surface.numVerts + 1);
    sv_calculate_facing_c_ref(m.surface.planes, nt, &light, facing.data());
    const uint8_t *cb = nullptr;
    if (lightPlanes &&
        sv_calculate_cull_bits_c_ref(m.surface.positions, m.surface.numVerts, &m.surface.bounds,
                                     lightPlanes, cull.data()) == 0) {
        cb = cull.data();
    }
    out.assign(sv_shadow_volume_capacity(m.surface.numIndices, m.surface.numSilEdges), 0);
    return sv_create_shadow_volume(sv_variant_by_name("c_ref"), out.data(), m.surface.indices,
                                   m.surface.numIndices, m.surface.silEdges, m.surface.numSilEdges,
                                   facing.data(), cb);
}

// The ISA levels this ctest entry checks, for sv_set_isa_limit.
std::vector<const char *> isa_levels() {
    std::vector<const char *> levels{"c", "sse2"};
    if (svtest::in_this_run(SV_ISA_SSE2 | SV_ISA_AVX2, "ISA level avx2")) levels.push_back("avx2");
    if (svtest::in_this_run(SV_ISA_SSE2 | SV_ISA_AVX2 | SV_ISA_AVX512, "ISA level avx512"))
        levels.push_back("avx512");
    return levels;
}

struct IsaLimitGuard {
    std::string saved;
    bool had;
    IsaLimitGuard() : had(sv_isa_limit_name() != nullptr) {
        if (had) saved = sv_isa_limit_name();
    }
    ~IsaLimitGuard() {
        sv_set_isa_limit(had ? saved.c_str() : nullptr);
        sv_plan_reset();
    }
};

// Runs the one-call pipeline on M and compares with the reference; OFFSET
// ints / bytes of misalignment on the output and facing buffers.
void expect_same_volume(const Mesh &m, const Vec4 &light, const Plane *lightPlanes, int offset,
                        const char *what, const sv_plan *plan = nullptr) {
    std::vector<int> want;
    const int n_want = reference_volume(m, light, lightPlanes, want);
    const size_t cap = sv_shadow_volume_capacity(m.surface.numIndices, m.surface.numSilEdges);
    const int nt = m.surface.numIndices / 3;
    // Guard words past the capacity: nothing may be written there.
    std::vector<int> out(cap + (size_t)offset + 16, 0x5A5A5A5A);
    std::vector<uint8_t> facing((size_t)nt + 1 + (size_t)offset + 64);
    std::vector<uint8_t> cull((size_t)m.surface.numVerts + 1);
    const int n = sv_shadow_volume_for_light(plan, &m.surface, &light, lightPlanes,
                                             out.data() + offset, cap, facing.data() + offset,
                                             cull.data());
    ASSERT_EQ(n, n_want) << what;
    if (n > 0) { // (memcmp of an empty reference: its data() may be NULL)
        EXPECT_EQ(0, std::memcmp(out.data() + offset, want.data(), sizeof(int) * (size_t)n))
            << what;
    }
    for (size_t i = cap + (size_t)offset; i < out.size(); i++) {
        ASSERT_EQ(out[i], 0x5A5A5A5A) << what << ": wrote past the capacity at " << i;
    }
}

SV_TIERED_TEST(ForLight, SameVolumeAsTheReferenceAtEveryIsaLevelAndSize) {
    IsaLimitGuard guard;
    std::mt19937 rng(20261203);
    std::vector<int> sizes;
    for (int t = 0; t <= 80; t++) sizes.push_back(t);
    for (int t : {127, 128, 129, 255, 256, 1000, 2047, 4099}) sizes.push_back(t);
    std::vector<Mesh> meshes;
    for (int t : sizes) meshes.push_back(make_mesh(t, rng));
    for (const char *level : isa_levels()) {
        ASSERT_EQ(0, sv_set_isa_limit(level));
        sv_plan_reset();
        for (const Mesh &m : meshes) {
            for (int l = 0; l < 4; l++) {
                const Vec4 light = random_light(rng);
                Plane box[SV_NUM_LIGHT_PLANES];
                light_box(m, l % 3, rng, box);
                const std::string what = std::string(level) + ", " +
                                         std::to_string(m.surface.numIndices / 3) +
                                         " triangles, light " + std::to_string(l);
                expect_same_volume(m, light, nullptr, 0, (what + ", no light volume").c_str());
                expect_same_volume(m, light, box, 0, (what + ", light volume").c_str());
                // Misaligned by 1 int / byte: kernels needing alignment are
                // stood in for.
                expect_same_volume(m, light, box, 1, (what + ", misaligned").c_str());
            }
        }
    }
}

TEST(ForLight, MeasuredPlanGivesTheSameVolume) {
    IsaLimitGuard guard;
    sv_plan_reset();
    ASSERT_GE(sv_plan_measure(0, nullptr, 0), 0);
    const sv_plan *p = sv_plan_for(100, SV_PLAN_ESTIMATE);
    EXPECT_STREQ(p->source, "measured");
    std::mt19937 rng(7);
    for (int t : {1, 17, 100, 333, 2000}) {
        const Mesh m = make_mesh(t, rng);
        for (int l = 0; l < 6; l++) {
            Plane box[SV_NUM_LIGHT_PLANES];
            light_box(m, 1, rng, box);
            expect_same_volume(m, random_light(rng), l % 2 ? box : nullptr, 0, "measured plan");
        }
    }
}

SV_TIERED_TEST(ForLight, FusedFacingCountMatchesFacingThenCount) {
    int nf = 0;
    const sv_facing_variant *fv = sv_facing_variants(&nf);
    std::mt19937 rng(99);
    std::uniform_real_distribution<float> u(-1.0f, 1.0f);
    for (int k = 0; k < nf; k++) {
        if (!svtest::in_this_run(fv[k].isa, fv[k].name)) continue;
        ASSERT_NE(fv[k].calculate_facing_count, nullptr) << fv[k].name;
        for (int n = 0; n <= 200; n++) {
            std::vector<Plane> planes((size_t)n);
            for (Plane &p : planes) p = Plane{u(rng), u(rng), u(rng), u(rng)};
            // Some planes the light lies on exactly (sum 0: not facing).
            if (n > 3) planes[(size_t)n / 2] = Plane{0, 0, 0, 0};
            const Vec4 light{u(rng), u(rng), u(rng), 1.0f};
            std::vector<uint8_t> a((size_t)n + 1, 0xEE), b((size_t)n + 1, 0xEE);
            sv_calculate_facing_c_ref(planes.data(), n, &light, a.data());
            const int count = fv[k].calculate_facing_count(planes.data(), n, &light, b.data());
            EXPECT_EQ(a, b) << fv[k].name << ", " << n << " triangles";
            EXPECT_EQ(count, sv_count_facing_c_ref(a.data(), n))
                << fv[k].name << ", " << n << " triangles";
        }
        uint8_t untouched = 0xEE;
        EXPECT_EQ(fv[k].calculate_facing_count(nullptr, -5, nullptr, &untouched), 0);
        EXPECT_EQ(untouched, 0xEE) << fv[k].name << ": a negative count wrote";
    }
}

// A pointer into BUF that is 4 bytes past a 16-byte boundary (BUF has 8
// spare elements of 4 bytes).
template <class T> T *off16(std::vector<T> &buf) {
    static_assert(sizeof(T) == 4, "4-byte elements");
    size_t k = 0;
    while (((uintptr_t)(buf.data() + k) & 15u) != 4u) k++;
    return buf.data() + k;
}

// The surface's input arrays misaligned too: indices 4 bytes past a 16-byte
// boundary (sse2_paper's CreateCapTriangles reads them with movdqa, so its
// stand-in must take over), planes and positions by one float (every
// facing and cull kernel loads them unaligned). At every ISA level, with
// and without a light volume.
SV_TIERED_TEST(ForLight, MisalignedInputArraysGiveTheSameVolume) {
    IsaLimitGuard guard;
    std::mt19937 rng(1515);
    std::vector<Mesh> meshes;
    for (int t : {0, 1, 3, 15, 16, 17, 31, 32, 33, 64, 100, 1000})
        meshes.push_back(make_mesh(t, rng));
    for (const char *level : isa_levels()) {
        ASSERT_EQ(0, sv_set_isa_limit(level));
        sv_plan_reset();
        for (const Mesh &src : meshes) {
            Mesh m = src; // the copy's surface still points at SRC's arrays
            const int nt = m.surface.numIndices / 3;
            std::vector<int> idx((size_t)m.surface.numIndices + 8);
            int *ip = off16(idx);
            std::copy(src.surface.indices, src.surface.indices + m.surface.numIndices, ip);
            std::vector<float> pl(4 * (size_t)nt + 8), ps(4 * (size_t)m.surface.numVerts + 8);
            float *pp = off16(pl), *vp = off16(ps);
            if (nt) std::memcpy(pp, src.surface.planes, sizeof(Plane) * (size_t)nt);
            if (m.surface.numVerts) {
                std::memcpy(vp, src.surface.positions, sizeof(Vec4) * (size_t)m.surface.numVerts);
            }
            m.surface.indices = ip;
            m.surface.planes = reinterpret_cast<const Plane *>(pp);
            m.surface.positions = reinterpret_cast<const Vec4 *>(vp);
            for (int l = 0; l < 3; l++) {
                const Vec4 light = random_light(rng);
                Plane box[SV_NUM_LIGHT_PLANES];
                light_box(m, l, rng, box);
                const std::string what = std::string(level) + ", " + std::to_string(nt) +
                                         " triangles, misaligned inputs, box " + std::to_string(l);
                for (int offset : {0, 1}) {
                    expect_same_volume(m, light, nullptr, offset,
                                       (what + ", no light volume").c_str());
                    expect_same_volume(m, light, box, offset, (what + ", light volume").c_str());
                }
            }
        }
    }
}

// A plan without the fused count (a caller's own sv_plan, or one built
// before the fused kernels): CalculateFacing, then the plan's CountFacing,
// stood in for when the facing bytes are not aligned as it needs
// (sse2_paper's movdqa at the sse2 level).
SV_TIERED_TEST(ForLight, PlanWithoutTheFusedCountGivesTheSameVolume) {
    IsaLimitGuard guard;
    std::mt19937 rng(2626);
    std::vector<Mesh> meshes;
    for (int t : {0, 1, 16, 17, 33, 100, 1000}) meshes.push_back(make_mesh(t, rng));
    for (const char *level : isa_levels()) {
        ASSERT_EQ(0, sv_set_isa_limit(level));
        sv_plan_reset();
        for (const Mesh &m : meshes) {
            sv_plan p = *sv_plan_for(m.surface.numIndices / 3, SV_PLAN_ESTIMATE);
            p.calculate_facing_count = nullptr;
            for (int offset : {0, 1}) {
                const std::string what = std::string(level) + ", " +
                                         std::to_string(m.surface.numIndices / 3) +
                                         " triangles, no fused count, offset " +
                                         std::to_string(offset);
                expect_same_volume(m, random_light(rng), nullptr, offset, what.c_str(), &p);
            }
        }
    }
}

TEST(ForLight, RefusesBadCallsAndWritesNothing) {
    std::mt19937 rng(3);
    const Mesh m = make_mesh(40, rng);
    const size_t cap = sv_shadow_volume_capacity(m.surface.numIndices, m.surface.numSilEdges);
    std::vector<int> out(cap, 0x77);
    std::vector<uint8_t> facing(41), cull((size_t)m.surface.numVerts);
    const Vec4 light{5, 5, 5, 1};
    Plane box[SV_NUM_LIGHT_PLANES];
    light_box(m, 1, rng, box);
    auto call = [&](const sv_surface *s, const Vec4 *l, const Plane *lp, int *o, size_t c,
                    uint8_t *f, uint8_t *cb) {
        return sv_shadow_volume_for_light(nullptr, s, l, lp, o, c, f, cb);
    };
    EXPECT_EQ(call(nullptr, &light, nullptr, out.data(), cap, facing.data(), nullptr), SV_E_NULL);
    EXPECT_EQ(call(&m.surface, nullptr, nullptr, out.data(), cap, facing.data(), nullptr),
              SV_E_NULL);
    EXPECT_EQ(call(&m.surface, &light, nullptr, nullptr, cap, facing.data(), nullptr), SV_E_NULL);
    EXPECT_EQ(call(&m.surface, &light, nullptr, out.data(), cap, nullptr, nullptr), SV_E_NULL);
    EXPECT_EQ(call(&m.surface, &light, box, out.data(), cap, facing.data(), nullptr), SV_E_NULL);
    EXPECT_EQ(call(&m.surface, &light, nullptr, out.data(), cap - 1, facing.data(), nullptr),
              SV_E_CAPACITY);
    sv_surface bad = m.surface;
    bad.numIndices = 5;
    EXPECT_EQ(call(&bad, &light, nullptr, out.data(), cap, facing.data(), nullptr), SV_E_COUNT);
    bad = m.surface;
    bad.numSilEdges = -1;
    EXPECT_EQ(call(&bad, &light, nullptr, out.data(), cap, facing.data(), nullptr), SV_E_COUNT);
    bad = m.surface;
    bad.planes = nullptr;
    EXPECT_EQ(call(&bad, &light, nullptr, out.data(), cap, facing.data(), nullptr), SV_E_NULL);
    bad = m.surface;
    bad.numIndices = 3 * 400000000; // 6 per triangle no longer fits an int
    bad.numSilEdges = 0;
    EXPECT_EQ(call(&bad, &light, nullptr, out.data(), SIZE_MAX, facing.data(), nullptr),
              SV_E_OVERFLOW);
    for (int v : out) ASSERT_EQ(v, 0x77) << "a refused call wrote output";
    // The empty surface casts nothing.
    sv_surface empty{};
    EXPECT_EQ(call(&empty, &light, nullptr, out.data(), 0, facing.data(), nullptr), 0);
    EXPECT_EQ(facing[0], 1); // the sentinel, as CalculateFacing writes it
}

} // namespace
