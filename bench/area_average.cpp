#include "area_average.h"

#include <algorithm>
#include <cassert>

namespace bench {

namespace {

// The original pixels low pixel i covers along one axis, with the covered fraction of each.
struct Footprint {
    uint32_t first = 0;
    std::vector<double> weights;  // sum: numerator / denominator
};

// In units of 1/denominator original pixels the footprint of low pixel i is
// [i · numerator, (i + 1) · numerator), and original pixel j is [j · den, (j + 1) · den).
std::vector<Footprint> footprints(uint32_t low_side, Magnification f) {
    std::vector<Footprint> result(low_side);
    for (uint32_t i = 0; i < low_side; ++i) {
        const uint64_t begin = uint64_t(i) * f.numerator, end = begin + f.numerator;
        Footprint& fp = result[i];
        fp.first = uint32_t(begin / f.denominator);
        for (uint64_t j = fp.first; j * f.denominator < end; ++j) {
            const uint64_t overlap = std::min(end, (j + 1) * f.denominator) - std::max(begin, j * f.denominator);
            fp.weights.push_back(double(overlap) / double(f.numerator));
        }
    }
    return result;
}

}  // namespace

ddt::Image areaAverage(const ddt::Image& original, Magnification factor) {
    assert(original.width % factor.numerator == 0 && original.height % factor.numerator == 0);
    const uint32_t channels = original.channels;
    const uint32_t low_w = factor.lowSide(original.width), low_h = factor.lowSide(original.height);
    const std::vector<Footprint> across = footprints(low_w, factor), down = footprints(low_h, factor);

    // Rows first: every original row averaged across to low_w pixels.
    std::vector<double> narrow(size_t(low_w) * original.height * channels, 0.0);
    for (uint32_t y = 0; y < original.height; ++y)
        for (uint32_t x = 0; x < low_w; ++x)
            for (size_t k = 0; k < across[x].weights.size(); ++k) {
                const float* in = original.row(y) + size_t(across[x].first + k) * channels;
                double* out = &narrow[(size_t(y) * low_w + x) * channels];
                for (uint32_t c = 0; c < channels; ++c) out[c] += across[x].weights[k] * in[c];
            }

    ddt::Image low;
    low.width = low_w;
    low.height = low_h;
    low.channels = channels;
    low.sample_type = original.sample_type;
    low.pixels.assign(size_t(low_w) * low_h * channels, 0.0f);
    for (uint32_t y = 0; y < low_h; ++y)
        for (uint32_t x = 0; x < low_w; ++x)
            for (uint32_t c = 0; c < channels; ++c) {
                double sum = 0.0;
                for (size_t k = 0; k < down[y].weights.size(); ++k)
                    sum += down[y].weights[k] * narrow[(size_t(down[y].first + k) * low_w + x) * channels + c];
                low.row(y)[size_t(x) * channels + c] = float(sum);
            }
    return low;
}

}  // namespace bench
