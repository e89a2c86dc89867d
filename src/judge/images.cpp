/*
 * The pictures of a frame (images.h).
 *
 * Copyright (C) 2026 the shadowvol authors. LGPL-2.1-or-later.
 */
#include "images.h"

#include <algorithm>
#include <stdexcept>

#include <stb/stb_image_write.h>

namespace sv::render {
namespace {

void put(Image &im, std::size_t i, uint8_t r, uint8_t g, uint8_t b) {
    im.rgb[3 * i] = r, im.rgb[3 * i + 1] = g, im.rgb[3 * i + 2] = b;
}

void dim_copy(const Image &shaded, Image &out, std::size_t i, int divisor) {
    for (int c = 0; c < 3; c++) out.rgb[3 * i + c] = (uint8_t)(shaded.rgb[3 * i + c] / divisor);
}

} // namespace

Image side_by_side(const std::vector<Image> &panels) {
    if (panels.empty()) return {};
    const int gap = 4;
    int w = 0;
    for (const Image &p : panels) w += p.width;
    w += gap * ((int)panels.size() - 1);
    Image out(w, panels[0].height);
    std::fill(out.rgb.begin(), out.rgb.end(), 255);
    int x0 = 0;
    for (const Image &p : panels) {
        for (int y = 0; y < p.height && y < out.height; y++) {
            std::copy(p.rgb.begin() + (std::ptrdiff_t)((std::size_t)y * p.width * 3),
                      p.rgb.begin() + (std::ptrdiff_t)((std::size_t)(y + 1) * p.width * 3),
                      out.at(x0, y));
        }
        x0 += p.width + gap;
    }
    return out;
}

Image stencil_image(const std::vector<uint8_t> &stencil, const Image &shaded) {
    Image out(shaded.width, shaded.height);
    for (std::size_t i = 0; i < stencil.size(); i++) {
        const uint8_t s = stencil[i];
        if (s == 0)
            dim_copy(shaded, out, i, 3);
        else if (s >= 128)
            put(out, i, 220, 60, 220);
        else if (s == 1)
            put(out, i, 60, 110, 255);
        else if (s == 2)
            put(out, i, 60, 200, 80);
        else if (s == 3)
            put(out, i, 230, 210, 60);
        else
            put(out, i, 230, 60, 50);
    }
    return out;
}

Image truth_image(const Truth &truth, const std::vector<uint8_t> &stencil, int width, int height) {
    Image out(width, height);
    for (int y = 0; y < height; y++) {
        for (int x = 0; x < width; x++) {
            const std::size_t i = (std::size_t)y * width + x;
            const uint8_t t = truth.cls[i];
            if (t == kTruthNone) continue;
            if (t == kTruthDark) {
                put(out, i, 40, 40, 48);
                continue;
            }
            const bool shadow = t == kTruthShadowed;
            if ((stencil[i] != 0) == shadow) {
                const uint8_t g = shadow ? 90 : 200;
                put(out, i, g, g, g);
            } else if (on_boundary(truth, width, height, x, y)) {
                put(out, i, 255, 220, 0);
            } else {
                put(out, i, 255, 0, 0);
            }
        }
    }
    return out;
}

Image difference_image(const std::vector<uint8_t> &cls, const Image &shaded) {
    Image out(shaded.width, shaded.height);
    for (std::size_t i = 0; i < cls.size(); i++) {
        switch (cls[i]) {
        case 0: dim_copy(shaded, out, i, 3); break;
        case 1: put(out, i, 0, 230, 255); break;
        case 2: put(out, i, 255, 150, 0); break;
        default: put(out, i, 255, 0, 0); break;
        }
    }
    return out;
}

void write_png(const std::string &path, const Image &image) {
    if (image.width <= 0 || image.height <= 0 ||
        !stbi_write_png(path.c_str(), image.width, image.height, 3, image.rgb.data(),
                        image.width * 3)) {
        throw std::runtime_error(path + ": cannot write the PNG file");
    }
}

} // namespace sv::render
