#include "stage_times.h"

#include <algorithm>
#include <chrono>

namespace ddt {

namespace {

using Clock = std::chrono::steady_clock;

double secondsSince(Clock::time_point start) { return std::chrono::duration<double>(Clock::now() - start).count(); }

// The app's band size (app/tiled_upscale.cpp, 16 Mi floats), so that render runs as the app's does.
const size_t kBandFloats = size_t(16) << 20;

}  // namespace

StageTimes timeStages(Backend& backend, const Image& image, OutputSize out, bool reconstruct) {
    StageTimes times;
    Clock::time_point start = Clock::now();
    backend.prepare(image);
    times.prepare_s = secondsSince(start);

    start = Clock::now();
    times.stats = backend.optimize();
    times.optimize_s = secondsSince(start);

    if (reconstruct) {
        start = Clock::now();
        backend.reconstruct(degradationFor(double(out.width) / image.width, double(out.height) / image.height));
        times.reconstruct_s = secondsSince(start);
    }

    // The band is allocated before the clock starts: the stage is the rendering.
    const size_t row_floats = size_t(out.width) * image.channels;
    const uint32_t band_rows = uint32_t(std::max<size_t>(1, kBandFloats / row_floats));
    std::vector<float> band(size_t(std::min(band_rows, out.height)) * row_floats);
    start = Clock::now();
    for (uint32_t y = 0; y < out.height; y += band_rows)
        backend.renderRows(out, y, std::min(out.height, y + band_rows), band.data());
    times.render_s = secondsSince(start);
    return times;
}

double median(std::vector<double> values) {
    std::sort(values.begin(), values.end());
    const size_t n = values.size();
    return n % 2 ? values[n / 2] : 0.5 * (values[n / 2 - 1] + values[n / 2]);
}

StageTimes medianStages(const std::vector<StageTimes>& runs) {
    StageTimes result = runs.front();
    auto stage = [&runs](double StageTimes::*member) {
        std::vector<double> values;
        for (const StageTimes& run : runs) values.push_back(run.*member);
        return median(values);
    };
    result.prepare_s = stage(&StageTimes::prepare_s);
    result.optimize_s = stage(&StageTimes::optimize_s);
    result.reconstruct_s = stage(&StageTimes::reconstruct_s);
    result.render_s = stage(&StageTimes::render_s);
    std::vector<double> device_ms;
    for (const StageTimes& run : runs) device_ms.push_back(run.stats.device_ms);
    result.stats.device_ms = median(device_ms);
    return result;
}

}  // namespace ddt
