/*
 * Copyright (C) 2026 the shadowvol authors. LGPL-2.1-or-later.
 */
#include "svg_plot.h"
#include "svg_common.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <stdexcept>

namespace svplot {

/* The primitives svg_common.h declares, shared with svg_scatter.cpp. */
namespace detail {

/* Okabe and Ito's colour-blind-safe palette (yellow left out: too pale on
 * white), then black; the marker shape also differs per series. */
const char *const kColours[] = {"#0072B2", "#D55E00", "#009E73", "#CC79A7",
                                "#E69F00", "#56B4E9", "#000000"};
const int kNumColours = sizeof kColours / sizeof kColours[0];

const char *colour(int k) { return kColours[((k % kNumColours) + kNumColours) % kNumColours]; }

std::string num(double v) {
    if (!std::isfinite(v)) {
        throw std::logic_error("svg_plot: a coordinate is not finite");
    }
    char s[32];
    std::snprintf(s, sizeof s, "%.2f", v);
    return s;
}

std::string attr(const char *name, const std::string &value) {
    return std::string(" ") + name + "=\"" + xml_escape(value) + "\"";
}

} // namespace detail

namespace {

/* Geometry, in SVG user units (pixels at 100%). */
constexpr double kWidth = 960;
constexpr double kMargin = 16;
constexpr double kPlotLeft = 72;   /* room for the y tick labels */
constexpr double kPlotRight = 730; /* the legend is to the right */
constexpr double kPlotHeight = 250;
constexpr double kTitleGap = 30; /* panel title above the plot */
constexpr double kAxisGap = 44;  /* x tick labels and x label below */
constexpr double kLine = 15;     /* caption and note line height */
constexpr double kPanelGap = 18;
constexpr double kMarkerSize = 4;

constexpr int kNumShapes = 5;

using detail::attr;
using detail::num;

/* One axis' mapping from data to pixels. */
struct Scale {
    bool log = false;
    double lo = 0, hi = 1; /* data range */
    double p0 = 0, p1 = 1; /* pixels of lo and hi */
    double operator()(double v) const {
        const double t = log ? (std::log10(v) - std::log10(lo)) / (std::log10(hi) - std::log10(lo))
                             : (v - lo) / (hi - lo);
        return p0 + t * (p1 - p0);
    }
    bool contains(double v) const { return v >= lo && v <= hi; }
};

/* The smallest of 1, 2, 5 x 10^k at least V. */
double nice_ceil(double v) {
    const double p = std::pow(10, std::floor(std::log10(v)));
    for (double m : {1.0, 2.0, 5.0, 10.0}) {
        if (m * p >= v * (1 - 1e-12)) {
            return m * p;
        }
    }
    return 10 * p;
}

/* A tick step of 1, 2 or 5 x 10^k giving 4 to 10 ticks on [0, HI]. */
double tick_step(double hi) {
    double step = nice_ceil(hi / 8);
    return step > 0 ? step : 1;
}

std::string y_label(double v) {
    char s[32];
    if (v == 0) {
        return "0";
    }
    if (std::fabs(v) >= 100 || std::fabs(v - std::round(v)) < 1e-9 * std::fabs(v)) {
        std::snprintf(s, sizeof s, "%.0f", v);
    } else {
        std::snprintf(s, sizeof s, "%.3g", v);
    }
    return s;
}

/* The marker of series K at (X, Y): a filled or hollow shape. */
std::string marker(int k, double x, double y, const char *colour, bool filled,
                   const std::string &tooltip) {
    const double r = kMarkerSize;
    std::string fill = filled ? colour : "#ffffff";
    std::string s;
    switch (k % kNumShapes) {
    case 0: s = "<circle cx=\"" + num(x) + "\" cy=\"" + num(y) + "\" r=\"" + num(r) + "\""; break;
    case 1:
        s = "<rect x=\"" + num(x - r) + "\" y=\"" + num(y - r) + "\" width=\"" + num(2 * r) +
            "\" height=\"" + num(2 * r) + "\"";
        break;
    case 2: /* triangle, point up */
        s = "<path d=\"M" + num(x) + " " + num(y - 1.2 * r) + " L" + num(x + 1.1 * r) + " " +
            num(y + 0.9 * r) + " L" + num(x - 1.1 * r) + " " + num(y + 0.9 * r) + " Z\"";
        break;
    case 3: /* diamond */
        s = "<path d=\"M" + num(x) + " " + num(y - 1.3 * r) + " L" + num(x + 1.3 * r) + " " +
            num(y) + " L" + num(x) + " " + num(y + 1.3 * r) + " L" + num(x - 1.3 * r) + " " +
            num(y) + " Z\"";
        break;
    default: /* triangle, point down */
        s = "<path d=\"M" + num(x) + " " + num(y + 1.2 * r) + " L" + num(x + 1.1 * r) + " " +
            num(y - 0.9 * r) + " L" + num(x - 1.1 * r) + " " + num(y - 0.9 * r) + " Z\"";
        break;
    }
    s += attr("fill", fill) + attr("stroke", colour) + " stroke-width=\"1.5\"";
    if (tooltip.empty()) {
        return s + "/>";
    }
    return s + "><title>" + xml_escape(tooltip) + "</title></" +
           (k % kNumShapes == 0   ? "circle"
            : k % kNumShapes == 1 ? "rect"
                                  : "path") +
           ">";
}

std::string text(double x, double y, const std::string &t, const char *extra = "") {
    return "<text x=\"" + num(x) + "\" y=\"" + num(y) + "\"" + extra + ">" + xml_escape(t) +
           "</text>";
}

void check_point(const Point &p, const Panel &panel) {
    if (!std::isfinite(p.x) || !std::isfinite(p.y) || p.x <= 0) {
        throw std::logic_error("svg_plot: panel " + panel.id +
                               ": a point is not finite or not positive in x");
    }
}

int style_of(const Series &s, size_t position) { return s.style >= 0 ? s.style : (int)position; }

/* The panel at vertical offset TOP; returns its height. */
double render_panel(std::string &out, const Panel &p, double top, const Document &d) {
    /* Data ranges. */
    double xmin = HUGE_VAL, xmax = -HUGE_VAL, ymin = HUGE_VAL, ymax = -HUGE_VAL;
    for (const Series &s : p.series) {
        for (const std::vector<Point> *pts : {&s.line, &s.loose}) {
            for (const Point &pt : *pts) {
                check_point(pt, p);
                xmin = std::min(xmin, pt.x);
                xmax = std::max(xmax, pt.x);
                ymin = std::min(ymin, pt.y);
                ymax = std::max(ymax, pt.y);
            }
        }
    }
    const bool empty = !(xmin <= xmax);
    if (empty) {
        xmin = 1;
        xmax = 10;
        ymin = 0;
        ymax = 1;
    }
    for (const VMarker &m : p.markers) {
        if (!std::isfinite(m.x) || m.x <= 0) {
            throw std::logic_error("svg_plot: panel " + p.id + ": marker " + m.label +
                                   " is not finite and positive");
        }
    }

    const double plotTop = top + kTitleGap;
    const double plotBottom = plotTop + kPlotHeight;
    Scale x;
    x.log = true;
    x.lo = std::pow(10, std::floor(std::log10(xmin)));
    x.hi = std::pow(10, std::ceil(std::log10(xmax)));
    if (x.hi <= x.lo) {
        x.hi = x.lo * 10;
    }
    x.p0 = kPlotLeft;
    x.p1 = kPlotRight;
    Scale y;
    y.log = ymin > 0 && ymax / ymin > kLogYSpan;
    if (y.log) {
        y.lo = std::pow(10, std::floor(std::log10(ymin)));
        y.hi = std::pow(10, std::ceil(std::log10(ymax)));
    } else {
        y.lo = 0;
        y.hi = ymax > 0 ? nice_ceil(ymax * 1.05) : 1;
    }
    y.p0 = plotBottom;
    y.p1 = plotTop;

    out += "<g class=\"panel\"" + attr("data-id", p.id) + ">\n";
    out += text(kPlotLeft, top + 18, p.title, " class=\"panel-title\"") + "\n";

    /* Grid and ticks. */
    out += "<g class=\"grid\">\n";
    for (double dec = x.lo; dec <= x.hi * 1.0001; dec *= 10) {
        for (int m = 1; m < 10; m++) {
            const double v = dec * m;
            if (v > x.hi * 1.0001) {
                break;
            }
            const double px = x(v);
            out += "<line x1=\"" + num(px) + "\" y1=\"" + num(plotTop) + "\" x2=\"" + num(px) +
                   "\" y2=\"" + num(plotBottom) + "\" class=\"" + (m == 1 ? "major" : "minor") +
                   "\"/>\n";
            if (m == 1) {
                out += text(px, plotBottom + 16, si(v), " text-anchor=\"middle\"") + "\n";
            }
        }
    }
    std::vector<double> yticks;
    if (y.log) {
        for (double dec = y.lo; dec <= y.hi * 1.0001; dec *= 10) {
            yticks.push_back(dec);
            if (y.hi / y.lo <= 1000) { /* few decades: 2 and 5 too */
                for (double m : {2.0, 5.0}) {
                    if (dec * m < y.hi) {
                        yticks.push_back(dec * m);
                    }
                }
            }
        }
    } else {
        const double step = tick_step(y.hi);
        for (int i = 0; i * step <= y.hi * 1.0001; i++) {
            yticks.push_back(i * step);
        }
    }
    for (double v : yticks) {
        const double py = y(v);
        out += "<line x1=\"" + num(kPlotLeft) + "\" y1=\"" + num(py) + "\" x2=\"" +
               num(kPlotRight) + "\" y2=\"" + num(py) + "\" class=\"major\"/>\n";
        out += text(kPlotLeft - 6, py + 4, y_label(v), " text-anchor=\"end\"") + "\n";
    }
    out += "</g>\n";
    out += "<rect x=\"" + num(kPlotLeft) + "\" y=\"" + num(plotTop) + "\" width=\"" +
           num(kPlotRight - kPlotLeft) + "\" height=\"" + num(kPlotHeight) +
           "\" class=\"frame\"/>\n";
    out += text((kPlotLeft + kPlotRight) / 2, plotBottom + 34, p.xLabel,
                " text-anchor=\"middle\"") +
           "\n";
    out += "<text transform=\"translate(" + num(kMargin + 4) + " " +
           num((plotTop + plotBottom) / 2) + ") rotate(-90)\" text-anchor=\"middle\">" +
           xml_escape(p.yLabel + (y.log ? " (log scale)" : "")) + "</text>\n";

    /* Vertical markers inside the range: a dashed line, its label at the
     * top (those beyond it go under the legend). */
    std::vector<const VMarker *> beyond;
    for (const VMarker &m : p.markers) {
        if (!x.contains(m.x)) {
            beyond.push_back(&m);
            continue;
        }
        const double px = x(m.x);
        out += "<g class=\"vmarker\"" + attr("data-label", m.label) + attr("data-x", num(m.x)) +
               "><line x1=\"" + num(px) + "\" y1=\"" + num(plotTop) + "\" x2=\"" + num(px) +
               "\" y2=\"" + num(plotBottom) + "\"/>" + text(px + 3, plotTop + 12, m.label) +
               "</g>\n";
    }

    /* Series: the polyline, then its markers. */
    for (size_t k = 0; k < p.series.size(); k++) {
        const Series &s = p.series[k];
        const int style = style_of(s, k);
        const char *colour = detail::colour(style);
        std::vector<Point> line = s.line;
        std::stable_sort(line.begin(), line.end(),
                         [](const Point &a, const Point &b) { return a.x < b.x; });
        out += "<g class=\"series-group\"" + attr("data-series", s.name) + ">\n";
        out += "<polyline class=\"series\"" + attr("data-series", s.name) + " points=\"";
        for (size_t i = 0; i < line.size(); i++) {
            out += (i ? " " : "") + num(x(line[i].x)) + "," + num(y(line[i].y));
        }
        out += "\"" + attr("stroke", colour) + " fill=\"none\" stroke-width=\"2\"/>\n";
        auto markers = [&](const std::vector<Point> &pts, bool filled) {
            for (const Point &pt : pts) {
                const std::string tip = s.name + ": " + (pt.label.empty() ? "" : pt.label + ", ") +
                                        si(pt.x) + ", " + y_label(pt.y);
                out += marker(style, x(pt.x), y(pt.y), colour, filled, tip) + "\n";
            }
        };
        markers(line, true);
        markers(s.loose, false);
        out += "</g>\n";
    }

    /* Legend, right of the plot. */
    double ly = plotTop + 8;
    const double lx = kPlotRight + 18;
    out += "<g class=\"legend\">\n";
    for (size_t k = 0; k < p.series.size(); k++) {
        const int style = style_of(p.series[k], k);
        const char *colour = detail::colour(style);
        out += "<line x1=\"" + num(lx) + "\" y1=\"" + num(ly) + "\" x2=\"" + num(lx + 28) +
               "\" y2=\"" + num(ly) + "\"" + attr("stroke", colour) + " stroke-width=\"2\"/>";
        out += marker(style, lx + 14, ly, colour, true, "");
        out += text(lx + 36, ly + 4, p.series[k].name) + "\n";
        ly += 18;
    }
    if (!p.series.empty()) {
        ly += 6;
        out += marker(0, lx + 14, ly, "#555555", true, "") + text(lx + 36, ly + 4, d.lineKey) +
               "\n";
        if (!d.looseKey.empty()) {
            ly += 18;
            out += marker(0, lx + 14, ly, "#555555", false, "") +
                   text(lx + 36, ly + 4, d.looseKey) + "\n";
        }
    }
    if (empty) {
        ly += 18;
        out += text(lx, ly + 4, "no points") + "\n";
    }
    if (!beyond.empty()) {
        ly += 24;
        out += text(lx, ly + 4, "beyond the axis:") + "\n";
    }
    for (const VMarker *m : beyond) {
        ly += 16;
        const bool right = m->x > x.hi;
        out += "<g class=\"vmarker\"" + attr("data-label", m->label) + attr("data-x", num(m->x)) +
               "><line x1=\"" + num(lx) + "\" y1=\"" + num(ly) + "\" x2=\"" + num(lx + 28) +
               "\" y2=\"" + num(ly) + "\"/>" +
               text(lx + 36, ly + 4,
                    m->label + " at " + si(m->x) + (right ? " \u2192" : " \u2190")) +
               "</g>\n";
    }
    out += "</g>\n";

    double cy = plotBottom + kAxisGap + 8;
    for (const std::string &c : p.caption) {
        out += text(kPlotLeft, cy, c, " class=\"caption\"") + "\n";
        cy += kLine;
    }
    out += "</g>\n";
    return cy - top;
}

/* Appends the UTF-8 encoding of U+FFFD. */
void replacement(std::string &out) { out += "\xef\xbf\xbd"; }

} // namespace

std::string xml_escape(const std::string &t) {
    std::string out;
    out.reserve(t.size());
    const unsigned char *s = (const unsigned char *)t.data();
    const size_t n = t.size();
    for (size_t i = 0; i < n;) {
        const unsigned char c = s[i];
        if (c < 0x80) {
            switch (c) {
            case '&': out += "&amp;"; break;
            case '<': out += "&lt;"; break;
            case '>': out += "&gt;"; break;
            case '"': out += "&quot;"; break;
            case '\'': out += "&apos;"; break;
            default:
                if ((c < 0x20 && c != '\t' && c != '\n') || c == 0x7f) {
                    replacement(out); /* not allowed in XML 1.0; DEL, replaced too */
                } else {
                    out += (char)c;
                }
            }
            i++;
            continue;
        }
        /* A multi-byte sequence: its length from the lead byte, then the
         * continuation bytes, no overlong form, no surrogate, <= U+10FFFF. */
        int len = c >= 0xf0 && c <= 0xf4 ? 4 : c >= 0xe0 ? 3 : c >= 0xc2 && c < 0xe0 ? 2 : 0;
        if (c > 0xf4) {
            len = 0;
        }
        bool ok = len > 0 && i + (size_t)len <= n;
        unsigned cp = ok ? (unsigned)(c & (0xff >> (len + 1))) : 0;
        for (int k = 1; ok && k < len; k++) {
            ok = (s[i + (size_t)k] & 0xc0) == 0x80;
            cp = cp << 6 | (s[i + (size_t)k] & 0x3f);
        }
        ok = ok && !(len == 3 && cp < 0x800) && !(len == 4 && (cp < 0x10000 || cp > 0x10ffff)) &&
             !(cp >= 0xd800 && cp <= 0xdfff) && cp != 0xfffe && cp != 0xffff;
        if (ok) {
            out.append(t, i, (size_t)len);
            i += (size_t)len;
        } else {
            replacement(out);
            i++;
        }
    }
    return out;
}

std::string si(double v) {
    char s[32];
    const double a = std::fabs(v);
    const char *suffix = "";
    double m = v;
    if (a >= 1e9) {
        m = v / 1e9;
        suffix = "G";
    } else if (a >= 1e6) {
        m = v / 1e6;
        suffix = "M";
    } else if (a >= 1e3) {
        m = v / 1e3;
        suffix = "k";
    }
    std::snprintf(s, sizeof s, "%.3g%s", m, suffix);
    return s;
}

std::string render(const Document &d) {
    std::string body;
    double top = kMargin;
    body += text(kMargin, top + 16, d.title, " class=\"title\"") + "\n";
    top += 26;
    for (const std::string &n : d.notes) {
        body += text(kMargin, top + 12, n, " class=\"note\"") + "\n";
        top += kLine;
    }
    top += 6;
    for (const Panel &p : d.panels) {
        top += render_panel(body, p, top, d) + kPanelGap;
    }
    const double height = top + kMargin;

    std::string out = "<?xml version=\"1.0\" encoding=\"UTF-8\"?>\n";
    out += "<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"" + num(kWidth) + "\" height=\"" +
           num(height) + "\" viewBox=\"0 0 " + num(kWidth) + " " + num(height) + "\">\n";
    out += "<title>" + xml_escape(d.title) + "</title>\n";
    out += "<style>\n"
           "text { font-family: sans-serif; font-size: 12px; fill: #222; }\n"
           ".title { font-size: 16px; font-weight: bold; }\n"
           ".panel-title { font-size: 14px; font-weight: bold; }\n"
           ".note, .caption { font-size: 11.5px; fill: #444; }\n"
           ".grid line.major { stroke: #d8d8d8; stroke-width: 1; }\n"
           ".grid line.minor { stroke: #efefef; stroke-width: 1; }\n"
           ".frame { fill: none; stroke: #888; stroke-width: 1; }\n"
           ".vmarker line { stroke: #7a1f1f; stroke-width: 1.5; stroke-dasharray: 6 4; }\n"
           ".vmarker text { fill: #7a1f1f; font-size: 11px; }\n"
           "</style>\n";
    out += "<rect width=\"100%\" height=\"100%\" fill=\"#ffffff\"/>\n";
    out += body;
    out += "</svg>\n";
    return out;
}

} // namespace svplot
