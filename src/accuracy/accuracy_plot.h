/*
 * A small SVG writer for one kind of chart: a log-log scatter plot with a
 * label per point, points grouped by colour, and a separate row under the
 * plot for points whose y is exactly 0 (a log axis has no place for them).
 * `shadowvol accuracy --plot` draws accuracy against speed with it.
 *
 * Copyright (C) 2026 the shadowvol authors. LGPL-2.1-or-later.
 */
#ifndef SV_ACCURACY_PLOT_H
#define SV_ACCURACY_PLOT_H

#include <string>
#include <vector>

namespace sv {
namespace acc {

struct PlotPoint {
    std::string label;
    std::string group; /* same group, same colour; listed in the legend */
    double x = 0;      /* > 0 (points with x <= 0 are left out, and noted) */
    double y = 0;      /* >= 0; 0 goes to the zero row */
};

struct PlotText {
    std::string title, subtitle, x_label, y_label, zero_label, footnote;
};

/* The whole SVG document. Text is escaped. */
std::string svg_loglog_scatter(const std::vector<PlotPoint> &points, const PlotText &text);

/* S with &, <, >, " escaped for XML text and attributes. */
std::string xml_escape(const std::string &s);

} // namespace acc
} // namespace sv

#endif
