#include "sampled_render.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include "nearest_fill.h"
#include "raster.h"

namespace ddt {

namespace {

// Sample coordinates along one axis, as the renderer tests them (core/image/render.cpp): in raster.h's
// exact units for vertices at pixel centres, snapped to the 1/kPositionOne grid of explicit
// positions. Non-decreasing in the output index.
std::vector<int64_t> sampleAxis(uint32_t in_size, uint32_t out_size, bool snapped) {
    std::vector<int64_t> s(out_size);
    for (uint32_t i = 0; i < out_size; ++i) {
        const int64_t exact = sampleCoord(i, in_size, out_size);
        s[i] = snapped ? snappedSample(exact, out_size) : exact;
    }
    return s;
}

// Output indices [first, end) whose sample coordinate lies in [lo, hi].
std::pair<size_t, size_t> samplesIn(const std::vector<int64_t>& s, int64_t lo, int64_t hi) {
    const auto first = std::lower_bound(s.begin(), s.end(), lo);
    return {size_t(first - s.begin()), size_t(std::upper_bound(first, s.end(), hi) - s.begin())};
}

// A sample lying exactly on a boundary edge belongs to the edge's triangle only when the
// raster tie-break (raster.h: a push right, then down) moves it inwards; one pushed out of the
// hull gets the edge's linear value here, so that the hull keeps its exact values (a known pixel
// at ×1 among them) rather than a neighbour's.
void fillBoundaryEdges(const Mesh& mesh, const Image& values, OutputSize out, Image& result) {
    const bool snapped = !mesh.positions.empty();
    const std::vector<int64_t> su = sampleAxis(mesh.width, out.width, snapped), sv = sampleAxis(mesh.height, out.height, snapped);
    const uint32_t c = values.channels;
    auto placeOf = [&](uint32_t v) -> std::pair<int64_t, int64_t> {
        if (snapped) return {mesh.positions[v].x, mesh.positions[v].y};
        return {vertexCoord(v % mesh.width, out.width), vertexCoord(v / mesh.width, out.height)};
    };
    auto fill = [&](size_t x, size_t y, const float* zp, const float* zq, double t) {
        float* pixel = result.pixels.data() + (y * out.width + x) * c;
        if (!std::isnan(pixel[0])) return;
        for (uint32_t k = 0; k < c; ++k) pixel[k] = float((1.0 - t) * zp[k] + t * zq[k]);
    };
    for (const EdgeVertices& edge : mesh.vertices) {
        if (edge.l != kNone && edge.r != kNone) continue;
        const auto [px, py] = placeOf(edge.a);
        const auto [qx, qy] = placeOf(edge.b);
        const float* za = values.pixels.data() + size_t(edge.a) * c;
        const float* zb = values.pixels.data() + size_t(edge.b) * c;
        const auto [x_first, x_end] = samplesIn(su, std::min(px, qx), std::max(px, qx));
        if (px == qx) {  // vertical: the rows along it
            const auto [y_first, y_end] = samplesIn(sv, std::min(py, qy), std::max(py, qy));
            for (size_t x = x_first; x < x_end; ++x)
                for (size_t y = y_first; y < y_end; ++y) fill(x, y, za, zb, double(sv[y] - py) / double(qy - py));
            continue;
        }
        for (size_t x = x_first; x < x_end; ++x) {
            // The line's row coordinate at su, py + (qy − py)(su − px) / (qx − px), when whole.
            const __int128 numerator = __int128(qy - py) * (su[x] - px), denominator = qx - px;
            if (numerator % denominator != 0) continue;
            const int64_t row = py + int64_t(numerator / denominator);
            const auto [y_first, y_end] = samplesIn(sv, row, row);
            for (size_t y = y_first; y < y_end; ++y) fill(x, y, za, zb, double(su[x] - px) / double(qx - px));
        }
    }
}

}  // namespace

Image renderSampledMesh(const Mesh& mesh, const Image& values, OutputSize out) {
    Image result;
    result.width = out.width;
    result.height = out.height;
    result.channels = values.channels;
    result.sample_type = values.sample_type;
    result.metadata = values.metadata;
    // NaN marks what no triangle covers: the renderer writes every covered pixel once, with a
    // finite value (the vertex values are finite: the readers refuse NaN and infinity).
    result.pixels.assign(size_t(out.width) * out.height * values.channels, std::numeric_limits<float>::quiet_NaN());
    const MeshRenderer renderer(mesh, values);
    renderInParallel(renderer, wholeRows(mesh.width, mesh.height, out, 0, out.height), values.channels,
                     result.pixels.data());
    fillBoundaryEdges(mesh, values, out, result);
    fillFromNearest(result.pixels.data(), out.width, out.height, values.channels);
    return result;
}

}  // namespace ddt
