// Copyright (C) 2026 the shadowvol authors. LGPL-2.1-or-later.
#include "model_surfaces.h"

#include <dirent.h>

#include <algorithm>
#include <cstdio>

#include "shadowvol_gltf.h"
#include "test_conditions.h"
#include <gtest/gtest.h>

namespace svtest {

std::vector<std::string> seed_model_paths(const std::string &set) {
    if (set == "bundled") return {std::string(SV_MODELS_DIR) + "/character_1344.glb"};
    /* The top of the folder, then its open/ folder (issue 27's open and
     * non-manifold characters: the seeds' routines take any triangle set). */
    std::vector<std::string> shared;
    for (const std::string &dir : {shared_models_dir(), shared_models_dir() + "/open"}) {
        DIR *d = opendir(dir.c_str());
        if (!d) {
            if (dir == shared_models_dir()) ADD_FAILURE() << dir << " cannot be read";
            continue;
        }
        std::vector<std::string> here;
        while (const dirent *e = readdir(d)) {
            const std::string n = e->d_name;
            if (n.size() > 4 && n.compare(n.size() - 4, 4, ".glb") == 0)
                here.push_back(dir + "/" + n);
        }
        closedir(d);
        std::sort(here.begin(), here.end());
        shared.insert(shared.end(), here.begin(), here.end());
    }
    return shared;
}

std::vector<sv::PreparedSurface> prepared_surfaces(const std::string &path) {
    const sv::GltfModel m = sv::load_gltf(path);
    std::vector<sv::PreparedSurface> out;
    for (const sv::GltfSurface &g : m.surfaces) {
        out.push_back(sv::prepare_surface(g.positions.data(), g.positions.size() / 3,
                                          g.indices.data(), g.indices.size()));
    }
    return out;
}

} // namespace svtest
