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

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <fstream>
#include <iostream>
#include <string>
#include <vector>

#include "backend.h"
#include "image_file.h"

namespace {

using Clock = std::chrono::steady_clock;

double secondsSince(Clock::time_point start) { return std::chrono::duration<double>(Clock::now() - start).count(); }

// Same band size as the app's writer loop (16 Mi floats), so "final" renders like the app does.
const size_t kBandFloats = size_t(16) << 20;

struct Options {
    std::string image = DDTUP_BENCH_DATA "/real/astronaut.png";
    std::vector<uint32_t> sizes = {256, 1024};
    uint32_t runs = 3;
    double scale = 8.0;
    std::string json;
};

struct RunResult {
    ddt::OptimizeStats stats;
    double init_s = 0.0, comp_s = 0.0, final_s = 0.0;
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

// The centred size × size crop of `photo`, or its mirror tiling when size exceeds a side.
ddt::Image benchInput(const ddt::Image& photo, uint32_t size) {
    ddt::Image image;
    image.width = image.height = size;
    image.channels = photo.channels;
    image.sample_type = photo.sample_type;
    image.pixels.resize(size_t(size) * size * photo.channels);
    auto source = [](uint32_t i, uint32_t size, uint32_t side) {
        if (size <= side) return (side - size) / 2 + i;
        const uint32_t period = 2 * side;  // reflect: 0 .. side−1, side−1 .. 0, ...
        const uint32_t j = i % period;
        return j < side ? j : period - 1 - j;
    };
    for (uint32_t y = 0; y < size; ++y) {
        const uint32_t sy = source(y, size, photo.height);
        for (uint32_t x = 0; x < size; ++x) {
            const uint32_t sx = source(x, size, photo.width);
            std::copy_n(photo.pixels.data() + (size_t(sy) * photo.width + sx) * photo.channels, photo.channels,
                        image.pixels.data() + (size_t(y) * size + x) * photo.channels);
        }
    }
    return image;
}

RunResult runOnce(const ddt::Image& image, ddt::OutputSize out, std::vector<float>& band) {
    RunResult result;
    std::unique_ptr<ddt::Backend> backend = ddt::makeCpuBackend();

    Clock::time_point start = Clock::now();
    backend->prepare(image);
    result.init_s = secondsSince(start);

    start = Clock::now();
    result.stats = backend->optimize();
    result.comp_s = secondsSince(start);

    start = Clock::now();
    const size_t row_floats = size_t(out.width) * image.channels;
    const uint32_t band_rows = uint32_t(std::max<size_t>(1, kBandFloats / row_floats));
    band.resize(size_t(std::min(band_rows, out.height)) * row_floats);
    for (uint32_t y = 0; y < out.height; y += band_rows)
        backend->renderRows(out, y, std::min(out.height, y + band_rows), band.data());
    result.final_s = secondsSince(start);
    return result;
}

double median(std::vector<double> values) {
    std::sort(values.begin(), values.end());
    const size_t n = values.size();
    return n % 2 ? values[n / 2] : 0.5 * (values[n / 2 - 1] + values[n / 2]);
}

bool sameStats(const ddt::OptimizeStats& a, const ddt::OptimizeStats& b) {
    return a.flips == b.flips && a.iterations == b.iterations && a.cost_init == b.cost_init &&
           a.cost_final == b.cost_final && a.capped == b.capped;
}

CaseResult runCase(const ddt::Image& photo, uint32_t size, const Options& options) {
    const ddt::Image image = benchInput(photo, size);
    CaseResult result;
    result.name = "astronaut-" + std::to_string(size);
    result.width = image.width;
    result.height = image.height;
    result.edges = uint32_t(ddt::gridEdgeCount(image.width, image.height));
    result.out = ddt::scaledOutputSize(image.width, image.height, options.scale);
    std::vector<float> band;
    std::vector<double> init, comp, final;
    for (uint32_t run = 0; run < options.runs; ++run) {
        const RunResult r = runOnce(image, result.out, band);
        if (run == 0) result.stats = r.stats;
        result.deterministic = result.deterministic && sameStats(r.stats, result.stats);
        init.push_back(r.init_s);
        comp.push_back(r.comp_s);
        final.push_back(r.final_s);
    }
    result.init_s = median(init);
    result.comp_s = median(comp);
    result.final_s = median(final);
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
