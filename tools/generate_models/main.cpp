// shadowvol_generate_models --out DIR [--scaling | --demo-scene]
//   DIR/character_1344.glb: the project's 1344-triangle, 2016-edge character.
//   --scaling: instead, the same character with each quad subdivided n x n
//   (n = 3, 9, 27: 12096, 108864 and 979776 triangles), for scaling runs.
//   --demo-scene: instead, DIR/demo_scene.glb (models/README.md).

#include <cstdio>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <string>

#include "model_gen.h"

namespace {

int usage(int status) {
    std::fprintf(
        status ? stderr : stdout,
        "usage: shadowvol_generate_models --out DIR [--scaling | --demo-scene]\n"
        "  writes DIR/character_1344.glb (closed, 2-manifold, 1344 triangles, 2016 edges);\n"
        "  with --scaling, writes DIR/character_12096.glb, character_108864.glb and\n"
        "  character_979776.glb (the same character, each quad subdivided 3x3, 9x9, 27x27);\n"
        "  with --demo-scene, writes DIR/demo_scene.glb (terrain, pillars, the skinned\n"
        "  walking character, lights, camera).\n");
    return status;
}

} // namespace

int main(int argc, char **argv) {
    std::string out;
    bool scaling = false, demo = false;
    for (int i = 1; i < argc; ++i) {
        if (!std::strcmp(argv[i], "--out") && i + 1 < argc)
            out = argv[++i];
        else if (!std::strcmp(argv[i], "--scaling"))
            scaling = true;
        else if (!std::strcmp(argv[i], "--demo-scene"))
            demo = true;
        else if (!std::strcmp(argv[i], "--help") || !std::strcmp(argv[i], "-h"))
            return usage(0);
        else {
            std::fprintf(stderr, "shadowvol_generate_models: unknown argument '%s'\n", argv[i]);
            return usage(2);
        }
    }
    if (out.empty()) {
        std::fprintf(stderr, "shadowvol_generate_models: --out DIR is required\n");
        return usage(2);
    }
    if (scaling && demo) {
        std::fprintf(stderr,
                     "shadowvol_generate_models: --scaling and --demo-scene exclude each other\n");
        return usage(2);
    }
    try {
        std::filesystem::create_directories(out);
        if (demo) {
            const std::vector<std::uint8_t> glb = svgen::write_demo_scene_glb();
            const std::filesystem::path path = std::filesystem::path(out) / "demo_scene.glb";
            std::ofstream f(path, std::ios::binary);
            f.write(reinterpret_cast<const char *>(glb.data()),
                    static_cast<std::streamsize>(glb.size()));
            f.close();
            if (!f) {
                std::fprintf(stderr, "shadowvol_generate_models: cannot write %s\n",
                             path.string().c_str());
                return 1;
            }
            std::printf("%s: %zu bytes\n", path.string().c_str(), glb.size());
            return 0;
        }
        const svgen::QuadMesh quads = svgen::build_character_quads();
        const int levels_default[] = {1};
        const int levels_scaling[] = {3, 9, 27};
        const int *levels = scaling ? levels_scaling : levels_default;
        const int count = scaling ? 3 : 1;
        for (int k = 0; k < count; ++k) {
            const svgen::TriMesh mesh = svgen::triangulate(quads, levels[k]);
            const std::string name = svgen::model_file_name(mesh);
            const std::vector<std::uint8_t> glb = svgen::write_glb(mesh,
                                                                   name.substr(0, name.size() - 4));
            const std::filesystem::path path = std::filesystem::path(out) / name;
            std::ofstream f(path, std::ios::binary);
            f.write(reinterpret_cast<const char *>(glb.data()),
                    static_cast<std::streamsize>(glb.size()));
            f.close();
            if (!f) {
                std::fprintf(stderr, "shadowvol_generate_models: cannot write %s\n",
                             path.string().c_str());
                return 1;
            }
            std::printf("%s: %zu triangles, %zu vertices, %zu bytes\n", path.string().c_str(),
                        mesh.num_triangles(), mesh.num_vertices(), glb.size());
        }
    } catch (const std::exception &e) {
        std::fprintf(stderr, "shadowvol_generate_models: %s\n", e.what());
        return 1;
    }
    return 0;
}
