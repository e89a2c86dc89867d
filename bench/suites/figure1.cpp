/*
 * Seed 004's Figure 1 for our scenes (Aila and Akenine-Moeller, "A
 * Hierarchical Shadow Volume Algorithm", 2004): from left to right in the
 * seed, the correct shadows; the low-resolution shadows (one sample per
 * tile); the tiles that may hold a shadow boundary; and the image put
 * together from per-pixel work in those tiles and the low-resolution
 * shadow elsewhere.
 *
 * One light (the preset's first), so each picture shows one shadow. The
 * pictures are drawn plainly, not through the lighting pass: every
 * visible triangle a grey (its albedo) by its normal, lit where the
 * picture's shadow says so and at a third of that where it is in shadow;
 * the sky white. The shadows come from the hierarchical stencil pass's
 * own frame: the per-pixel stencil (brute force's, byte for byte, which
 * is checked), its boundary tiles (StencilPassResult::boundary_tile_mask)
 * and, for the low-resolution picture, each tile's sample (its first
 * pixel, the sample of stage 1) spread over the tile. Outside boundary
 * tiles a tile's stencil is the same at every pixel (each volume adds one
 * count to all of it), so the composed picture equals the correct one:
 * the tool counts the pixels where it does not and fails on any.
 *
 * Copyright (C) 2026 the shadowvol authors. LGPL-2.1-or-later.
 */
#include "figure1.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <memory>
#include <stdexcept>
#include <vector>

#include "frame.h"
#include "images.h"
#include "scene_presets.h"
#include "shadowvol_gltf.h"
#include "workload.h"

namespace svbench {
namespace {

using sv::render::Frame;
using sv::render::Image;
using sv::render::RenderOptions;

/* Each pixel's plain grey (0-1, per channel) from its triangle's normal
 * and albedo; negative for the sky. */
std::vector<float> plain_shade(const sv::Scene &scene, const Frame &f) {
    const std::size_t n = (std::size_t)f.width * (std::size_t)f.height;
    std::vector<float> rgb(3 * n, -1.0f);
    /* A fixed direction, up and towards the camera's side: the picture's
     * form, independent of the shadow it shows. */
    const double kx = 0.3, ky = 0.85, kz = 0.43;
    for (std::size_t i = 0; i < n; i++) {
        const int32_t id = f.target.ids[i];
        if (id < 0) continue;
        const auto it = std::upper_bound(f.surface_first_id.begin(), f.surface_first_id.end(), id);
        const std::size_t s = (std::size_t)(it - f.surface_first_id.begin()) - 1;
        const sv::SceneSurface &surface = scene.surfaces[s];
        const int t = id - f.surface_first_id[s];
        if (t < 0 || t >= surface.prepared.num_triangles()) continue;
        const Plane &p = surface.prepared.planes[(std::size_t)t];
        const double len = std::sqrt((double)p.a * p.a + (double)p.b * p.b + (double)p.c * p.c);
        const double lit = len > 0 ? std::fabs(p.a * kx + p.b * ky + p.c * kz) / len : 1.0;
        for (int c = 0; c < 3; c++) {
            rgb[3 * i + (std::size_t)c] = (float)((0.35 + 0.65 * lit) *
                                                  surface.albedo[(std::size_t)c]);
        }
    }
    return rgb;
}

/* The plain picture with SHADOW (per pixel, 1 in shadow); TINT(i, rgb)
 * may change a pixel's colour after. */
template <class Tint>
Image picture(const Frame &f, const std::vector<float> &shade, const std::vector<uint8_t> &shadow,
              Tint &&tint) {
    Image img(f.width, f.height);
    for (int y = 0; y < f.height; y++) {
        for (int x = 0; x < f.width; x++) {
            const std::size_t i = (std::size_t)y * (std::size_t)f.width + (std::size_t)x;
            double c[3] = {1, 1, 1};
            if (shade[3 * i] >= 0) {
                const double k = shadow[i] ? 0.33 : 1.0;
                for (int j = 0; j < 3; j++) c[j] = shade[3 * i + (std::size_t)j] * k;
            }
            tint(i, c);
            uint8_t *px = img.at(x, y);
            for (int j = 0; j < 3; j++) {
                px[j] = (uint8_t)std::lround(255.0 * std::pow(std::clamp(c[j], 0.0, 1.0), 1 / 2.2));
            }
        }
    }
    return img;
}

} // namespace

int run_figure1(const SeedCommand &cmd, const std::string &out_dir, int tile) {
    const std::string name = cmd.scenePreset.empty() ? "knights" : cmd.scenePreset;
    const int width = cmd.sceneWidth ? cmd.sceneWidth : 640;
    const int height = cmd.sceneHeight ? cmd.sceneHeight : 400;
    std::unique_ptr<ScenePreset> preset;
    try {
        preset = make_scene_preset(name, (double)width / height, SV_MODELS_DIR, cmd.sharedModels,
                                   SV_DEMO_SCENE);
    } catch (const std::exception &e) {
        std::fprintf(stderr, "shadowvol bench: --preset %s: %s\n", name.c_str(), e.what());
        return 3;
    }
    sv::Scene scene = preset->at(0);
    if (scene.lights.empty()) {
        std::fprintf(stderr, "shadowvol bench: --preset %s: the scene has no light\n",
                     name.c_str());
        return 3;
    }
    scene.lights.resize(1);
    RenderOptions o;
    o.width = width, o.height = height;
    o.threads = 0;
    o.stencil = sv::render::StencilMethod::hierarchical;
    o.stencil_tile = tile;
    const Frame f = sv::render::render_frame(scene, o);
    RenderOptions bf = o;
    bf.stencil = sv::render::StencilMethod::brute_force;
    const Frame g = sv::render::render_frame(scene, bf);
    const std::vector<uint8_t> &stencil = f.lights[0].stencil;
    const std::vector<uint8_t> &boundary = f.lights[0].stencil_boundary_tiles;
    const int tiles_x = (width + tile - 1) / tile, tiles_y = (height + tile - 1) / tile;
    if (boundary.size() != (std::size_t)tiles_x * (std::size_t)tiles_y) {
        std::fprintf(stderr, "shadowvol bench: --figure1: no boundary tiles from hier\n");
        return 1;
    }
    const std::size_t n = (std::size_t)width * (std::size_t)height;
    std::vector<uint8_t> correct(n), lowres(n), composed(n), in_boundary(n);
    for (int y = 0; y < height; y++) {
        for (int x = 0; x < width; x++) {
            const std::size_t i = (std::size_t)y * (std::size_t)width + (std::size_t)x;
            const int tx = x / tile, ty = y / tile;
            const std::size_t sample = (std::size_t)(ty * tile) * (std::size_t)width +
                                       (std::size_t)(tx * tile);
            correct[i] = stencil[i] != 0;
            lowres[i] = stencil[sample] != 0;
            in_boundary[i] = boundary[(std::size_t)ty * (std::size_t)tiles_x + (std::size_t)tx];
            composed[i] = in_boundary[i] ? correct[i] : lowres[i];
        }
    }
    std::size_t differ = 0, lowres_wrong = 0, boundary_tiles = 0;
    for (std::size_t i = 0; i < n; i++) {
        differ += composed[i] != correct[i];
        lowres_wrong += lowres[i] != correct[i];
    }
    for (uint8_t b : boundary) boundary_tiles += b;
    const std::vector<float> shade = plain_shade(scene, f);
    auto none = [](std::size_t, double *) {};
    /* Boundary tiles: green over the correct shadows (the seed's third
     * picture); in the composed one, a darker grey where per-pixel work
     * was done (its fourth). */
    auto green = [&](std::size_t i, double *c) {
        if (!in_boundary[i]) return;
        c[0] = 0.5 * c[0] + 0.5 * 0.05, c[1] = 0.5 * c[1] + 0.5 * 0.75, c[2] = 0.5 * c[2];
    };
    auto darker = [&](std::size_t i, double *c) {
        if (in_boundary[i])
            for (int j = 0; j < 3; j++) c[j] *= 0.55;
    };
    const std::string stem = out_dir + "/" + (name.find('/') == std::string::npos ? name : "scene");
    try {
        sv::render::write_png(stem + "_correct.png", picture(f, shade, correct, none));
        sv::render::write_png(stem + "_lowres.png", picture(f, shade, lowres, none));
        sv::render::write_png(stem + "_boundary.png", picture(f, shade, correct, green));
        sv::render::write_png(stem + "_composed.png", picture(f, shade, composed, darker));
    } catch (const std::exception &e) {
        std::fprintf(stderr, "shadowvol bench: --out: %s\n", e.what());
        return 2;
    }
    const bool equal_to_bf = stencil == g.lights[0].stencil;
    std::printf("figure 1: %s, %dx%d, light 0 of %zu, hier with %dx%d tiles\n",
                preset->describe().c_str(), width, height, preset->at(0).lights.size(), tile, tile);
    std::printf("tiles %d, boundary tiles %zu (%.1f%%); low-resolution shadow wrong on %zu pixels "
                "(%.2f%%), all in boundary tiles\n",
                tiles_x * tiles_y, boundary_tiles,
                100.0 * (double)boundary_tiles / (double)(tiles_x * tiles_y), lowres_wrong,
                100.0 * (double)lowres_wrong / (double)n);
    std::printf("composed = correct: %s (%zu pixels differ); hier's stencil = bf's: %s\n",
                differ == 0 ? "yes" : "NO", differ, equal_to_bf ? "yes" : "NO");
    std::printf("images: %s_{correct,lowres,boundary,composed}.png\n", stem.c_str());
    return differ == 0 && equal_to_bf ? 0 : 1;
}

} // namespace svbench
