#include "point_mesh.h"

#include <algorithm>
#include <cmath>
#include <numeric>
#include <sstream>

#include "delaunay.h"
#include "user_error.h"

namespace ddt {

namespace {

// A coordinate in pixels, formatted as the user wrote it as near as %g shows it.
std::string number(double value) {
    std::ostringstream text;
    text << value;
    return text.str();
}

uint32_t frameSide(double largest) {
    const double side = std::ceil(largest) + 1.0;
    return side >= double(UINT32_MAX) ? UINT32_MAX : std::max(2u, uint32_t(side));
}

// Points on pixel centres covering at least 1/kDenseFactor of the frame's pixels take the
// image's mesh (implicit positions) and a frame-sized values image: at that density the image
// costs at most kDenseFactor times the points' values.
constexpr uint64_t kDenseFactor = 16;

// Nearest 1/kPositionOne pixel; the caller has checked that the coordinate lies in the frame.
int32_t fixedPoint(double pixels) { return int32_t(std::lround(pixels * kPositionOne)); }

}  // namespace

Frame frameOfPoints(const PointSamples& points) {
    const double largest_x = points.x.empty() ? 0.0 : *std::max_element(points.x.begin(), points.x.end());
    const double largest_y = points.y.empty() ? 0.0 : *std::max_element(points.y.begin(), points.y.end());
    return {frameSide(largest_x), frameSide(largest_y)};
}

SampleSet mergePoints(const PointSamples& points, Frame frame) {
    const size_t n = points.size();
    const uint32_t c = points.channels;
    std::vector<Position> places(n);
    for (size_t i = 0; i < n; ++i) {
        if (points.x[i] > double(frame.width - 1) || points.y[i] > double(frame.height - 1))
            throw UserError("point " + std::to_string(i + 1) + " at (" + number(points.x[i]) + ", " +
                            number(points.y[i]) + ") lies outside the " + std::to_string(frame.width) + "×" +
                            std::to_string(frame.height) + " frame (pixel centres 0 to " +
                            std::to_string(frame.width - 1) + ", 0 to " + std::to_string(frame.height - 1) + ")");
        places[i] = {fixedPoint(points.x[i]), fixedPoint(points.y[i])};
    }
    // Row-major order, which delaunayOfPoints takes; file order among equal places.
    std::vector<uint32_t> order(n);
    std::iota(order.begin(), order.end(), 0u);
    std::stable_sort(order.begin(), order.end(), [&](uint32_t p, uint32_t q) {
        return places[p].y != places[q].y ? places[p].y < places[q].y : places[p].x < places[q].x;
    });
    auto valuesOf = [&](uint32_t i) { return points.values.data() + size_t(i) * c; };
    std::vector<uint32_t> kept;  // the first of each place, in row-major order
    kept.reserve(n);
    for (uint32_t i : order) {
        if (!kept.empty() && places[kept.back()].x == places[i].x && places[kept.back()].y == places[i].y) {
            const uint32_t first = kept.back();
            if (!std::equal(valuesOf(first), valuesOf(first) + c, valuesOf(i)))
                throw UserError("points " + std::to_string(first + 1) + " and " + std::to_string(i + 1) +
                                " lie at the same place (" + number(points.x[i]) + ", " + number(points.y[i]) +
                                ", to 1/" + std::to_string(kPositionOne) + " pixel) with different values");
            continue;
        }
        kept.push_back(i);
    }
    std::vector<Position> distinct(kept.size());
    for (size_t k = 0; k < kept.size(); ++k) distinct[k] = places[kept[k]];
    if (std::string problem = delaunayInputProblem(distinct); !problem.empty())
        throw UserError("the points cannot be triangulated (" + problem + ")");

    SampleSet result;
    Image& values = result.values;
    values.channels = c;
    values.sample_type = points.sample_type;
    const bool alpha = c == 2 || c == 4;
    // Vertex v's value at `pixel`: colour premultiplied, as images hold it (core/image.h).
    auto store = [&](uint32_t i, float* pixel) {
        std::copy_n(valuesOf(i), c, pixel);
        if (alpha)
            for (uint32_t k = 0; k + 1 < c; ++k) pixel[k] *= pixel[c - 1];
    };
    const uint64_t frame_pixels = uint64_t(frame.width) * frame.height;
    const bool on_centres = std::all_of(distinct.begin(), distinct.end(), [](Position p) {
        return p.x % kPositionOne == 0 && p.y % kPositionOne == 0;
    });
    if (on_centres && frame_pixels <= kDenseFactor * distinct.size()) {
        // Every point on a pixel centre, and at least 1/kDenseFactor of them: the pixels' own
        // mesh (implicit positions, the image's vertex ids), as --mask builds it. The renderer
        // then samples exactly as for an image, so a full grid of points renders as the image.
        std::vector<uint32_t>& ids = result.pixel_ids;
        ids.resize(kept.size());
        values.width = frame.width;
        values.height = frame.height;
        values.pixels.assign(frame_pixels * c, 0.0f);
        for (size_t k = 0; k < kept.size(); ++k) {
            ids[k] = uint32_t(distinct[k].y / kPositionOne) * frame.width + uint32_t(distinct[k].x / kPositionOne);
            store(kept[k], values.pixels.data() + size_t(ids[k]) * c);
        }
        return result;
    }
    result.places = std::move(distinct);
    values.width = uint32_t(kept.size());
    values.height = 1;
    values.pixels.resize(kept.size() * c);
    for (size_t k = 0; k < kept.size(); ++k) store(kept[k], values.pixels.data() + k * c);
    return result;
}

Mesh triangulateMerged(const SampleSet& merged, Frame frame, Backend& backend) {
    return merged.places.empty() ? backend.delaunayPixels(frame.width, frame.height, merged.pixel_ids)
                                 : backend.delaunayPoints(frame.width, frame.height, merged.places);
}

SampledPoints triangulatePoints(const PointSamples& points, Frame frame) {
    SampleSet merged = mergePoints(points, frame);
    Mesh mesh = merged.places.empty() ? delaunayOfPixels(frame.width, frame.height, merged.pixel_ids)
                                      : delaunayOfPoints(frame.width, frame.height, merged.places);
    return {std::move(mesh), std::move(merged.values)};
}

}  // namespace ddt
