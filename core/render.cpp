#include "render.h"

#include <algorithm>
#include <cassert>
#include <cmath>

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

// Calls visit(x, y, triangle index, l0, l1, l2) for every sample of the window, each once.
template <typename Visit>
void MeshRenderer::visitSamples(const RenderWindow& window, Visit visit) const {
    // w, h: the crop the mesh covers; in_w, in_h: the whole input, which sets the sampling.
    const uint32_t w = image_.width, h = image_.height;
    const uint32_t in_w = window.input_width, in_h = window.input_height;
    const uint32_t out_w = window.out.width, out_h = window.out.height;
    const uint32_t cx = window.crop_x, cy = window.crop_y;
    assert(cx + w <= in_w && cy + h <= in_h && window.x_end <= out_w && window.y_end <= out_h);
    if (window.x_begin >= window.x_end || window.y_begin >= window.y_end) return;
    // Crop rows the window's samples fall in, widened by the tallest triangle.
    const int64_t unit = vertexCoord(1, out_h);
    const uint32_t v_first = uint32_t(sampleCoord(window.y_begin, in_h, out_h) / unit);
    const uint32_t v_last = uint32_t((sampleCoord(window.y_end - 1, in_h, out_h) + unit - 1) / unit);
    const uint32_t local_first = v_first > cy ? v_first - cy : 0;
    const uint32_t top_first = local_first > tallest_ ? local_first - tallest_ : 0;
    const uint32_t top_last = std::min(v_last > cy ? v_last - cy : 0, h - 1);

    for (uint32_t i = first_in_row_[top_first]; i < first_in_row_[top_last + 1]; ++i) {
        const Triangle& t = triangles_[i];
        const Bounds b = boundsOf(t, w);
        const uint32_t x_lo = std::max(firstSampleAtOrAfter(b.x0 + cx, in_w, out_w), window.x_begin);
        const uint32_t x_hi = std::min(lastSampleAtOrBefore(b.x1 + cx, in_w, out_w), window.x_end - 1);
        const uint32_t y_lo = std::max(firstSampleAtOrAfter(b.y0 + cy, in_h, out_h), window.y_begin);
        const uint32_t y_hi = std::min(lastSampleAtOrBefore(b.y1 + cy, in_h, out_h), window.y_end - 1);
        if (x_lo > x_hi || y_lo > y_hi) continue;

        const int64_t px[3] = {vertexCoord(t.v0 % w + cx, out_w), vertexCoord(t.v1 % w + cx, out_w),
                               vertexCoord(t.v2 % w + cx, out_w)};
        const int64_t py[3] = {vertexCoord(t.v0 / w + cy, out_h), vertexCoord(t.v1 / w + cy, out_h),
                               vertexCoord(t.v2 / w + cy, out_h)};
        for (uint32_t y = y_lo; y <= y_hi; ++y) {
            const int64_t sv = sampleCoord(y, in_h, out_h);
            const int dir_v = sampleDirection(sv, in_h, out_h);
            for (uint32_t x = x_lo; x <= x_hi; ++x) {
                const int64_t su = sampleCoord(x, in_w, out_w);
                const int dir_u = sampleDirection(su, in_w, out_w);
                bool inside = true;
                int64_t weight[3];  // edge function opposite each vertex = its barycentric weight × 2·area
                for (int k = 0; k < 3 && inside; ++k) {
                    int p = (k + 1) % 3, q = (k + 2) % 3;
                    inside = sampleSide(px[p], py[p], px[q], py[q], su, sv, dir_u, dir_v) > 0;
                    weight[k] = (px[q] - px[p]) * (sv - py[p]) - (py[q] - py[p]) * (su - px[p]);
                }
                if (!inside) continue;
                const double total = double(weight[0]) + double(weight[1]) + double(weight[2]);
                visit(x, y, i, double(weight[0]) / total, double(weight[1]) / total, double(weight[2]) / total);
            }
        }
    }
}

void MeshRenderer::renderWindow(const RenderWindow& window, float* rows) const {
    const uint32_t c = image_.channels;
    const size_t row_floats = size_t(window.width()) * c;
    const float* values = image_.pixels.data();
    const bool alpha = image_.hasAlpha();
    visitSamples(window, [&](uint32_t x, uint32_t y, uint32_t i, double l0, double l1, double l2) {
        const Triangle& t = triangles_[i];
        const float* z[3] = {values + size_t(t.v0) * c, values + size_t(t.v1) * c, values + size_t(t.v2) * c};
        float* pixel = rows + size_t(y - window.y_begin) * row_floats + size_t(x - window.x_begin) * c;
        if (!bubbles_) {
            for (uint32_t k = 0; k < c; ++k) pixel[k] = float(l0 * z[0][k] + l1 * z[1][k] + l2 * z[2][k]);
            return;
        }
        const float* b[3] = {bubbles_->data() + size_t(t.e0) * c, bubbles_->data() + size_t(t.e1) * c,
                             bubbles_->data() + size_t(t.e2) * c};
        for (uint32_t k = 0; k < c; ++k) {
            const double value = l0 * z[0][k] + l1 * z[1][k] + l2 * z[2][k] +
                                 4.0 * (l1 * l2 * b[0][k] + l2 * l0 * b[1][k] + l0 * l1 * b[2][k]);
            pixel[k] = float(std::clamp<double>(value, std::min({z[0][k], z[1][k], z[2][k]}),
                                                std::max({z[0][k], z[1][k], z[2][k]})));
        }
        if (alpha)
            for (uint32_t k = 0; k + 1 < c; ++k) pixel[k] = std::min(pixel[k], pixel[c - 1]);
    });
}

void MeshRenderer::locateSamples(OutputSize out, uint32_t y_begin, uint32_t y_end, SampleHit* hits) const {
    visitSamples(wholeRows(image_.width, image_.height, out, y_begin, y_end),
                 [&](uint32_t x, uint32_t y, uint32_t i, double l0, double l1, double l2) {
                     hits[size_t(y - y_begin) * out.width + x] = {i, {float(l0), float(l1), float(l2)}};
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
