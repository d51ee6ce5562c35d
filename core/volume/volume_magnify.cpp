#include "volume_magnify.h"

#include <algorithm>
#include <cassert>
#include <chrono>
#include <limits>
#include <utility>

#include "tet_mesh.h"
#include "tet_resample.h"

namespace ddt {

namespace {

double secondsSince(std::chrono::steady_clock::time_point start) {
    return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

// One axis of a brick: the input voxels its mesh covers and the output voxels it resamples.
struct BrickSpan {
    uint32_t vertex_begin, vertex_end;  // [begin, end) input voxels, margins included
    uint32_t out_begin, out_end;        // output voxels whose samples lie in the core
};

// The first output voxel along an axis (n in, m out) whose sample lies at or after input index
// c, in the exact units of tet_resample.h (2m per input voxel; samples clamped to the box).
uint32_t firstOutputAtOrAfter(uint32_t c, uint32_t n, uint32_t m) {
    const int64_t at = int64_t(2) * m * c;
    uint32_t i = 0;
    // The samples ascend; a binary search over i of clamp((2i + 1) n − m, 0, 2m(n − 1)).
    uint32_t lo = 0, hi = m;
    while (lo < hi) {
        i = lo + (hi - lo) / 2;
        const int64_t sample = std::clamp<int64_t>((2 * int64_t(i) + 1) * n - m, 0, int64_t(2) * m * (n - 1));
        if (sample < at) lo = i + 1;
        else hi = i;
    }
    return lo;
}

std::vector<BrickSpan> spansOf(uint32_t n, uint32_t m, uint32_t side, uint32_t margin) {
    std::vector<BrickSpan> spans;
    for (uint32_t c = 0; c < n - 1 || spans.empty(); c += side) {
        const uint32_t next = std::min(c + side, n - 1);
        BrickSpan span;
        span.vertex_begin = c > margin ? c - margin : 0;
        span.vertex_end = std::min(n, next + margin + 1);
        span.out_begin = firstOutputAtOrAfter(c, n, m);
        span.out_end = next == n - 1 ? m : firstOutputAtOrAfter(next, n, m);
        spans.push_back(span);
        if (next == n - 1) break;
    }
    return spans;
}

// The brick's values: input voxels [begin, end) per axis.
std::vector<float> brickValues(const Volume& volume, const std::array<uint32_t, 3>& begin,
                               const std::array<uint32_t, 3>& size) {
    std::vector<float> values;
    values.reserve(size_t(size[0]) * size[1] * size[2]);
    for (uint32_t z = 0; z < size[2]; ++z)
        for (uint32_t y = 0; y < size[1]; ++y) {
            const float* row = &volume.values[volume.indexOf(begin[0], begin[1] + y, begin[2] + z)];
            values.insert(values.end(), row, row + size[0]);
        }
    return values;
}

void addStats(VolumeMagnifyStats& total, const TetLawsonStats& lawson) {
    total.lawson.cost_before += lawson.cost_before;
    total.lawson.cost_after += lawson.cost_after;
    for (uint32_t k = 0; k < kFlipKindCount; ++k) total.lawson.flips[k] += lawson.flips[k];
    total.lawson.iterations = std::max(total.lawson.iterations, lawson.iterations);
    total.lawson.capped |= lawson.capped;
}

}  // namespace

std::vector<VolumeBrick> volumeBricks(const std::array<uint32_t, 3>& size, const std::array<uint32_t, 3>& new_size,
                                      uint32_t side, uint32_t margin) {
    std::array<std::vector<BrickSpan>, 3> spans;
    for (int a = 0; a < 3; ++a) spans[a] = spansOf(size[a], new_size[a], side ? side : kMaxTetMeshSide, margin);
    std::vector<VolumeBrick> bricks;
    for (const BrickSpan& z : spans[2])
        for (const BrickSpan& y : spans[1])
            for (const BrickSpan& x : spans[0]) {
                VolumeBrick brick;
                brick.mesh_size = {x.vertex_end - x.vertex_begin, y.vertex_end - y.vertex_begin, z.vertex_end - z.vertex_begin};
                brick.window = {size, new_size, {x.vertex_begin, y.vertex_begin, z.vertex_begin},
                                {x.out_begin, y.out_begin, z.out_begin}, {x.out_end, y.out_end, z.out_end}};
                bricks.push_back(brick);
            }
    return bricks;
}

std::vector<float> magnifyVolumeValues(const Volume& volume, const std::array<uint32_t, 3>& new_size,
                                       const VolumeMagnifyOptions& options, VolumeMagnifyStats& stats) {
    stats = {};
    const bool whole = options.brick_side == 0 && volume.voxelCount() <= kMaxVoxelsInOneMesh;
    const uint32_t side = whole ? 0 : options.brick_side ? options.brick_side : kDefaultBrickSide;
    const auto [lo, hi] = std::minmax_element(volume.values.begin(), volume.values.end());
    TetLawsonOptions lawson;
    lawson.weight = options.weight;
    // NaN marks a voxel no brick resampled; there is none (tested).
    std::vector<float> out(size_t(new_size[0]) * new_size[1] * new_size[2], std::numeric_limits<float>::quiet_NaN());
    for (const VolumeBrick& brick : volumeBricks(volume.size, new_size, side, options.margin)) {
        auto start = std::chrono::steady_clock::now();
        const std::vector<float> values =
            brick.mesh_size == volume.size ? volume.values : brickValues(volume, brick.window.vertex_offset, brick.mesh_size);
        TetMesh mesh = kuhnTetMesh(brick.mesh_size);
        TetCostField field;
        field.size = brick.mesh_size;
        field.spacing = spacingOf(volume.index_to_world);
        field.values = normalizedValues(values, double(*lo), double(*hi));
        stats.tets_before += mesh.tetCount();
        addStats(stats, options.optimize ? options.optimize(mesh, std::move(field), options.weight)
                                         : optimizeTetMeshSerial(mesh, field, lawson));
        stats.tets_after += mesh.tetCount();
        ++stats.bricks;
        stats.optimize_s += secondsSince(start);

        // The resampling reads only the tets' vertices: the neighbours' 16 bytes a slot go
        // first, so that the resampler's own memory (a device's copy of the vertices, the
        // output) comes within what the flips took.
        std::vector<TetNeighbours>().swap(mesh.neighbours);
        start = std::chrono::steady_clock::now();
        if (options.resample)
            options.resample(mesh, values, brick.window, out.data());
        else
            resampleTetsInto(mesh, values, brick.window, out.data());
        stats.resample_s += secondsSince(start);
    }
    return out;
}

}  // namespace ddt
