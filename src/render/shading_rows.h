/*
 * The lighting pass's row kernels (internal to src/render): one row of
 * pixels shaded from per-triangle terms gathered into arrays, in C, in
 * AVX2 (four pixels per step, in double) and in AVX-512 (eight).
 *
 * Every version computes, per pixel and in the same order, the very
 * operations the pass was first written with (visible_point's ray and
 * plane intersection, Lambert with the range window and the spot cone,
 * the display table), each one an IEEE operation rounded the same way in
 * a scalar and in a vector lane (the project builds with
 * -ffp-contract=off): the bytes are the same in every version and at
 * every thread count. The clamps are written as the vector min and max
 * compute them (a NaN goes to the bound), so the C and the SIMD agree on
 * every input; a non-finite radiance shows as black.
 *
 * Copyright (C) 2026 the shadowvol authors. LGPL-2.1-or-later.
 */
#ifndef SV_RENDER_SHADING_ROWS_H
#define SV_RENDER_SHADING_ROWS_H

#include <cstddef>
#include <cstdint>

namespace sv::render::detail {

/* Per triangle of the frame (indexed by its id), worked out once a frame. */
struct ShadeTriangle {
    /* visible_point's plane: n = (b - a) x (c - a), unnormalised, and
     * dot(n, a - eye), so the ray's parameter is numerator / dot(n, dir). */
    double n[3], numerator;
    /* The surface's stored plane normal (unit, float widened): which side
     * is seen and the Lambert term. */
    double normal[3];
    /* Bit L: light L (of the current group of 64) may light the triangle
     * (it faces the light: the facing bytes its volume was built from). */
    uint64_t facing_bits;
    int32_t surface;
    int32_t ground; /* the ground's checker */
};
static_assert(sizeof(ShadeTriangle) == 72, "ShadeTriangle: 8-byte aligned, no hidden padding");

/* A light's constants, worked out once a frame. */
struct ShadeLight {
    int kind; /* 0 point, 1 spot, 2 directional (LightKind's order) */
    int has_range, has_soft_cone;
    double position[3], direction[3];
    double color[3];
    double intensity, inv_range2, cos_outer, cos_inner;
    /* A spot's quick test (cos_outer > 0 only): a point P with
     * d = position - P, n = -dot(d, direction) <= 0 or n^2 <
     * dark_cos2 * dot(d, d) is outside the cone for certain (dark_cos2 is
     * cos_outer^2 shrunk by 1e-9, far beyond the rounding of the cone's own
     * test), so its light is 0 without the square root and divides. 0: no
     * quick test. */
    double dark_cos2;
};

/* A pixel not covered (sky), or a padding lane. */
constexpr uint8_t kShadeSky = 0, kShadeVisible = 1;

/* One row: per pixel the triangle it shows (ids into TRIANGLES) and its
 * lights' stencils. COLUMN_NX holds the width rounded up to 4 values. */
struct ShadeRowInputs {
    int width = 0;
    double ny = 0;                     /* the row's 1 - 2 (py + 0.5) / height */
    const double *column_nx = nullptr; /* per column: 2 (px + 0.5) / width - 1 */
    double eye[3], forward[3], right[3], up[3];
    const int32_t *ids = nullptr; /* the row's triangle ids (-1 sky) */
    const ShadeTriangle *triangles = nullptr;
    const double *albedo = nullptr;     /* per surface, 3 each */
    const ShadeLight *lights = nullptr; /* the current group's (at most 64) */
    int num_lights = 0;
    const uint8_t *const *stencil = nullptr; /* per light of the group: its stencil's row */
    double ambient = 0;
    bool first_group = true, last_group = true;
    /* Linear radiance before the albedo (in and out between groups of
     * lights): red, green and blue planes of ACCUM_STRIDE doubles each;
     * read unless FIRST_GROUP, written unless LAST_GROUP (a frame of one
     * group has none). */
    double *accum = nullptr;
    std::size_t accum_stride = 0;
    const uint8_t *display =
        nullptr; /* to_display's table: kDisplaySteps * kDisplayMax + 1, and 3 readable bytes */
    uint8_t sky[3] = {0, 0, 0}; /* the row's sky colour, displayed */
    uint8_t *rgb = nullptr;     /* the row's output, 3 bytes per pixel */
    /* Added to: the lanes that went through a point or spot light's square
     * root and divides (the C kernel's pixels; a SIMD kernel's whole
     * steps): the divider's work, what bounds the pass. */
    uint64_t *divider_lanes = nullptr;
};

/* Linear radiance to display: a table of 1/kDisplaySteps steps up to
 * kDisplayMax (shading_pass.cpp builds it). */
constexpr int kDisplaySteps = 1024, kDisplayMax = 8;

using ShadeRowKernel = void (*)(const ShadeRowInputs &row);

void shade_row_c(const ShadeRowInputs &row);
void shade_row_avx2(const ShadeRowInputs &row);
void shade_row_avx512(const ShadeRowInputs &row);

} // namespace sv::render::detail

#endif
