#include "gmsd.h"

#include <cassert>
#include <cmath>

namespace bench {

namespace {

const double kStabiliser = 170.0;  // c, the authors' T

struct Plane {
    uint32_t width = 0, height = 0;
    std::vector<double> values;

    // Zero outside the plane, as conv2's padding.
    double at(int64_t x, int64_t y) const {
        if (x < 0 || y < 0 || x >= int64_t(width) || y >= int64_t(height)) return 0.0;
        return values[size_t(y) * width + size_t(x)];
    }
};

Plane luma(const ddt::ByteImage& image) {
    Plane plane{image.width, image.height, std::vector<double>(size_t(image.width) * image.height)};
    for (size_t i = 0; i < plane.values.size(); ++i) {
        const uint8_t* p = &image.values[i * image.channels];
        plane.values[i] = image.channels >= 3 ? 0.299 * p[0] + 0.587 * p[1] + 0.114 * p[2] : double(p[0]);
    }
    return plane;
}

Plane averagedAndHalved(const Plane& in) {
    Plane out{(in.width + 1) / 2, (in.height + 1) / 2, {}};
    out.values.resize(size_t(out.width) * out.height);
    for (uint32_t y = 0; y < out.height; ++y)
        for (uint32_t x = 0; x < out.width; ++x) {
            const int64_t sx = 2 * int64_t(x), sy = 2 * int64_t(y);
            out.values[size_t(y) * out.width + x] =
                0.25 * (in.at(sx, sy) + in.at(sx + 1, sy) + in.at(sx, sy + 1) + in.at(sx + 1, sy + 1));
        }
    return out;
}

Plane gradientMagnitude(const Plane& in) {
    Plane out{in.width, in.height, std::vector<double>(in.values.size())};
    for (int64_t y = 0; y < int64_t(in.height); ++y)
        for (int64_t x = 0; x < int64_t(in.width); ++x) {
            double gx = 0.0, gy = 0.0;
            for (int64_t d = -1; d <= 1; ++d) {
                gx += in.at(x - 1, y + d) - in.at(x + 1, y + d);
                gy += in.at(x + d, y - 1) - in.at(x + d, y + 1);
            }
            out.values[size_t(y) * in.width + size_t(x)] = std::sqrt(gx * gx + gy * gy) / 3.0;
        }
    return out;
}

}  // namespace

double gradientMagnitudeSimilarityDeviation(const ddt::ByteImage& original, const ddt::ByteImage& other) {
    assert(original.width == other.width && original.height == other.height && original.channels == other.channels);
    assert(original.width >= 2 && original.height >= 2);
    const Plane mx = gradientMagnitude(averagedAndHalved(luma(original)));
    const Plane my = gradientMagnitude(averagedAndHalved(luma(other)));
    const size_t n = mx.values.size();
    std::vector<double> similarity(n);
    double sum = 0.0;
    for (size_t i = 0; i < n; ++i) {
        const double a = mx.values[i], b = my.values[i];
        similarity[i] = (2.0 * a * b + kStabiliser) / (a * a + b * b + kStabiliser);
        sum += similarity[i];
    }
    const double mean = sum / double(n);
    double squares = 0.0;
    for (double s : similarity) squares += (s - mean) * (s - mean);
    return n > 1 ? std::sqrt(squares / double(n - 1)) : 0.0;
}

}  // namespace bench
