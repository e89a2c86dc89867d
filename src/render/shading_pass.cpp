/*
 * The shading pass of shading_pass.h: per frame the terms of every
 * triangle and light (shading_rows.h), then each row of pixels through
 * the row kernel of the frame's ISA, one band of rows per task.
 *
 * Copyright (C) 2026 the shadowvol authors. LGPL-2.1-or-later.
 */
#include "shading_pass.h"

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <cmath>
#include <vector>

#include "frame_math.h"
#include "pass_bins.h"
#include "shading_rows.h"
#include "shading_terms.h"
#include "shadowvol.h"

namespace sv::render {

using namespace detail;

namespace {

/* Lights per group: the width of ShadeTriangle::facing_bits. A frame with
 * more lights shades in several sweeps, adding each group's light to the
 * accumulators of the one before. */
constexpr int kLightGroup = 64;

ShadeLight shade_light(const SceneLight &light) {
    ShadeLight l{};
    l.kind = light.kind == LightKind::point ? 0 : light.kind == LightKind::spot ? 1 : 2;
    l.has_range = light.range > 0;
    l.position[0] = light.position.x, l.position[1] = light.position.y,
    l.position[2] = light.position.z;
    l.direction[0] = light.direction.x, l.direction[1] = light.direction.y,
    l.direction[2] = light.direction.z;
    for (int c = 0; c < 3; c++) l.color[c] = light.color[(std::size_t)c];
    l.intensity = light.intensity;
    l.inv_range2 = light.range > 0 ? 1.0 / (light.range * light.range) : 0;
    l.cos_outer = std::cos(light.outer_degrees * kPi / 180.0);
    l.cos_inner = std::cos(light.inner_degrees * kPi / 180.0);
    l.has_soft_cone = l.cos_inner > l.cos_outer;
    l.dark_cos2 = l.kind == 1 && l.cos_outer > 1e-6 ? l.cos_outer * l.cos_outer * (1 - 1e-9) : 0;
    return l;
}

/* Linear radiance to an 8-bit display value: a soft shoulder 1 - e^-1.2x
 * (so several lights overlapping do not wash out one light's shadow) and
 * gamma 2.2, through a table of 1/kDisplaySteps steps up to kDisplayMax
 * (a pow and an exp per channel and pixel were most of the lighting pass). */
const std::vector<uint8_t> &display_table() {
    static const std::vector<uint8_t> table = [] {
        /* 3 bytes more than the entries, read (never used) by the AVX-512
         * row kernel's 4-byte gathers. */
        std::vector<uint8_t> t((std::size_t)kDisplaySteps * kDisplayMax + 1 + 3, 0);
        for (int i = 0; i <= kDisplaySteps * kDisplayMax; i++) {
            const double v = 1.0 - std::exp(-1.2 * i / kDisplaySteps);
            t[(std::size_t)i] = (uint8_t)std::lround(255.0 * std::pow(v, 1.0 / 2.2));
        }
        return t;
    }();
    return table;
}

/* The sky's colour (the row kernels look surfaces up by display_index). */
uint8_t to_display8(double linear) { return display_table()[display_index(linear)]; }

/* Every triangle's terms for this frame, indexed by its id, with the
 * facing bits of lights [FIRST_LIGHT, FIRST_LIGHT + 64). */
void triangle_terms(const Scene &scene, const Frame &f,
                    const std::vector<const uint8_t *> &lit_facing, int first_light,
                    std::vector<ShadeTriangle> &out) {
    const int num_surfaces = (int)scene.surfaces.size();
    const int num_lights = std::min(kLightGroup, (int)f.lights.size() - first_light);
    std::size_t total = 0;
    for (const SceneSurface &s : scene.surfaces) total += (std::size_t)s.prepared.num_triangles();
    out.resize(total);
    for (int si = 0; si < num_surfaces; si++) {
        const PreparedSurface &p = scene.surfaces[(std::size_t)si].prepared;
        const bool ground = scene.surfaces[(std::size_t)si].ground;
        const int first_id = f.surface_first_id[(std::size_t)si];
        tbb::parallel_for(
            tbb::blocked_range<int>(0, p.num_triangles(), 4096),
            [&](const tbb::blocked_range<int> &r) {
                for (int t = r.begin(); t != r.end(); t++) {
                    ShadeTriangle &st = out[(std::size_t)first_id + (std::size_t)t];
                    const int *tri = &p.indices[3 * (std::size_t)t];
                    /* visible_point's arithmetic, once per triangle. */
                    const Vec3d a = vertex(p, tri[0]);
                    const Vec3d n = cross(sub(vertex(p, tri[1]), a), sub(vertex(p, tri[2]), a));
                    st.n[0] = n.x, st.n[1] = n.y, st.n[2] = n.z;
                    st.numerator = dot(n, sub(a, f.camera.eye));
                    const Plane &pl = p.planes[(std::size_t)t];
                    st.normal[0] = pl.a, st.normal[1] = pl.b, st.normal[2] = pl.c;
                    uint64_t bits = 0;
                    for (int li = 0; li < num_lights; li++) {
                        const uint8_t *facing =
                            lit_facing[(std::size_t)(first_light + li) * num_surfaces + si];
                        if (facing && facing[(std::size_t)t]) bits |= uint64_t{1} << li;
                    }
                    st.facing_bits = bits;
                    st.surface = si;
                    st.ground = ground ? 1 : 0;
                }
            });
    }
}

} // namespace

uint8_t display_byte(double linear) { return to_display8(linear); }

ShadingResult shading_pass(const Scene &scene, const Frame &f,
                           const std::vector<const uint8_t *> &lit_facing, double ambient,
                           unsigned isa, std::vector<ShadeTriangle> &triangles) {
    ShadingResult result;
    const uint64_t k0 = ticks();
    const int width = f.width, height = f.height;
    const int num_lights = (int)f.lights.size();
    const std::size_t padded = ((std::size_t)width + 3) & ~std::size_t{3};
    result.rgb.assign((std::size_t)width * height * 3, 0);
    const ShadeRowKernel kernel = (isa & SV_ISA_AVX512) != 0 ? shade_row_avx512
                                  : (isa & SV_ISA_AVX2) != 0 ? shade_row_avx2
                                                             : shade_row_c;

    std::vector<double> column_nx(padded, 0.0);
    for (int px = 0; px < width; px++) column_nx[(std::size_t)px] = ((px + 0.5) / width) * 2 - 1;
    std::vector<double> albedo(3 * scene.surfaces.size());
    for (std::size_t si = 0; si < scene.surfaces.size(); si++) {
        for (int c = 0; c < 3; c++)
            albedo[3 * si + (std::size_t)c] = scene.surfaces[si].albedo[(std::size_t)c];
    }
    std::vector<ShadeLight> lights;
    lights.reserve((std::size_t)num_lights);
    for (const LightFrame &lf : f.lights) lights.push_back(shade_light(lf.light));
    const uint8_t *display = display_table().data();

    /* Per band: the radiance accumulators between groups of lights. */
    std::vector<std::vector<double>> accum((std::size_t)band_count(height));
    std::vector<uint64_t> divider_lanes((std::size_t)band_count(height), 0);
    const int groups = std::max(1, (num_lights + kLightGroup - 1) / kLightGroup);
    for (int g = 0; g < groups; g++) {
        const int first_light = g * kLightGroup;
        const int group_lights = std::min(kLightGroup, num_lights - first_light);
        triangle_terms(scene, f, lit_facing, first_light, triangles);
        parallel(band_count(height), [&](int b) {
            const raster::RowBand band = band_rows(b, height);
            std::vector<double> &acc = accum[(std::size_t)b];
            if (groups > 1) acc.resize(3 * padded * (std::size_t)kBandRows);
            std::vector<const uint8_t *> stencil_rows((std::size_t)std::max(group_lights, 0));
            ShadeRowInputs row;
            row.width = width;
            row.column_nx = column_nx.data();
            const Vec3d eye = f.camera.eye;
            row.eye[0] = eye.x, row.eye[1] = eye.y, row.eye[2] = eye.z;
            row.forward[0] = f.ray_forward.x, row.forward[1] = f.ray_forward.y,
            row.forward[2] = f.ray_forward.z;
            row.right[0] = f.ray_right.x, row.right[1] = f.ray_right.y,
            row.right[2] = f.ray_right.z;
            row.up[0] = f.ray_up.x, row.up[1] = f.ray_up.y, row.up[2] = f.ray_up.z;
            row.triangles = triangles.data();
            row.albedo = albedo.data();
            row.lights = lights.data() + first_light;
            row.num_lights = std::max(group_lights, 0);
            row.stencil = stencil_rows.data();
            row.ambient = ambient;
            row.first_group = g == 0;
            row.last_group = g == groups - 1;
            row.accum_stride = padded;
            row.display = display;
            uint64_t lanes = 0; /* a local: the kernel's rgb stores cannot alias it */
            row.divider_lanes = &lanes;
            for (int py = band.row_begin; py < band.row_end; py++) {
                const std::size_t first = (std::size_t)py * width;
                row.ny = 1 - ((py + 0.5) / height) * 2;
                row.ids = &f.target.ids[first];
                row.accum = groups > 1
                                ? acc.data() + 3 * padded * (std::size_t)(py - band.row_begin)
                                : nullptr;
                for (int li = 0; li < row.num_lights; li++) {
                    stencil_rows[(std::size_t)li] =
                        &f.lights[(std::size_t)first_light + (std::size_t)li].stencil[first];
                }
                const double sky = 0.30 + 0.25 * (1.0 - (double)py / height);
                row.sky[0] = to_display8(sky * 0.55), row.sky[1] = to_display8(sky * 0.65),
                row.sky[2] = to_display8(sky);
                row.rgb = &result.rgb[3 * first];
                kernel(row);
            }
            divider_lanes[(std::size_t)b] += lanes;
        });
    }
    for (const uint64_t n : divider_lanes) result.divider_lanes += n;
    result.ticks = ticks() - k0;
    return result;
}

} // namespace sv::render
