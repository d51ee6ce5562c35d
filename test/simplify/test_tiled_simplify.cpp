// A simplification in tiles (app/simplified_upscale.h): the tiles own every output pixel once,
// their meshes join without cracks, the shared lines keep the picture's pixels, and the
// vertex fraction holds overall.
#include <catch2/catch.hpp>

#include <cmath>
#include <limits>

#include "metrics.h"
#include "raster.h"
#include "render.h"
#include "simplified_upscale.h"
#include "test_support.h"
#include "user_error.h"
#include "vulkan_backend.h"

using namespace ddt;
using namespace ddt::test;

namespace {

// The untiled output rows that `upscaleSimplified` hands over, assembled.
std::vector<float> assembled(Backend& backend, const Image& image, OutputSize out, double fraction,
                             const TileOptions& options, SimplifiedUpscale& result) {
    const size_t row_floats = size_t(out.width) * image.channels;
    std::vector<float> whole(row_floats * out.height, std::numeric_limits<float>::quiet_NaN());
    uint32_t next_row = 0;
    result = upscaleSimplified(backend, image, out, fraction, 0.0, options, [&](OutputRows&& rows) {
        CHECK(rows.y_begin == next_row);  // in order, each row once
        next_row = rows.y_end;
        std::copy_n(rows.floats.get(), rows.rows() * row_floats, whole.begin() + rows.y_begin * row_floats);
    });
    CHECK(next_row == out.height);
    return whole;
}

Image imageOf(const std::vector<float>& pixels, OutputSize out, const Image& like) {
    return makeImage(out.width, out.height, like.channels, pixels);
}

}  // namespace

TEST_CASE("tiled simplify: output pixels go to the tile whose mesh holds their snapped sample") {
    // Brute force: the first output index whose sample, snapped as the renderer snaps it on a
    // mesh with explicit positions, lies at or after c.
    bool snapping_matters = false;
    for (auto [in, out] : {std::pair{300u, 600u}, std::pair{300u, 713u}, std::pair{97u, 1000u}, std::pair{300u, 2999u}, std::pair{64u, 64u}}) {
        for (uint32_t c = 1; c < in; ++c) {
            uint32_t first = 0;
            while (first < out && snappedSample(sampleCoord(first, in, out), out) < int64_t(c) * kPositionOne) ++first;
            INFO(in << " → " << out << ", c = " << c);
            REQUIRE(firstSnappedOutputOf(c, in, out) == first);
            snapping_matters = snapping_matters || first != firstOutputOf(c, in, out);
        }
        CHECK(firstSnappedOutputOf(0, in, out) == 0);
        CHECK(firstSnappedOutputOf(in, in, out) == out);
    }
    // At some scale a sample just before a line snaps onto it: owning by exact samples would
    // leave it to a tile whose mesh it falls off.
    CHECK(snapping_matters);
}

namespace {

// Simplifies `photo` in tiles of `side` pixels on `backend`, tile by tile, each rendered by
// itself into a NaN-filled output (a pixel no tile renders stays NaN), and through
// upscaleSimplified; checks that they join and agree, and with `quality`, that the tiles
// score about as the whole does.
void checkTilesJoin(Backend& backend, const Image& photo, uint32_t side, const std::vector<OutputSize>& outputs,
                    bool quality) {
    const uint32_t w = photo.width, h = photo.height;
    const double fraction = 0.1;
    for (OutputSize out : outputs) {
        INFO("output " << out.width << "×" << out.height);
        // Each tile rendered by itself into a NaN-filled output: a pixel no tile renders stays NaN.
        const size_t row_floats = size_t(out.width) * photo.channels;
        std::vector<float> tiles_output(row_floats * out.height, std::numeric_limits<float>::quiet_NaN());
        std::vector<uint8_t> owners(size_t(out.width) * out.height, 0);
        uint64_t expected_vertices = 0, kept_vertices = 0;
        std::vector<uint32_t> lines_x, lines_y;  // the cores' first columns and rows inside the picture
        for (uint32_t y0 = 0; y0 < h; y0 = stripEnd(h, y0, side)) {
            for (SimplifiedTile& tile : planSimplifiedStrip(w, h, out, y0, stripEnd(h, y0, side), side)) {
                OptimizeStats optimized;
                const ParallelSimplifyStats stats = simplifyTile(backend, photo, tile, fraction, 0.0, optimized);
                CHECK(checkMesh(tile.mesh) == "");
                expected_vertices += uint64_t(std::ceil(fraction * tile.core.width() * tile.core.height()));
                kept_vertices += stats.vertices_after;
                if (tile.core.x0 > 0 && y0 == 0) lines_x.push_back(tile.core.x0);
                if (tile.core.y0 > 0 && tile.core.x0 == 0) lines_y.push_back(tile.core.y0);
                const MeshRenderer renderer(tile.mesh, tile.values);
                const RenderWindow window{w, h, out, tile.crop.x0, tile.crop.y0, tile.output.x0, tile.output.x1,
                                          tile.output.y0, tile.output.y1};
                renderer.renderWindow(window, tiles_output.data() + tile.output.y0 * row_floats + tile.output.x0 * photo.channels,
                                      row_floats);
                for (uint32_t y = tile.output.y0; y < tile.output.y1; ++y)
                    for (uint32_t x = tile.output.x0; x < tile.output.x1; ++x) ++owners[size_t(y) * out.width + x];
            }
        }
        CHECK(std::all_of(owners.begin(), owners.end(), [](uint8_t n) { return n == 1; }));
        CHECK(std::none_of(tiles_output.begin(), tiles_output.end(), [](float v) { return std::isnan(v); }));
        // Each tile keeps its core's share: the fraction holds overall.
        CHECK(kept_vertices == expected_vertices);
        CHECK(!lines_x.empty());
        CHECK(!lines_y.empty());

        // upscaleSimplified with --tile renders the same meshes, band by band.
        TileOptions options;
        options.tile = side;
        SimplifiedUpscale tiled;
        const std::vector<float> through_app = assembled(backend, photo, out, fraction, options, tiled);
        CHECK(samePixels(through_app, tiles_output));
        CHECK(tiled.simplify.vertices_before == w * h);
        CHECK(tiled.simplify.vertices_after == kept_vertices);

        if (out.width == w) {
            // At the input's size each pixel centre is a sample: on the shared lines the vertices
            // kept their pixels, so the output there is the picture itself.
            for (uint32_t y = 0; y < h; ++y)
                for (uint32_t x : lines_x)
                    for (uint32_t k = 0; k < photo.channels; ++k)
                        REQUIRE(through_app[size_t(y) * row_floats + x * photo.channels + k] ==
                                photo.pixels[(size_t(y) * w + x) * photo.channels + k]);
            for (uint32_t y : lines_y)
                for (uint32_t x = 0; x < w; ++x)
                    for (uint32_t k = 0; k < photo.channels; ++k)
                        REQUIRE(through_app[size_t(y) * row_floats + x * photo.channels + k] ==
                                photo.pixels[(size_t(y) * w + x) * photo.channels + k]);
            if (!quality) continue;
            // And the whole scores about as the untiled simplification does against the picture.
            SimplifiedUpscale whole;
            const std::vector<float> untiled = assembled(backend, photo, out, fraction, {}, whole);
            const double psnr_tiled = peakSignalToNoiseRatio(toBytes(photo), toBytes(imageOf(through_app, out, photo)));
            const double psnr_whole = peakSignalToNoiseRatio(toBytes(photo), toBytes(imageOf(untiled, out, photo)));
            INFO("PSNR against the picture: tiled " << psnr_tiled << " dB, whole " << psnr_whole << " dB");
            // 64-pixel tiles spend about a third of a 10 % share on their shared lines (2/64 of
            // the pixels), which the whole mesh spends on texture: measured 35.5 dB against
            // 38.5. A seam that does not join (a crack, a step in colour) costs far more.
            CHECK(psnr_tiled > psnr_whole - 4.0);
        }
    }
}

}  // namespace

TEST_CASE("tiled simplify: the tiles' meshes join without cracks, as upscaleSimplified renders them") {
    const Image photo = photoCrop();
    std::unique_ptr<Backend> backend = makeCpuBackend();
    checkTilesJoin(*backend, photo, 64,
                   {OutputSize{photo.width, photo.height}, scaledOutputSize(photo.width, photo.height, 2.0), OutputSize{713, 471}}, true);
}

TEST_CASE("tiled simplify: on a Vulkan device, one tile at a time", "[vulkan]") {
    const Image photo = photoPiece();
    VulkanOptions options;
    options.validation = true;
    VulkanBackend vulkan(options);
    checkTilesJoin(vulkan, photo, 64, {OutputSize{photo.width, photo.height}, OutputSize{237, 165}}, false);
    CHECK(vulkan.validationMessages() == 0);
}

TEST_CASE("tiled simplify: --mesh is refused with tiles, before any output") {
    const Image photo = photoPiece();
    std::unique_ptr<Backend> backend = makeCpuBackend();
    StitchedMesh mesh(photo.width, photo.height);
    TileOptions options;
    options.tile = 64;
    options.mesh = &mesh;
    bool rows = false;
    CHECK_THROWS_AS(upscaleSimplified(*backend, photo, {photo.width, photo.height}, 0.1, 0.0, options,
                                      [&](OutputRows&&) { rows = true; }),
                    UserError);
    CHECK(!rows);
}
