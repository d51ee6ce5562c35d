#include "sampled_render.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include "nearest_fill.h"
#include "raster.h"

namespace ddt {

namespace {

// Sample coordinates of output indices [begin, end) along one axis, as the renderer tests
// them (core/image/render.cpp): in raster.h's exact units for vertices at pixel centres,
// snapped to the 1/kPositionOne grid of explicit positions. Non-decreasing in the index.
std::vector<int64_t> sampleAxis(uint32_t begin, uint32_t end, uint32_t in_size, uint32_t out_size, bool snapped) {
    std::vector<int64_t> s(end - begin);
    for (uint32_t i = begin; i < end; ++i) {
        const int64_t exact = sampleCoord(i, in_size, out_size);
        s[i - begin] = snapped ? snappedSample(exact, out_size) : exact;
    }
    return s;
}

// Indices [first, end) into `s` whose sample coordinate lies in [lo, hi].
std::pair<size_t, size_t> samplesIn(const std::vector<int64_t>& s, int64_t lo, int64_t hi) {
    const auto first = std::lower_bound(s.begin(), s.end(), lo);
    return {size_t(first - s.begin()), size_t(std::upper_bound(first, s.end(), hi) - s.begin())};
}

}  // namespace

std::vector<HullEdge> hullEdgesOf(const Mesh& mesh, const RenderWindow& frame) {
    std::vector<HullEdge> edges;
    const bool snapped = !mesh.positions.empty();
    auto placeOf = [&](uint32_t v) -> std::pair<int64_t, int64_t> {
        // Explicit positions are the crop's, moved by its offset as the renderer moves them.
        if (snapped)
            return {mesh.positions[v].x + int64_t(frame.crop_x) * kPositionOne,
                    mesh.positions[v].y + int64_t(frame.crop_y) * kPositionOne};
        return {vertexCoord(v % mesh.width + frame.crop_x, frame.out.width),
                vertexCoord(v / mesh.width + frame.crop_y, frame.out.height)};
    };
    for (const EdgeVertices& edge : mesh.vertices) {
        if (edge.l != kNone && edge.r != kNone) continue;
        const auto [px, py] = placeOf(edge.a);
        const auto [qx, qy] = placeOf(edge.b);
        edges.push_back({edge.a, edge.b, px, py, qx, qy, edge.l != kNone});
    }
    return edges;
}

void fillOnHullEdges(const std::vector<HullEdge>& edges, bool snapped, const Image& values, const RenderWindow& window,
                     float* rows, size_t row_stride) {
    const uint32_t c = values.channels;
    if (row_stride == 0) row_stride = size_t(window.width()) * c;
    const std::vector<int64_t> su = sampleAxis(window.x_begin, window.x_end, window.input_width, window.out.width, snapped);
    const std::vector<int64_t> sv = sampleAxis(window.y_begin, window.y_end, window.input_height, window.out.height, snapped);
    auto fill = [&](size_t x, size_t y, const float* zp, const float* zq, double t) {
        float* pixel = rows + y * row_stride + x * c;
        if (!std::isnan(pixel[0])) return;
        for (uint32_t k = 0; k < c; ++k) pixel[k] = float((1.0 - t) * zp[k] + t * zq[k]);
    };
    for (const HullEdge& edge : edges) {
        const int64_t px = edge.px, py = edge.py, qx = edge.qx, qy = edge.qy;
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

bool hullContains(const std::vector<HullEdge>& edges, int64_t x, int64_t y) {
    for (const HullEdge& edge : edges) {
        // The hull lies on the side of the edge's one triangle: left of a→b when it is l.
        const __int128 side = __int128(edge.qx - edge.px) * (y - edge.py) - __int128(edge.qy - edge.py) * (x - edge.px);
        if (edge.inside_left ? side < 0 : side > 0) return false;
    }
    return true;
}

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
    const RenderWindow whole = wholeRows(mesh.width, mesh.height, out, 0, out.height);
    fillOnHullEdges(hullEdgesOf(mesh, whole), !mesh.positions.empty(), values, whole, result.pixels.data());
    fillFromNearest(result.pixels.data(), out.width, out.height, values.channels);
    return result;
}

}  // namespace ddt
