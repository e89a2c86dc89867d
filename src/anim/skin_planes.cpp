/*
 * Skinning and planes in one pass (include/shadowvol_anim.h): the
 * schedule that cuts a surface into segments, the kernel table, and the
 * call for a posed surface. The kernels and their table are in
 * src/deform/skin_planes_kernels.c.
 *
 * Copyright (C) 2026 the shadowvol authors. LGPL-2.1-or-later.
 */
#include "shadowvol_anim.h"

#include <cstring>
#include <string>

#include "shadowvol_planes.h"

namespace sv {

SkinPlanesSchedule skin_planes_schedule(const int *indices, int num_triangles,
                                        std::size_t num_vertices, int segment_triangles) {
    const int n = sv_skin_planes_schedule(indices, num_triangles, num_vertices, segment_triangles,
                                          nullptr, nullptr, 0);
    if (n == SV_E_INDEX_RANGE) {
        for (long i = 0; i < 3L * num_triangles; i++) {
            if (indices[i] < 0 || static_cast<std::size_t>(indices[i]) >= num_vertices) {
                throw PrepareError("skin_planes_schedule: index " + std::to_string(i) + " is " +
                                   std::to_string(indices[i]) + ", not a vertex of " +
                                   std::to_string(num_vertices));
            }
        }
    }
    if (n < 0) {
        throw PrepareError(num_triangles < 0 ? "skin_planes_schedule: a negative triangle count"
                                             : "skin_planes_schedule: no indices for " +
                                                   std::to_string(num_triangles) + " triangles");
    }
    SkinPlanesSchedule s;
    s.vertex_end.resize(static_cast<std::size_t>(n));
    s.triangle_end.resize(static_cast<std::size_t>(n));
    sv_skin_planes_schedule(indices, num_triangles, num_vertices, segment_triangles,
                            s.vertex_end.data(), s.triangle_end.data(), n);
    return s;
}

const SkinPlanesKernel *skin_planes_kernels(int *count) { return sv_skin_planes_variants(count); }

const SkinPlanesKernel *skin_planes_kernel_by_name(const char *name) {
    return sv_skin_planes_variant_by_name(name);
}

sv_skin_planes_args skin_planes_args(const AnimatedSurface &surface, const float *joint_matrices,
                                     const SkinPlanesSchedule &schedule, float *out,
                                     Plane *planes) {
    const PreparedSurface &p = surface.prepared;
    sv_skin_planes_args a{};
    a.joint_matrices = joint_matrices;
    a.rest = surface.rest_positions.data();
    a.joints = surface.joints.data();
    a.weights = surface.weights.data();
    a.influences = surface.influences;
    a.num_vertices = surface.rest_positions.size() / 3;
    a.indices = p.indices.data();
    a.num_triangles = p.num_triangles();
    a.segments = static_cast<int>(schedule.triangle_end.size());
    a.vertex_end = schedule.vertex_end.data();
    a.triangle_end = schedule.triangle_end.data();
    a.out = out;
    a.planes = planes;
    return a;
}

void pose_surface_with_planes(const AnimatedAsset &asset, const AnimatedSurface &surface,
                              const Pose &pose, const Mat4d &root, const SkinPlanesKernel &k,
                              const SkinPlanesSchedule &schedule, float *out, Plane *planes) {
    if (surface.skin < 0) {
        throw PrepareError(surface.name + ": pose_surface_with_planes needs a skinned surface");
    }
    AlignedVector<float> jm(16 * asset.skins[surface.skin].joints.size());
    joint_matrices(asset, surface.skin, pose, root, jm.data());
    const sv_skin_planes_args a = skin_planes_args(surface, jm.data(), schedule, out, planes);
    k.fn(&a);
}

} // namespace sv
