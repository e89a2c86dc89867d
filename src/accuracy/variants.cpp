/*
 * The table of measured facing variants (accuracy_variants.h).
 *
 * Copyright (C) 2026 the shadowvol authors. LGPL-2.1-or-later.
 */
#include "accuracy_variants.h"

namespace sv {
namespace acc {

SurfaceData make_surface_data(const PreparedSurface &s, const float center[3], float radius) {
    SurfaceData d;
    d.surface = &s;
    d.planes_d = double_planes(s);
    d.planes16 = fixed16_planes(s);
    d.cull16 = cull_triangles16(s, false);
    d.cull_blocks = cull_blocks(s, false);
    d.eps_distance = kEpsBiasDistanceRadii * radius;
    d.eps_angle = kEpsBiasAngle;
    for (int i = 0; i < 3; i++) d.center[i] = center[i];
    return d;
}

namespace {

/* The reference's planes through one of appendix A's implementations. */
template <sv_calculate_facing_fn F>
int run_planes(const SurfaceData &d, const Vec4 &l, const uint8_t *, uint8_t *facing) {
    F(d.surface->planes.data(), d.surface->num_triangles(), &l, facing);
    return 0;
}

template <void (*F)(const PlaneD *, int, const Vec4 *, uint8_t *)>
int run_double(const SurfaceData &d, const Vec4 &l, const uint8_t *, uint8_t *facing) {
    F(d.planes_d.data(), d.surface->num_triangles(), &l, facing);
    return 0;
}

template <void (*F)(const sv_plane16_block *, int, const Vec4 *, uint8_t *)>
int run_fixed16(const SurfaceData &d, const Vec4 &l, const uint8_t *, uint8_t *facing) {
    F(d.planes16.data(), d.surface->num_triangles(), &l, facing);
    return 0;
}

template <int (*F)(const float *, const int *, int, const Vec4 *, uint8_t *)>
int run_exact(const SurfaceData &d, const Vec4 &l, const uint8_t *, uint8_t *facing) {
    return F(d.surface->positions.data(), d.surface->indices.data(), d.surface->num_triangles(), &l,
             facing);
}

/* Seed 001's view culling with the light as the viewer: its front-facing
 * decision (s >= 0, fixed16's s) as the facing byte. It differs from
 * fixed16's s > 0 only where s is exactly 0, so fixed16's bound holds;
 * the vertex bits are not computed (the study compares decisions). */
int run_cull_compact(const SurfaceData &d, const Vec4 &l, const uint8_t *, uint8_t *facing) {
    const int nt = d.surface->num_triangles();
    sv_backface_compact(d.cull16.data(), nt, 0, &l, nullptr, facing);
    facing[nt] = 1;
    return 0;
}

template <sv_backface_blocks_fn F>
int run_cull_blocks(const SurfaceData &d, const Vec4 &l, const uint8_t *, uint8_t *facing) {
    const int nt = d.surface->num_triangles();
    F(d.cull_blocks.data(), nt, 0, &l, nullptr, facing);
    facing[nt] = 1;
    return 0;
}

/* The threshold is part of the timed work: a renderer computes it per
 * light too. */
int run_eps_bias(const SurfaceData &d, const Vec4 &l, const uint8_t *previous, uint8_t *facing) {
    const float t = sv_eps_bias_threshold(d.eps_distance, d.eps_angle, d.center, &l);
    sv_calculate_facing_eps_bias(d.surface->planes.data(), d.surface->num_triangles(), &l, t,
                                 previous, facing);
    return 0;
}

unsigned facing_isa(const char *name) {
    const sv_facing_variant *v = sv_facing_variant_by_name(name);
    return v ? v->isa : ~0u;
}

constexpr unsigned kAvx2 = SV_ISA_SSE2 | SV_ISA_AVX2;

std::vector<Variant> build() {
    using A = FacingArithmetic;
    std::vector<Variant> v;
    v.push_back({"c_ref", SV_ISA_NONE, Contract::bounded, A::float_planes, nullptr, "c_ref",
                 "appendix A: float planes, float dot product (the paper's C)",
                 run_planes<sv_calculate_facing_c_ref>});
    /* sv_facing_variants' SIMD implementations: bit-identical to c_ref. */
    v.push_back({"c_ref_sse2", facing_isa("sse2"), Contract::same_as, A::float_planes, "c_ref",
                 "c_ref", "appendix A in SSE2 (sv_facing_variants: sse2)",
                 run_planes<sv_calculate_facing_sse2>});
    v.push_back({"c_ref_avx2", facing_isa("avx2"), Contract::same_as, A::float_planes, "c_ref",
                 "c_ref", "appendix A in AVX2 (sv_facing_variants: avx2)",
                 run_planes<sv_calculate_facing_avx2>});
    v.push_back({"c_ref_avx512", facing_isa("avx512"), Contract::same_as, A::float_planes, "c_ref",
                 "c_ref", "appendix A in AVX-512 (sv_facing_variants: avx512)",
                 run_planes<sv_calculate_facing_avx512>});
    v.push_back({"fma", SV_ISA_NONE, Contract::bounded, A::float_planes_fma, nullptr, "fma",
                 "float planes, dot product as three fmaf", run_planes<sv_calculate_facing_fma>});
    v.push_back({"fma_avx2", kAvx2, Contract::same_as, A::float_planes_fma, "fma", "fma",
                 "fma, eight planes per step (AVX2 + FMA)",
                 run_planes<sv_calculate_facing_fma_avx2>});
    v.push_back({"double", SV_ISA_NONE, Contract::bounded, A::double_planes, nullptr, "double",
                 "double planes (32 bytes), double dot product",
                 run_double<sv_calculate_facing_double>});
    v.push_back({"double_avx2", kAvx2, Contract::same_as, A::double_planes, "double", "double",
                 "double, four planes per vector (AVX2)",
                 run_double<sv_calculate_facing_double_avx2>});
    v.push_back({"fixed16", SV_ISA_NONE, Contract::bounded, A::fixed16, nullptr, "fixed16",
                 "seed 001: int16 normals + float tn, 10 bytes per triangle",
                 run_fixed16<sv_calculate_facing_fixed16>});
    v.push_back({"fixed16_avx2", kAvx2, Contract::same_as, A::fixed16, "fixed16", "fixed16",
                 "fixed16, eight triangles per block (AVX2)",
                 run_fixed16<sv_calculate_facing_fixed16_avx2>});
    v.push_back({"fixed16_avx2_prefetch", kAvx2, Contract::same_as, A::fixed16, "fixed16",
                 "fixed16", "fixed16_avx2 with prefetcht0 four blocks ahead",
                 run_fixed16<sv_calculate_facing_fixed16_avx2_prefetch>});
    v.push_back(
        {"cull_compact", SV_ISA_NONE, Contract::bounded, A::fixed16, nullptr, "cull_compact",
         "seed 001's view culling, 16-byte triangles: front = fixed16's s >= 0", run_cull_compact});
    v.push_back({"cull_compact_sse2", SV_ISA_SSE2, Contract::same_as, A::fixed16, "cull_compact",
                 "cull_compact", "seed 001's compact SIMD: 4 per step (SSE2)",
                 run_cull_blocks<sv_backface_compact_sse2>});
    v.push_back({"cull_compact_sse2_prefetch", SV_ISA_SSE2, Contract::same_as, A::fixed16,
                 "cull_compact", "cull_compact", "cull_compact_sse2 with prefetcht0 1 KiB ahead",
                 run_cull_blocks<sv_backface_compact_sse2_prefetch>});
    v.push_back({"cull_compact_avx2", kAvx2, Contract::same_as, A::fixed16, "cull_compact",
                 "cull_compact", "compact view culling, 8 per step (AVX2)",
                 run_cull_blocks<sv_backface_compact_avx2>});
    v.push_back({"cull_compact_avx512", kAvx2 | SV_ISA_AVX512, Contract::same_as, A::fixed16,
                 "cull_compact", "cull_compact", "compact view culling, 16 per step (AVX-512)",
                 run_cull_blocks<sv_backface_compact_avx512>});
    v.push_back({"eps_bias", SV_ISA_NONE, Contract::biased, A::float_planes, nullptr, "eps_bias",
                 "c_ref's s > threshold (1e-5 radius + 1e-5 rad band)", run_eps_bias});
    v.push_back({"exact", SV_ISA_NONE, Contract::exact, A::float_planes, nullptr, "exact",
                 "exact orientation: double filter + expansion arithmetic",
                 run_exact<sv_calculate_facing_exact>});
    v.push_back({"exact_avx2", kAvx2, Contract::same_as, A::float_planes, "exact", "exact",
                 "exact, the filter four triangles at a time (AVX2)",
                 run_exact<sv_calculate_facing_exact_avx2>});
    return v;
}

} // namespace

const std::vector<Variant> &variants() {
    static const std::vector<Variant> v = build();
    return v;
}

const Variant *variant_by_name(const std::string &name) {
    for (const Variant &v : variants()) {
        if (name == v.name) return &v;
    }
    return nullptr;
}

bool runnable(const Variant &v) { return (v.isa & sv_cpu_isa()) == v.isa; }

} // namespace acc
} // namespace sv
