#include "svg_plot.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>

namespace bench {

namespace {

// Canvas and plot area, in SVG user units; the legend sits right of the plot.
const double kWidth = 960, kHeight = 600;
const double kLeft = 80, kRight = 640, kTop = 50, kBottom = 520;
const double kLegendX = 660;
const size_t kNoteChars = 50;  // what fits right of the plot at the notes' font size

struct Range {
    double lo = std::numeric_limits<double>::infinity();
    double hi = -std::numeric_limits<double>::infinity();
    void extend(double v) { lo = std::min(lo, v), hi = std::max(hi, v); }
};

std::string escaped(const std::string& text) {
    std::string out;
    for (char c : text) out += c == '&' ? "&amp;" : c == '<' ? "&lt;" : c == '>' ? "&gt;" : std::string(1, c);
    return out;
}

// `note` broken at spaces into lines of at most kNoteChars (longer words stay whole).
std::vector<std::string> wrapped(const std::string& note) {
    std::vector<std::string> lines(1);
    size_t begin = 0;
    while (begin < note.size()) {
        size_t end = note.find(' ', begin);
        if (end == std::string::npos) end = note.size();
        const std::string word = note.substr(begin, end - begin);
        if (!lines.back().empty() && lines.back().size() + 1 + word.size() > kNoteChars) lines.emplace_back();
        lines.back() += (lines.back().empty() ? "" : " ") + word;
        begin = end + 1;
    }
    return lines;
}

std::string number(double v) {
    char text[32];
    std::snprintf(text, sizeof text, "%.1f", v);
    return text;
}

std::string tickLabel(double v) {
    char text[32];
    std::snprintf(text, sizeof text, "%g", v);
    return text;
}

// Position of v on a log axis from lo to hi mapped onto [a, b].
double logPosition(double v, const Range& r, double a, double b) {
    return a + (b - a) * (std::log10(v) - std::log10(r.lo)) / (std::log10(r.hi) - std::log10(r.lo));
}

std::string text(double x, double y, const std::string& content, const char* anchor, int size = 13,
                 const std::string& extra = "") {
    return "<text x=\"" + number(x) + "\" y=\"" + number(y) + "\" font-size=\"" + std::to_string(size) +
           "\" text-anchor=\"" + anchor + "\"" + extra + ">" + escaped(content) + "</text>\n";
}

std::string line(double x1, double y1, double x2, double y2, const std::string& style) {
    return "<line x1=\"" + number(x1) + "\" y1=\"" + number(y1) + "\" x2=\"" + number(x2) + "\" y2=\"" + number(y2) +
           "\" " + style + "/>\n";
}

std::string marker(double x, double y, const PlotSeries& s) {
    const std::string fill = s.hollow ? "none" : s.colour;
    return "<circle cx=\"" + number(x) + "\" cy=\"" + number(y) + "\" r=\"3.5\" fill=\"" + fill + "\" stroke=\"" +
           s.colour + "\" stroke-width=\"1.5\"/>\n";
}

}  // namespace

std::string renderLogLogSvg(const Plot& plot) {
    Range xr, yr;
    for (const PlotSeries& s : plot.series)
        for (auto [x, y] : s.points)
            if (x > 0 && y > 0) xr.extend(x), yr.extend(y);
    for (const PlotTick& t : plot.x_ticks) xr.extend(t.value);
    if (!(xr.lo < xr.hi)) xr = {1, 10};
    if (!(yr.lo <= yr.hi)) yr = {1, 10};
    // A little room around the data; y spans whole decades so its ticks frame the plot.
    xr = {xr.lo / 1.25, xr.hi * 1.25};
    yr = {std::pow(10.0, std::floor(std::log10(yr.lo))), std::pow(10.0, std::ceil(std::log10(yr.hi)))};
    if (yr.hi <= yr.lo) yr.hi = yr.lo * 10;

    auto px = [&](double x) { return logPosition(x, xr, kLeft, kRight); };
    auto py = [&](double y) { return logPosition(y, yr, kBottom, kTop); };

    std::string svg = "<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"" + number(kWidth) + "\" height=\"" +
                      number(kHeight) + "\" viewBox=\"0 0 " + number(kWidth) + " " + number(kHeight) +
                      "\" font-family=\"sans-serif\">\n<rect width=\"100%\" height=\"100%\" fill=\"white\"/>\n";
    svg += text((kLeft + kRight) / 2, 28, plot.title, "middle", 16, " font-weight=\"bold\"");
    const std::string grid = "stroke=\"#dddddd\" stroke-width=\"1\"";
    for (double decade = yr.lo; decade < yr.hi * 1.001; decade *= 10)
        for (double step : {1.0, 2.0, 5.0}) {
            const double y = decade * step;
            if (y > yr.hi * 1.001) break;
            svg += line(kLeft, py(y), kRight, py(y), grid);
            svg += text(kLeft - 8, py(y) + 4, tickLabel(y), "end");
        }
    for (const PlotTick& t : plot.x_ticks) {
        svg += line(px(t.value), kTop, px(t.value), kBottom, grid);
        svg += text(px(t.value), kBottom + 20, t.label, "middle");
    }
    svg += "<rect x=\"" + number(kLeft) + "\" y=\"" + number(kTop) + "\" width=\"" + number(kRight - kLeft) +
           "\" height=\"" + number(kBottom - kTop) + "\" fill=\"none\" stroke=\"black\"/>\n";
    svg += text((kLeft + kRight) / 2, kBottom + 50, plot.x_label, "middle", 14);
    svg += text(22, (kTop + kBottom) / 2, plot.y_label, "middle", 14,
                " transform=\"rotate(-90 22 " + number((kTop + kBottom) / 2) + ")\"");

    double legend_y = kTop + 10;
    for (const PlotSeries& s : plot.series) {
        std::vector<std::pair<double, double>> points;
        for (auto p : s.points)
            if (p.first > 0 && p.second > 0) points.push_back(p);
        std::sort(points.begin(), points.end());
        const std::string stroke = "stroke=\"" + s.colour + "\" stroke-width=\"2\"" +
                                   (s.dash.empty() ? "" : " stroke-dasharray=\"" + s.dash + "\"");
        if (s.connect && points.size() > 1) {
            svg += "<polyline fill=\"none\" " + stroke + " points=\"";
            for (auto [x, y] : points) svg += number(px(x)) + "," + number(py(y)) + " ";
            svg += "\"/>\n";
        }
        for (auto [x, y] : points) svg += marker(px(x), py(y), s);
        if (s.connect) svg += line(kLegendX, legend_y, kLegendX + 30, legend_y, stroke);
        svg += marker(kLegendX + 15, legend_y, s);
        svg += text(kLegendX + 38, legend_y + 4, s.label + (points.empty() ? " (no data)" : ""), "start", 12);
        legend_y += 20;
    }
    legend_y += 10;
    for (const std::string& note : plot.notes) {
        for (const std::string& note_line : wrapped(note)) {
            svg += text(kLegendX, legend_y, note_line, "start", 11, " fill=\"#555555\"");
            legend_y += 15;
        }
        legend_y += 4;
    }
    return svg + "</svg>\n";
}

}  // namespace bench
