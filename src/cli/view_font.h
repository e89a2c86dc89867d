/*
 * shadowvol view's on-screen line (issue 30): a 5x7 bitmap font of the
 * project's own, drawn into an RGB image. Letters are drawn upper-case; a
 * character it has no glyph for is drawn as a box.
 *
 * Copyright (C) 2026 the shadowvol authors. LGPL-2.1-or-later.
 */
#ifndef SV_CLI_VIEW_FONT_H
#define SV_CLI_VIEW_FONT_H

#include <string>

#include "images.h"

namespace svcli {

constexpr int kGlyphWidth = 5, kGlyphHeight = 7, kGlyphAdvance = 6;

/* Draws TEXT with its top-left corner at (X, Y), each glyph pixel a
 * SCALE x SCALE square of colour (R, G, B), on a band darkened to a
 * third behind the line so that it reads on any picture; clipped to the
 * image. */
void draw_text(sv::render::Image &image, int x, int y, const std::string &text, int scale,
               uint8_t r, uint8_t g, uint8_t b);

/* The width in pixels TEXT takes at SCALE. */
int text_width(const std::string &text, int scale);

} // namespace svcli

#endif
