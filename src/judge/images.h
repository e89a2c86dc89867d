/*
 * The pictures of a frame (issue 12): the shaded image, each light's
 * stencil counts, the truth comparison and the difference from Mesa, as
 * RGB images; PNG files through Debian's libstb (stb_image_write).
 *
 * Copyright (C) 2026 the shadowvol authors. LGPL-2.1-or-later.
 */
#ifndef SV_RENDER_IMAGES_H
#define SV_RENDER_IMAGES_H

#include <cstdint>
#include <string>
#include <vector>

#include "truth.h"

namespace sv::render {

struct Image {
    int width = 0, height = 0;
    std::vector<uint8_t> rgb; /* row 0 = top */
    Image() = default;
    Image(int w, int h) : width(w), height(h), rgb((std::size_t)w * h * 3, 0) {}
    uint8_t *at(int x, int y) { return &rgb[((std::size_t)y * width + x) * 3]; }
};

/* Panels side by side (all the same height), with a 4-pixel gap. */
Image side_by_side(const std::vector<Image> &panels);

/* A stencil as colours: 0 black over a dim copy of the shaded image;
 * counts 1, 2, 3, 4+ blue, green, yellow, red; counts that read as
 * negative (128-255: more back than front faces counted) magenta. */
Image stencil_image(const std::vector<uint8_t> &stencil, const Image &shaded);

/* Truth against the stencil: lit and agreeing light grey, shadowed and
 * agreeing dark grey, dark (facing away) darker, background black;
 * a mismatch on a boundary yellow, a mismatch off it red. */
Image truth_image(const Truth &truth, const std::vector<uint8_t> &stencil, int width, int height);

/* Pixels where two stencils differ, over a dim copy of SHADED: CLASS[i]
 * gives the colour (1 cyan: on a volume triangle's edge; 2 orange: at a
 * depth tie; 3 red: anything else; 0: equal). */
Image difference_image(const std::vector<uint8_t> &cls, const Image &shaded);

/* Writes IMAGE as PNG; throws std::runtime_error naming PATH on failure. */
void write_png(const std::string &path, const Image &image);

} // namespace sv::render

#endif
