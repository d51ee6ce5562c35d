#include "ddt_timing.h"

#include <algorithm>
#include <cassert>
#include <chrono>

namespace bench {

namespace {

using Clock = std::chrono::steady_clock;

double secondsSince(Clock::time_point start) { return std::chrono::duration<double>(Clock::now() - start).count(); }

// Bands of at most this many floats (64 MiB) keep Fig. 13's largest outputs in memory.
const size_t kBandFloats = size_t(16) << 20;

// One run of the three stages. Rows go to `rows`, which advances with y when it holds the
// whole image (`whole`) and is reused for every band otherwise.
DdtRun runOnce(ddt::Backend& backend, const PngInMemory& input, ddt::OutputSize out, float* rows, bool whole,
               uint32_t band_rows) {
    DdtRun run;
    Clock::time_point start = Clock::now();
    // The decoded image must outlive rendering: the backend reads its values.
    const ddt::Image image = decodePng(input);
    backend.prepare(image);
    run.times.init_s = secondsSince(start);

    start = Clock::now();
    run.stats = backend.optimize();
    run.times.comp_s = secondsSince(start);

    start = Clock::now();
    const size_t row_floats = size_t(out.width) * input.channels;
    for (uint32_t y = 0; y < out.height; y += band_rows) {
        const uint32_t y_end = std::min(out.height, y + band_rows);
        backend.renderRows(out, y, y_end, whole ? rows + y * row_floats : rows);
    }
    run.times.final_s = secondsSince(start);
    return run;
}

double median(std::vector<double> values) {
    assert(!values.empty());
    std::sort(values.begin(), values.end());
    const size_t mid = values.size() / 2;
    return values.size() % 2 == 1 ? values[mid] : 0.5 * (values[mid - 1] + values[mid]);
}

ddt::StageTimes medianTimes(const std::vector<DdtRun>& runs) {
    std::vector<double> init, comp, final;
    for (const DdtRun& run : runs) {
        init.push_back(run.times.init_s);
        comp.push_back(run.times.comp_s);
        final.push_back(run.times.final_s);
    }
    return {median(init), median(comp), median(final)};
}

}  // namespace

DdtMeasurement measureDdt(const DdtMethod& method, const PngInMemory& input, ddt::OutputSize out, uint32_t warmups,
                          uint32_t repeats, ddt::Image* output) {
    assert(repeats > 0);
    std::unique_ptr<ddt::Backend> backend = makeMethodBackend(method);
    const size_t row_floats = size_t(out.width) * input.channels;
    // Memory is allocated and touched before the timers start.
    std::vector<float> band;
    uint32_t band_rows = out.height;
    if (output) {
        output->width = out.width;
        output->height = out.height;
        output->channels = input.channels;
        output->sample_type = ddt::SampleType::UInt8;
        output->pixels.assign(row_floats * out.height, 0.0f);
    } else {
        band_rows = uint32_t(std::clamp<size_t>(kBandFloats / row_floats, 1, out.height));
        band.assign(row_floats * band_rows, 0.0f);
    }
    float* rows = output ? output->pixels.data() : band.data();

    DdtMeasurement measurement;
    for (uint32_t i = 0; i < warmups; ++i) runOnce(*backend, input, out, rows, output != nullptr, band_rows);
    for (uint32_t i = 0; i < repeats; ++i)
        measurement.runs.push_back(runOnce(*backend, input, out, rows, output != nullptr, band_rows));
    measurement.median = medianTimes(measurement.runs);
    return measurement;
}

}  // namespace bench
