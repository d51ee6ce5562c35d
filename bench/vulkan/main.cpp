// Stage benchmark of the Vulkan backend, for GPU machines: per input, every flip rule's
// prepare, optimize (wall time and GPU timestamps), consistent reconstruction and render
// times, with iterations, rounds, dispatches and flips, next to the CPU backend on the same
// input; with --profile, the device time per kernel and per iteration. Links no OpenImageIO (only ddtup_vulkan
// and ddtup_core), so that bench/gpu-bundle can copy it with the Vulkan loader to a machine
// that has a GPU driver and nothing else. Inputs: synthetic squares (synthetic_image.h), or
// raw 8-bit pixels (raw_image.h), whole or as squares (--sizes) cut or mirrored from them.
//   ddtup-bench-vulkan [--sizes 256,1024,2048] [--rules localmax,exproi-maxgain] [--runs 3]
//                      [--scale 2] [--plain] [--profile] [--no-active-set] [--no-cpu]
//                      [--device N] [--raw PATH --raw-size WxHxC]
#include <CLI/CLI.hpp>

#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <memory>
#include <string>
#include <thread>
#include <vector>

#include "backend.h"
#include "flip_rule.h"
#include "raw_image.h"
#include "square_input.h"
#include "stage_times.h"
#include "synthetic_image.h"
#include "vulkan_backend.h"

namespace {

using namespace ddt;

struct Options {
    std::vector<uint32_t> sizes = {256, 1024, 2048};
    std::vector<std::string> rules = {kDefaultFlipRule, "exproi-maxgain"};
    int runs = 3, device = -1;
    double scale = 2.0;
    bool plain = false, profile = false, no_active_set = false, no_cpu = false;
    std::string raw_path, raw_size;
};

// The serial CPU backend gets one run from this many input pixels up: it takes seconds there.
constexpr uint64_t kCpuSingleRunPixels = uint64_t(2048) * 2048;

StageTimes measure(Backend& backend, const Image& image, OutputSize out, bool reconstruct, int runs) {
    std::vector<StageTimes> times;
    for (int run = 0; run < runs; ++run) times.push_back(timeStages(backend, image, out, reconstruct));
    return medianStages(times);
}

void printHeader() {
    std::printf("%-11s %-16s %8s %8s %8s %8s %8s %8s %7s %6s %7s %8s %9s %10s %8s\n", "input", "backend", "prepare",
                "optimize", "device", "recon", "render", "total", "opt/cpu", "iters", "rounds", "max/iter", "dispatch",
                "flips", "cost/cpu");
}

// One row; `cpu` is the CPU backend's result on the same input, or null.
void printRow(const std::string& input, const std::string& backend, const StageTimes& t, bool reconstructed,
              const StageTimes* cpu) {
    const OptimizeStats& s = t.stats;
    const bool gpu = s.dispatches > 0;
    auto dash = [](bool known, const char* format, double value) {
        char text[32] = "-";
        if (known) std::snprintf(text, sizeof text, format, value);
        return std::string(text);
    };
    const std::string device = dash(gpu, "%.3f", s.device_ms * 1e-3);
    const std::string recon = dash(reconstructed, "%.3f", t.reconstruct_s);
    const std::string speed = dash(cpu, "%.2f", cpu ? t.optimize_s / cpu->optimize_s : 0.0);
    const std::string rounds = dash(gpu, "%.0f", double(s.rounds));
    const std::string most_rounds = dash(gpu, "%.0f", s.max_rounds_in_iteration);
    const std::string dispatches = dash(gpu, "%.0f", double(s.dispatches));
    const std::string cost = dash(cpu, "%.4f", cpu ? s.cost_final / cpu->stats.cost_final : 0.0);
    std::printf("%-11s %-16s %8.3f %8.3f %8s %8s %8.3f %8.3f %7s %6u %7s %8s %9s %10llu %8s%s\n", input.c_str(),
                backend.c_str(), t.prepare_s, t.optimize_s, device.c_str(), recon.c_str(), t.render_s, t.total_s(),
                speed.c_str(), s.iterations, rounds.c_str(), most_rounds.c_str(), dispatches.c_str(),
                static_cast<unsigned long long>(s.flips), cost.c_str(), s.capped ? " (capped)" : "");
    std::fflush(stdout);
}

// The square sides to run, in order; 0: the raw image as it is. Inputs are made one at a time
// (a 4096² input is 200 MB of floats).
std::vector<uint32_t> inputSides(const Options& options, bool sizes_given) {
    if (!options.raw_path.empty() && !sizes_given) return {0};
    return options.sizes;
}

int run(const Options& options, bool sizes_given) {
    std::vector<std::string> rules = options.rules;
    if (rules.size() == 1 && rules[0] == "table") rules = tableFlipRules();
    std::vector<std::unique_ptr<VulkanBackend>> backends;
    for (const std::string& rule : rules) {
        VulkanOptions vulkan;
        vulkan.rule = rule;
        vulkan.active_set = !options.no_active_set;
        vulkan.device_index = options.device;
        vulkan.profile = options.profile;
        backends.push_back(std::make_unique<VulkanBackend>(vulkan));
    }
    std::unique_ptr<Backend> cpu = options.no_cpu ? nullptr : makeCpuBackend();
    const bool reconstruct = !options.plain;

    Image raw;
    if (!options.raw_path.empty()) raw = readRawImage(options.raw_path, parseRawSize(options.raw_size));
    const char* lp_threads = std::getenv("LP_NUM_THREADS");
    std::printf("device: %s (%s, %s); %u hardware threads; LP_NUM_THREADS=%s\n",
                backends.empty() ? "-" : backends[0]->device().name.c_str(),
                backends.empty() ? "-" : deviceTypeName(backends[0]->device().type),
                backends.empty() ? "-" : backends[0]->device().driver.c_str(), std::thread::hardware_concurrency(),
                lp_threads ? lp_threads : "unset");
    std::printf("input: %s; x%g, %s surface, rendered in bands into memory; median of %d run(s) (cpu: 1 from 2048^2); "
                "active set %s; times in s\n",
                raw.width ? (options.raw_path + " " + options.raw_size).c_str() : "synthetic (synthetic_image.h)",
                options.scale, reconstruct ? "consistent" : "plain", options.runs,
                options.no_active_set ? "off" : "on");

    // Warm-up: the first dispatch of each kernel compiles it.
    const Image warm = syntheticImage(64, 64);
    for (auto& backend : backends) measure(*backend, warm, scaledOutputSize(64, 64, options.scale), reconstruct, 1);

    printHeader();
    for (uint32_t side : inputSides(options, sizes_given)) {
        const Image image = raw.width == 0 ? syntheticImage(side, side) : side == 0 ? raw : squareInput(raw, side);
        const OutputSize out = scaledOutputSize(image.width, image.height, options.scale);
        const std::string problem = checkOutputSize(image.width, image.height, out);
        if (!problem.empty()) throw UserError(problem);
        const std::string name = std::to_string(image.width) + "x" + std::to_string(image.height);
        StageTimes serial;
        if (cpu) {
            const bool large = uint64_t(image.width) * image.height >= kCpuSingleRunPixels;
            serial = measure(*cpu, image, out, reconstruct, large ? 1 : options.runs);
            printRow(name, "cpu (serial)", serial, reconstruct, nullptr);
        }
        for (size_t i = 0; i < backends.size(); ++i)
            printRow(name, rules[i], measure(*backends[i], image, out, reconstruct, options.runs), reconstruct,
                     cpu ? &serial : nullptr);
    }
    if (options.profile) {
        std::printf("\ndevice time per kernel, all inputs and runs (warm-up included):\n");
        for (size_t i = 0; i < backends.size(); ++i)
            for (const auto& [kernel, time] : backends[i]->kernelTimes())
                std::printf("  %-18s %-12s %8llu dispatches %10.1f ms\n", rules[i].c_str(), kernel.c_str(),
                            static_cast<unsigned long long>(time.dispatches), time.ms);
        // Where an optimisation spends its time: the first iterations test nearly every edge.
        std::printf("\ndevice time per iteration (ms), all inputs and runs:\n");
        for (size_t i = 0; i < backends.size(); ++i) {
            const auto times = backends[i]->kernelTimes();
            size_t iterations = 0;
            for (const auto& [kernel, time] : times) iterations = std::max(iterations, time.iteration_ms.size());
            std::printf("  %-18s iteration", rules[i].c_str());
            for (const auto& [kernel, time] : times) std::printf(" %10s", kernel.c_str());
            std::printf("\n");
            for (size_t k = 0; k < iterations; ++k) {
                std::printf("  %-18s %9zu", "", k + 1);
                for (const auto& [kernel, time] : times)
                    std::printf(" %10.1f", k < time.iteration_ms.size() ? time.iteration_ms[k] : 0.0);
                std::printf("\n");
            }
        }
    }
    // With the validation layer on (DDTUP_VALIDATION=1, as the test suite runs), a message fails the run.
    uint32_t messages = 0;
    for (const auto& backend : backends) messages += backend->validationMessages();
    if (messages > 0) {
        std::fprintf(stderr, "ddtup-bench-vulkan: %u Vulkan validation message(s)\n", messages);
        return 1;
    }
    return 0;
}

}  // namespace

int main(int argc, char** argv) {
    Options options;
    CLI::App app{"ddtup Vulkan stage benchmark: flip rules vs the CPU backend, without OpenImageIO",
                 "ddtup-bench-vulkan"};
    auto* sizes = app.add_option("--sizes", options.sizes, "Square input sides (with --raw: squares cut from it)")
                      ->delimiter(',')
                      ->check(CLI::Range(2u, 16384u))
                      ->capture_default_str();
    app.add_option("--rules", options.rules, "Vulkan flip rules ('table': all of Table 1)")
        ->delimiter(',')
        ->capture_default_str();
    app.add_option("--runs", options.runs, "Runs per case; the median is reported")
        ->check(CLI::Range(1, 1000))
        ->capture_default_str();
    app.add_option("--scale", options.scale, "Magnification of the render stage")
        ->check(CLI::Range(1.0, 64.0))
        ->capture_default_str();
    app.add_option("--device", options.device, "Vulkan device index (ddtup --list-devices)");
    app.add_option("--raw", options.raw_path, "Input: raw 8-bit interleaved pixels instead of the synthetic image");
    auto* raw_size = app.add_option("--raw-size", options.raw_size, "Size of --raw: WxHxC (C = 1 to 4 channels)");
    app.get_option("--raw")->needs(raw_size);
    raw_size->needs("--raw");
    app.add_flag("--plain", options.plain, "Plain DDT surface: no consistent reconstruction stage");
    app.add_flag("--profile", options.profile, "Also report device time per kernel");
    app.add_flag("--no-active-set", options.no_active_set, "Re-test every edge in every iteration");
    app.add_flag("--no-cpu", options.no_cpu, "Do not run the CPU backend");
    CLI11_PARSE(app, argc, argv);

    try {
        return run(options, sizes->count() > 0);
    } catch (const std::exception& error) {
        std::fprintf(stderr, "ddtup-bench-vulkan: %s\n", error.what());
        return 1;
    }
}
