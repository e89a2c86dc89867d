// Copyright (C) 2026 the shadowvol authors. LGPL-2.1-or-later.
#include "model_surfaces.h"

#include <dirent.h>

#include <algorithm>
#include <cstdio>

#include "shadowvol_gltf.h"

namespace svtest {

std::vector<std::string> seed_model_paths() {
    std::vector<std::string> p{std::string(SV_MODELS_DIR) + "/character_1344.glb"};
    const std::string dir = SV_SHARED_MODELS_DIR;
    DIR *d = opendir(dir.c_str());
    if (!d) {
        std::printf("[  NOTE    ] %s is missing: only the bundled character is tested\n",
                    dir.c_str());
        return p;
    }
    std::vector<std::string> shared;
    while (const dirent *e = readdir(d)) {
        const std::string n = e->d_name;
        if (n.size() > 4 && n.compare(n.size() - 4, 4, ".glb") == 0) shared.push_back(dir + "/" + n);
    }
    closedir(d);
    std::sort(shared.begin(), shared.end());
    p.insert(p.end(), shared.begin(), shared.end());
    return p;
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
