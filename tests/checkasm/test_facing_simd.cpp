// Appendices A and B in SIMD (src/core/x86/facing_simd.c) against the reference C:
// every facing and cull byte bit-identical, for every count 0..200 (every
// tail of every vector width) at every input alignment, with ordinary and
// extreme values (NaN, +-Inf, -0.0, subnormals, FLT_MAX), with and without
// FTZ/DAZ, and nothing written outside the documented bytes.
//
// Copyright (C) 2026 the shadowvol authors. LGPL-2.1-or-later.
#include "test_support.h"

#include <xmmintrin.h>

#include <cfloat>
#include <cmath>
#include <limits>

namespace {

using svtest::checked_call;
using svtest::GuardedBuffer;
using svtest::Rng;

// A float: mostly ordinary, sometimes one of the values where a SIMD
// version could round or compare differently from the C.
float random_float(Rng &rng, bool extremes) {
    if (extremes && rng.chance(0.2)) {
        static const float special[] = {0.0f,
                                        -0.0f,
                                        std::numeric_limits<float>::quiet_NaN(),
                                        std::numeric_limits<float>::infinity(),
                                        -std::numeric_limits<float>::infinity(),
                                        FLT_MAX,
                                        -FLT_MAX,
                                        FLT_MIN,
                                        -FLT_MIN,
                                        std::numeric_limits<float>::denorm_min(),
                                        -std::numeric_limits<float>::denorm_min(),
                                        1e-40f,
                                        3e38f};
        return special[rng.below(sizeof special / sizeof special[0])];
    }
    return (float)(rng.unit() * 4.0 - 2.0);
}

// Runs F with MXCSR's FTZ and DAZ bits set to FTZ_DAZ, then restores MXCSR.
template <class F> void with_ftz_daz(bool ftz_daz, F &&f) {
    const unsigned saved = _mm_getcsr();
    _mm_setcsr(ftz_daz ? (saved | 0x8040u) : (saved & ~0x8040u));
    f();
    _mm_setcsr(saved);
}

// One instance per variant of sv_facing_variants() (c_ref against itself
// included): Variants/FacingSimd.CalculateFacingIsBitIdenticalToTheReference/avx512.
class FacingSimd : public svtest::FacingVariantTest {};

INSTANTIATE_TEST_SUITE_P(Variants, FacingSimd, ::testing::ValuesIn(svtest::facing_variant_names()),
                         svtest::param_name);

TEST_P(FacingSimd, CalculateFacingIsBitIdenticalToTheReference) {
    Rng rng = svtest::rng_for("FacingSimd.CalculateFacing");
    SCOPED_TRACE(svtest::seed_trace());
    for (bool extremes : {false, true}) {
        for (bool ftz : {false, true}) {
            for (int n = 0; n <= 200; n++) {
                if (svtest::stop_after_failures()) return;
                // Planes at a random 4-byte offset from a 64-byte line.
                GuardedBuffer planes_buf(sizeof(Plane) * (size_t)n, 4 * rng.below(16));
                Plane *planes = planes_buf.as<Plane>();
                for (int i = 0; i < n; i++) {
                    planes[i] = {random_float(rng, extremes), random_float(rng, extremes),
                                 random_float(rng, extremes), random_float(rng, extremes)};
                }
                const float w = rng.chance(0.5)   ? 1.0f
                                : rng.chance(0.5) ? 0.0f
                                                  : random_float(rng, extremes);
                const Vec4 light = {random_float(rng, extremes), random_float(rng, extremes),
                                    random_float(rng, extremes), w};
                // Grazing planes: the light within rounding of the plane, so
                // the sign of the sum depends on the order of its additions
                // (a version that adds in another order fails here).
                for (int i = 0; i < n; i++) {
                    if (!rng.chance(0.5)) continue;
                    Plane &p = planes[i];
                    const double partial = (double)p.a * light.x + (double)p.b * light.y;
                    if (light.w != 0.0f) {
                        p.d = (float)(-(partial + (double)p.c * light.z) / light.w);
                    } else if (light.z != 0.0f) {
                        p.c = (float)(-partial / light.z);
                    }
                }
                std::vector<uint8_t> want((size_t)n + 1, 0xEE);
                with_ftz_daz(ftz,
                             [&] { sv_calculate_facing_c_ref(planes, n, &light, want.data()); });
                const size_t out_off = rng.below(64);
                GuardedBuffer out((size_t)n + 1, out_off);
                out.fill(0xEE);
                with_ftz_daz(ftz, [&] {
                    checked_call(abi, v->calculate_facing, planes, n, &light, out.data());
                });
                EXPECT_EQ(std::memcmp(out.data(), want.data(), (size_t)n + 1), 0)
                    << v->name << " n=" << n << " extremes=" << extremes << " ftz=" << ftz;
                EXPECT_TRUE(out.guards_intact()) << v->name << " wrote out of bounds, n=" << n;
                EXPECT_TRUE(planes_buf.guards_intact());
                // The fused twin (sv_calculate_facing_count_*): the same
                // bytes on the same inputs, and their count, under the ABI
                // checker like the unfused form.
                ASSERT_NE(v->calculate_facing_count, nullptr) << v->name;
                GuardedBuffer out2((size_t)n + 1, rng.below(64));
                out2.fill(0xEE);
                int count = -1;
                with_ftz_daz(ftz, [&] {
                    count = checked_call(abi, v->calculate_facing_count, planes, n, &light,
                                         out2.data());
                });
                EXPECT_EQ(std::memcmp(out2.data(), want.data(), (size_t)n + 1), 0)
                    << v->name << " fused, n=" << n << " extremes=" << extremes << " ftz=" << ftz;
                EXPECT_EQ(count, sv_count_facing_c_ref(want.data(), n))
                    << v->name << " fused count, n=" << n << " extremes=" << extremes;
                EXPECT_TRUE(out2.guards_intact())
                    << v->name << " fused wrote out of bounds, n=" << n;
            }
        }
    }
}

TEST_P(FacingSimd, CalculateCullBitsIsBitIdenticalToTheReference) {
    Rng rng = svtest::rng_for("FacingSimd.CalculateCullBits");
    SCOPED_TRACE(svtest::seed_trace());
    int inside = 0, culled = 0;
    for (bool extremes : {false, true}) {
        for (bool ftz : {false, true}) {
            for (int n = 0; n <= 200; n++) {
                if (svtest::stop_after_failures()) return;
                GuardedBuffer pos_buf(sizeof(Vec4) * (size_t)n, 4 * rng.below(16));
                Vec4 *pos = pos_buf.as<Vec4>();
                for (int i = 0; i < n; i++) {
                    pos[i] = {random_float(rng, extremes), random_float(rng, extremes),
                              random_float(rng, extremes), 1.0f};
                }
                // Grazing vertices (set below, once the planes are known).
                const bool grazing = rng.chance(0.5);
                // A light box around a random center: some planes cut the
                // points' box, some leave it entirely in front.
                const float c[3] = {(float)(rng.unit() * 4 - 2), (float)(rng.unit() * 4 - 2),
                                    (float)(rng.unit() * 4 - 2)};
                const float h[3] = {(float)(rng.unit() * 4), (float)(rng.unit() * 4),
                                    (float)(rng.unit() * 4)};
                Plane planes[SV_NUM_LIGHT_PLANES];
                for (int a = 0; a < 3; a++) {
                    float nrm[3] = {0, 0, 0};
                    nrm[a] = 1;
                    planes[2 * a] = {nrm[0], nrm[1], nrm[2], -(c[a] - h[a])};
                    planes[2 * a + 1] = {-nrm[0], -nrm[1], -nrm[2], c[a] + h[a]};
                }
                if (extremes && rng.chance(0.3)) {
                    planes[rng.below(6)] = {random_float(rng, true), random_float(rng, true),
                                            random_float(rng, true), random_float(rng, true)};
                }
                if (grazing) {
                    // Tilted planes, and half the vertices within rounding
                    // of one of them.
                    for (Plane &p : planes) {
                        p.a += (float)(rng.unit() - 0.5);
                        p.b += (float)(rng.unit() - 0.5);
                        p.c += (float)(rng.unit() - 0.5);
                    }
                    for (int i = 0; i < n; i++) {
                        const Plane &p = planes[rng.below(6)];
                        if (!rng.chance(0.5) || p.c == 0.0f) continue;
                        pos[i].z = (float)(-((double)p.a * pos[i].x + (double)p.b * pos[i].y +
                                             (double)p.d) /
                                           p.c);
                    }
                }
                Bounds bounds = {{0, 0, 0, 0}, {2, 2, 2, 0}};
                if (rng.chance(0.3)) bounds = {{c[0], c[1], c[2], 0}, {0.1f, 0.1f, 0.1f, 0}};
                std::vector<uint8_t> want((size_t)n, 0xEE);
                int want_ret = 0;
                with_ftz_daz(ftz, [&] {
                    want_ret = sv_calculate_cull_bits_c_ref(pos, n, &bounds, planes, want.data());
                });
                inside += want_ret;
                for (uint8_t b : want) culled += b != 0 && b != 0xEE;
                const size_t out_off = rng.below(64);
                GuardedBuffer out((size_t)n, out_off);
                out.fill(0xEE);
                int ret = -1;
                with_ftz_daz(ftz, [&] {
                    ret = checked_call(abi, v->calculate_cull_bits, pos, n, &bounds, planes,
                                       out.data());
                });
                EXPECT_EQ(ret, want_ret) << v->name << " n=" << n;
                // Returning 1 leaves cullBits untouched (0xEE stays).
                // (memcmp of 0 bytes still needs valid pointers: an empty
                // vector's data() may be null.)
                EXPECT_TRUE(n == 0 || std::memcmp(out.data(), want.data(), (size_t)n) == 0)
                    << v->name << " n=" << n << " extremes=" << extremes << " ftz=" << ftz;
                EXPECT_TRUE(out.guards_intact()) << v->name << " wrote out of bounds, n=" << n;
            }
        }
    }
    // Both outcomes were exercised.
    EXPECT_GT(inside, 10);
    EXPECT_GT(culled, 1000);
}

TEST_P(FacingSimd, NegativeCountsWriteNothing) {
    const Vec4 light = {1, 2, 3, 1};
    const Bounds b = {{0, 0, 0, 0}, {1, 1, 1, 0}};
    Plane planes[SV_NUM_LIGHT_PLANES] = {};
    GuardedBuffer out(0, 0);
    checked_call(abi, v->calculate_facing, (const Plane *)nullptr, -5, &light, out.data());
    EXPECT_EQ(checked_call(abi, v->calculate_cull_bits, (const Vec4 *)nullptr, -5, &b, planes,
                           out.data()),
              0);
    EXPECT_TRUE(out.guards_intact()) << v->name;
}

TEST(FacingSimdTable, OrderedAndBestIsRunnable) {
    int n = 0;
    const sv_facing_variant *all = sv_facing_variants(&n);
    ASSERT_GE(n, 4);
    EXPECT_STREQ(all[0].name, "c_ref");
    EXPECT_EQ(sv_facing_variant_by_name("avx2"), &all[2]);
    EXPECT_EQ(sv_facing_variant_by_name("nope"), nullptr);
    const sv_facing_variant *best = sv_best_facing_variant();
    EXPECT_EQ(best->isa & sv_cpu_isa(), best->isa);
    // (The variant tests' old "no SIMD variant ran": with SSE2 the best is
    // a SIMD one, so its instances ran.)
    if (sv_cpu_isa() & SV_ISA_SSE2) {
        EXPECT_STRNE(best->name, "c_ref") << "no SIMD variant runs";
    }
}

} // namespace
