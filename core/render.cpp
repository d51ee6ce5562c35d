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

MeshRenderer::MeshRenderer(const Mesh& mesh, const Image& image, OutputSize out) : image_(image), out_(out) {
    assert(image.width == mesh.width && image.height == mesh.height);
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

void MeshRenderer::renderRows(uint32_t y_begin, uint32_t y_end, float* rows) const {
    const uint32_t w = image_.width, h = image_.height, c = image_.channels;
    const uint32_t out_w = out_.width, out_h = out_.height;
    // Input rows the band's samples fall in, widened by the tallest triangle.
    const uint32_t v_first = uint32_t(sampleCoord(y_begin, h, out_h) / vertexCoord(1, out_h));
    const uint32_t v_last = uint32_t((sampleCoord(y_end - 1, h, out_h) + vertexCoord(1, out_h) - 1) / vertexCoord(1, out_h));
    const uint32_t top_first = v_first > tallest_ ? v_first - tallest_ : 0;
    const uint32_t top_last = std::min(v_last, h - 1);

    for (uint32_t i = first_in_row_[top_first]; i < first_in_row_[top_last + 1]; ++i) {
        const Triangle& t = triangles_[i];
        const Bounds b = boundsOf(t, w);
        const uint32_t x_lo = firstSampleAtOrAfter(b.x0, w, out_w);
        const uint32_t x_hi = std::min(lastSampleAtOrBefore(b.x1, w, out_w), out_w - 1);
        const uint32_t y_lo = std::max(firstSampleAtOrAfter(b.y0, h, out_h), y_begin);
        const uint32_t y_hi = std::min(lastSampleAtOrBefore(b.y1, h, out_h), y_end - 1);
        if (x_lo > x_hi || y_lo > y_hi) continue;

        const int64_t px[3] = {vertexCoord(t.v0 % w, out_w), vertexCoord(t.v1 % w, out_w), vertexCoord(t.v2 % w, out_w)};
        const int64_t py[3] = {vertexCoord(t.v0 / w, out_h), vertexCoord(t.v1 / w, out_h), vertexCoord(t.v2 / w, out_h)};
        const float* z[3] = {image_.pixels.data() + size_t(t.v0) * c, image_.pixels.data() + size_t(t.v1) * c,
                             image_.pixels.data() + size_t(t.v2) * c};
        for (uint32_t y = y_lo; y <= y_hi; ++y) {
            const int64_t sv = sampleCoord(y, h, out_h);
            const int dir_v = sampleDirection(sv, h, out_h);
            float* out_row = rows + size_t(y - y_begin) * out_w * c;
            for (uint32_t x = x_lo; x <= x_hi; ++x) {
                const int64_t su = sampleCoord(x, w, out_w);
                const int dir_u = sampleDirection(su, w, out_w);
                bool inside = true;
                int64_t weight[3];  // edge function opposite each vertex = its barycentric weight × 2·area
                for (int k = 0; k < 3 && inside; ++k) {
                    int p = (k + 1) % 3, q = (k + 2) % 3;
                    inside = sampleSide(px[p], py[p], px[q], py[q], su, sv, dir_u, dir_v) > 0;
                    weight[k] = (px[q] - px[p]) * (sv - py[p]) - (py[q] - py[p]) * (su - px[p]);
                }
                if (!inside) continue;
                const double total = double(weight[0]) + double(weight[1]) + double(weight[2]);
                const double l0 = double(weight[0]) / total, l1 = double(weight[1]) / total,
                             l2 = double(weight[2]) / total;
                float* pixel = out_row + size_t(x) * c;
                for (uint32_t k = 0; k < c; ++k) pixel[k] = float(l0 * z[0][k] + l1 * z[1][k] + l2 * z[2][k]);
            }
        }
    }
}

Image renderImage(const Mesh& mesh, const Image& image, OutputSize out) {
    Image result;
    result.width = out.width;
    result.height = out.height;
    result.channels = image.channels;
    result.sample_type = image.sample_type;
    result.metadata = image.metadata;
    result.pixels.resize(size_t(out.width) * out.height * image.channels);
    MeshRenderer(mesh, image, out).renderRows(0, out.height, result.pixels.data());
    return result;
}

}  // namespace ddt
