/*
 * Copyright (C) 2026 the shadowvol authors. LGPL-2.1-or-later.
 */
#include "model_list.h"

#include <algorithm>
#include <cctype>
#include <filesystem>
#include <system_error>

namespace svbench {

namespace fs = std::filesystem;

namespace {

bool is_gltf_name(const fs::path &p) {
    std::string ext = p.extension().string();
    std::transform(ext.begin(), ext.end(), ext.begin(),
                   [](unsigned char c) { return (char)std::tolower(c); });
    return ext == ".glb" || ext == ".gltf";
}

/* The glTF files directly in DIR, sorted by name; empty when DIR is not a
 * readable folder. */
std::vector<std::string> gltf_files_in(const std::string &dir) {
    std::vector<std::string> files;
    std::error_code ec;
    for (fs::directory_iterator it(dir, ec), end; !ec && it != end; it.increment(ec)) {
        std::error_code fec;
        if (it->is_regular_file(fec) && is_gltf_name(it->path())) {
            files.push_back(it->path().string());
        }
    }
    std::sort(files.begin(), files.end());
    return files;
}

/* The path without "." and "..": for the header, and so that two
 * spellings of one file run once. */
std::string canonical(const std::string &p) {
    std::error_code ec;
    const fs::path c = fs::weakly_canonical(p, ec);
    return ec ? p : c.string();
}

} // namespace

ModelList resolve_models(const std::vector<std::string> &args, const std::string &bundled,
                         const std::string &shared) {
    ModelList list;
    std::vector<std::string> seen;
    auto add_file = [&](const std::string &path) {
        const std::string id = canonical(path);
        if (std::find(seen.begin(), seen.end(), id) == seen.end()) {
            seen.push_back(id);
            list.models.push_back(ModelSpec{false, path});
        }
    };
    const std::string sharedDir = canonical(shared);
    bool synthetic = false, all = false;
    if (args.empty()) {
        add_file(bundled);
    }
    for (const std::string &a : args) {
        std::error_code ec;
        if (a == "synthetic") {
            if (!synthetic) {
                list.models.push_back(ModelSpec{true, ""});
            }
            synthetic = true;
        } else if (a == "all") {
            all = true;
            add_file(bundled);
            for (const std::string &f : gltf_files_in(sharedDir)) {
                add_file(f);
            }
        } else if (fs::is_directory(a, ec)) {
            const std::vector<std::string> files = gltf_files_in(a);
            if (files.empty()) {
                throw ModelListError("no .glb or .gltf file in the folder " + a);
            }
            for (const std::string &f : files) {
                add_file(f);
            }
        } else {
            add_file(a);
        }
    }

    std::error_code ec;
    const std::string &where = sharedDir;
    const size_t real = gltf_files_in(where).size();
    std::string note;
    if (!fs::is_directory(where, ec)) {
        note = "real characters: none here (" + where +
               " does not exist; it holds the third-party glTF characters)";
    } else if (all) {
        note = "real characters: the " + std::to_string(real) + " glTF files in " + where +
               " (--model all)";
    } else {
        note = "real characters: " + std::to_string(real) + " glTF files in " + where +
               " not run; add --model all (or --model " + where + ")";
    }
    std::string names, line;
    for (const ModelSpec &m : list.models) {
        const std::string name = m.synthetic ? std::string("synthetic")
                                             : fs::path(m.path).filename().string();
        if (!line.empty() && line.size() + name.size() > 80) {
            names += line + ",\n          ";
            line.clear();
        }
        line += (line.empty() ? "" : ", ") + name;
    }
    list.note = names + line + "\n          " + note;
    return list;
}

} // namespace svbench
