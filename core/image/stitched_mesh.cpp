#include "stitched_mesh.h"

#include <algorithm>
#include <array>
#include <cassert>

namespace ddt {

void StitchedMesh::add(const Mesh& mesh, const PixelRect& crop, const PixelRect& core) {
    const uint32_t cw = crop.width();
    assert(mesh.positions.empty() || (crop.width() == width_ && crop.height() == height_ && core.width() == width_ &&
                                      core.height() == height_));
    if (!mesh.positions.empty()) positions_ = mesh.positions;
    forEachTriangle(mesh, [&](const Triangle& t) {
        uint32_t ids[3], sum_x = 0, sum_y = 0;
        const uint32_t local[3] = {t.v0, t.v1, t.v2};
        for (int k = 0; k < 3; ++k) {
            const uint32_t x = crop.x0 + local[k] % cw, y = crop.y0 + local[k] / cw;
            ids[k] = y * width_ + x;
            sum_x += x;
            sum_y += y;
        }
        // The centroid (sum / 3) in [x0, x1) × [y0, y1), in integers.
        if (sum_x >= 3 * core.x0 && sum_x < 3 * core.x1 && sum_y >= 3 * core.y0 && sum_y < 3 * core.y1)
            triangles_.insert(triangles_.end(), ids, ids + 3);
    });
}

void StitchedMesh::append(StitchedMesh&& other) {
    triangles_.insert(triangles_.end(), other.triangles_.begin(), other.triangles_.end());
    other.triangles_ = {};
}

std::vector<uint32_t> StitchedMesh::take() {
    std::vector<std::array<uint32_t, 3>> sorted(triangles_.size() / 3);
    for (size_t i = 0; i < sorted.size(); ++i) {
        const uint32_t* t = &triangles_[3 * i];
        const int first = t[0] <= t[1] && t[0] <= t[2] ? 0 : t[1] <= t[2] ? 1 : 2;
        sorted[i] = {t[first], t[(first + 1) % 3], t[(first + 2) % 3]};  // a rotation keeps the orientation
    }
    std::sort(sorted.begin(), sorted.end());
    triangles_.clear();
    triangles_.shrink_to_fit();
    std::vector<uint32_t> result;
    result.reserve(3 * sorted.size());
    for (const auto& t : sorted) result.insert(result.end(), t.begin(), t.end());
    return result;
}

std::string StitchedMesh::check(const std::vector<uint32_t>& triangles, uint32_t width, uint32_t height,
                                const std::vector<Position>& positions) {
    const uint32_t vertices = width * height;
    const size_t count = triangles.size() / 3;
    if (count == 0) return "no triangles";
    if (!positions.empty() && positions.size() != vertices) return "positions for another grid";
    auto where = [&](uint32_t v) {  // appended piece by piece: GCC 12 warns falsely (-Wrestrict) on "(" + ...
        std::string text = "(";
        return text.append(std::to_string(v % width)).append(", ").append(std::to_string(v / width)).append(")");
    };
    // Coordinates in pixels (the grid's, of any size) or in 1/kPositionOne pixels (explicit).
    struct Point {
        int64_t x, y;
    };
    const int64_t unit = positions.empty() ? 1 : kPositionOne;
    auto at = [&](uint32_t v) {
        return positions.empty() ? Point{v % width, v / width} : Point{positions[v].x, positions[v].y};
    };
    __int128 doubled_area = 0;  // in units², exact
    // The directed edges by their start vertex (compressed rows), to find each one's reverse.
    std::vector<uint32_t> first(size_t(vertices) + 1, 0);
    for (size_t i = 0; i < count; ++i) {
        const uint32_t* t = &triangles[3 * i];
        if (t[0] >= vertices || t[1] >= vertices || t[2] >= vertices) return "a vertex outside the grid";
        const Point p = at(t[0]), q = at(t[1]), r = at(t[2]);
        const __int128 orient = __int128(q.x - p.x) * (r.y - p.y) - __int128(q.y - p.y) * (r.x - p.x);
        if (orient <= 0) return "the triangle " + where(t[0]) + " " + where(t[1]) + " " + where(t[2]) + " is not positive";
        doubled_area += orient;
        for (int k = 0; k < 3; ++k) ++first[t[k] + 1];
    }
    if (doubled_area != __int128(2) * (width - 1) * (height - 1) * unit * unit)
        return "the triangles' area is not the grid's";
    for (uint32_t v = 0; v < vertices; ++v) first[v + 1] += first[v];
    std::vector<uint32_t> ends(first.begin(), first.end() - 1), targets(3 * count);
    for (size_t i = 0; i < count; ++i)
        for (int k = 0; k < 3; ++k) targets[ends[triangles[3 * i + k]]++] = triangles[3 * i + (k + 1) % 3];
    auto has = [&](uint32_t from, uint32_t to) {
        return std::find(targets.begin() + first[from], targets.begin() + first[from + 1], to) !=
               targets.begin() + first[from + 1];
    };
    // A segment along one side of the rectangle (longer than a step where simplification
    // removed the border vertices between).
    const int64_t right = (width - 1) * unit, bottom = (height - 1) * unit;
    auto onBorder = [&](uint32_t u, uint32_t v) {
        const Point a = at(u), b = at(v);
        return (a.y == b.y && (a.y == 0 || a.y == bottom)) || (a.x == b.x && (a.x == 0 || a.x == right));
    };
    for (uint32_t u = 0; u < vertices; ++u) {
        std::sort(targets.begin() + first[u], targets.begin() + first[u + 1]);
        if (std::adjacent_find(targets.begin() + first[u], targets.begin() + first[u + 1]) != targets.begin() + first[u + 1])
            return "two triangles share the edge from " + where(u) + " the same way round (an overlap)";
    }
    for (uint32_t u = 0; u < vertices; ++u)
        for (uint32_t j = first[u]; j < first[u + 1]; ++j)
            if (!has(targets[j], u) && !onBorder(u, targets[j]))
                return "the edge " + where(u) + "–" + where(targets[j]) + " has a triangle on one side only (a gap)";
    return "";
}

}  // namespace ddt
