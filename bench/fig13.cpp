#include "fig13.h"

#include <cstdio>
#include <filesystem>

#include "scaling.h"
#include "svg_plot.h"
#include "text_file.h"

namespace bench {

namespace {

// Colour per method, in scalingMethods() order; the stage plot tells methods by dashes.
const char* const kMethodColours[] = {"#1f77b4", "#d62728", "#2ca02c"};
const char* const kMethodDashes[] = {"", "7 4", "2 3"};

struct Stage {
    const char* name;
    const char* colour;
    double (*seconds)(const DdtMeasurement&);
};
const Stage kStages[] = {
    {"time-init", "#9467bd", [](const DdtMeasurement& m) { return m.median.init_s; }},
    {"time-comp", "#ff7f0e", [](const DdtMeasurement& m) { return m.median.comp_s; }},
    {"time-final", "#17becf", [](const DdtMeasurement& m) { return m.median.final_s; }},
};

std::string csvOf(const BenchResults& results) {
    std::string csv =
        "dataset,image,width,height,pixels,method,runs,time_init_s,time_comp_s,time_final_s,time_sum_s,flips,"
        "iterations\n";
    for (const ScalingResult& r : results.scaling) {
        const DdtMeasurement& m = r.measurement;
        char line[512];
        std::snprintf(line, sizeof line, "%s,%s,%u,%u,%llu,%s,%zu,%.6f,%.6f,%.6f,%.6f,%llu,%u\n", r.dataset.c_str(),
                      r.image.c_str(), r.width, r.height, static_cast<unsigned long long>(r.width) * r.height,
                      r.method_key.c_str(), m.runs.size(), m.median.init_s, m.median.comp_s, m.median.final_s,
                      m.medianSum(), static_cast<unsigned long long>(m.runs.front().stats.flips),
                      m.runs.front().stats.iterations);
        csv += line;
    }
    return csv;
}

// x ticks at the powers of two on the √2 ladder: 64², 128², …
std::vector<PlotTick> sizeTicks(const BenchResults& results) {
    uint32_t largest = 64;
    for (const ScalingResult& r : results.scaling) largest = std::max({largest, r.width, r.height});
    std::vector<PlotTick> ticks;
    for (uint32_t side = 64; side <= largest; side *= 2)
        ticks.push_back({double(side) * side, std::to_string(side) + "²"});
    return ticks;
}

std::vector<std::pair<double, double>> pointsOf(const BenchResults& results, const std::string& dataset,
                                                const std::string& method_key,
                                                double (*seconds)(const DdtMeasurement&)) {
    std::vector<std::pair<double, double>> points;
    for (const ScalingResult& r : results.scaling)
        if (r.dataset == dataset && r.method_key == method_key)
            points.push_back({double(r.width) * r.height, seconds(r.measurement)});
    return points;
}

std::vector<std::string> commonNotes(const BenchResults& results) {
    std::vector<std::string> notes = {
        "×" + std::to_string(kScalingFactor) + " magnification; median of " + std::to_string(results.scaling_repeats) +
            " run(s) after " + std::to_string(results.warmups) + " warm-up",
        "time-init: PNG decode from memory + prepare",
        "time-final: render into memory (no encode)",
    };
    for (const DdtMethod& method : results.scaling_methods)
        if (!method.unavailable.empty()) notes.push_back(method.label + ": n/a, " + method.unavailable);
    return notes;
}

Plot runtimePlot(const BenchResults& results) {
    Plot plot;
    plot.title = "Fig. 13: time-sum against input size";
    plot.x_label = "input size (pixels, log scale)";
    plot.y_label = "time-sum (s, log scale)";
    plot.x_ticks = sizeTicks(results);
    for (size_t i = 0; i < results.scaling_methods.size(); ++i) {
        const DdtMethod& method = results.scaling_methods[i];
        if (!method.unavailable.empty()) continue;
        auto sum = [](const DdtMeasurement& m) { return m.medianSum(); };
        plot.series.push_back({method.label + ", one image resized", kMethodColours[i], "", true, false,
                               pointsOf(results, "resized", method.key, sum)});
        plot.series.push_back({method.label + ", every set image", kMethodColours[i], "", false, true,
                               pointsOf(results, "set", method.key, sum)});
    }
    plot.notes = commonNotes(results);
    const std::string image = std::filesystem::path(results.scaling_image).filename().string();
    plot.notes.insert(plot.notes.begin(), "resized: " + image + " at n × n; every set image at its own size");
    return plot;
}

Plot stagesPlot(const BenchResults& results) {
    Plot plot;
    plot.title = "Fig. 13: stage times against input size (one image resized)";
    plot.x_label = "input size (pixels, log scale)";
    plot.y_label = "stage time (s, log scale)";
    plot.x_ticks = sizeTicks(results);
    for (size_t i = 0; i < results.scaling_methods.size(); ++i) {
        const DdtMethod& method = results.scaling_methods[i];
        if (!method.unavailable.empty()) continue;
        for (const Stage& stage : kStages)
            plot.series.push_back({method.label + ", " + stage.name, stage.colour, kMethodDashes[i], true, false,
                                   pointsOf(results, "resized", method.key, stage.seconds)});
    }
    plot.notes = commonNotes(results);
    return plot;
}

}  // namespace

void writeFig13(const BenchResults& results, const std::string& out_dir) {
    writeTextFile(out_dir + "/fig13.csv", csvOf(results));
    writeTextFile(out_dir + "/fig13_runtime.svg", renderLogLogSvg(runtimePlot(results)));
    writeTextFile(out_dir + "/fig13_stages.svg", renderLogLogSvg(stagesPlot(results)));
}

}  // namespace bench
