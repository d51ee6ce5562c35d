#include "indexed_mesh.h"

#include <cassert>
#include <utility>

#include "mesh.h"

namespace ddt {

namespace {

// Builds the file's vertex and face arrays: positions and colours in, faces wound
// counter-clockwise whatever order they are given in.
class MeshBuilder {
public:
    // Positions in the frame of `input`'s pixels; `frame` overrides it where the values are
    // not an image of the frame (a point file's, one value per vertex).
    MeshBuilder(const Image& input, OutputSize out, double height, OutputSize frame = {})
        : input_(input), sx_(double(out.width) / (frame.width ? frame.width : input.width)),
          sy_(double(out.height) / (frame.height ? frame.height : input.height)), height_(height) {
        mesh_.channels = input.channels;
        mesh_.colour_type = input.sample_type;
        mesh_.out = out;
    }

    // A vertex at (x, y) of the output, y down, with the colour of input pixel (px, py).
    uint32_t addVertex(double x, double y, uint32_t px, uint32_t py) {
        return addVertex(x, y, input_.row(py) + size_t(px) * input_.channels);
    }
    // A vertex at (x, y) of the output, y down, with the colour `pixel` (premultiplied).
    uint32_t addVertex(double x, double y, const float* pixel) {
        const uint32_t c = input_.channels;
        float straight[4];
        const float alpha = input_.hasAlpha() ? pixel[c - 1] : 1.0f;
        for (uint32_t k = 0; k < c; ++k)
            straight[k] = !input_.hasAlpha() || k + 1 == c ? pixel[k] : alpha > 0.0f ? pixel[k] / alpha : 0.0f;
        mesh_.colours.insert(mesh_.colours.end(), straight, straight + c);
        const double luma = c < 3 ? straight[0] : 0.2126 * straight[0] + 0.7152 * straight[1] + 0.0722 * straight[2];
        mesh_.positions.insert(mesh_.positions.end(), {x, double(mesh_.out.height) - y, height_ * luma});
        return mesh_.vertexCount() - 1;
    }
    // The vertex of pixel (px, py) at `p` (input pixels × kPositionOne).
    uint32_t addPixelVertex(uint32_t px, uint32_t py, Position p) {
        return addVertex(outputX(p), outputY(p), px, py);
    }
    // Where position p lies in the output, y down.
    double outputX(Position p) const { return (double(p.x) / kPositionOne + 0.5) * sx_; }
    double outputY(Position p) const { return (double(p.y) / kPositionOne + 0.5) * sy_; }

    void addFace(uint32_t a, uint32_t b, uint32_t c) {
        const double* p = &mesh_.positions[3 * size_t(a)];
        const double* q = &mesh_.positions[3 * size_t(b)];
        const double* r = &mesh_.positions[3 * size_t(c)];
        const double orient = (q[0] - p[0]) * (r[1] - p[1]) - (q[1] - p[1]) * (r[0] - p[0]);
        assert(orient != 0.0);
        if (orient < 0.0) std::swap(b, c);
        mesh_.faces.insert(mesh_.faces.end(), {a, b, c});
    }

    IndexedMesh take() { return std::move(mesh_); }

private:
    const Image& input_;
    double sx_, sy_, height_;
    IndexedMesh mesh_;
};

}  // namespace

IndexedMesh indexedMeshOf(const std::vector<uint32_t>& triangles, const std::vector<Position>& positions,
                          const Image& input, OutputSize out, double height) {
    const uint32_t w = input.width, h = input.height;
    const double W = out.width, H = out.height;
    MeshBuilder builder(input, out, height);
    auto at = [&](uint32_t v) { return positions.empty() ? gridPosition(v, w) : positions[v]; };
    // The vertices the triangles use, in id order (all of the grid's but for a simplified mesh).
    std::vector<uint32_t> index(size_t(w) * h, kNone);
    for (uint32_t v : triangles) index[v] = 0;
    for (uint32_t v = 0; v < w * h; ++v)
        if (index[v] != kNone) index[v] = builder.addPixelVertex(v % w, v / w, at(v));
    for (size_t t = 0; t + 2 < triangles.size(); t += 3)
        builder.addFace(index[triangles[t]], index[triangles[t + 1]], index[triangles[t + 2]]);

    // The ring: each hull vertex's copy on the rectangle's side, then the four corners. A side
    // with n vertices gets n copies and 2(n − 1) triangles; a corner is on two sides.
    using Point = std::pair<double, double>;
    // Walks one side's used vertices in order; returns its first and last copies.
    auto side = [&](uint32_t n, auto pixel_at, auto copy_at) {
        uint32_t previous_pixel = kNone, previous_copy = kNone, first_copy = kNone;
        for (uint32_t i = 0; i < n; ++i) {
            const uint32_t pixel_id = pixel_at(i);
            if (index[pixel_id] == kNone) continue;
            const auto [cx, cy] = copy_at(at(pixel_id));
            const uint32_t pixel = index[pixel_id], copy = builder.addVertex(cx, cy, pixel_id % w, pixel_id / w);
            if (previous_pixel != kNone) {
                builder.addFace(previous_pixel, pixel, copy);
                builder.addFace(previous_pixel, copy, previous_copy);
            }
            if (first_copy == kNone) first_copy = copy;
            previous_pixel = pixel;
            previous_copy = copy;
        }
        return std::pair<uint32_t, uint32_t>{first_copy, previous_copy};
    };
    const auto top = side(w, [&](uint32_t i) { return i; }, [&](Position p) { return Point{builder.outputX(p), 0.0}; });
    const auto bottom =
        side(w, [&](uint32_t i) { return (h - 1) * w + i; }, [&](Position p) { return Point{builder.outputX(p), H}; });
    const auto left = side(h, [&](uint32_t i) { return i * w; }, [&](Position p) { return Point{0.0, builder.outputY(p)}; });
    const auto right =
        side(h, [&](uint32_t i) { return i * w + w - 1; }, [&](Position p) { return Point{W, builder.outputY(p)}; });
    // Each corner square: the corner pixel, its copies on the two sides, the rectangle's corner.
    auto corner = [&](uint32_t px, uint32_t py, uint32_t horizontal_copy, uint32_t vertical_copy, double cx, double cy) {
        const uint32_t c = builder.addVertex(cx, cy, px, py), pixel = index[py * w + px];
        builder.addFace(pixel, horizontal_copy, c);
        builder.addFace(pixel, c, vertical_copy);
    };
    corner(0, 0, top.first, left.first, 0.0, 0.0);
    corner(w - 1, 0, top.second, right.first, W, 0.0);
    corner(0, h - 1, bottom.first, left.second, 0.0, H);
    corner(w - 1, h - 1, bottom.second, right.second, W, H);
    return builder.take();
}

IndexedMesh indexedSampleMeshOf(const Mesh& mesh, const Image& values, OutputSize frame, OutputSize out, double height) {
    MeshBuilder builder(values, out, height, frame);
    const uint32_t c = values.channels;
    // The vertices the triangles use, in id order: a mask's known pixels, a point file's points.
    std::vector<uint32_t> index(mesh.vertexCount(), kNone);
    forEachTriangle(mesh, [&](const Triangle& t) { index[t.v0] = index[t.v1] = index[t.v2] = 0; });
    for (uint32_t v = 0; v < mesh.vertexCount(); ++v)
        if (index[v] != kNone) {
            const Position p = positionOf(mesh, v);
            index[v] = builder.addVertex(builder.outputX(p), builder.outputY(p), values.pixels.data() + size_t(v) * c);
        }
    forEachTriangle(mesh, [&](const Triangle& t) { builder.addFace(index[t.v0], index[t.v1], index[t.v2]); });
    return builder.take();
}

}  // namespace ddt
