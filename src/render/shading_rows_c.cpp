/*
 * The lighting pass's row kernel in plain C++: the reference of
 * shading_rows.h, one pixel at a time.
 *
 * Copyright (C) 2026 the shadowvol authors. LGPL-2.1-or-later.
 */
#include <cmath>
#include <cstddef>

#include "shading_rows.h"
#include "shading_terms.h"

namespace sv::render::detail {

void shade_row_c(const ShadeRowInputs &row) {
    for (int px = 0; px < row.width; px++) {
        uint8_t *out = row.rgb + 3 * (std::size_t)px;
        const int32_t id = row.ids[px];
        if (id < 0) {
            if (row.last_group) out[0] = row.sky[0], out[1] = row.sky[1], out[2] = row.sky[2];
            continue;
        }
        const ShadeTriangle &tri = row.triangles[id];
        /* The camera ray through the pixel's centre meets the triangle's
         * plane (visible_point). */
        const double nx = row.column_nx[px];
        double dir[3], p[3];
        for (int k = 0; k < 3; k++)
            dir[k] = row.forward[k] + (row.right[k] * nx + row.up[k] * row.ny);
        const double den = dot3(tri.n, dir);
        const double t = den != 0 ? tri.numerator / den : 0;
        for (int k = 0; k < 3; k++) p[k] = row.eye[k] + dir[k] * t;
        /* The radiance: from the sweep before (in ACCUM) or the ambient
         * term; back to ACCUM for the sweep after. */
        double acc[3];
        auto saved = [&](int c) { return row.accum + (std::size_t)c * row.accum_stride + px; };
        if (row.first_group) {
            double base = row.ambient;
            if (tri.ground) base *= checker_odd(p[0], p[2]) ? 0.9 : 1.0;
            acc[0] = acc[1] = acc[2] = base;
        } else {
            for (int c = 0; c < 3; c++) acc[c] = *saved(c);
        }
        const double to_eye[3] = {row.eye[0] - p[0], row.eye[1] - p[1], row.eye[2] - p[2]};
        if (dot3(tri.normal, to_eye) > 0) {
            for (int li = 0; li < row.num_lights; li++) {
                if (row.stencil[li][px] != 0 || !((tri.facing_bits >> li) & 1)) continue;
                const double en = irradiance(row.lights[li], p, tri.normal, row.divider_lanes);
                for (int c = 0; c < 3; c++) acc[c] += en * row.lights[li].color[c];
            }
        }
        if (row.last_group) {
            const double *albedo = row.albedo + 3 * (std::size_t)tri.surface;
            for (int c = 0; c < 3; c++) out[c] = row.display[display_index(acc[c] * albedo[c])];
        } else {
            for (int c = 0; c < 3; c++) *saved(c) = acc[c];
        }
    }
}

} // namespace sv::render::detail
