/*
 * The log-log scatter plot of svg_scatter.h.
 *
 * Layout: a plot area with decade grid lines (both axes log10, the range
 * widened to whole decades around the data), a zero row below it, the
 * legend on the right. Labels sit right of their point; a label that would
 * overlap one already placed is moved down (then up) in steps of its
 * height, so points with the same accuracy (the SIMD twins of a variant)
 * stay readable.
 *
 * Copyright (C) 2026 the shadowvol authors. LGPL-2.1-or-later.
 */
#include "svg_scatter.h"

#include "svg_common.h"
#include "svg_plot.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <map>

namespace svplot {

namespace {

constexpr double kWidth = 960, kHeight = 620;
constexpr double kLeft = 90, kRight = 220, kTop = 70, kBottom = 110; /* margins */
constexpr double kZeroRow = 36; /* height of the y = 0 row under the plot */
constexpr double kLabelH = 13;  /* label line height */
constexpr double kCharW = 6.6;  /* approximate width of a 11px character */

using detail::num;

/* "10^k" as SVG text with a superscript. */
std::string decade_label(int k) {
    if (k == 0) return "1";
    if (k == 1) return "10";
    return "10<tspan dy=\"-6\" font-size=\"9\">" + std::to_string(k) + "</tspan>";
}

struct Box {
    double x0, y0, x1, y1;
    bool overlaps(const Box &o) const { return x0 < o.x1 && o.x0 < x1 && y0 < o.y1 && o.y0 < y1; }
};

} // namespace

std::string render_loglog_scatter(const std::vector<ScatterPoint> &points,
                                  const ScatterText &text) {
    std::vector<ScatterPoint> pts;
    int dropped = 0;
    for (const ScatterPoint &p : points) {
        if (p.x > 0 && std::isfinite(p.x) && p.y >= 0 && std::isfinite(p.y)) {
            pts.push_back(p);
        } else {
            dropped++;
        }
    }
    /* Whole decades around the data (at least one decade each way). */
    double xmin = 1, xmax = 10, ymin = 1e-6, ymax = 1e-1;
    bool firstx = true, firsty = true;
    for (const ScatterPoint &p : pts) {
        xmin = firstx ? p.x : std::min(xmin, p.x);
        xmax = firstx ? p.x : std::max(xmax, p.x);
        firstx = false;
        if (p.y > 0) {
            ymin = firsty ? p.y : std::min(ymin, p.y);
            ymax = firsty ? p.y : std::max(ymax, p.y);
            firsty = false;
        }
    }
    int x0 = (int)std::floor(std::log10(xmin)), x1 = (int)std::ceil(std::log10(xmax));
    int y0 = (int)std::floor(std::log10(ymin)), y1 = (int)std::ceil(std::log10(ymax));
    if (x1 <= x0) x1 = x0 + 1;
    if (y1 <= y0) y1 = y0 + 1;

    const double pw = kWidth - kLeft - kRight, ph = kHeight - kTop - kBottom - kZeroRow;
    auto px = [&](double x) { return kLeft + (std::log10(x) - x0) / (x1 - x0) * pw; };
    auto py = [&](double y) {
        if (y <= 0) return kTop + ph + kZeroRow * 0.6;
        return kTop + ph - (std::log10(y) - y0) / (y1 - y0) * ph;
    };

    std::string s;
    s += "<?xml version=\"1.0\" encoding=\"UTF-8\"?>\n";
    s += "<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"" + num(kWidth) + "\" height=\"" +
         num(kHeight) + "\" viewBox=\"0 0 " + num(kWidth) + " " + num(kHeight) +
         "\" font-family=\"DejaVu Sans, Arial, sans-serif\" font-size=\"11\">\n";
    s += "<rect width=\"100%\" height=\"100%\" fill=\"white\"/>\n";
    s += "<text x=\"" + num(kLeft) + "\" y=\"28\" font-size=\"16\" font-weight=\"bold\">" +
         xml_escape(text.title) + "</text>\n";
    s += "<text x=\"" + num(kLeft) + "\" y=\"48\" fill=\"#444\">" + xml_escape(text.subtitle) +
         "</text>\n";

    /* Grid and axes. */
    s += "<g stroke=\"#ddd\" stroke-width=\"1\">\n";
    for (int k = x0; k <= x1; k++) {
        const double x = px(std::pow(10.0, k));
        s += "<line x1=\"" + num(x) + "\" y1=\"" + num(kTop) + "\" x2=\"" + num(x) + "\" y2=\"" +
             num(kTop + ph + kZeroRow) + "\"/>\n";
    }
    for (int k = y0; k <= y1; k++) {
        const double y = py(std::pow(10.0, k));
        s += "<line x1=\"" + num(kLeft) + "\" y1=\"" + num(y) + "\" x2=\"" + num(kLeft + pw) +
             "\" y2=\"" + num(y) + "\"/>\n";
    }
    s += "</g>\n";
    s += "<rect x=\"" + num(kLeft) + "\" y=\"" + num(kTop) + "\" width=\"" + num(pw) +
         "\" height=\"" + num(ph) + "\" fill=\"none\" stroke=\"#333\"/>\n";
    s += "<rect x=\"" + num(kLeft) + "\" y=\"" + num(kTop + ph) + "\" width=\"" + num(pw) +
         "\" height=\"" + num(kZeroRow) + "\" fill=\"#f6f6f6\" stroke=\"#333\"/>\n";
    for (int k = x0; k <= x1; k++) {
        s += "<text x=\"" + num(px(std::pow(10.0, k))) + "\" y=\"" +
             num(kTop + ph + kZeroRow + 16) + "\" text-anchor=\"middle\">" + decade_label(k) +
             "</text>\n";
    }
    for (int k = y0; k <= y1; k++) {
        s += "<text x=\"" + num(kLeft - 8) + "\" y=\"" + num(py(std::pow(10.0, k)) + 4) +
             "\" text-anchor=\"end\">" + decade_label(k) + "</text>\n";
    }
    s += "<text x=\"" + num(kLeft - 8) + "\" y=\"" + num(py(0) + 4) + "\" text-anchor=\"end\">" +
         xml_escape(text.zero_label) + "</text>\n";
    s += "<text x=\"" + num(kLeft + pw / 2) + "\" y=\"" + num(kTop + ph + kZeroRow + 38) +
         "\" text-anchor=\"middle\" font-size=\"12\">" + xml_escape(text.x_label) + "</text>\n";
    s += "<text transform=\"translate(24," + num(kTop + ph / 2) +
         ") rotate(-90)\" text-anchor=\"middle\" font-size=\"12\">" + xml_escape(text.y_label) +
         "</text>\n";

    /* Colours by group, in order of appearance. */
    std::map<std::string, std::string> colour;
    std::vector<std::string> groups;
    for (const ScatterPoint &p : pts) {
        if (!colour.count(p.group)) {
            colour[p.group] = detail::colour((int)groups.size());
            groups.push_back(p.group);
        }
    }

    /* Points, then labels placed without overlaps (greedy, in order of y). */
    std::vector<std::size_t> order(pts.size());
    for (std::size_t i = 0; i < order.size(); i++) order[i] = i;
    std::stable_sort(order.begin(), order.end(),
                     [&](std::size_t a, std::size_t b) { return py(pts[a].y) < py(pts[b].y); });
    std::vector<Box> placed;
    for (const ScatterPoint &p : pts) {
        s += "<circle cx=\"" + num(px(p.x)) + "\" cy=\"" + num(py(p.y)) + "\" r=\"4.5\" fill=\"" +
             colour[p.group] + "\" stroke=\"#222\" stroke-width=\"0.6\"/>\n";
        placed.push_back({px(p.x) - 5, py(p.y) - 5, px(p.x) + 5, py(p.y) + 5});
    }
    for (std::size_t i : order) {
        const ScatterPoint &p = pts[i];
        const double w = kCharW * (double)p.label.size();
        const double x = px(p.x) + 7;
        double y = py(p.y) + 4;
        Box b{x, y - kLabelH + 3, x + w, y + 3};
        for (int step = 1; step < 40; step++) {
            bool clash = false;
            for (const Box &o : placed) clash = clash || b.overlaps(o);
            if (!clash) break;
            const int ring = (step + 1) / 2; /* 1, 1, 2, 2, ...: below, above, ... */
            const double dy = (step % 2 ? 1 : -1) * ring * kLabelH;
            b = Box{x, py(p.y) + 4 + dy - kLabelH + 3, x + w, py(p.y) + 4 + dy + 3};
            y = py(p.y) + 4 + dy;
        }
        placed.push_back(b);
        if (std::fabs(y - (py(p.y) + 4)) > 1) {
            s += "<line x1=\"" + num(px(p.x)) + "\" y1=\"" + num(py(p.y)) + "\" x2=\"" + num(x) +
                 "\" y2=\"" + num(y - 4) + "\" stroke=\"#999\" stroke-width=\"0.5\"/>\n";
        }
        s += "<text x=\"" + num(x) + "\" y=\"" + num(y) + "\">" + xml_escape(p.label) + "</text>\n";
    }

    /* Legend. */
    double ly = kTop + 10;
    const double lx = kLeft + pw + 24;
    s += "<text x=\"" + num(lx) + "\" y=\"" + num(ly) + "\" font-weight=\"bold\">family</text>\n";
    for (const std::string &g : groups) {
        ly += 18;
        s += "<circle cx=\"" + num(lx + 5) + "\" cy=\"" + num(ly - 4) + "\" r=\"4.5\" fill=\"" +
             colour[g] + "\" stroke=\"#222\" stroke-width=\"0.6\"/>\n";
        s += "<text x=\"" + num(lx + 16) + "\" y=\"" + num(ly) + "\">" + xml_escape(g) +
             "</text>\n";
    }
    std::string foot = text.footnote;
    if (dropped) {
        foot += (foot.empty() ? "" : " ") + std::to_string(dropped) +
                " point(s) without a positive speed left out.";
    }
    s += "<text x=\"" + num(kLeft) + "\" y=\"" + num(kHeight - 14) + "\" fill=\"#444\">" +
         xml_escape(foot) + "</text>\n";
    s += "</svg>\n";
    return s;
}

} // namespace svplot
