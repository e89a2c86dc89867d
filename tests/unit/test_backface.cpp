// Seed 001's view back-face culling: the non-compact method bit for bit
// against a C reference written here; every compact method bit for bit
// against the scalar compact one (front bytes, count, vertex bits) on every
// count from 0 (tails, padding lanes filled with would-be front-facing
// garbage); the compact decision within fixed16's error bound of the exact
// predicate on every model; vertex bits exactly those of the front-facing
// triangles; the caller's MXCSR without effect; bad input.
//
// Copyright (C) 2026 the shadowvol authors. LGPL-2.1-or-later.
#include <gtest/gtest.h>

#include <xmmintrin.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <vector>

#include "model_surfaces.h"
#include "shadowvol_accuracy.h"
#include "shadowvol_backface.h"
#include "test_support.h"

using svtest::Rng;

namespace {

struct Result {
    int count = -1;
    std::vector<uint8_t> front;
    std::vector<uint32_t> bits;
    bool operator==(const Result &o) const {
        return count == o.count && front == o.front && bits == o.bits;
    }
};

std::size_t words(int nv) { return ((std::size_t)nv + 31) / 32; }

// The non-compact listing, written out again: TN = (P w - V) . N, left to
// right in float, front when TN <= 0 (this file is built without
// contraction).
template <class Triangles> Result reference_noncompact(const Triangles &t, int nv, const Vec4 &v) {
    Result r;
    r.count = 0;
    r.front.resize(t.size());
    r.bits.assign(words(nv), 0);
    for (std::size_t i = 0; i < t.size(); i++) {
        const float tx = t[i].px * v.w - v.x, ty = t[i].py * v.w - v.y, tz = t[i].pz * v.w - v.z;
        const float tn = tx * t[i].nx + ty * t[i].ny + tz * t[i].nz;
        r.front[i] = tn <= 0.0f;
        if (r.front[i]) {
            r.count++;
            for (uint16_t x : {t[i].v1, t[i].v2, t[i].v3}) r.bits[x >> 5] |= 1u << (x & 31);
        }
    }
    return r;
}

// Bits and count as they must follow from front bytes and the indices.
void expect_consistent(const Result &r, const int *indices, int nt, int nv) {
    std::vector<uint32_t> want(words(nv), 0);
    int count = 0;
    for (int t = 0; t < nt; t++) {
        if (!r.front[(std::size_t)t]) continue;
        count++;
        for (int k = 0; k < 3; k++) {
            const int x = indices[3 * t + k];
            want[(std::size_t)x >> 5] |= 1u << (x & 31);
        }
    }
    EXPECT_EQ(r.count, count);
    EXPECT_EQ(r.bits, want);
}

// Runs F with guard words after the bit array (which must survive) and
// filled with garbage before (which must be cleared).
template <class F> Result run(F f, int nt, int nv) {
    Result r;
    r.front.assign((std::size_t)nt, 0x55);
    std::vector<uint32_t> bits(words(nv) + 4, 0xDEADBEEF);
    r.count = f(bits.data(), r.front.data());
    for (std::size_t k = words(nv); k < bits.size(); k++) EXPECT_EQ(bits[k], 0xDEADBEEFu);
    bits.resize(words(nv));
    r.bits = bits;
    return r;
}

// The block methods this ctest entry checks (svtest::in_this_run; asked
// in each test, which is what marks it as one that loops over variants).
std::vector<const sv::BackfaceBlockVariant *> runnable_block_variants() {
    std::vector<const sv::BackfaceBlockVariant *> r;
    for (const sv::BackfaceBlockVariant &b : sv::backface_block_variants()) {
        if (svtest::in_this_run(b.isa, b.name)) r.push_back(&b);
    }
    return r;
}

// Every method on one surface and view: the non-compact one against the
// reference, the block ones against the scalar compact one, all
// consistent. Returns the compact result.
Result check_all(const sv::PreparedSurface &s, const sv::AlignedVector<sv_cull_triangle> &t32,
                 const sv::AlignedVector<sv_cull_triangle16> &t16,
                 const sv::AlignedVector<sv_cull_block4> &blocks, const Vec4 &view) {
    const int nt = s.num_triangles(), nv = s.num_vertices();
    const Result nc =
        run([&](uint32_t *b,
                uint8_t *f) { return sv_backface_noncompact(t32.data(), nt, nv, &view, b, f); },
            nt, nv);
    EXPECT_TRUE(nc == reference_noncompact(t32, nv, view));
    expect_consistent(nc, s.indices.data(), nt, nv);
    const Result c =
        run([&](uint32_t *b,
                uint8_t *f) { return sv_backface_compact(t16.data(), nt, nv, &view, b, f); },
            nt, nv);
    expect_consistent(c, s.indices.data(), nt, nv);
    for (const sv::BackfaceBlockVariant *v : runnable_block_variants()) {
        const Result r = run([&](uint32_t *b,
                                 uint8_t *f) { return v->fn(blocks.data(), nt, nv, &view, b, f); },
                             nt, nv);
        EXPECT_TRUE(r == c) << v->name;
        // Without the front bytes (the benchmark's call): the same count and bits.
        std::vector<uint32_t> bits(words(nv), 0xFFFFFFFF);
        EXPECT_EQ(v->fn(blocks.data(), nt, nv, &view, bits.data(), nullptr), c.count) << v->name;
        EXPECT_EQ(bits, c.bits) << v->name;
    }
    return c;
}

Vec4 random_view(Rng &rng, const Bounds &b) {
    const float r = std::max({b.extents.x, b.extents.y, b.extents.z, 1e-3f});
    const double dist = std::pow(10.0, 4 * rng.unit()) * 0.5; /* 0.5 to 5000 radii */
    double d[3], len = 0;
    for (double &c : d) {
        c = 2 * rng.unit() - 1;
        len += c * c;
    }
    len = std::sqrt(len) + 1e-12;
    if (rng.chance(0.2))
        return Vec4{(float)(d[0] / len), (float)(d[1] / len), (float)(d[2] / len), 0};
    return Vec4{b.center.x + (float)(dist * r * d[0] / len),
                b.center.y + (float)(dist * r * d[1] / len),
                b.center.z + (float)(dist * r * d[2] / len), 1};
}

// Once per model set (bundled, SharedModels: tests/support/model_surfaces.h).
class BackfaceModels : public ::testing::TestWithParam<std::string> {};
INSTANTIATE_TEST_SUITE_P(ModelSets, BackfaceModels, ::testing::ValuesIn(svtest::model_sets()),
                         svtest::param_name);

SV_TIERED_TEST_P(BackfaceModels, EveryModelEveryMethodAndTheBound) {
    Rng rng = svtest::rng_for("Backface.Models");
    SCOPED_TRACE(svtest::seed_trace());
    long decided = 0, uncertain = 0, wrong_in_band = 0;
    for (const std::string &path : svtest::seed_model_paths(GetParam())) {
        for (const sv::PreparedSurface &s : svtest::prepared_surfaces(path)) {
            SCOPED_TRACE(path);
            const sv::AlignedVector<sv_cull_triangle> t32v = sv::cull_triangles(s);
            const sv::AlignedVector<sv_cull_triangle16> t16 = sv::cull_triangles16(s);
            const sv::AlignedVector<sv_cull_block4> blocks = sv::cull_blocks(s);
            std::vector<sv::TriangleErrorModel> em;
            for (int t = 0; t < s.num_triangles(); t++) {
                em.push_back(
                    sv::triangle_error_model(&s.positions[3 * (std::size_t)s.indices[3 * t]],
                                             &s.positions[3 * (std::size_t)s.indices[3 * t + 1]],
                                             &s.positions[3 * (std::size_t)s.indices[3 * t + 2]]));
            }
            const Bounds b = sv::surface_bounds(s);
            const int views = s.num_triangles() > 20000 ? 3 : 12;
            for (int i = 0; i < views; i++) {
                Vec4 view = random_view(rng, b);
                if (i == 0 && s.num_triangles() > 0) {
                    // On a triangle's plane (a grazing view): the band where
                    // the bound promises nothing.
                    const int t = (int)rng.below((uint32_t)s.num_triangles());
                    const float *p = &s.positions[3 * (std::size_t)s.indices[3 * t]];
                    view = Vec4{p[0], p[1], p[2], 1};
                }
                const Result c = check_all(s, t32v, t16, blocks, view);
                // The compact decision is the exact one wherever |D| > B.
                for (int t = 0; t < s.num_triangles(); t++) {
                    const float *p0 = &s.positions[3 * (std::size_t)s.indices[3 * t]];
                    const float *p1 = &s.positions[3 * (std::size_t)s.indices[3 * t + 1]];
                    const float *p2 = &s.positions[3 * (std::size_t)s.indices[3 * t + 2]];
                    const double D = sv::exact_signed_distance(p0, p1, p2, view);
                    const double B = sv::facing_error_bound(sv::FacingArithmetic::fixed16,
                                                            em[(std::size_t)t], view);
                    if (std::fabs(D) > B) {
                        decided++;
                        ASSERT_EQ(c.front[(std::size_t)t], D > 0 ? 1 : 0)
                            << "triangle " << t << " D " << D << " bound " << B;
                    } else {
                        uncertain++;
                        wrong_in_band += c.front[(std::size_t)t] != (D >= 0);
                    }
                }
            }
        }
    }
    EXPECT_GT(decided, 0);
    std::printf("[  NOTE    ] compact: %ld decisions outside the bound (all exact), %ld within "
                "it (%ld of them differ from the exact D >= 0)\n",
                decided, uncertain, wrong_in_band);
}

// Random data, every count: NaN, inf, zero normals, huge tn; the last
// block's padding lanes hold would-be front-facing garbage that must not
// count. The block methods equal the scalar compact one; the non-compact
// one equals its reference.
SV_TIERED_TEST(Backface, EveryCountAndPaddingLanes) {
    Rng rng = svtest::rng_for("Backface.Counts");
    SCOPED_TRACE(svtest::seed_trace());
    const float specials[] = {0.0f, -0.0f, NAN, INFINITY, -INFINITY, 1e30f, -1e30f, 1e-40f};
    for (int n = 0; n <= 200; n++) {
        const int nv = 1 + (int)rng.below(300);
        std::vector<sv_cull_triangle16> t16((std::size_t)n);
        std::vector<sv_cull_triangle> t32((std::size_t)n);
        std::vector<int> idx;
        for (int t = 0; t < n; t++) {
            sv_cull_triangle16 &c = t16[(std::size_t)t];
            auto comp = [&] { return (int16_t)((int)rng.below(65535) - 32767); };
            c.nx = rng.chance(0.05) ? 0 : comp();
            c.ny = comp();
            c.nz = comp();
            c.tn = rng.chance(0.1) ? specials[rng.below(8)] : (float)(rng.unit() * 4 - 2);
            if (t % 7 == 3) {
                // Ties: a zero normal makes s = -tn * w exactly, so s = +0,
                // -0, or a NaN of either sign. The scalar test (s >= 0:
                // both zeros front-facing, NaN not) must hold in every
                // lane (erratum B1-3: the seed's SIMD listing tested sign
                // bits instead).
                const float ties[] = {0.0f, -0.0f, NAN, -NAN};
                c.nx = c.ny = c.nz = 0;
                c.tn = ties[rng.below(4)];
            }
            c.v1 = (uint16_t)rng.below((uint32_t)nv);
            c.v2 = (uint16_t)rng.below((uint32_t)nv);
            c.v3 = (uint16_t)rng.below((uint32_t)nv);
            idx.insert(idx.end(), {c.v1, c.v2, c.v3});
            t32[(std::size_t)t] = sv_cull_triangle{(float)rng.unit(),
                                                   (float)rng.unit(),
                                                   (float)rng.unit(),
                                                   c.nx / 32767.0f,
                                                   c.ny / 32767.0f,
                                                   c.nz / 32767.0f,
                                                   c.v1,
                                                   c.v2,
                                                   c.v3,
                                                   0};
            if (rng.chance(0.05)) t32[(std::size_t)t].px = specials[rng.below(8)];
        }
        // The blocks (sv::cull_blocks transposes; a wrong transpose shows
        // as a difference from the scalar method), then padding that would
        // be front-facing if counted.
        sv::AlignedVector<sv_cull_block4> blocks = sv::cull_blocks(t16.data(), t16.size());
        for (int t = n; t < 4 * (int)blocks.size(); t++) {
            sv_cull_block4 &b = blocks[(std::size_t)t / 4];
            b.tn[t % 4] = -1e30f;
            b.nx[t % 4] = b.ny[t % 4] = b.nz[t % 4] = 0;
            b.v[t % 4][0] = b.v[t % 4][1] = b.v[t % 4][2] = 0;
        }
        for (int rep = 0; rep < 3; rep++) {
            const Vec4 view{(float)(rng.unit() * 200 - 100), (float)(rng.unit() * 200 - 100),
                            (float)(rng.unit() * 200 - 100), rep == 2 ? 0.0f : 1.0f};
            SCOPED_TRACE("n " + std::to_string(n) + " rep " + std::to_string(rep));
            const Result nc = run(
                [&](uint32_t *b, uint8_t *f) {
                    return sv_backface_noncompact(t32.data(), n, nv, &view, b, f);
                },
                n, nv);
            EXPECT_TRUE(nc == reference_noncompact(t32, nv, view));
            const Result c =
                run([&](uint32_t *b,
                        uint8_t *f) { return sv_backface_compact(t16.data(), n, nv, &view, b, f); },
                    n, nv);
            expect_consistent(c, idx.data(), n, nv);
            for (const sv::BackfaceBlockVariant *v : runnable_block_variants()) {
                const Result r =
                    run([&](uint32_t *b,
                            uint8_t *f) { return v->fn(blocks.data(), n, nv, &view, b, f); },
                        n, nv);
                EXPECT_TRUE(r == c) << v->name;
            }
        }
    }
}

// The caller's FTZ/DAZ and rounding mode change nothing: subnormal views
// and normals' products.
SV_TIERED_TEST(Backface, CallerMxcsrHasNoEffect) {
    Rng rng = svtest::rng_for("Backface.Mxcsr");
    sv::AlignedVector<sv_cull_block4> blocks(64);
    std::vector<sv_cull_triangle16> t16(256);
    for (int t = 0; t < 256; t++) {
        sv_cull_block4 &b = blocks[(std::size_t)t / 4];
        b.tn[t % 4] = t16[(std::size_t)t].tn = (float)(rng.unit() - 0.5) * 1e-38f;
        b.nx[t % 4] = t16[(std::size_t)t].nx = (int16_t)((int)rng.below(201) - 100);
    }
    const Vec4 view{1e-36f, 0, 0, 1};
    std::vector<uint8_t> want(256), got(256);
    const int n0 = sv_backface_compact(t16.data(), 256, 0, &view, nullptr, want.data());
    const unsigned saved = _mm_getcsr();
    _mm_setcsr(saved | 0x8040u | 0x6000u); /* FTZ, DAZ, round toward zero */
    const int n1 = sv_backface_compact(t16.data(), 256, 0, &view, nullptr, got.data());
    std::vector<std::pair<const char *, std::vector<uint8_t>>> simd;
    for (const sv::BackfaceBlockVariant *v : runnable_block_variants()) {
        std::vector<uint8_t> f(256);
        v->fn(blocks.data(), 256, 0, &view, nullptr, f.data());
        simd.push_back({v->name, f});
    }
    const unsigned inside = _mm_getcsr();
    _mm_setcsr(saved);
    EXPECT_EQ(inside & ~0x3Fu, (saved | 0x8040u | 0x6000u) & ~0x3Fu); /* restored to the caller's */
    EXPECT_EQ(n0, n1);
    EXPECT_EQ(want, got);
    for (auto &s : simd) EXPECT_EQ(s.second, want) << s.first;
    // Subnormal products are what the test exercises: some triangle must
    // be decided by them.
    EXPECT_GT(n0, 0);
    EXPECT_LT(n0, 256);
}

SV_TIERED_TEST(Backface, BadInput) {
    // More than 65536 vertices: the 16-bit layouts refuse, unless the
    // vertex numbers are dropped (the decision alone).
    std::vector<float> pos;
    std::vector<uint32_t> idx;
    for (uint32_t v = 0; v < 65537 + 2; v++)
        pos.insert(pos.end(), {(float)v, (float)(v % 7), (float)(v % 3)});
    idx.insert(idx.end(), {0u, 1u, 65538u});
    const sv::PreparedSurface s = sv::prepare_surface(pos.data(), pos.size() / 3, idx.data(),
                                                      idx.size());
    EXPECT_THROW(sv::cull_triangles(s), sv::BackfaceError);
    EXPECT_THROW(sv::cull_triangles16(s), sv::BackfaceError);
    EXPECT_THROW(sv::cull_blocks(s), sv::BackfaceError);
    const auto b = sv::cull_blocks(s, false);
    ASSERT_EQ(b.size(), 1u);
    EXPECT_EQ(b[0].v[0][2], 0);
    // A negative count writes nothing and returns 0.
    uint32_t bits[2] = {7, 7};
    uint8_t front[2] = {9, 9};
    const Vec4 view{0, 0, 1, 1};
    EXPECT_EQ(sv_backface_noncompact(nullptr, -1, 40, &view, bits, front), 0);
    EXPECT_EQ(sv_backface_compact(nullptr, -5, 40, &view, bits, front), 0);
    for (const sv::BackfaceBlockVariant *v : runnable_block_variants()) {
        EXPECT_EQ(v->fn(nullptr, -1, 40, &view, bits, front), 0) << v->name;
    }
    EXPECT_EQ(bits[0], 7u);
    EXPECT_EQ(front[0], 9);
    // No triangles: the bits are cleared, the count is 0.
    for (const sv::BackfaceBlockVariant *v : runnable_block_variants()) {
        bits[0] = bits[1] = 7;
        EXPECT_EQ(v->fn(nullptr, 0, 40, &view, bits, nullptr), 0) << v->name;
        EXPECT_EQ(bits[0], 0u);
        EXPECT_EQ(bits[1], 0u);
    }
}

} // namespace
