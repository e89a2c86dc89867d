/*
 * Copyright (C) 2026 the shadowvol authors. LGPL-2.1-or-later.
 */
#include "model_workload.h"

#include <cstdint>
#include <limits>
#include <new>
#include <vector>

#include "shadowvol_gltf.h"
#include "shadowvol_mesh.h"

namespace svbench {

namespace {

std::string file_name(const std::string &path) {
    const size_t slash = path.find_last_of('/');
    return slash == std::string::npos ? path : path.substr(slash + 1);
}

/* All surfaces as one triangle soup: positions appended, indices offset by
 * the vertices before them. */
void merge(const sv::GltfModel &m, std::vector<float> &positions, std::vector<uint32_t> &indices) {
    for (const sv::GltfSurface &s : m.surfaces) {
        const size_t base = positions.size() / 3;
        if (base + s.num_vertices() > std::numeric_limits<uint32_t>::max()) {
            throw WorkloadError(m.path + ": more than 2^32 vertices in all surfaces together");
        }
        positions.insert(positions.end(), s.positions.begin(), s.positions.end());
        for (uint32_t i : s.indices) {
            indices.push_back(i + (uint32_t)base);
        }
    }
}

} // namespace

Workload load_model_surface(const std::string &path) {
    sv::GltfModel model;
    std::vector<float> positions;
    std::vector<uint32_t> indices;
    sv::PreparedSurface prepared;
    try {
        model = sv::load_gltf(path);
        merge(model, positions, indices);
        prepared = sv::prepare_surface(positions.data(), positions.size() / 3, indices.data(),
                                       indices.size());
    } catch (const sv::GltfError &e) {
        throw WorkloadError(e.what());
    } catch (const sv::PrepareError &e) {
        throw WorkloadError(path + ": " + e.what());
    } catch (const std::bad_alloc &) {
        throw WorkloadError(path + ": out of memory");
    }
    if (prepared.num_triangles() == 0) {
        throw WorkloadError(path + ": no triangles to build shadow volumes from");
    }
    Workload w = workload_from_surface(prepared, file_name(path), path);
    w.surfaces = (int)model.surfaces.size();
    return w;
}

Workload make_model_workload(const std::string &path, const LightTargets &targets, int numLights,
                             uint64_t seed, const Vec4 *fixed) {
    Workload w = load_model_surface(path);
    place_lights(w, targets, numLights, seed, fixed);
    return w;
}

} // namespace svbench
