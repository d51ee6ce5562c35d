#include "grid_filters.h"

#include <algorithm>
#include <cassert>
#include <cmath>
#include <vector>

#include "parallel.h"

namespace bench {

namespace {

// Keys' cubic convolution kernel with a = −0.5 (Catmull–Rom): it interpolates (1 at 0, 0 at the
// other integers) and reproduces quadratics.
double catmullRom(double t) {
    t = std::abs(t);
    if (t < 1.0) return (1.5 * t - 2.5) * t * t + 1.0;
    if (t < 2.0) return ((-0.5 * t + 2.5) * t - 4.0) * t + 2.0;
    return 0.0;
}

// Per output index along one axis: the input indices it reads (clamped: edge replication) and
// their weights.
constexpr int kMaxTaps = 4;
struct AxisTaps {
    int taps = 0;
    std::vector<std::array<uint32_t, kMaxTaps>> index;
    std::vector<std::array<double, kMaxTaps>> weight;
};

AxisTaps axisTaps(uint32_t n, uint32_t m, GridFilter filter) {
    AxisTaps axis;
    axis.taps = filter == GridFilter::trilinear ? 2 : 4;
    axis.index.resize(m);
    axis.weight.resize(m);
    for (uint32_t i = 0; i < m; ++i) {
        const double u = ddt::inputIndexOf(i, n, m), base = std::floor(u);
        // Linear: taps base, base + 1; cubic: base − 1 … base + 2.
        const int64_t first = int64_t(base) - (axis.taps / 2 - 1);
        for (int k = 0; k < axis.taps; ++k) {
            axis.index[i][k] = uint32_t(std::clamp<int64_t>(first + k, 0, int64_t(n) - 1));
            const double distance = u - double(first + k);
            axis.weight[i][k] = filter == GridFilter::trilinear ? 1.0 - std::abs(distance) : catmullRom(distance);
        }
    }
    return axis;
}

// One separable pass: `values` (size `dims`) resampled along `axis` with `taps`.
std::vector<float> resampleAxis(const std::vector<float>& values, const std::array<uint32_t, 3>& dims, int axis,
                                const AxisTaps& taps) {
    std::array<uint32_t, 3> out_dims = dims;
    out_dims[axis] = uint32_t(taps.index.size());
    const std::array<size_t, 3> stride = {1, dims[0], size_t(dims[0]) * dims[1]};
    std::vector<float> out(size_t(out_dims[0]) * out_dims[1] * out_dims[2]);
    // One task item per output row (a fixed y and z).
    ddt::parallelFor(size_t(out_dims[1]) * out_dims[2], 16, [&](size_t begin, size_t end) {
        for (size_t row = begin; row < end; ++row) {
            const std::array<uint32_t, 3> at = {0, uint32_t(row % out_dims[1]), uint32_t(row / out_dims[1])};
            float* target = &out[row * out_dims[0]];
            for (uint32_t x = 0; x < out_dims[0]; ++x) {
                std::array<uint32_t, 3> p = at;
                p[0] = x;
                const uint32_t i = p[axis];
                size_t base = 0;
                for (int a = 0; a < 3; ++a)
                    if (a != axis) base += p[a] * stride[a];
                double sum = 0.0;
                for (int k = 0; k < taps.taps; ++k)
                    sum += taps.weight[i][k] * double(values[base + taps.index[i][k] * stride[axis]]);
                target[x] = float(sum);
            }
        }
    });
    return out;
}

}  // namespace

ddt::Volume resampleGrid(const ddt::Volume& volume, const std::array<uint32_t, 3>& new_size, GridFilter filter) {
    assert(volume.values.size() == volume.voxelCount());
    std::vector<float> values = volume.values;
    std::array<uint32_t, 3> dims = volume.size;
    for (int axis = 0; axis < 3; ++axis) {
        assert(new_size[axis] >= 1);
        values = resampleAxis(values, dims, axis, axisTaps(volume.size[axis], new_size[axis], filter));
        dims[axis] = new_size[axis];
    }
    ddt::Volume result;
    result.size = new_size;
    result.values = std::move(values);
    result.type = volume.type;
    result.index_to_world = ddt::resampledAffine(volume.index_to_world, volume.size, new_size);
    result.metadata = volume.metadata;
    return result;
}

}  // namespace bench
