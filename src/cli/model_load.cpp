/*
 * Copyright (C) 2026 the shadowvol authors. LGPL-2.1-or-later.
 */
#include "model_load.h"

#include <cstdio>
#include <new>

namespace svcli {

/* Loads and prepares every surface; a failure is reported on stderr and
 * gives false. */
bool load_model(const char *command, const std::string &path, const std::string &mesh,
                long long max_triangles, LoadedModel *out) {
    sv::GltfLoadOptions options;
    options.mesh_name = mesh;
    if (max_triangles >= 0) {
        options.max_triangles = (std::size_t)max_triangles;
        options.max_vertices = 2 * (std::size_t)max_triangles;
    }
    try {
        sv::GltfModel m = sv::load_gltf(path, options);
        out->path = path;
        out->notes = m.notes;
        for (sv::GltfSurface &g : m.surfaces) {
            Surface s;
            try {
                s.prepared = sv::prepare_surface(g.positions.data(), g.num_vertices(),
                                                 g.indices.data(), g.indices.size());
            } catch (const sv::PrepareError &e) {
                std::fprintf(stderr, "shadowvol %s: %s: surface %s: %s\n", command, path.c_str(),
                             g.name.c_str(), e.what());
                return false;
            }
            s.source = std::move(g);
            s.source.positions.clear();
            s.source.positions.shrink_to_fit();
            s.source.indices.clear();
            s.source.indices.shrink_to_fit();
            out->surfaces.push_back(std::move(s));
        }
    } catch (const sv::GltfError &e) {
        std::fprintf(stderr, "shadowvol %s: %s\n", command, e.what());
        return false;
    } catch (const std::bad_alloc &) {
        std::fprintf(stderr, "shadowvol %s: %s: out of memory\n", command, path.c_str());
        return false;
    }
    return true;
}

} // namespace svcli
