// The models the seed tests (silhouette finders, back-face culling) run on:
// the bundled character and every .glb in ../shared/models when present,
// each surface prepared on its own.
//
// Copyright (C) 2026 the shadowvol authors. LGPL-2.1-or-later.
#pragma once

#include <string>
#include <vector>

#include "shadowvol_mesh.h"

namespace svtest {

// The bundled character first, then the shared folder's .glb files sorted;
// prints a note when that folder is missing.
std::vector<std::string> seed_model_paths();

// The surfaces of a model, each prepared on its own.
std::vector<sv::PreparedSurface> prepared_surfaces(const std::string &path);

} // namespace svtest
