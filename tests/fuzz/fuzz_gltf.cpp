/*
 * libFuzzer target: a glTF file, end to end (issue 17). Built twice:
 * fuzz_glb (GLB bytes: inputs without the "glTF" magic are rejected) and
 * fuzz_gltf_json (-DSV_FUZZ_JSON: .gltf JSON text with embedded base64
 * buffers, with the dictionary tests/fuzz/gltf.dict).
 *
 * The pipeline goes past loading: every surface is prepared, and on the
 * surfaces small enough to check quickly, the volumes of three lights are
 * built by every variant this CPU runs and checked by the project's own
 * verifier (closure, and the winding-number identity in space). A finding
 * is: a crash or sanitizer report; an exception other than sv::GltfError
 * and sv::PrepareError; a message that is not bounded, printable UTF-8; a
 * volume that is not closed or overruns its capacity; a volume of a closed
 * mesh that the verifier finds wrong in space (not "cannot decide").
 *
 * Copyright (C) 2026 the shadowvol authors. LGPL-2.1-or-later.
 */
#include <algorithm>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <string>

#include "fuzz_support.h"
#include "shadowvol_gltf.h"
#include "shadowvol_mesh.h"
#include "shadowvol_verify.h"

namespace {

using svfuzz::check_message;
using svfuzz::finding;

/* What each input gets, sized so an input takes about a millisecond:
 * every variant's volume for kLights lights, checked closed and equal to
 * c_ref's, on surfaces up to kMaxClosureTriangles; the in-space check of
 * the verifier (kPoints points a light) up to kMaxVerifiedTriangles. */
constexpr int kMaxClosureTriangles = 5000;
constexpr int kMaxVerifiedTriangles = 300;
constexpr int kLights = 2;
constexpr int kPoints = 8;
constexpr int kMaxSurfaces = 4;

/* Every variant's volume of P for L, against c_ref's: the same index list
 * (every variant computes exactly what the reference computes), closed. */
void check_volumes(const sv::PreparedSurface &p, const sv::VerifyLight &l,
                   const std::vector<const sv_variant *> &variants, const std::string &name) {
    const int nt = p.num_triangles();
    sv::AlignedVector<uint8_t> facing0((size_t)nt + 1, 1);
    sv_calculate_facing_c_ref(p.planes.data(), nt, &l.light, facing0.data());
    facing0[(size_t)nt] = 1;
    const size_t capacity = sv_shadow_volume_capacity(p.num_indices(), p.num_sil_edges());
    std::vector<int> reference;
    for (const sv_variant *v : variants) {
        sv::AlignedVector<uint8_t> facing = facing0;
        sv::AlignedVector<int> out(capacity);
        const int n = sv_create_shadow_volume_checked(v, out.data(), capacity, p.indices.data(),
                                                      p.num_indices(), p.num_vertices(),
                                                      p.sil_edges.data(), p.num_sil_edges(),
                                                      facing.data(), nullptr);
        if (n < 0) {
            finding(name + ": variant " + v->name +
                    " refused a prepared surface: " + sv_status_string(n));
        }
        const sv::ClosureResult c = sv::check_closure(out.data(), n, p.num_vertices());
        if (!c.closed) finding(name + ": variant " + v->name + ": " + c.problem);
        if (v == variants.front()) {
            reference.assign(out.data(), out.data() + n);
        } else if (reference.size() != (size_t)n ||
                   !std::equal(reference.begin(), reference.end(), out.data())) {
            finding(name + ": variant " + v->name + " differs from " + variants.front()->name);
        }
    }
}

uint64_t hash_bytes(const uint8_t *data, size_t size) {
    uint64_t h = 1469598103934665603ull;
    for (size_t i = 0; i < size; i++) h = (h ^ data[i]) * 1099511628211ull;
    return h;
}

} // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size) {
    const bool glb = size >= 4 && std::memcmp(data, "glTF", 4) == 0;
#ifdef SV_FUZZ_JSON
    if (glb) return -1;
    const char *name = "fuzz.gltf";
#else
    if (!glb) return -1;
    const char *name = "fuzz.glb";
#endif
    sv::GltfLoadOptions options;
    options.external_files = false;
    options.max_triangles = std::size_t(1) << 18;
    options.max_vertices = std::size_t(1) << 19;
    options.max_nodes = std::size_t(1) << 16;
    sv::GltfModel model;
    try {
        model = sv::load_gltf_memory(data, size, name, options);
    } catch (const sv::GltfError &e) {
        check_message(e.what(), "GltfError message");
        return 0;
    }
    for (const std::string &n : model.notes) check_message(n, "note");
    const std::vector<const sv_variant *> variants = sv::supported_variants();
    const uint64_t seed = hash_bytes(data, size);
    int checked = 0;
    for (const sv::GltfSurface &g : model.surfaces) {
        check_message(g.name, "surface name");
        sv::PreparedSurface p;
        try {
            p = sv::prepare_surface(g.positions.data(), g.num_vertices(), g.indices.data(),
                                    g.indices.size());
        } catch (const sv::PrepareError &e) {
            check_message(e.what(), "PrepareError message");
            continue;
        }
        if (p.num_triangles() == 0 || p.num_triangles() > kMaxClosureTriangles ||
            checked >= kMaxSurfaces) {
            continue;
        }
        checked++;
        const sv::PrepareReport &r = p.report;
        const bool closed = r.boundary_edges == 0 && r.non_manifold_edges == 0 &&
                            r.same_direction_edges == 0;
        const std::vector<sv::VerifyLight> lights = sv::make_verify_lights(p, kLights, seed);
        for (const sv::VerifyLight &l : lights) check_volumes(p, l, variants, g.name);
        if (p.num_triangles() > kMaxVerifiedTriangles) continue;
        sv::VerifyOptions vo;
        vo.points_per_light = kPoints;
        for (const sv::VerifyLight &l : lights) {
            const sv::LightResult res = sv::verify_light(p, l, variants, vo, seed + 1);
            if (res.ok) continue;
            const bool structural = res.failure.find("not closed") != std::string::npos ||
                                    res.failure.find("capacity") != std::string::npos;
            if (structural || closed) {
                finding(std::string("surface ") + g.name + (closed ? " (closed)" : " (open)") +
                        ": " + res.failure);
            }
        }
    }
    return 0;
}
