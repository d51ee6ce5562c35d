#include "upscale_job.h"

#include <algorithm>
#include <chrono>
#include <filesystem>
#include <iostream>

#include "vulkan_backend.h"

namespace ddt {

namespace {

namespace fs = std::filesystem;

double secondsSince(std::chrono::steady_clock::time_point start) {
    return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

// Bands of at most this many floats keep memory flat for huge outputs.
const size_t kBandFloats = size_t(16) << 20;

// Catches every spelling of the same file: "./x/../a.png", symlinks, hard links.
void checkNotOverwritingInput(const std::string& input, const std::string& output) {
    std::error_code ec;
    bool same = fs::exists(output, ec) ? fs::equivalent(input, output, ec)
                                       : fs::weakly_canonical(input, ec) == fs::weakly_canonical(output, ec);
    if (same) throw UserError(output + ": output is the input file; refusing to overwrite it");
}

void checkMagnifiable(const std::string& input, const Image& header) {
    if (header.width < 2 || header.height < 2)
        throw UserError(input + ": DDT needs at least 2×2 pixels (got " + std::to_string(header.width) + "×" +
                        std::to_string(header.height) + ")");
}

// OIIO keeps sizes in int, so no format holds more than 2^31 - 1 pixels a side.
void checkOutputSides(const std::string& output, OutputSize out) {
    const uint32_t max_side = 2147483647u;
    if (out.width > max_side || out.height > max_side)
        throw UserError(output + ": the output would be " + std::to_string(out.width) + "×" + std::to_string(out.height) +
                        " pixels or more; at most " + std::to_string(max_side) + " a side");
}

}  // namespace

OutputSize requestedOutputSize(const Settings& settings, uint32_t width, uint32_t height) {
    if (settings.width && settings.height) return {settings.width, settings.height};
    if (settings.width) return outputSizeForWidth(width, height, settings.width);
    if (settings.height) return outputSizeForHeight(width, height, settings.height);
    return scaledOutputSize(width, height, settings.scale);
}

std::unique_ptr<Backend> makeBackend(const Settings& settings) {
    if (settings.backend == "cpu") return makeCpuBackend();
    VulkanOptions options;
    if (!settings.variant.empty()) options.rule = settings.variant;
    options.active_set = settings.active_set;
    options.device_index = settings.device;
    auto backend = std::make_unique<VulkanBackend>(options);
    // Users of other Vulkan upscalers were silently given a software device and thought it hung.
    if (backend->device().isCpu() && !settings.quiet)
        std::cerr << "ddtup: note: running on " << backend->device().name
                  << ", a CPU Vulkan device (no GPU found); expect it to be slower than a GPU\n";
    return backend;
}

JobReport runUpscaleJob(const Settings& settings) {
    JobReport report;
    checkNotOverwritingInput(settings.input, settings.output);

    auto start = std::chrono::steady_clock::now();
    ImageReader reader(settings.input);
    const Image& header = reader.header();
    checkMagnifiable(settings.input, header);
    report.out = requestedOutputSize(settings, header.width, header.height);
    checkOutputSides(settings.output, report.out);
    if (std::string problem = checkOutputSize(header.width, header.height, report.out); !problem.empty())
        throw UserError(settings.input + ": " + problem);
    // Open the output before decoding the input: an unwritable path, or a size the format
    // cannot hold, fails before any of the long parts.
    ImageWriter writer(settings.output, report.out.width, report.out.height, header);
    const Image image = reader.read();
    std::unique_ptr<Backend> backend = makeBackend(settings);
    try {
        backend->prepare(image);
    } catch (const UserError& error) {
        throw UserError(settings.input + ": " + error.what());
    }
    report.times.init_s = secondsSince(start);

    start = std::chrono::steady_clock::now();
    report.stats = backend->optimize();
    report.times.comp_s = secondsSince(start);

    start = std::chrono::steady_clock::now();
    const size_t row_floats = size_t(report.out.width) * image.channels;
    const uint32_t band_rows = uint32_t(std::max<size_t>(1, kBandFloats / row_floats));
    std::vector<float> band(size_t(std::min(band_rows, report.out.height)) * row_floats);
    for (uint32_t y = 0; y < report.out.height; y += band_rows) {
        uint32_t y_end = std::min(report.out.height, y + band_rows);
        backend->renderRows(report.out, y, y_end, band.data());
        writer.writeRows(y, y_end, band.data());
    }
    writer.commit();
    report.times.final_s = secondsSince(start);
    report.notes = writer.notes();
    return report;
}

}  // namespace ddt
