/*
 * libFuzzer target: a glTF scene in time (issues 13 and 17): GLB bytes
 * through the animated loader (nodes, animations, skins, lights, cameras)
 * and past it: every animation posed at its start, middle and end and
 * beyond; every surface posed by every skinning kernel the CPU runs (each
 * must give the C reference's bits); planes derived by every planes
 * variant (each must give the C reference's bits); the volumes of the
 * file's lights (or of two lights around the surface) built by the best
 * variant and checked closed; the lights and cameras at each pose made
 * into a scene and validated.
 *
 * A finding: a crash or sanitizer report, an exception other than
 * GltfError, PrepareError and SceneError (the documented refusals), a
 * message that is not bounded printable UTF-8, a kernel that differs from
 * its reference, an open volume.
 *
 * Copyright (C) 2026 the shadowvol authors. LGPL-2.1-or-later.
 */
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <string>
#include <vector>

#include "shadowvol_anim.h"
#include "fuzz_support.h"
#include "shadowvol_gltf.h"
#include "shadowvol_planes.h"
#include "shadowvol_scene.h"
#include "shadowvol_verify.h"

namespace {

using svfuzz::check_message;
using svfuzz::finding;

/* Sized so an input takes about a millisecond. */
constexpr int kMaxSurfaceTriangles = 20000;
constexpr int kMaxAnimations = 2;
constexpr int kMaxSurfaces = 4;

void check_pose(const sv::AnimatedAsset &a, const sv::Pose &pose, const std::string &when) {
    int kernels = 0;
    const sv::SkinningKernel *table = sv::skinning_kernels(&kernels);
    int nplanes = 0;
    const sv_planes_variant *planes = sv_planes_variants(&nplanes);
    const sv::Mat4d root;
    int surfaces = 0;
    for (const sv::AnimatedSurface &s : a.surfaces) {
        if (s.prepared.num_triangles() > kMaxSurfaceTriangles || ++surfaces > kMaxSurfaces)
            continue;
        const std::size_t nv = (std::size_t)s.prepared.num_vertices();
        std::vector<float> ref(3 * nv + 3, 0.5f), out(3 * nv + 3, 0.5f);
        sv::pose_surface(a, s, pose, root, ref.data(), &table[0]);
        if (ref[3 * nv] != 0.5f) finding(s.name + ": c_ref skinning wrote past its vertices");
        for (int k = 1; k < kernels; k++) {
            if ((table[k].isa & sv_cpu_isa()) != table[k].isa) continue;
            std::fill(out.begin(), out.end(), 0.5f);
            sv::pose_surface(a, s, pose, root, out.data(), &table[k]);
            if (std::memcmp(out.data(), ref.data(), out.size() * sizeof(float)) != 0) {
                finding(s.name + " " + when + ": skinning kernel " + table[k].name +
                        " differs from c_ref");
            }
        }
        /* Planes of the posed surface, every variant against c_ref's bits. */
        const int nt = s.prepared.num_triangles();
        std::vector<Plane> p0((std::size_t)nt + 1), p1((std::size_t)nt + 1);
        sv_derive_planes_c_ref(ref.data(), s.prepared.indices.data(), nt, p0.data());
        for (int k = 1; k < nplanes; k++) {
            if ((planes[k].isa & sv_cpu_isa()) != planes[k].isa) continue;
            planes[k].derive_planes(ref.data(), s.prepared.indices.data(), nt, p1.data());
            if (std::memcmp(p0.data(), p1.data(), (std::size_t)nt * sizeof(Plane)) != 0) {
                finding(s.name + " " + when + ": planes variant " + planes[k].name +
                        " differs from c_ref");
            }
        }
        /* A volume from the posed surface stays closed (the topology is
         * fixed; only positions moved). */
        bool finite = true;
        for (std::size_t i = 0; i < 3 * nv; i++) finite &= std::isfinite(ref[i]);
        if (!finite || nt == 0) continue;
        sv::PreparedSurface posed = s.prepared;
        std::memcpy(posed.positions.data(), ref.data(), 3 * nv * sizeof(float));
        std::memcpy(posed.planes.data(), p0.data(), (std::size_t)nt * sizeof(Plane));
        const Vec4 lights[2] = {{ref[0] + 3.f, ref[1] + 5.f, ref[2] + 7.f, 1.f},
                                {0.3f, 0.9f, -0.2f, 0.f}};
        for (const Vec4 &L : lights) {
            sv::AlignedVector<uint8_t> facing((std::size_t)nt + 1, 1);
            sv_calculate_facing_c_ref(posed.planes.data(), nt, &L, facing.data());
            sv::AlignedVector<int> idx(
                sv_shadow_volume_capacity(posed.num_indices(), posed.num_sil_edges()));
            const int n = sv_create_shadow_volume(sv_best_variant(), idx.data(),
                                                  posed.indices.data(), posed.num_indices(),
                                                  posed.sil_edges.data(), posed.num_sil_edges(),
                                                  facing.data(), nullptr);
            const sv::ClosureResult c = sv::check_closure(idx.data(), n, posed.num_vertices());
            if (!c.closed) finding(s.name + " " + when + ": volume not closed: " + c.problem);
        }
    }
    /* Lights and cameras at the pose: a refusal is SceneError, nothing else. */
    sv::Scene scene;
    for (std::size_t i = 0; i < a.lights.size(); i++)
        scene.lights.push_back(sv::light_at(a, (int)i, pose, root));
    for (std::size_t i = 0; i < a.cameras.size(); i++) {
        double aspect = 0;
        scene.camera = sv::camera_at(a, (int)i, pose, root, &aspect);
    }
}

} // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size) {
    if (size < 4 || std::memcmp(data, "glTF", 4) != 0) return -1;
    sv::AnimatedAsset a;
    try {
        a = sv::load_animated_gltf_memory(data, size, "fuzz.glb");
    } catch (const sv::GltfError &e) {
        check_message(e.what(), "GltfError message");
        return 0;
    } catch (const sv::PrepareError &e) {
        check_message(e.what(), "PrepareError message");
        return 0;
    }
    for (const std::string &n : a.notes) check_message(n, "note");
    try {
        check_pose(a, sv::pose_at(a, -1, 0), "at the file's pose");
        for (int k = 0; k < (int)a.animations.size() && k < kMaxAnimations; k++) {
            const sv::Animation &an = a.animations[(std::size_t)k];
            for (double t :
                 {an.start, 0.5 * (an.start + an.end), an.end, an.end + 1.0, an.start - 1.0}) {
                check_pose(a, sv::pose_at(a, k, t), "animation " + std::to_string(k));
            }
        }
        (void)sv::find_animation(a, "0");
    } catch (const sv::GltfError &e) {
        check_message(e.what(), "GltfError message");
    } catch (const sv::SceneError &e) {
        check_message(e.what(), "SceneError message");
    }
    return 0;
}
