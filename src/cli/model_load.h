/*
 * A glTF model loaded and every surface prepared, for the commands that
 * take one (inspect, verify, tune): one surface per mesh instance of the
 * scene, all primitives of the mesh merged, in world space.
 *
 * Copyright (C) 2026 the shadowvol authors. LGPL-2.1-or-later.
 */
#ifndef SV_CLI_MODEL_LOAD_H
#define SV_CLI_MODEL_LOAD_H

#include <string>
#include <vector>

#include "shadowvol_gltf.h"
#include "shadowvol_mesh.h"

namespace svcli {

struct Surface {
    sv::GltfSurface source; /* positions and indices dropped after preparing */
    sv::PreparedSurface prepared;
};

struct LoadedModel {
    std::string path;
    std::vector<Surface> surfaces;
    std::vector<std::string> notes;
};

/* Loads PATH (only the mesh MESH when not empty; MAX_TRIANGLES < 0: the
 * loader's default limits) and prepares every surface into OUT. A failure
 * is reported on stderr as "shadowvol COMMAND: ..." and gives false. */
bool load_model(const char *command, const std::string &path, const std::string &mesh,
                long long max_triangles, LoadedModel *out);

} // namespace svcli

#endif
