/*
 * The second chart of the SVG module (beside svg_plot.h's line plots, with
 * the same escaping, number format and palette): a log-log scatter plot
 * with a label per point, points grouped by colour, and a separate row
 * under the plot for points whose y is exactly 0 (a log axis has no place
 * for them). `shadowvol accuracy --plot` draws accuracy against speed with
 * it.
 *
 * Copyright (C) 2026 the shadowvol authors. LGPL-2.1-or-later.
 */
#ifndef SV_MEASURE_SVG_SCATTER_H
#define SV_MEASURE_SVG_SCATTER_H

#include <string>
#include <vector>

namespace svplot {

struct ScatterPoint {
    std::string label;
    std::string group; /* same group, same colour; listed in the legend */
    double x = 0;      /* > 0 (points with x <= 0 are left out, and noted) */
    double y = 0;      /* >= 0; 0 goes to the zero row */
};

struct ScatterText {
    std::string title, subtitle, x_label, y_label, zero_label, footnote;
};

/* The whole SVG document. Text is escaped (svg_plot.h's xml_escape). */
std::string render_loglog_scatter(const std::vector<ScatterPoint> &points, const ScatterText &text);

} // namespace svplot

#endif
