// Optimize-stage benchmark: the Vulkan flip rules against the serial reference on square
// inputs made from one photo (256², 1024², 2048² by default), with the counts that bound the
// parallel version (iterations, rounds, dispatches) and, with --profile, the device time
// per kernel. Run by people, built by CI:
//   ddtup_bench_vulkan [--sizes 256,1024] [--rules localmax,maxgain] [--runs 3] [--profile]
//                      [--no-active-set] [--device N] [--image PATH]
#include <CLI/CLI.hpp>

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <string>
#include <vector>

#include "backend.h"
#include "flip_rule.h"
#include "vulkan_backend.h"
#include "image_file.h"

namespace {

using namespace ddt;

// A size × size image cut from `photo`, mirrored where the photo is smaller, so texture
// continues without seams.
Image squareFrom(const Image& photo, uint32_t size) {
    Image image;
    image.width = image.height = size;
    image.channels = photo.channels;
    image.pixels.resize(size_t(size) * size * photo.channels);
    auto mirror = [](uint32_t i, uint32_t n) {
        uint32_t period = 2 * n;
        uint32_t j = i % period;
        return j < n ? j : period - 1 - j;
    };
    for (uint32_t y = 0; y < size; ++y)
        for (uint32_t x = 0; x < size; ++x)
            for (uint32_t k = 0; k < photo.channels; ++k)
                image.pixels[(size_t(y) * size + x) * photo.channels + k] =
                    photo.row(mirror(y, photo.height))[mirror(x, photo.width) * photo.channels + k];
    return image;
}

struct Measurement {
    OptimizeStats stats;
    double seconds = 0.0;  // optimize wall time, median over runs
};

Measurement measure(Backend& backend, const Image& image, int runs) {
    std::vector<double> times;
    Measurement m;
    for (int run = 0; run < runs; ++run) {
        backend.prepare(image);
        auto start = std::chrono::steady_clock::now();
        m.stats = backend.optimize();
        times.push_back(std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count());
    }
    std::sort(times.begin(), times.end());
    m.seconds = times[times.size() / 2];
    return m;
}

std::vector<std::string> splitList(const std::string& text) {
    std::vector<std::string> items;
    size_t start = 0;
    while (start <= text.size()) {
        size_t end = text.find(',', start);
        if (end == std::string::npos) end = text.size();
        if (end > start) items.push_back(text.substr(start, end - start));
        start = end + 1;
    }
    return items;
}

}  // namespace

int main(int argc, char** argv) {
    CLI::App app{"ddtup optimize benchmark: Vulkan flip rules vs the serial reference"};
    std::string sizes_text = "256,1024,2048";
    std::string rules_text = std::string(kDefaultFlipRule) + ",exproi-maxgain";
    std::string image_path = std::string(DDTUP_BENCH_DATA) + "/real/astronaut.png";
    int runs = 3, device = -1;
    bool profile = false, no_active_set = false, skip_serial = false;
    app.add_option("--sizes", sizes_text, "Square input sides")->capture_default_str();
    app.add_option("--rules", rules_text, "Vulkan flip rules, comma-separated ('table' for all)")->capture_default_str();
    app.add_option("--image", image_path, "Photo the inputs are cut from")->capture_default_str();
    app.add_option("--runs", runs, "Runs per case; the median is reported")->capture_default_str();
    app.add_option("--device", device, "Vulkan device index");
    app.add_flag("--profile", profile, "Also report device time per kernel");
    app.add_flag("--no-active-set", no_active_set, "Re-test every edge in every iteration");
    app.add_flag("--skip-serial", skip_serial, "Do not run the serial reference");
    CLI11_PARSE(app, argc, argv);

    try {
        const Image photo = readImage(image_path);
        std::vector<std::string> rules = rules_text == "table" ? tableFlipRules() : splitList(rules_text);
        std::vector<std::unique_ptr<VulkanBackend>> backends;
        for (const std::string& rule : rules) {
            VulkanOptions options;
            options.rule = rule;
            options.active_set = !no_active_set;
            options.device_index = device;
            options.profile = profile;
            backends.push_back(std::make_unique<VulkanBackend>(options));
        }
        const char* threads = std::getenv("LP_NUM_THREADS");
        std::printf("device: %s (%s); LP_NUM_THREADS=%s; median of %d run(s); active set %s\n",
                    backends.empty() ? "-" : backends[0]->device().name.c_str(),
                    backends.empty() ? "-" : deviceTypeName(backends[0]->device().type), threads ? threads : "unset",
                    runs, no_active_set ? "off" : "on");

        // Warm up: the first dispatch of each kernel compiles it.
        const Image warm = squareFrom(photo, 64);
        for (auto& backend : backends) measure(*backend, warm, 1);

        std::printf("%-6s %-18s %9s %9s %8s %6s %8s %10s %9s %10s %8s\n", "size", "rule", "comp s", "device s",
                    "x serial", "iters", "rounds", "max/iter", "dispatch", "flips", "cost/ser");
        for (const std::string& size_text : splitList(sizes_text)) {
            const uint32_t size = uint32_t(std::stoul(size_text));
            const Image image = squareFrom(photo, size);
            Measurement serial;
            if (!skip_serial) {
                std::unique_ptr<Backend> cpu = makeCpuBackend();
                serial = measure(*cpu, image, size >= 2048 ? 1 : runs);
                std::printf("%-6u %-18s %9.3f %9s %8s %6u %8s %10s %9s %10llu %8.4f\n", size, "serial (cpu)",
                            serial.seconds, "-", "1.00", serial.stats.iterations, "-", "-", "-",
                            static_cast<unsigned long long>(serial.stats.flips), 1.0);
            }
            for (size_t i = 0; i < backends.size(); ++i) {
                const Measurement m = measure(*backends[i], image, runs);
                const OptimizeStats& s = m.stats;
                std::printf("%-6u %-18s %9.3f %9.3f %8.2f %6u %8llu %10u %9llu %10llu %8.4f%s\n", size,
                            rules[i].c_str(), m.seconds, s.device_ms * 1e-3,
                            skip_serial ? 0.0 : m.seconds / serial.seconds, s.iterations,
                            static_cast<unsigned long long>(s.rounds), s.max_rounds_in_iteration,
                            static_cast<unsigned long long>(s.dispatches), static_cast<unsigned long long>(s.flips),
                            skip_serial ? 0.0 : s.cost_final / serial.stats.cost_final, s.capped ? " (capped)" : "");
            }
            std::fflush(stdout);
        }
        if (profile) {
            std::printf("\ndevice time per kernel, all sizes and runs:\n");
            for (size_t i = 0; i < backends.size(); ++i)
                for (const auto& [kernel, time] : backends[i]->kernelTimes())
                    std::printf("  %-18s %-12s %8llu dispatches %10.1f ms\n", rules[i].c_str(), kernel.c_str(),
                                static_cast<unsigned long long>(time.dispatches), time.ms);
        }
    } catch (const UserError& error) {
        std::fprintf(stderr, "ddtup_bench_vulkan: %s\n", error.what());
        return 1;
    }
    return 0;
}
