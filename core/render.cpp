#include "render.h"

#include <algorithm>
#include <cassert>
#include <cmath>

#include "channel_count.h"
#include "raster.h"

namespace ddt {

namespace {

// Saturates instead of wrapping, so an absurd request (-s 1e12) stays absurd for the checks.
uint32_t roundedSide(double side) { return side >= 4294967295.0 ? UINT32_MAX : uint32_t(std::llround(side)); }

uint32_t topRow(const Triangle& t, uint32_t width) { return std::min({t.v0, t.v1, t.v2}) / width; }

struct Bounds {
    uint32_t x0, x1, y0, y1;
};

Bounds boundsOf(const Triangle& t, uint32_t width) {
    uint32_t xs[3] = {t.v0 % width, t.v1 % width, t.v2 % width};
    uint32_t ys[3] = {t.v0 / width, t.v1 / width, t.v2 / width};
    return {*std::min_element(xs, xs + 3), *std::max_element(xs, xs + 3), *std::min_element(ys, ys + 3),
            *std::max_element(ys, ys + 3)};
}

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

MeshRenderer::MeshRenderer(const Mesh& mesh, const Image& image, const std::vector<float>* bubbles)
    : image_(image), bubbles_(bubbles) {
    assert(image.width == mesh.width && image.height == mesh.height);
    assert(!bubbles || bubbles->size() == size_t(mesh.edgeCount()) * image.channels);
    std::vector<Triangle> triangles = listTriangles(mesh);
    // Counting sort by top row, so a band of output rows visits only nearby triangles.
    first_in_row_.assign(mesh.height + 1, 0);
    for (const Triangle& t : triangles) {
        ++first_in_row_[topRow(t, mesh.width) + 1];
        Bounds b = boundsOf(t, mesh.width);
        tallest_ = std::max(tallest_, b.y1 - b.y0);
    }
    for (uint32_t y = 0; y < mesh.height; ++y) first_in_row_[y + 1] += first_in_row_[y];
    triangles_.resize(triangles.size());
    std::vector<uint32_t> next(first_in_row_.begin(), first_in_row_.end() - 1);
    for (const Triangle& t : triangles) triangles_[next[topRow(t, mesh.width)]++] = t;
}

void MeshRenderer::renderRows(OutputSize out, uint32_t y_begin, uint32_t y_end, float* rows) const {
    renderWindow(wholeRows(image_.width, image_.height, out, y_begin, y_end), rows);
}

namespace {

// Where the window's samples lie: their coordinates (raster.h's units) per output column, and
// the first and last output column or row whose sample lies at or after / at or before each
// crop column or row, clamped to the window. Tables, so that no division or clamp is left
// for the triangles and samples.
struct SampleGrid {
    std::vector<int64_t> su;         // per window column
    std::vector<int8_t> dir_u;       // per window column
    std::vector<uint32_t> col_first, col_last;  // per crop column
    std::vector<uint32_t> row_first, row_last;  // per crop row in [row_base, row_base + size)
    uint32_t row_base = 0;
};

SampleGrid sampleGridOf(const RenderWindow& window, uint32_t crop_w, uint32_t row_begin, uint32_t row_end) {
    const uint32_t in_w = window.input_width, in_h = window.input_height;
    const uint32_t out_w = window.out.width, out_h = window.out.height;
    SampleGrid grid;
    grid.su.resize(window.width());
    grid.dir_u.resize(window.width());
    for (uint32_t x = window.x_begin; x < window.x_end; ++x) {
        grid.su[x - window.x_begin] = sampleCoord(x, in_w, out_w);
        grid.dir_u[x - window.x_begin] = int8_t(sampleDirection(grid.su[x - window.x_begin], in_w, out_w));
    }
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

}  // namespace

// For every triangle with samples in the window, calls visit(triangle index) once; it returns
// a callable that visitSamples calls as sample(x, y, l0, l1, l2) for each of them, each
// sample of the window once.
template <typename Visit>
void MeshRenderer::visitSamples(const RenderWindow& window, Visit visit) const {
    // w, h: the crop the mesh covers; in_w, in_h: the whole input, which sets the sampling.
    const uint32_t w = image_.width, h = image_.height;
    const uint32_t in_h = window.input_height;
    const uint32_t out_w = window.out.width, out_h = window.out.height;
    const uint32_t cx = window.crop_x, cy = window.crop_y;
    assert(cx + w <= window.input_width && cy + h <= in_h && window.x_end <= out_w && window.y_end <= out_h);
    if (window.x_begin >= window.x_end || window.y_begin >= window.y_end) return;
    // Crop rows the window's samples fall in, widened by the tallest triangle.
    const int64_t unit = vertexCoord(1, out_h);
    const uint32_t v_first = uint32_t(sampleCoord(window.y_begin, in_h, out_h) / unit);
    const uint32_t v_last = uint32_t((sampleCoord(window.y_end - 1, in_h, out_h) + unit - 1) / unit);
    const uint32_t local_first = v_first > cy ? v_first - cy : 0;
    const uint32_t top_first = local_first > tallest_ ? local_first - tallest_ : 0;
    const uint32_t top_last = std::min(v_last > cy ? v_last - cy : 0, h - 1);
    const SampleGrid grid = sampleGridOf(window, w, top_first, std::min(h, top_last + tallest_ + 1));

    for (uint32_t i = first_in_row_[top_first]; i < first_in_row_[top_last + 1]; ++i) {
        const Triangle& t = triangles_[i];
        const uint32_t xs[3] = {t.v0 % w, t.v1 % w, t.v2 % w}, ys[3] = {t.v0 / w, t.v1 / w, t.v2 / w};
        const uint32_t x_lo = grid.col_first[std::min({xs[0], xs[1], xs[2]})];
        const uint32_t x_hi = grid.col_last[std::max({xs[0], xs[1], xs[2]})];
        const uint32_t y_lo = grid.row_first[std::min({ys[0], ys[1], ys[2]}) - grid.row_base];
        const uint32_t y_hi = grid.row_last[std::max({ys[0], ys[1], ys[2]}) - grid.row_base];
        if (x_lo > x_hi || y_lo > y_hi) continue;

        int64_t px[3], py[3];
        for (int k = 0; k < 3; ++k) {
            px[k] = vertexCoord(xs[k] + cx, out_w);
            py[k] = vertexCoord(ys[k] + cy, out_h);
        }
        // Edge k runs from vertex p = k + 1 to q = k + 2 (mod 3), opposite vertex k. Its edge
        // function (q − p) × (s − p) is weight[k] = slope[k]·su + offset[k] along a row, in
        // wrapping 64-bit arithmetic: the terms may pass 2^63, the sum is the exact value.
        int64_t edge_dx[3], edge_dy[3];
        uint64_t slope[3];
        for (int k = 0; k < 3; ++k) {
            const int p = (k + 1) % 3, q = (k + 2) % 3;
            edge_dx[k] = px[q] - px[p];
            edge_dy[k] = py[q] - py[p];
            slope[k] = uint64_t(-edge_dy[k]);
        }
        auto sample = visit(i);
        for (uint32_t y = y_lo; y <= y_hi; ++y) {
            const int64_t sv = sampleCoord(y, in_h, out_h);
            const int dir_v = sampleDirection(sv, in_h, out_h);
            uint64_t offset[3];
            for (int k = 0; k < 3; ++k) {
                const int p = (k + 1) % 3;
                offset[k] = uint64_t(edge_dx[k] * (sv - py[p])) + uint64_t(edge_dy[k]) * uint64_t(px[p]);
            }
            // The samples a convex triangle covers are consecutive along a row (the tie rule
            // moves them all the same way, but for the hull's last column, which is last).
            bool entered = false;
            for (uint32_t x = x_lo; x <= x_hi; ++x) {
                const int64_t su = grid.su[x - window.x_begin];
                // The edge function opposite each vertex is its barycentric weight × 2·area.
                int64_t weight[3];
                for (int k = 0; k < 3; ++k) weight[k] = int64_t(slope[k] * uint64_t(su) + offset[k]);
                bool inside = (weight[0] | weight[1] | weight[2]) >= 0;
                if (inside && (weight[0] == 0 || weight[1] == 0 || weight[2] == 0)) {  // on an edge's line: the tie rule
                    for (int k = 0; k < 3 && inside; ++k) {
                        const int p = (k + 1) % 3, q = (k + 2) % 3;
                        inside = sampleSide(px[p], py[p], px[q], py[q], su, sv, grid.dir_u[x - window.x_begin], dir_v) > 0;
                    }
                }
                if (!inside) {
                    if (entered) break;
                    continue;
                }
                entered = true;
                const double total = double(weight[0]) + double(weight[1]) + double(weight[2]);
                sample(x, y, double(weight[0]) / total, double(weight[1]) / total, double(weight[2]) / total);
            }
        }
    }
}

void MeshRenderer::renderWindow(const RenderWindow& window, float* rows) const {
    withChannelCount(image_.channels, [&](auto channels) {
        constexpr uint32_t c = decltype(channels)::value;
        const size_t row_floats = size_t(window.width()) * c;
        const size_t x_begin = window.x_begin, y_begin = window.y_begin;
        const float* values = image_.pixels.data();
        const float* bubbles = bubbles_ ? bubbles_->data() : nullptr;
        const bool alpha = image_.hasAlpha();
        visitSamples(window, [&](uint32_t i) {
            // The triangle's vertex values and bubbles per channel, and the range a sample keeps to.
            const Triangle& t = triangles_[i];
            // Doubles, converted once here rather than at every sample.
            double z[3][c], b[3][c] = {}, lo[c], hi[c];
            for (uint32_t k = 0; k < c; ++k) {
                z[0][k] = values[size_t(t.v0) * c + k];
                z[1][k] = values[size_t(t.v1) * c + k];
                z[2][k] = values[size_t(t.v2) * c + k];
                lo[k] = std::min({z[0][k], z[1][k], z[2][k]});
                hi[k] = std::max({z[0][k], z[1][k], z[2][k]});
                if (bubbles) {
                    b[0][k] = bubbles[size_t(t.e0) * c + k];
                    b[1][k] = bubbles[size_t(t.e1) * c + k];
                    b[2][k] = bubbles[size_t(t.e2) * c + k];
                }
            }
            return [=](uint32_t x, uint32_t y, double l0, double l1, double l2) {
                float* pixel = rows + (y - y_begin) * row_floats + (x - x_begin) * c;
                if (!bubbles) {
                    for (uint32_t k = 0; k < c; ++k) pixel[k] = float(l0 * z[0][k] + l1 * z[1][k] + l2 * z[2][k]);
                    return;
                }
                for (uint32_t k = 0; k < c; ++k) {
                    const double value = l0 * z[0][k] + l1 * z[1][k] + l2 * z[2][k] +
                                         4.0 * (l1 * l2 * b[0][k] + l2 * l0 * b[1][k] + l0 * l1 * b[2][k]);
                    pixel[k] = float(std::clamp(value, lo[k], hi[k]));
                }
                if (alpha)
                    for (uint32_t k = 0; k + 1 < c; ++k) pixel[k] = std::min(pixel[k], pixel[c - 1]);
            };
        });
    });
}

void MeshRenderer::locateSamples(OutputSize out, uint32_t y_begin, uint32_t y_end, SampleHit* hits) const {
    visitSamples(wholeRows(image_.width, image_.height, out, y_begin, y_end), [&](uint32_t i) {
        return [=](uint32_t x, uint32_t y, double l0, double l1, double l2) {
            hits[size_t(y - y_begin) * out.width + x] = {i, {float(l0), float(l1), float(l2)}};
        };
    });
}

Image renderImage(const Mesh& mesh, const Image& image, OutputSize out, const std::vector<float>* bubbles) {
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
