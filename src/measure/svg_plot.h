/*
 * Line plots as SVG, written with nothing but the standard library: the
 * scaling run's picture (scaling_plot.h), and anything else the bench may
 * want to draw. A document is a title and a column of panels; a panel has
 * a logarithmic x axis, a y axis (linear from 0, or logarithmic when the
 * values span more than kLogYSpan), one polyline with filled markers per
 * series, loose hollow markers (points of the same series that are not
 * part of its line), vertical marker lines, a legend and caption lines.
 *
 * The output is well-formed XML (text escaped, invalid UTF-8 and control
 * characters replaced) with every number finite; elements carry classes a
 * test or a script can find: <g class="panel" data-id=...>,
 * <polyline class="series" data-series=...> (one per series,
 * inside <g class="series-group">), <g class="vmarker"
 * data-label=...>. Non-finite coordinates, or x <= 0 on the log axis, are
 * a bug in the caller: std::logic_error.
 *
 * Copyright (C) 2026 the shadowvol authors. LGPL-2.1-or-later.
 */
#ifndef SV_BENCH_SVG_PLOT_H
#define SV_BENCH_SVG_PLOT_H

#include <string>
#include <vector>

namespace svplot {

/* y spans more than this factor (and all y > 0): log y axis. */
constexpr double kLogYSpan = 20;

struct Point {
    double x = 0, y = 0;
    std::string label; /* the point's tooltip, before its coordinates */
};

struct Series {
    std::string name;         /* legend; data-series */
    int style = -1;           /* colour and marker shape: the same number gives
                                  the same look in every panel; -1: by position */
    std::vector<Point> line;  /* joined, in x order, filled markers */
    std::vector<Point> loose; /* markers only, hollow */
};

/* A vertical line at X (a cache size, in the x axis's unit). One outside
 * the axis's range is listed under the legend, with its X and an arrow
 * towards the side it lies beyond. */
struct VMarker {
    std::string label; /* "L2 1 MiB" */
    double x = 0;
};

struct Panel {
    std::string id; /* data-id: what a script looks the panel up by */
    std::string title;
    std::string xLabel, yLabel;
    std::vector<Series> series;
    std::vector<VMarker> markers;
    std::vector<std::string> caption; /* lines under the plot */
};

struct Document {
    std::string title;
    std::vector<std::string> notes; /* lines under the title */
    std::string lineKey;            /* what the joined, filled markers are */
    std::string looseKey;           /* what the hollow markers are ("" when none) */
    std::vector<Panel> panels;
};

/* The SVG document, ending in a newline. */
std::string render(const Document &d);

/* TEXT made safe as XML character data and attribute values: & < > " '
 * escaped, control characters other than tab and newline and invalid
 * UTF-8 replaced by U+FFFD. */
std::string xml_escape(const std::string &text);

/* 1344 -> "1.34k", 979776 -> "980k", 1e6 -> "1M": axis and tooltip labels. */
std::string si(double v);

} // namespace svplot

#endif
