/*
 * Which models a `shadowvol bench` run times, from its --model values:
 *
 *   (none)      the bundled character, models/character_1344.glb: the
 *               paper's sizes, and fast enough for the default run
 *   FILE        any glTF file (.glb or .gltf)
 *   DIR         every .glb and .gltf file in the folder, by name
 *   all         the bundled character and every real character in
 *               ../shared/models (when that folder exists)
 *   synthetic   the torus with generated facing patterns at the paper's
 *               exact ratios (synthetic_workload.h)
 *
 * Repeatable; a model named twice runs once. A file called "all" or
 * "synthetic" is ./all or ./synthetic.
 *
 * Copyright (C) 2026 the shadowvol authors. LGPL-2.1-or-later.
 */
#ifndef SV_BENCH_MODEL_LIST_H
#define SV_BENCH_MODEL_LIST_H

#include <stdexcept>
#include <string>
#include <vector>

namespace svbench {

struct ModelSpec {
    bool synthetic = false;
    std::string path; /* glTF file, when not synthetic */
};

struct ModelList {
    std::vector<ModelSpec> models;
    /* One line for the header: what runs, and where the real characters
     * are (or that their folder is missing) and how to include them. */
    std::string note;
};

/* A folder without glTF files; a message for the user. */
class ModelListError : public std::runtime_error {
public:
    using std::runtime_error::runtime_error;
};

/* BUNDLED: the bundled character's file; SHARED: the folder of the real
 * characters. Files are not opened here (the loader reports those). */
ModelList resolve_models(const std::vector<std::string> &args, const std::string &bundled,
                         const std::string &shared);

} // namespace svbench

#endif
