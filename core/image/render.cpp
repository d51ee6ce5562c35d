#include "render.h"

#include <algorithm>
#include <array>
#include <cassert>
#include <cmath>

#include "channel_count.h"
#include "divide_by.h"
#include "lattice_samples.h"
#include "parallel.h"
#include "raster.h"

namespace ddt {

namespace {

// The triangle tables are made in chunks of edges: enough edges to be worth a task, few
// enough chunks that their counts per row stay small.
const uint32_t kEdgesPerChunk = 16384, kMostChunks = 64;

// Two doubles in one SIMD value (the GCC/Clang vector extension), for two channels or two
// weights of a sample: the arithmetic is lane-wise IEEE double precision, so each lane gets
// exactly the scalar expression's value.
typedef double DoublePair __attribute__((vector_size(2 * sizeof(double))));

// Saturates instead of wrapping, so an absurd request (-s 1e12) stays absurd for the checks.
uint32_t roundedSide(double side) { return side >= 4294967295.0 ? UINT32_MAX : uint32_t(std::llround(side)); }

}  // namespace

OutputSize scaledOutputSize(uint32_t width, uint32_t height, double scale) {
    return {roundedSide(scale * width), roundedSide(scale * height)};
}

OutputSize outputSizeForWidth(uint32_t width, uint32_t height, uint32_t out_width) {
    return {out_width, roundedSide(double(out_width) * height / width)};
}

OutputSize outputSizeForHeight(uint32_t width, uint32_t height, uint32_t out_height) {
    return {roundedSide(double(out_height) * width / height), out_height};
}

std::string checkOutputSize(uint32_t width, uint32_t height, OutputSize out) {
    if (out.width < width || out.height < height) return "ddtup only magnifies: the output must be at least the input size";
    double product = double(width) * height * out.width * out.height;
    if (product >= std::ldexp(1.0, 60)) return "output too large for exact rasterisation (input × output pixels ≥ 2^60)";
    return "";
}

RenderWindow wholeRows(uint32_t width, uint32_t height, OutputSize out, uint32_t y_begin, uint32_t y_end) {
    RenderWindow window;
    window.input_width = width;
    window.input_height = height;
    window.out = out;
    window.x_end = out.width;
    window.y_begin = y_begin;
    window.y_end = y_end;
    return window;
}

int64_t snappedSample(int64_t s, uint32_t out_size) {
    const unsigned __int128 twice_out = 2 * uint64_t(out_size);
    return int64_t((2 * (unsigned __int128)(s) * kPositionOne + twice_out) / (2 * twice_out));
}

MeshRenderer::MeshRenderer(const Mesh& mesh, const Image& image, const float* bubbles)
    : image_(image), bubbles_(bubbles), width_(mesh.width), height_(mesh.height), by_width_(std::max(mesh.width, 2u)),
      positions_(mesh.positions) {
    assert(image.pixels.size() >= size_t(mesh.vertexCount()) * image.channels);
    // The triangles sorted by top row (counting sort, stable), so a band of output rows visits
    // only nearby triangles. Chunks of edges are counted and placed on the threads, each
    // chunk's triangles after the earlier chunks' in every row: the order one pass would give.
    const uint32_t edges = mesh.edgeCount(), rows = mesh.height;
    const uint32_t chunks = std::clamp<uint32_t>(edges / kEdgesPerChunk, 1, kMostChunks);
    auto edgesOf = [&](size_t chunk) { return std::pair{uint32_t(uint64_t(edges) * chunk / chunks), uint32_t(uint64_t(edges) * (chunk + 1) / chunks)}; };
    std::vector<uint32_t> next(size_t(chunks) * rows, 0), tallest(chunks, 0);  // next: per chunk, per top row
    parallelFor(chunks, 1, [&](size_t begin, size_t end) {
        for (size_t chunk = begin; chunk < end; ++chunk) {
            uint32_t* count = next.data() + chunk * rows;
            forEachTriangle(mesh, edgesOf(chunk).first, edgesOf(chunk).second, [&](const Triangle& t) {
                const auto [top, bottom] = rowsOf(t);
                ++count[top];
                tallest[chunk] = std::max(tallest[chunk], bottom - top);
            });
        }
    });
    tallest_ = *std::max_element(tallest.begin(), tallest.end());
    first_in_row_.assign(rows + 1, 0);
    uint32_t placed = 0;
    for (uint32_t y = 0; y < rows; ++y) {
        first_in_row_[y] = placed;
        for (uint32_t chunk = 0; chunk < chunks; ++chunk) {
            const uint32_t count = next[size_t(chunk) * rows + y];
            next[size_t(chunk) * rows + y] = placed;
            placed += count;
        }
    }
    first_in_row_[rows] = placed;
    triangles_.resize(placed);
    parallelFor(chunks, 1, [&](size_t begin, size_t end) {
        for (size_t chunk = begin; chunk < end; ++chunk) {
            uint32_t* place = next.data() + chunk * rows;
            forEachTriangle(mesh, edgesOf(chunk).first, edgesOf(chunk).second,
                            [&](const Triangle& t) { triangles_[place[rowsOf(t).first]++] = t; });
        }
    });
}

std::pair<uint32_t, uint32_t> MeshRenderer::rowsOf(const Triangle& t) const {
    if (positions_.empty())
        return {by_width_.quotient(std::min({t.v0, t.v1, t.v2})), by_width_.quotient(std::max({t.v0, t.v1, t.v2}))};
    const int32_t y0 = positions_[t.v0].y, y1 = positions_[t.v1].y, y2 = positions_[t.v2].y;
    const uint32_t top = uint32_t(std::min({y0, y1, y2})) >> kPositionBits;
    const uint32_t bottom = (uint32_t(std::max({y0, y1, y2})) + kPositionOne - 1) >> kPositionBits;
    return {top, bottom};
}

MeshRenderer::MeshRenderer(MeshRenderer&& tables, const Image& image, const float* bubbles)
    : image_(image), bubbles_(bubbles), width_(tables.width_), height_(tables.height_), by_width_(tables.by_width_),
      positions_(std::move(tables.positions_)),
      triangles_(std::move(tables.triangles_)), first_in_row_(std::move(tables.first_in_row_)),
      tallest_(tables.tallest_) {
    // Not against tables.image_: a surface taken over is often the one `tables` read, moved.
    assert(image.pixels.size() >= (positions_.empty() ? size_t(width_) * height_ : positions_.size()) * image.channels);
}

void MeshRenderer::renderRows(OutputSize out, uint32_t y_begin, uint32_t y_end, float* rows) const {
    renderWindow(wholeRows(width_, height_, out, y_begin, y_end), rows);
}

namespace {

// Where the window's samples lie, per window column and row: their coordinates and tie
// directions (raster.h). On the grid's mesh the coordinates are raster.h's exact ones; on a
// mesh with explicit positions they are snapped to the positions' fixed-point grid
// (glsl/fixed_position.h: to the nearest 1/1024 pixel), so that vertices and samples share one
// unit and every edge function is exact in 64 bits.
struct SampleAxes {
    uint32_t x_begin = 0, y_begin = 0;
    std::vector<int64_t> su, sv;
    std::vector<int8_t> dir_u, dir_v;
};

SampleAxes sampleAxesOf(const RenderWindow& window, bool snapped) {
    const uint32_t in_w = window.input_width, in_h = window.input_height;
    const uint32_t out_w = window.out.width, out_h = window.out.height;
    SampleAxes axes;
    axes.x_begin = window.x_begin;
    axes.y_begin = window.y_begin;
    auto fill = [&](uint32_t begin, uint32_t end, uint32_t in, uint32_t out, std::vector<int64_t>& s, std::vector<int8_t>& dir) {
        for (uint32_t i = begin; i < end; ++i) {
            const int64_t exact = sampleCoord(i, in, out);
            s.push_back(snapped ? snappedSample(exact, out) : exact);
            dir.push_back(int8_t(sampleDirection(exact, in, out)));
        }
    };
    fill(window.x_begin, window.x_end, in_w, out_w, axes.su, axes.dir_u);
    fill(window.y_begin, window.y_end, in_h, out_h, axes.sv, axes.dir_v);
    return axes;
}

// The grid's bounds: the first and last output column or row whose sample lies at or after /
// at or before each crop column or row, clamped to the window. Tables, so that no division or
// clamp is left for the triangles.
struct GridBounds {
    std::vector<uint32_t> col_first, col_last;  // per crop column
    std::vector<uint32_t> row_first, row_last;  // per crop row in [row_base, row_base + size)
    uint32_t row_base = 0;
};

GridBounds gridBoundsOf(const RenderWindow& window, uint32_t crop_w, uint32_t row_begin, uint32_t row_end) {
    const uint32_t in_w = window.input_width, in_h = window.input_height;
    const uint32_t out_w = window.out.width, out_h = window.out.height;
    GridBounds grid;
    grid.col_first.resize(crop_w);
    grid.col_last.resize(crop_w);
    for (uint32_t x = 0; x < crop_w; ++x) {
        grid.col_first[x] = std::max(firstSampleAtOrAfter(x + window.crop_x, in_w, out_w), window.x_begin);
        grid.col_last[x] = std::min(lastSampleAtOrBefore(x + window.crop_x, in_w, out_w), window.x_end - 1);
    }
    grid.row_base = row_begin;
    grid.row_first.resize(row_end - row_begin);
    grid.row_last.resize(row_end - row_begin);
    for (uint32_t y = row_begin; y < row_end; ++y) {
        grid.row_first[y - row_begin] = std::max(firstSampleAtOrAfter(y + window.crop_y, in_h, out_h), window.y_begin);
        grid.row_last[y - row_begin] = std::min(lastSampleAtOrBefore(y + window.crop_y, in_h, out_h), window.y_end - 1);
    }
    return grid;
}

// The window's samples in [lo, hi] along one axis (coordinates ascending): output indices
// [first, end), empty if none.
std::pair<uint32_t, uint32_t> samplesWithin(const std::vector<int64_t>& s, uint32_t begin, int64_t lo, int64_t hi) {
    const auto first = std::lower_bound(s.begin(), s.end(), lo), end = std::upper_bound(first, s.end(), hi);
    return {begin + uint32_t(first - s.begin()), begin + uint32_t(end - s.begin())};
}

// Calls sample(x, y, l0, l1, l2) for the samples of window columns [x_lo, x_hi] and rows
// [y_lo, y_hi] that lie in the positive triangle with vertices (px, py)[k], in the samples'
// units, row by row; l are the barycentric weights.
template <typename Sample>
void scanTriangle(const SampleAxes& axes, const int64_t px[3], const int64_t py[3], uint32_t x_lo, uint32_t x_hi,
                  uint32_t y_lo, uint32_t y_hi, const Sample& sample) {
    // Edge k runs from vertex p = k + 1 to q = k + 2 (mod 3), opposite vertex k. Its edge
    // function (q − p) × (s − p) is weight[k] = slope[k]·su + offset[k] along a row, in
    // wrapping 64-bit arithmetic: the terms may pass 2^63, the sum is the exact value.
    int64_t edge_dx[3], edge_dy[3];
    uint64_t slope[3];
    // Bit k of ties[v][u]: whether a sample on edge k's line counts as inside by the tie
    // rule (raster.h's sampleSide), for a sample pushed along v backwards (v = 0) or
    // forwards (1) and along u backwards (u = 0) or forwards (1).
    uint32_t ties[2][2] = {};
    for (int k = 0; k < 3; ++k) {
        const int p = (k + 1) % 3, q = (k + 2) % 3;
        edge_dx[k] = px[q] - px[p];
        edge_dy[k] = py[q] - py[p];
        slope[k] = uint64_t(-edge_dy[k]);
        for (int v = 0; v < 2; ++v) {
            ties[v][1] |= uint32_t(edge_dy[k] != 0 ? edge_dy[k] < 0 : (v ? edge_dx[k] > 0 : edge_dx[k] < 0)) << k;
            ties[v][0] |= uint32_t(edge_dy[k] != 0 ? edge_dy[k] > 0 : (v ? edge_dx[k] > 0 : edge_dx[k] < 0)) << k;
        }
    }
    for (uint32_t y = y_lo; y <= y_hi; ++y) {
        const int64_t sv = axes.sv[y - axes.y_begin];
        const uint32_t* row_ties = ties[axes.dir_v[y - axes.y_begin] > 0];
        uint64_t offset[3];
        for (int k = 0; k < 3; ++k) {
            const int p = (k + 1) % 3;
            offset[k] = uint64_t(edge_dx[k] * (sv - py[p])) + uint64_t(edge_dy[k]) * uint64_t(px[p]);
        }
        // The samples a convex triangle covers are consecutive along a row (the tie rule
        // moves them all the same way, but for the hull's last column, which is last).
        bool entered = false;
        for (uint32_t x = x_lo; x <= x_hi; ++x) {
            const int64_t su = axes.su[x - axes.x_begin];
            // The edge function opposite each vertex is its barycentric weight × 2·area.
            int64_t weight[3];
            for (int k = 0; k < 3; ++k) weight[k] = int64_t(slope[k] * uint64_t(su) + offset[k]);
            const uint32_t on_line =
                uint32_t(weight[0] == 0) | uint32_t(weight[1] == 0) << 1 | uint32_t(weight[2] == 0) << 2;
            const bool inside = (weight[0] | weight[1] | weight[2]) >= 0 &&
                                (on_line & ~row_ties[axes.dir_u[x - axes.x_begin] > 0]) == 0;
            if (!inside) {
                if (entered) break;
                continue;
            }
            entered = true;
            const double total = double(weight[0]) + double(weight[1]) + double(weight[2]);
            // Two of the divisions in one instruction.
            const DoublePair l01 = DoublePair{double(weight[0]), double(weight[1])} / total;
            sample(x, y, l01[0], l01[1], double(weight[2]) / total);
        }
    }
}

}  // namespace

// The triangles whose samples can fall in the window's rows: those whose top row lies in the
// crop rows the window samples, widened upwards by the tallest triangle.
std::pair<uint32_t, uint32_t> MeshRenderer::trianglesAround(const RenderWindow& window) const {
    const uint32_t h = height_, in_h = window.input_height, out_h = window.out.height, cy = window.crop_y;
    if (window.x_begin >= window.x_end || window.y_begin >= window.y_end) return {0, 0};
    const int64_t unit = vertexCoord(1, out_h);
    const uint32_t v_first = uint32_t(sampleCoord(window.y_begin, in_h, out_h) / unit);
    const uint32_t v_last = uint32_t((sampleCoord(window.y_end - 1, in_h, out_h) + unit - 1) / unit);
    const uint32_t local_first = v_first > cy ? v_first - cy : 0;
    const uint32_t top_first = local_first > tallest_ ? local_first - tallest_ : 0;
    const uint32_t top_last = std::min(v_last > cy ? v_last - cy : 0, h - 1);
    return {first_in_row_[top_first], first_in_row_[top_last + 1]};
}

// For every triangle of [first, end) with samples in the window, calls visit(triangle index)
// once; it returns a callable that visitSamples calls as sample(x, y, l0, l1, l2) for each of
// them, in row-major order. Each sample of the window lies in exactly one triangle.
template <typename Visit>
void MeshRenderer::visitSamples(const RenderWindow& window, uint32_t first, uint32_t end, Visit visit) const {
    // w, h: the crop the mesh covers; the whole input (window.input_*) sets the sampling.
    const uint32_t w = width_, h = height_;
    const uint32_t out_w = window.out.width, out_h = window.out.height;
    const uint32_t cx = window.crop_x, cy = window.crop_y;
    assert(cx + w <= window.input_width && cy + h <= window.input_height);
    assert(window.x_end <= out_w && window.y_end <= out_h);
    if (window.x_begin >= window.x_end || window.y_begin >= window.y_end || first >= end) return;
    const bool explicit_positions = !positions_.empty();
    const SampleAxes axes = sampleAxesOf(window, explicit_positions);
    int64_t px[3], py[3];
    if (explicit_positions) {
        // Positions are the crop's: moved by its offset to the whole input's, as samples are.
        const int64_t x_offset = int64_t(cx) * kPositionOne, y_offset = int64_t(cy) * kPositionOne;
        for (uint32_t i = first; i < end; ++i) {
            const Triangle& t = triangles_[i];
            const uint32_t ids[3] = {t.v0, t.v1, t.v2};
            for (int k = 0; k < 3; ++k) px[k] = positions_[ids[k]].x + x_offset, py[k] = positions_[ids[k]].y + y_offset;
            const auto [x_lo, x_end] =
                samplesWithin(axes.su, window.x_begin, std::min({px[0], px[1], px[2]}), std::max({px[0], px[1], px[2]}));
            const auto [y_lo, y_end] =
                samplesWithin(axes.sv, window.y_begin, std::min({py[0], py[1], py[2]}), std::max({py[0], py[1], py[2]}));
            if (x_lo < x_end && y_lo < y_end) scanTriangle(axes, px, py, x_lo, x_end - 1, y_lo, y_end - 1, visit(i));
        }
        return;
    }
    // The crop rows these triangles span: sorted by top row, each at most tallest_ rows high.
    const uint32_t top_first = rowsOf(triangles_[first]).first, top_last = rowsOf(triangles_[end - 1]).first;
    const GridBounds grid = gridBoundsOf(window, w, top_first, std::min(h, top_last + tallest_ + 1));
    const DivideBy by_width(w);
    // At exactly ×3 a triangle of the grid's mesh needs no scan (lattice_samples.h).
    const bool thirds = out_w == 3 * window.input_width && out_h == 3 * window.input_height;
    for (uint32_t i = first; i < end; ++i) {
        const Triangle& t = triangles_[i];
        const uint32_t ys[3] = {by_width.quotient(t.v0), by_width.quotient(t.v1), by_width.quotient(t.v2)};
        const uint32_t xs[3] = {t.v0 - ys[0] * w, t.v1 - ys[1] * w, t.v2 - ys[2] * w};
        const uint32_t x_lo = grid.col_first[std::min({xs[0], xs[1], xs[2]})];
        const uint32_t x_hi = grid.col_last[std::max({xs[0], xs[1], xs[2]})];
        const uint32_t y_lo = grid.row_first[std::min({ys[0], ys[1], ys[2]}) - grid.row_base];
        const uint32_t y_hi = grid.row_last[std::max({ys[0], ys[1], ys[2]}) - grid.row_base];
        if (x_lo > x_hi || y_lo > y_hi) continue;
        auto sample = visit(i);
        if (thirds) {
            const uint32_t x[3] = {xs[0] + cx, xs[1] + cx, xs[2] + cx}, y[3] = {ys[0] + cy, ys[1] + cy, ys[2] + cy};
            if (visitLatticeTriangle(x, y, window.input_width, window.input_height, x_lo, x_hi + 1, y_lo, y_hi + 1, sample))
                continue;
        }
        for (int k = 0; k < 3; ++k) {
            px[k] = vertexCoord(xs[k] + cx, out_w);
            py[k] = vertexCoord(ys[k] + cy, out_h);
        }
        scanTriangle(axes, px, py, x_lo, x_hi, y_lo, y_hi, sample);
    }
}

void MeshRenderer::renderWindow(const RenderWindow& window, float* rows, size_t row_stride) const {
    withChannelCount(image_.channels, [&](auto channels) {
        constexpr uint32_t c = decltype(channels)::value, pairs = (c + 1) / 2;
        const size_t row_floats = row_stride ? row_stride : size_t(window.width()) * c;
        const size_t x_begin = window.x_begin, y_begin = window.y_begin;
        const float* values = image_.pixels.data();
        const float* bubbles = bubbles_;
        const bool alpha = image_.hasAlpha();
        const auto [first, end] = trianglesAround(window);
        visitSamples(window, first, end, [&](uint32_t i) {
            // The triangle's vertex values and bubbles in pairs of channels (an odd count padded
            // with 0), as doubles, and the range a sample keeps to.
            const Triangle& t = triangles_[i];
            auto pairsOf = [&](const float* p) {
                std::array<DoublePair, pairs> result;
                for (uint32_t k = 0; k < c; ++k) result[k / 2][k % 2] = p[k];
                if (c % 2) result[pairs - 1][1] = 0.0;
                return result;
            };
            const std::array<DoublePair, pairs> z[3] = {
                pairsOf(values + size_t(t.v0) * c), pairsOf(values + size_t(t.v1) * c), pairsOf(values + size_t(t.v2) * c)};
            std::array<DoublePair, pairs> b[3] = {}, lo, hi;
            for (uint32_t p = 0; p < pairs; ++p) {  // std::min and std::max of the three, lane by lane
                lo[p] = z[1][p] < z[0][p] ? z[1][p] : z[0][p];
                lo[p] = z[2][p] < lo[p] ? z[2][p] : lo[p];
                hi[p] = z[0][p] < z[1][p] ? z[1][p] : z[0][p];
                hi[p] = hi[p] < z[2][p] ? z[2][p] : hi[p];
            }
            if (bubbles)
                b[0] = pairsOf(bubbles + size_t(t.e0) * c), b[1] = pairsOf(bubbles + size_t(t.e1) * c),
                b[2] = pairsOf(bubbles + size_t(t.e2) * c);
            return [=](uint32_t x, uint32_t y, double l0, double l1, double l2) {
                float* pixel = rows + (y - y_begin) * row_floats + (x - x_begin) * c;
                auto store = [&](uint32_t p, DoublePair value) {
                    pixel[2 * p] = float(value[0]);
                    if (2 * p + 1 < c) pixel[2 * p + 1] = float(value[1]);
                };
                if (!bubbles) {
                    for (uint32_t p = 0; p < pairs; ++p) store(p, l0 * z[0][p] + l1 * z[1][p] + l2 * z[2][p]);
                    return;
                }
                const double l12 = l1 * l2, l20 = l2 * l0, l01 = l0 * l1;
                for (uint32_t p = 0; p < pairs; ++p) {
                    const DoublePair value = l0 * z[0][p] + l1 * z[1][p] + l2 * z[2][p] +
                                             4.0 * (l12 * b[0][p] + l20 * b[1][p] + l01 * b[2][p]);
                    // std::clamp's comparisons, lane by lane.
                    store(p, value < lo[p] ? lo[p] : hi[p] < value ? hi[p] : value);
                }
                if (alpha)
                    for (uint32_t k = 0; k + 1 < c; ++k) pixel[k] = std::min(pixel[k], pixel[c - 1]);
            };
        });
    });
}

void MeshRenderer::locateSamples(OutputSize out, uint32_t first, uint32_t end, std::vector<SampleHit>& hits,
                                 uint32_t* ends) const {
    const uint32_t start = uint32_t(hits.size());
    // About as many samples in each triangle as on average.
    hits.reserve(start + size_t(1.25 * double(out.width) * out.height / triangles_.size() * (end - first)) + 16);
    std::fill(ends, ends + (end - first), 0);  // first each triangle's count
    visitSamples(wholeRows(width_, height_, out, 0, out.height), first, end, [&](uint32_t i) {
        return [&, count = ends + (i - first)](uint32_t x, uint32_t y, double l0, double l1, double l2) {
            hits.push_back({y * out.width + x, {float(l0), float(l1), float(l2)}});
            ++*count;
        };
    });
    uint32_t total = start;
    for (uint32_t i = 0; i < end - first; ++i) ends[i] = total += ends[i];
}

void renderInParallel(const MeshRenderer& renderer, const RenderWindow& window, uint32_t channels, float* rows,
                      const BandFinish& finish) {
    const size_t row_floats = size_t(window.width()) * channels;
    parallelFor(window.height(), kRowsPerRenderBand, [&](size_t begin, size_t end) {
        RenderWindow band = window;
        band.y_begin = window.y_begin + uint32_t(begin);
        band.y_end = window.y_begin + uint32_t(end);
        renderer.renderWindow(band, rows + begin * row_floats);
        if (finish) finish(band, rows + begin * row_floats);
    });
}

Image renderImage(const Mesh& mesh, const Image& image, OutputSize out, const float* bubbles) {
    Image result;
    result.width = out.width;
    result.height = out.height;
    result.channels = image.channels;
    result.sample_type = image.sample_type;
    result.metadata = image.metadata;
    result.pixels.resize(size_t(out.width) * out.height * image.channels);
    MeshRenderer(mesh, image, bubbles).renderRows(out, 0, out.height, result.pixels.data());
    return result;
}

}  // namespace ddt
