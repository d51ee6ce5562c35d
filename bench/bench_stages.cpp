// Times the backend stages of the paper's Table 1 on fixed inputs: init (build the mesh and
// the cost field), comp (optimize) and final (render ×S into memory, in the app's bands; no
// file is written). One line per case, the median of N runs, and a JSON summary.
//
// Input: bench/data/real/astronaut.png (512×512 RGB, Eileen Collins, NASA photo, public
// domain; byte-identical copy of shared/data/images/real/astronaut.png, from
// python3-skimage 0.19.3). A case of size S ≤ 512 is the centred S×S crop; a larger one
// mirrors the photo across its right and bottom edges (1024² = the photo 2×2, reflected, so
// there are no seams).
//
//   build/bench/ddtup_bench_stages [--runs N] [--sizes 256,1024] [--scale 8] [--json FILE]
#include <CLI/CLI.hpp>

#include <cstdio>
#include <fstream>
#include <iostream>
#include <string>
#include <vector>

#include "backend.h"
#include "image_file.h"
#include "square_input.h"
#include "stage_times.h"

namespace {

struct Options {
    std::string image = DDTUP_BENCH_DATA "/real/astronaut.png";
    std::vector<uint32_t> sizes = {256, 1024};
    uint32_t runs = 3;
    double scale = 8.0;
    std::string json;
};

struct CaseResult {
    std::string name;
    uint32_t width = 0, height = 0, edges = 0;
    ddt::OutputSize out;
    ddt::OptimizeStats stats;  // identical in every run (the optimizer is deterministic)
    double init_s = 0.0, comp_s = 0.0, final_s = 0.0;  // medians
    bool deterministic = true;

    double flipsPerSecond() const { return comp_s > 0 ? double(stats.flips) / comp_s : 0.0; }
    // Every sweep of the serial optimizer passes every edge once: it tests it, or skips it when
    // its gain provably did not change since its last test (same result as testing it).
    double edgesTestedPerSecond() const { return comp_s > 0 ? double(stats.iterations) * edges / comp_s : 0.0; }
};

bool sameStats(const ddt::OptimizeStats& a, const ddt::OptimizeStats& b) {
    return a.flips == b.flips && a.iterations == b.iterations && a.cost_init == b.cost_init &&
           a.cost_final == b.cost_final && a.capped == b.capped;
}

CaseResult runCase(const ddt::Image& photo, uint32_t size, const Options& options) {
    const ddt::Image image = ddt::squareInput(photo, size);
    CaseResult result;
    result.name = "astronaut-" + std::to_string(size);
    result.width = image.width;
    result.height = image.height;
    result.edges = uint32_t(ddt::gridEdgeCount(image.width, image.height));
    result.out = ddt::scaledOutputSize(image.width, image.height, options.scale);
    std::vector<ddt::StageTimes> runs;
    for (uint32_t run = 0; run < options.runs; ++run) {
        runs.push_back(ddt::timeStages(*ddt::makeCpuBackend(), image, result.out, false));
        result.deterministic = result.deterministic && sameStats(runs.back().stats, runs.front().stats);
    }
    const ddt::StageTimes times = ddt::medianStages(runs);
    result.stats = times.stats;
    result.init_s = times.prepare_s;
    result.comp_s = times.optimize_s;
    result.final_s = times.render_s;
    return result;
}

void printLine(const CaseResult& c) {
    std::printf("%-16s %4ux%-4u -> %5ux%-5u  flips %9llu  sweeps %3u  cost-init %11.3f  cost-final %11.3f  "
                "improvement %6.1f%%  init %7.3f s  comp %8.3f s  final %7.3f s  %8.3g flips/s  %8.3g edges/s%s%s\n",
                c.name.c_str(), c.width, c.height, c.out.width, c.out.height, (unsigned long long)c.stats.flips,
                c.stats.iterations, c.stats.cost_init, c.stats.cost_final, c.stats.improvement(), c.init_s, c.comp_s,
                c.final_s, c.flipsPerSecond(), c.edgesTestedPerSecond(), c.stats.capped ? "  CAPPED" : "",
                c.deterministic ? "" : "  NONDETERMINISTIC");
    std::fflush(stdout);
}

void writeJson(const std::string& path, const Options& options, const std::vector<CaseResult>& cases) {
    std::ofstream out(path);
    if (!out) throw ddt::UserError(path + ": cannot open for writing");
    out.precision(17);
    out << "{\n  \"bench\": \"stages\",\n  \"backend\": \"cpu\",\n  \"image\": \"" << options.image << "\",\n"
        << "  \"runs\": " << options.runs << ",\n  \"scale\": " << options.scale << ",\n  \"statistic\": \"median\",\n"
        << "  \"cases\": [\n";
    for (size_t i = 0; i < cases.size(); ++i) {
        const CaseResult& c = cases[i];
        out << "    {\"name\": \"" << c.name << "\", \"width\": " << c.width << ", \"height\": " << c.height
            << ", \"out_width\": " << c.out.width << ", \"out_height\": " << c.out.height << ", \"edges\": " << c.edges
            << ", \"flips\": " << c.stats.flips << ", \"sweeps\": " << c.stats.iterations
            << ", \"cost_init\": " << c.stats.cost_init << ", \"cost_final\": " << c.stats.cost_final
            << ", \"improvement_percent\": " << c.stats.improvement() << ", \"capped\": " << (c.stats.capped ? "true" : "false")
            << ", \"deterministic\": " << (c.deterministic ? "true" : "false") << ", \"init_s\": " << c.init_s
            << ", \"comp_s\": " << c.comp_s << ", \"final_s\": " << c.final_s
            << ", \"flips_per_s\": " << c.flipsPerSecond() << ", \"edges_tested_per_s\": " << c.edgesTestedPerSecond()
            << "}" << (i + 1 < cases.size() ? "," : "") << "\n";
    }
    out << "  ]\n}\n";
    if (!out) throw ddt::UserError(path + ": write failed");
}

}  // namespace

int main(int argc, char** argv) {
    Options options;
    CLI::App app{"Times the serial backend's init, comp and final stages", "ddtup_bench_stages"};
    app.add_option("--image", options.image, "Photo to crop or mirror-tile")->capture_default_str();
    app.add_option("--sizes", options.sizes, "Square input sizes")->delimiter(',')->capture_default_str();
    app.add_option("--runs", options.runs, "Runs per case; times are their median")
        ->check(CLI::Range(1u, 1000u))
        ->capture_default_str();
    app.add_option("--scale", options.scale, "Magnification of the final stage")
        ->check(CLI::Range(1.0, 64.0))
        ->capture_default_str();
    app.add_option("--json", options.json, "Also write a machine-readable summary here");
    CLI11_PARSE(app, argc, argv);
    for (uint32_t size : options.sizes)
        if (size < 2) {
            std::cerr << "ddtup_bench_stages: --sizes must be at least 2 (got " << size << ")\n";
            return 2;
        }

    try {
        const ddt::Image photo = ddt::readImage(options.image);
        std::printf("# cpu backend, median of %u runs; final renders x%g in bands; edges/s = sweeps x edges / comp\n",
                    options.runs, options.scale);
        std::vector<CaseResult> cases;
        for (uint32_t size : options.sizes) {
            cases.push_back(runCase(photo, size, options));
            printLine(cases.back());
        }
        if (!options.json.empty()) writeJson(options.json, options, cases);
    } catch (const ddt::UserError& error) {
        std::cerr << "ddtup_bench_stages: " << error.what() << "\n";
        return 1;
    }
    return 0;
}
