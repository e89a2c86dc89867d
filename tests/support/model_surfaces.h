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

// The models of one set of svtest::model_sets() (tests/support/test_conditions.h):
// "bundled" (the bundled character) or "SharedModels" (every .glb of
// ../shared/models, sorted, then every .glb of its open/ folder).
std::vector<std::string> seed_model_paths(const std::string &set);

// The surfaces of a model, each prepared on its own.
std::vector<sv::PreparedSurface> prepared_surfaces(const std::string &path);

} // namespace svtest
