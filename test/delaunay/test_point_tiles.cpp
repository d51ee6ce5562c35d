// A point file's points in tiles (app/delaunay/sampled_tile.h, core/delaunay/known_points.h):
// the grown crop's Delaunay triangulation holds every whole-frame triangle near its rect, and
// tiled outputs equal the untiled ones, gaps across tile borders and on the frame's corners and
// edges included, on both backends.
#include <catch2/catch.hpp>

#include <algorithm>
#include <array>
#include <memory>
#include <random>
#include <set>

#include "backend.h"
#include "delaunay.h"
#include "delaunay/sampled_tile.h"
#include "delaunay/sampled_upscale.h"
#include "known_points.h"
#include "test_support.h"
#include "tiles_check.h"
#include "tiled_upscale.h"

namespace {

using namespace ddt;

struct Points {
    std::vector<Position> places;  // row-major, distinct
    Image values;                  // one pixel a place
};

// `count` points at random places of a w × h frame (1/1024 pixel apart at the finest, off the
// pixel centres), none inside the given discs (x, y, radius), coloured by `image` at the
// nearest pixel; one point on each frame corner keeps the hull the frame's rectangle.
Points scatteredPoints(uint32_t w, uint32_t h, uint32_t seed, int count, const std::vector<std::array<int, 3>>& gaps,
                       const Image& image) {
    std::mt19937 rng(seed);
    std::uniform_int_distribution<int32_t> x(0, int32_t(w - 1) * kPositionOne), y(0, int32_t(h - 1) * kPositionOne);
    auto inGap = [&](const Position& p) {
        for (const auto& [cx, cy, r] : gaps) {
            const double dx = double(p.x) / kPositionOne - cx, dy = double(p.y) / kPositionOne - cy;
            if (dx * dx + dy * dy < double(r) * r) return true;
        }
        return false;
    };
    std::set<std::pair<int32_t, int32_t>> row_major;  // (y, x)
    for (int i = 0; i < count; ++i) {
        const Position p{x(rng), y(rng)};
        if (!inGap(p)) row_major.insert({p.y, p.x});
    }
    Points points;
    for (const auto& [py, px] : row_major) points.places.push_back({px, py});
    const uint32_t c = image.channels;
    points.values.width = uint32_t(points.places.size());
    points.values.height = 1;
    points.values.channels = c;
    for (const Position& p : points.places) {
        const uint32_t px = uint32_t((p.x + kPositionOne / 2) / kPositionOne) % image.width;
        const uint32_t py = uint32_t((p.y + kPositionOne / 2) / kPositionOne) % image.height;
        const float* pixel = image.pixels.data() + (size_t(py) * image.width + px) * c;
        points.values.pixels.insert(points.values.pixels.end(), pixel, pixel + c);
    }
    return points;
}

// The triangles of `mesh`, a mesh of points moved by (dx, dy) units, as sorted triples of places.
using PlacedTriangle = std::array<std::pair<int32_t, int32_t>, 3>;
std::set<PlacedTriangle> trianglesOf(const Mesh& mesh, int32_t dx, int32_t dy) {
    std::set<PlacedTriangle> triangles;
    forEachTriangle(mesh, [&](const Triangle& t) {
        PlacedTriangle placed;
        const uint32_t ids[3] = {t.v0, t.v1, t.v2};
        for (int k = 0; k < 3; ++k) placed[k] = {mesh.positions[ids[k]].x + dx, mesh.positions[ids[k]].y + dy};
        std::sort(placed.begin(), placed.end());
        triangles.insert(placed);
    });
    return triangles;
}

// Whether the triangle meets the rect's pixel centres' rectangle: its bounding box does (a
// superset of the triangles meeting it, all of which the crop must hold).
bool near(const PlacedTriangle& t, const PixelRect& rect) {
    int32_t x0 = t[0].first, x1 = x0, y0 = t[0].second, y1 = y0;
    for (const auto& [x, y] : t) x0 = std::min(x0, x), x1 = std::max(x1, x), y0 = std::min(y0, y), y1 = std::max(y1, y);
    return x1 >= int32_t(rect.x0) * kPositionOne && x0 <= int32_t(rect.x1 - 1) * kPositionOne &&
           y1 >= int32_t(rect.y0) * kPositionOne && y0 <= int32_t(rect.y1 - 1) * kPositionOne;
}

}  // namespace

TEST_CASE("known points: a grown crop's triangulation, with the far samples its check adds, holds every whole-frame triangle near its rect") {
    const uint32_t w = 160, h = 120;
    const Image colours = test::photoPiece();
    // Inside the frame, and on its corners and left edge, where the hull's long thin triangles
    // have circles centred outside the frame (known_samples.h: not covered by the rule).
    const PixelRect inside[] = {{60, 40, 80, 60}, {30, 50, 130, 56}};
    const PixelRect border[] = {{0, 0, 20, 20}, {140, 100, 160, 120}, {0, 60, 12, 90}};
    size_t checked = 0, missing_without_rule = 0, missing_without_check = 0, extras = 0;
    for (uint32_t seed = 1; seed <= 4; ++seed) {
        // 1 point per 8 pixels, gaps across the rects' borders, on corners and on an edge.
        const Points points = scatteredPoints(w, h, seed, int(w * h / 8),
                                              {{70, 40, 12}, {80, 60, 7}, {0, 0, 9}, {159, 119, 6}, {0, 75, 10}}, colours);
        KnownPoints known(w, h, points.places, points.values);
        known.measureHoles();
        const std::set<PlacedTriangle> whole = trianglesOf(delaunayOfPoints(w, h, points.places), 0, 0);
        auto meshOf = [&](const PixelRect& crop, const std::vector<uint32_t>& extra) {
            REQUIRE(known.problemIn(crop).empty());
            const SampleSet samples = known.samplesIn(PackedImage(), crop, extra);
            CHECK(samples.values.width == samples.places.size());
            const PixelRect bounds = known.boundsOf(crop, extra);
            return delaunayOfPoints(bounds.width(), bounds.height(), samples.places);
        };
        auto trianglesIn = [&](const PixelRect& crop, const std::vector<uint32_t>& extra = {}) {
            const PixelRect bounds = known.boundsOf(crop, extra);
            return trianglesOf(meshOf(crop, extra), int32_t(bounds.x0) * kPositionOne, int32_t(bounds.y0) * kPositionOne);
        };
        // The count of whole-frame triangles near `rect` that `got` lacks.
        auto missing = [&](const std::set<PlacedTriangle>& got, const PixelRect& rect) {
            size_t count = 0;
            for (const PlacedTriangle& t : whole) count += near(t, rect) && got.count(t) == 0;
            return count;
        };
        for (const PixelRect& rect : inside) {
            CAPTURE(seed, rect.x0, rect.y0);
            // Inside, the rule alone holds every triangle; grown by 3 pixels alone, some are missed.
            for (const PlacedTriangle& t : whole) checked += near(t, rect);
            CHECK(missing(trianglesIn(known.cropFor(rect, w)), rect) == 0);
            missing_without_rule += missing(trianglesIn(known.cropFor(rect, 3)), rect);
        }
        for (const PixelRect& rect : border) {
            CAPTURE(seed, rect.x0, rect.y0);
            for (const PlacedTriangle& t : whole) checked += near(t, rect);
            const PixelRect crop = known.cropFor(rect, w);
            missing_without_check += missing(trianglesIn(crop), rect);
            // With the samples along the frame's border and those beyond the crop that break its
            // triangles near rect, until none does.
            std::vector<uint32_t> extra = known.samplesAlongBorder(crop);
            CHECK_FALSE(extra.empty());
            for (int round = 0;; ++round) {
                REQUIRE(round < 20);
                const std::vector<uint32_t> more = known.samplesBreaking(meshOf(crop, extra), crop, extra, rect);
                if (more.empty()) break;
                extra.insert(extra.end(), more.begin(), more.end());
                std::sort(extra.begin(), extra.end());
            }
            CHECK(missing(trianglesIn(crop, extra), rect) == 0);
            extras += extra.size();
        }
    }
    CHECK(checked > 1000);
    CHECK(missing_without_rule > 0);
    CHECK(missing_without_check > 0);
    // The bands along the sides (about 1/8 of 2 · 160 · 12 pixels each) and a few more.
    CHECK(extras < 12 * 600);
}

TEST_CASE("known points: a crop holds exactly the points of its pixel centres' rectangle, moved by its corner") {
    // Points at the crop's edges (in), just past them (out) and between pixel centres.
    const std::vector<Position> places = {{0, 0},         {10 * 1024, 0},      {3 * 1024, 2 * 1024 - 1},
                                          {3 * 1024, 2 * 1024}, {5 * 1024 + 512, 3 * 1024}, {8 * 1024, 5 * 1024},
                                          {8 * 1024 + 1, 6 * 1024}, {2 * 1024, 9 * 1024}};
    Image values;
    values.width = uint32_t(places.size());
    values.height = 1;
    values.channels = 1;
    for (size_t i = 0; i < places.size(); ++i) values.pixels.push_back(float(i));
    const KnownPoints known(11, 10, places, values);
    const SampleSet crop = known.samplesIn(PackedImage(), {3, 2, 9, 7});  // centres x 3 … 8, y 2 … 6
    // In: (3, 2), (5.5, 3), (8, 5); out: y just below 2, x just past 8, y 9, the corners.
    REQUIRE(crop.places.size() == 3);
    CHECK(crop.places[0] == Position{0, 0});
    CHECK(crop.places[1] == Position{2 * 1024 + 512, 1024});
    CHECK(crop.places[2] == Position{5 * 1024, 3 * 1024});
    CHECK(crop.values.pixels == std::vector<float>{3.0f, 4.0f, 5.0f});
    CHECK(known.problemIn({3, 2, 9, 7}).empty());
    CHECK(known.problemIn({0, 0, 3, 2}) == "fewer than 3 points");
}

TEST_CASE("point tiles: tiled outputs equal the untiled one, gaps across tile borders included", "[vulkan]") {
    const Image photo = test::photoCrop();  // 300 × 200, the colours
    const uint32_t w = photo.width, h = photo.height;
    // 10 % of the pixels as points; gaps centred on the 64-pixel tiles' borders (cores of
    // 60 × 50: x = 60, 120, 180, 240, y = 50, 100, 150), two wider than the 16-pixel overlap,
    // on the frame's corners and its left and bottom edges (the fill outside the hull).
    const Points points = scatteredPoints(
        w, h, 11, int(w * h / 10),
        {{60, 50, 12}, {120, 100, 20}, {240, 150, 18}, {0, 0, 10}, {299, 0, 6}, {0, 120, 7}, {150, 199, 9}, {299, 199, 5}},
        photo);
    Image header;
    header.width = w;
    header.height = h;
    header.channels = photo.channels;
    test::checkTilesMatchOnePiece(
        PackedImage(header), kPointTileOverlap,
        [&](Backend& backend, OutputSize out, const test::RowSink& sink) {
            upscaleFromSamples(backend, points.values, backend.delaunayPoints(w, h, points.places), out, sink);
        },
        [&] { return std::make_unique<KnownPoints>(w, h, points.places, points.values); });
}
