// Log–log line plots written as standalone SVG: Fig. 13's runtime against input size.
#pragma once

#include <string>
#include <utility>
#include <vector>

namespace bench {

struct PlotSeries {
    std::string label;
    std::string colour;                             // any SVG colour
    std::string dash;                               // SVG stroke-dasharray; "" for a solid line
    bool connect = true;                            // a line through the points in x order; false: markers only
    bool hollow = false;                            // open circles instead of dots
    std::vector<std::pair<double, double>> points;  // (x, y), both > 0
};

struct PlotTick {
    double value;
    std::string label;
};

struct Plot {
    std::string title;
    std::string x_label;
    std::string y_label;
    std::vector<PlotTick> x_ticks;  // labelled x positions; y gets 1-2-5 ticks
    std::vector<PlotSeries> series;
    std::vector<std::string> notes;  // lines below the legend
};

std::string renderLogLogSvg(const Plot& plot);

}  // namespace bench
