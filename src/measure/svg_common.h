/*
 * What the SVG writers of this module share (svg_plot.cpp's line plots,
 * svg_scatter.cpp's scatter plot): one number format, one attribute
 * writer, one palette. Internal to src/measure.
 *
 * Copyright (C) 2026 the shadowvol authors. LGPL-2.1-or-later.
 */
#ifndef SV_MEASURE_SVG_COMMON_H
#define SV_MEASURE_SVG_COMMON_H

#include <string>

namespace svplot {
namespace detail {

/* V with two decimals; a non-finite V is a bug in the caller:
 * std::logic_error. */
std::string num(double v);

/* ` name="value"`, the value escaped (xml_escape). */
std::string attr(const char *name, const std::string &value);

/* Colour K of the palette (Okabe and Ito's colour-blind-safe colours,
 * then black), cycling; any K, negative too. */
const char *colour(int k);

} // namespace detail
} // namespace svplot

#endif
