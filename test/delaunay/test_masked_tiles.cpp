// A mask's known pixels in tiles (app/delaunay/sampled_tile.h): the grown crop's Delaunay
// triangulation holds every whole-image triangle near its tile (core/delaunay/known_pixels.h),
// and tiled outputs equal the untiled ones, holes across tile borders and on the image's
// border included (a border mostly unknown among them: long, thin hull triangles along it),
// on both backends.
#include <catch2/catch.hpp>

#include <algorithm>
#include <array>
#include <cmath>
#include <functional>
#include <memory>
#include <random>
#include <set>

#include "backend.h"
#include "delaunay.h"
#include "delaunay/sampled_upscale.h"
#include "known_pixels.h"
#include "test_support.h"
#include "tiles_check.h"
#include "tiled_upscale.h"

namespace {

using namespace ddt;

// Black discs and scratches on white: `holes` discs of radius 1 to `largest` at random, one
// disc on each given place, and a thin diagonal scratch across the whole image.
KnownPixels holedMask(uint32_t w, uint32_t h, uint32_t seed, int holes, int largest,
                      const std::vector<std::array<int, 3>>& placed) {
    std::vector<uint8_t> known(size_t(w) * h, 1);
    auto disc = [&](int cx, int cy, int r) {
        for (int y = std::max(0, cy - r); y <= std::min(int(h) - 1, cy + r); ++y)
            for (int x = std::max(0, cx - r); x <= std::min(int(w) - 1, cx + r); ++x)
                if ((x - cx) * (x - cx) + (y - cy) * (y - cy) <= r * r) known[size_t(y) * w + x] = 0;
    };
    std::mt19937 rng(seed);
    std::uniform_int_distribution<int> x(0, int(w) - 1), y(0, int(h) - 1), r(1, largest);
    for (int i = 0; i < holes; ++i) disc(x(rng), y(rng), r(rng));
    for (const auto& [cx, cy, radius] : placed) disc(cx, cy, radius);
    for (uint32_t t = 0; t < std::min(w, h); ++t) known[size_t(t) * w + (t * 3 / 2) % w] = 0;  // the scratch
    return KnownPixels(w, h, std::move(known));
}

// The mask whose known pixels are those where `known(x, y)`.
KnownPixels maskOf(uint32_t w, uint32_t h, const std::function<bool(uint32_t, uint32_t)>& known) {
    std::vector<uint8_t> bytes(size_t(w) * h);
    for (uint32_t y = 0; y < h; ++y)
        for (uint32_t x = 0; x < w; ++x) bytes[size_t(y) * w + x] = known(x, y);
    return KnownPixels(w, h, std::move(bytes));
}

// Borders mostly unknown (known_samples.h: circles centred outside the frame, which the rule
// cannot follow), on a w × h frame: the (the left column known at y = 0, h / 2 and
// h − 1 only, the top row at its two ends only), its mirror (the right column, the bottom
// row), and a run on each side, each run taking a corner, the top one two rows deep in part.
std::vector<std::pair<std::string, KnownPixels>> unknownBorders(uint32_t w, uint32_t h) {
    auto few = [&](uint32_t y) { return y == 0 || y == h / 2 || y == h - 1; };
    return {{"left column and top row",
             maskOf(w, h, [&](uint32_t x, uint32_t y) { return x == 0 ? few(y) : y != 0 || x == w - 1; })},
            {"right column and bottom row",
             maskOf(w, h, [&](uint32_t x, uint32_t y) { return x == w - 1 ? few(y) : y != h - 1 || x == 0; })},
            {"a run on each side", maskOf(w, h, [&](uint32_t x, uint32_t y) {
                 const bool top = y == 0 && x < w * 2 / 3, deeper = y == 1 && x >= w / 3 && x < w / 2;
                 const bool left = x == 0 && y < h * 3 / 4, right = x == w - 1 && y >= h / 7;
                 const bool bottom = y == h - 1 && x >= w / 6;
                 return !(top || deeper || left || right || bottom);
             })}};
}

// The triangles of `mesh` as sorted triples of whole-image pixel ids, the mesh being of the
// crop at (x0, y0) of a `width`-wide image; with `only`, those with a vertex in it; with
// `boxed`, those whose bounding box meets it.
std::set<std::array<uint32_t, 3>> trianglesOf(const Mesh& mesh, uint32_t x0, uint32_t y0, uint32_t width,
                                              const PixelRect* only = nullptr, const PixelRect* boxed = nullptr) {
    std::set<std::array<uint32_t, 3>> triangles;
    forEachTriangle(mesh, [&](const Triangle& t) {
        std::array<uint32_t, 3> ids{};
        bool touches = only == nullptr;
        PixelRect box{UINT32_MAX, UINT32_MAX, 0, 0};
        for (int k = 0; k < 3; ++k) {
            const uint32_t v = k == 0 ? t.v0 : k == 1 ? t.v1 : t.v2;
            const uint32_t x = v % mesh.width + x0, y = v / mesh.width + y0;
            ids[k] = y * width + x;
            if (only && x >= only->x0 && x < only->x1 && y >= only->y0 && y < only->y1) touches = true;
            box = {std::min(box.x0, x), std::min(box.y0, y), std::max(box.x1, x + 1), std::max(box.y1, y + 1)};
        }
        if (boxed && (box.x1 <= boxed->x0 || box.x0 >= boxed->x1 || box.y1 <= boxed->y0 || box.y0 >= boxed->y1)) return;
        std::sort(ids.begin(), ids.end());
        if (touches) triangles.insert(ids);
    });
    return triangles;
}

}  // namespace

TEST_CASE("known pixels: a grown crop's triangulation holds every whole-image triangle touching its rect") {
    const uint32_t w = 120, h = 90;
    const PixelRect rects[] = {{40, 30, 60, 50}, {0, 0, 20, 20}, {100, 70, 120, 90}, {10, 40, 110, 45}};
    size_t missing_when_not_grown = 0;
    for (uint32_t seed = 1; seed <= 4; ++seed) {
        KnownPixels known = holedMask(w, h, seed, 12, 9, {{50, 40, 8}});
        known.measureHoles();
        const Mesh whole = delaunayOfPixels(w, h, known.idsIn({0, 0, w, h}));
        for (const PixelRect& rect : rects) {
            CAPTURE(seed, rect.x0, rect.y0);
            const PixelRect crop = known.cropFor(rect, w);
            const std::set<std::array<uint32_t, 3>> wanted = trianglesOf(whole, 0, 0, w, &rect);
            auto croppedTriangles = [&](const PixelRect& c) {
                REQUIRE(known.problemIn(c).empty());
                return trianglesOf(delaunayOfPixels(c.width(), c.height(), known.idsIn(c)), c.x0, c.y0, w);
            };
            const std::set<std::array<uint32_t, 3>> got = croppedTriangles(crop);
            CHECK(std::includes(got.begin(), got.end(), wanted.begin(), wanted.end()));
            // The rule is needed: the rect grown by the tiles' usual 3 pixels alone misses some.
            const std::set<std::array<uint32_t, 3>> near = croppedTriangles(known.cropFor(rect, 3));
            for (const auto& t : wanted) missing_when_not_grown += near.count(t) == 0;
        }
    }
    CHECK(missing_when_not_grown > 0);
}

TEST_CASE("known pixels: the crop grows to hold a hole next to its rect, and no further without holes") {
    std::vector<uint8_t> bytes(100 * 100, 1);
    KnownPixels full(100, 100, bytes);
    full.measureHoles();
    const PixelRect rect{40, 40, 60, 60};
    const PixelRect plain = full.cropFor(rect, 100);
    // No hole: the distance is 0 everywhere, so 2 · (0 + 1) + 1 = 3 pixels a side.
    CHECK((plain.x0 == 37 && plain.y0 == 37 && plain.x1 == 63 && plain.y1 == 63));
    for (uint32_t y = 45; y < 55; ++y)
        for (uint32_t x = 60; x < 80; ++x) bytes[y * 100 + x] = 0;  // 20 × 10 beside the rect's right side
    KnownPixels holed(100, 100, bytes);
    holed.measureHoles();
    const PixelRect grown = holed.cropFor(rect, 100);
    // Its circles are at most about 10 wide (the hole's height): 2 · 5 + 3 pixels, not the
    // hole's whole length, whatever is further right.
    CHECK(grown.x1 == 60 + 13);
    CHECK((grown.x0 == 27 && grown.y0 == 27 && grown.y1 == 73));  // the same growth on every side
    CHECK(holed.cropFor(rect, 4).x1 == 64);  // the growth is capped
}

TEST_CASE("known pixels: a crop whose known pixels cannot be triangulated is the whole image") {
    // Known: the top row, and one pixel at the far corner; a capped crop near the top holds
    // only collinear pixels.
    std::vector<uint8_t> bytes(100 * 100, 0);
    std::fill_n(bytes.begin(), 100, uint8_t(1));
    bytes.back() = 1;
    KnownPixels known(100, 100, bytes);
    known.measureHoles();
    const PixelRect crop = known.cropFor({40, 0, 60, 20}, 4);
    CHECK((crop.x0 == 0 && crop.y0 == 0 && crop.x1 == 100 && crop.y1 == 100));
    CHECK(known.problemIn({36, 0, 64, 24}) == "all points are collinear");
}

TEST_CASE("masked tiles: tiled outputs equal the untiled one, holes across tile borders included", "[vulkan]") {
    const Image image = test::photoCrop();  // 300 × 200
    const uint32_t w = image.width, h = image.height;
    // Holes centred on the 64-pixel tiles' borders (cores of 60 × 50: x = 60, 120, 180, 240,
    // y = 50, 100, 150), on the image's corners and its left edge (the fill outside the hull),
    // two wider than the 16-pixel overlap.
    const KnownPixels mask = holedMask(w, h, 7, 40, 6,
                                       {{60, 50, 12}, {120, 100, 20}, {240, 150, 9}, {0, 0, 10}, {0, 120, 7}, {299, 199, 5}});
    test::checkTilesMatchOnePiece(
        PackedImage(image), kDefaultOverlap,
        [&](Backend& backend, OutputSize out, const test::RowSink& sink) {
            upscaleFromSamples(backend, image, backend.delaunayPixels(w, h, mask.idsIn({0, 0, w, h})), out, sink);
        },
        [&] { return std::make_unique<KnownPixels>(mask); });
}

TEST_CASE("known pixels: a border crop, with the far pixels its check adds, holds every whole-image triangle near its rect") {
    const uint32_t w = 120, h = 90;
    // On each side and corner, and one inside.
    const PixelRect rects[] = {{0, 0, 20, 20},     {50, 0, 70, 15},   {100, 70, 120, 90}, {0, 35, 12, 55},
                               {108, 30, 120, 50}, {40, 80, 60, 90},  {100, 0, 120, 20},  {0, 70, 20, 90},
                               {50, 35, 70, 55}};
    size_t checked = 0, missing_without_check = 0;
    for (const auto& [name, known] : unknownBorders(w, h)) {
        KnownPixels measured = known;
        measured.measureHoles();
        const Mesh whole = delaunayOfPixels(w, h, measured.idsIn({0, 0, w, h}));
        for (const PixelRect& rect : rects) {
            CAPTURE(name, rect.x0, rect.y0);
            const PixelRect crop = measured.cropFor(rect, w);
            auto meshOf = [&](const std::vector<uint32_t>& extra) {
                const SampleSet samples = measured.samplesIn(PackedImage(), crop, extra);
                const PixelRect bounds = measured.boundsOf(crop, extra);
                return delaunayOfPixels(bounds.width(), bounds.height(), samples.pixel_ids);
            };
            // The whole-image triangles whose bounding boxes meet `rect` (a superset of those
            // meeting it, which the check covers) that the crop's mesh lacks.
            auto missing = [&](const std::vector<uint32_t>& extra) {
                const PixelRect bounds = measured.boundsOf(crop, extra);
                const auto got = trianglesOf(meshOf(extra), bounds.x0, bounds.y0, w);
                size_t count = 0;
                for (const auto& t : trianglesOf(whole, 0, 0, w, nullptr, &rect)) count += got.count(t) == 0;
                return count;
            };
            checked += trianglesOf(whole, 0, 0, w, nullptr, &rect).size();
            missing_without_check += missing({});
            std::vector<uint32_t> extra = measured.samplesAlongBorder(crop);
            CHECK(extra.empty());  // a mask has no band: known_pixels.h
            for (int round = 0;; ++round) {
                REQUIRE(round < 20);
                const std::vector<uint32_t> more = measured.samplesBreaking(meshOf(extra), crop, extra, rect);
                if (more.empty()) break;
                extra.insert(extra.end(), more.begin(), more.end());
                std::sort(extra.begin(), extra.end());
            }
            CHECK(missing(extra) == 0);
        }
    }
    CHECK(checked > 1000);
    CHECK(missing_without_check > 0);
}

TEST_CASE("known pixels: a crop of a mask whose border is known needs no far pixels") {
    // Holes inside, some across the rects: the rule alone holds the triangles, so the tiles of
    // an ordinary photograph's mask keep their crops (no whole-width crops along the border).
    const uint32_t w = 120, h = 90;
    const KnownPixels holed = holedMask(w, h, 3, 12, 9, {{50, 40, 8}, {10, 10, 6}});
    KnownPixels known = maskOf(w, h, [&](uint32_t x, uint32_t y) {
        return holed.known(x, y) || x == 0 || y == 0 || x == w - 1 || y == h - 1;
    });
    known.measureHoles();
    for (const PixelRect& rect : {PixelRect{0, 0, 20, 20}, PixelRect{40, 30, 60, 50}, PixelRect{100, 70, 120, 90}}) {
        CAPTURE(rect.x0, rect.y0);
        const PixelRect crop = known.cropFor(rect, w);
        const Mesh mesh = delaunayOfPixels(crop.width(), crop.height(), known.idsIn(crop));
        CHECK(known.samplesBreaking(mesh, crop, {}, rect).empty());
    }
}

TEST_CASE("masked tiles: tiled outputs equal the untiled one with a border mostly unknown", "[vulkan]") {
    const Image image = test::photoCrop();  // 300 × 200
    const uint32_t w = image.width, h = image.height;
    for (const auto& [name, mask] : unknownBorders(w, h)) {
        INFO(name);
        test::checkTilesMatchOnePiece(
            PackedImage(image), kDefaultOverlap,
            [&, &mask = mask](Backend& backend, OutputSize out, const test::RowSink& sink) {
                upscaleFromSamples(backend, image, backend.delaunayPixels(w, h, mask.idsIn({0, 0, w, h})), out, sink);
            },
            [&mask = mask] { return std::make_unique<KnownPixels>(mask); });
    }
}
