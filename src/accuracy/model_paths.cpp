/*
 * The models `shadowvol accuracy` measures by default: the bundled
 * character and every .glb in the shared models folder (CMake's
 * SV_SHARED_MODELS_DIR), with a note saying which folder was searched and,
 * visibly, when it is missing.
 *
 * Copyright (C) 2026 the shadowvol authors. LGPL-2.1-or-later.
 */
#include "accuracy_study.h"

#include <algorithm>

#include <dirent.h>

#ifndef SV_MODELS_DIR
#error "SV_MODELS_DIR must name the bundled models folder"
#endif
#ifndef SV_SHARED_MODELS_DIR
#error "SV_SHARED_MODELS_DIR must name the real characters' folder"
#endif

namespace sv {
namespace acc {

DefaultModels default_models(bool bundled_only) {
    DefaultModels d;
    d.paths.push_back(std::string(SV_MODELS_DIR) + "/character_1344.glb");
    d.shared_dir = SV_SHARED_MODELS_DIR;
    if (bundled_only) {
        d.note = "the bundled character only (--quick); the real characters are in " + d.shared_dir;
        return d;
    }
    DIR *dir = opendir(d.shared_dir.c_str());
    if (!dir) {
        d.note = "NOTE: the real characters' folder " + d.shared_dir +
                 " (SV_SHARED_MODELS_DIR) is missing: only the bundled character is measured";
        return d;
    }
    d.shared_found = true;
    std::vector<std::string> shared;
    while (const dirent *e = readdir(dir)) {
        const std::string n = e->d_name;
        if (n.size() > 4 && n.compare(n.size() - 4, 4, ".glb") == 0) {
            shared.push_back(d.shared_dir + "/" + n);
        }
    }
    closedir(dir);
    std::sort(shared.begin(), shared.end());
    d.paths.insert(d.paths.end(), shared.begin(), shared.end());
    d.note = "the bundled character and " + std::to_string(shared.size()) + " model(s) from " +
             d.shared_dir;
    if (shared.empty())
        d.note = "NOTE: no .glb in " + d.shared_dir + ": only the bundled character";
    return d;
}

} // namespace acc
} // namespace sv
