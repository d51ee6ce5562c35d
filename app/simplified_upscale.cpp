#include "simplified_upscale.h"

#include <algorithm>
#include <cmath>
#include <mutex>
#include <optional>
#include <vector>

#include "backend_pool.h"
#include "edge_collapse.h"
#include "memory_size.h"
#include "raster.h"
#include "tiling.h"
#include "user_error.h"

namespace ddt {

namespace {

using Sink = std::function<void(OutputRows&& rows)>;

// Output rows go out in bands of at most this many floats (8 MiB), as tiles' do.
const size_t kBandFloats = size_t(2) << 20;

// Bytes one tile of side `side` holds while it is optimized and simplified (its crop is a
// pixel wider and taller).
uint64_t tileBytes(const Backend& backend, uint32_t side, uint32_t channels) {
    const uint64_t optimizing = backend.memoryNeeded(side + 1, side + 1, channels, false);
    if (optimizing == UINT64_MAX) return UINT64_MAX;
    return optimizing + backend.simplifyMemoryNeeded(side + 1, side + 1, channels);
}

// The whole image: optimized, simplified and rendered in one piece.
SimplifiedUpscale simplifyWhole(Backend& backend, const Image& image, OutputSize out, uint32_t target, double max_error,
                                const TileOptions& options, const Sink& sink, const TileStepCallback& on_step) {
    SimplifiedUpscale result;
    if (on_step) on_step({0, 1, TilePhase::Optimize});
    backend.prepare(image);
    result.optimize = backend.optimize();
    Mesh mesh = backend.takeMesh();
    result.values = image;
    result.simplify = backend.simplify(mesh, result.values, target, max_error);
    if (options.mesh) options.mesh->add(mesh, {0, 0, image.width, image.height}, {0, 0, image.width, image.height});

    const MeshRenderer renderer(mesh, result.values);
    if (on_step) on_step({0, 1, TilePhase::Render});
    const size_t row_floats = size_t(out.width) * image.channels;
    const uint32_t band_rows = uint32_t(std::max<size_t>(1, kBandFloats / row_floats));
    for (uint32_t y = 0; y < out.height; y += band_rows) {
        OutputRows band(y, std::min(out.height, y + band_rows), row_floats);
        renderInParallel(renderer, wholeRows(image.width, image.height, out, band.y_begin, band.y_end), image.channels,
                         band.floats.get());
        sink(std::move(band));
    }
    return result;
}

struct TiledRun {
    TiledRun(BackendPool& pool, const Image& picture, OutputSize size, double share, double error, const Sink& rows,
             const TileStepCallback& step)
        : backends(pool), image(picture), out(size), fraction(share), max_error(error), sink(rows), on_step(step) {}

    BackendPool& backends;
    const Image& image;
    OutputSize out;
    double fraction, max_error;
    const Sink& sink;
    const TileStepCallback& on_step;
    uint32_t tiles = 0;  // in all, for on_step
    std::mutex mutex;    // tiles in parallel report their steps and statistics one at a time
    SimplifiedUpscale result;
};

// Optimizes and simplifies one tile on a backend of the pool.
void simplifyPooledTile(TiledRun& run, SimplifiedTile& tile, uint32_t index) {
    if (run.on_step) {
        std::lock_guard lock(run.mutex);
        run.on_step({index, run.tiles, TilePhase::Optimize});
    }
    run.backends.withBackend([&](Backend& backend) {
        OptimizeStats optimized;
        const ParallelSimplifyStats simplified = simplifyTile(backend, run.image, tile, run.fraction, run.max_error, optimized);
        std::lock_guard lock(run.mutex);
        addStats(run.result.optimize, optimized);
        ParallelSimplifyStats& total = run.result.simplify;
        total.vertices_before += simplified.vertices_before;
        total.vertices_after += simplified.vertices_after;
        total.collapses += simplified.collapses;
        total.last_cost = std::max(total.last_cost, simplified.last_cost);
        total.rounds = std::max(total.rounds, simplified.rounds);
    });
}

// Renders a strip's output rows from its tiles' meshes, band by band.
void renderStrip(TiledRun& run, const std::vector<SimplifiedTile>& tiles) {
    std::vector<std::optional<MeshRenderer>> renderers(tiles.size());
    parallelFor(tiles.size(), 1, [&](size_t begin, size_t end) {
        for (size_t i = begin; i < end; ++i) renderers[i].emplace(tiles[i].mesh, tiles[i].values);
    });
    const uint32_t channels = run.image.channels;
    const size_t row_floats = size_t(run.out.width) * channels;
    const uint32_t band_rows = uint32_t(std::max<size_t>(1, kBandFloats / row_floats));
    const uint32_t y0 = tiles.front().output.y0, y1 = tiles.front().output.y1;
    for (uint32_t y = y0; y < y1; y += band_rows) {
        OutputRows band(y, std::min(y1, y + band_rows), row_floats);
        parallelFor(tiles.size(), 1, [&](size_t begin, size_t end) {
            for (size_t i = begin; i < end; ++i) {
                const SimplifiedTile& tile = tiles[i];
                const RenderWindow window{run.image.width, run.image.height, run.out,  tile.crop.x0, tile.crop.y0,
                                          tile.output.x0,  tile.output.x1,   band.y_begin, band.y_end};
                renderers[i]->renderWindow(window, band.floats.get() + size_t(tile.output.x0) * channels, row_floats);
            }
        });
        run.sink(std::move(band));
    }
}

SimplifiedUpscale simplifyTiled(Backend& backend, const Image& image, OutputSize out, double fraction, double max_error,
                                uint32_t side, const Sink& sink, const TileStepCallback& on_step) {
    BackendPool backends(backend, tilesAtOnce(backend));
    TiledRun run(backends, image, out, fraction, max_error, sink, on_step);
    for (uint32_t y = 0; y < image.height; y = stripEnd(image.height, y, side))
        run.tiles += uint32_t(planStrip(image.width, image.height, out, y, stripEnd(image.height, y, side), side, 0).size());
    uint32_t index = 0;
    for (uint32_t y0 = 0; y0 < image.height;) {
        const uint32_t y1 = stripEnd(image.height, y0, side);
        std::vector<SimplifiedTile> tiles = planSimplifiedStrip(image.width, image.height, out, y0, y1, side);
        auto simplifyTiles = [&](size_t begin, size_t end) {
            for (size_t i = begin; i < end; ++i) simplifyPooledTile(run, tiles[i], index + uint32_t(i));
        };
        if (backends.size() > 1) parallelFor(tiles.size(), 1, simplifyTiles);
        else simplifyTiles(0, tiles.size());  // one device: a tile at a time
        if (on_step) on_step({index, run.tiles, TilePhase::Render});
        renderStrip(run, tiles);
        index += uint32_t(tiles.size());
        y0 = y1;
    }
    return std::move(run.result);
}

}  // namespace

uint32_t firstSnappedOutputOf(uint32_t c, uint32_t in_size, uint32_t out_size) {
    uint32_t first = firstOutputOf(c, in_size, out_size);
    if (c == 0 || c >= in_size) return first;
    while (first > 0 && snappedSample(sampleCoord(first - 1, in_size, out_size), out_size) >= int64_t(c) * kPositionOne)
        --first;
    return first;
}

std::vector<SimplifiedTile> planSimplifiedStrip(uint32_t width, uint32_t height, OutputSize out, uint32_t y0, uint32_t y1,
                                                uint32_t side) {
    std::vector<SimplifiedTile> tiles;
    for (const Tile& planned : planStrip(width, height, out, y0, y1, side, 0)) {
        SimplifiedTile tile;
        tile.core = planned.core;
        tile.crop = {tile.core.x0, tile.core.y0, std::min(width, tile.core.x1 + 1), std::min(height, tile.core.y1 + 1)};
        tile.output = {firstSnappedOutputOf(tile.core.x0, width, out.width),
                       firstSnappedOutputOf(tile.core.y0, height, out.height),
                       firstSnappedOutputOf(tile.core.x1, width, out.width),
                       firstSnappedOutputOf(tile.core.y1, height, out.height)};
        const bool right = tile.crop.x1 > tile.core.x1, below = tile.crop.y1 > tile.core.y1;
        tile.shared = (right ? tile.crop.height() : 0) + (below ? tile.crop.width() : 0) - (right && below ? 1 : 0);
        tiles.push_back(std::move(tile));
    }
    return tiles;
}

ParallelSimplifyStats simplifyTile(Backend& backend, const Image& image, SimplifiedTile& tile, double fraction,
                                   double max_error, OptimizeStats& optimized) {
    Image crop = cropOf(image, tile.crop);
    backend.prepare(crop);
    optimized = backend.optimize();
    tile.mesh = backend.takeMesh();
    tile.mesh.locked_sides = uint32_t(tile.crop.x0 > 0) | uint32_t(tile.crop.x1 < image.width) << 1 |
                             uint32_t(tile.crop.y0 > 0) << 2 | uint32_t(tile.crop.y1 < image.height) << 3;
    tile.values = std::move(crop);  // the picture the simplifier reads, and then the vertices' colours
    const uint32_t target = simplifiedVertexCount(tile.core.width(), tile.core.height(), fraction) + tile.shared;
    ParallelSimplifyStats stats = backend.simplify(tile.mesh, tile.values, target, max_error);
    // Every tile samples as a mesh with explicit positions does, also one left whole.
    makePositionsExplicit(tile.mesh);
    stats.vertices_before -= tile.shared;
    stats.vertices_after -= tile.shared;
    return stats;
}

uint32_t simplifiedVertexCount(uint32_t width, uint32_t height, double fraction) {
    return uint32_t(std::max<uint64_t>(4, uint64_t(std::ceil(fraction * double(width) * height))));
}

uint32_t simplifyTileSide(const Backend& backend, uint32_t width, uint32_t height, uint32_t channels, uint32_t tile) {
    const bool asks_tiles = tile && tile < std::max(width, height);
    if (!asks_tiles && untiledMemoryProblem(backend, width, height, channels,
                                            backend.simplifyMemoryNeeded(width, height, channels))
                           .empty())
        return 0;
    const uint64_t limit = backend.memoryLimit(), usable = limit - limit / 8;
    const uint32_t sharers = tilesAtOnce(backend);
    uint32_t side = asks_tiles ? tile : kSimplifyTileSide;
    auto fits = [&](uint32_t s) {
        const uint64_t bytes = tileBytes(backend, s, channels);
        return bytes != UINT64_MAX && bytes <= usable / sharers;
    };
    while (side > kMinTileSide && !fits(side)) side = std::max(kMinTileSide, side / 2);
    if (!fits(side))
        throw UserError("simplification in tiles of " + std::to_string(side) + " pixels needs about " +
                        mebibytes(tileBytes(backend, side, channels) * sharers) + ", more than the " + mebibytes(usable) +
                        " the backend may use (--memory sets it for the CPU backend)");
    return side;
}

SimplifiedUpscale upscaleSimplified(Backend& backend, const Image& image, OutputSize out, double fraction, double max_error,
                                    const TileOptions& options, const Sink& sink, const TileStepCallback& on_step) {
    if (image.width > kMaxPositionedSide || image.height > kMaxPositionedSide)
        throw UserError("simplification places vertices on a fixed-point grid for sides up to " +
                        std::to_string(kMaxPositionedSide) + " pixels, and " + std::to_string(image.width) + "×" +
                        std::to_string(image.height) + " is wider or taller");
    const uint32_t side = simplifyTileSide(backend, image.width, image.height, image.channels, options.tile);
    if (!side)
        return simplifyWhole(backend, image, out, simplifiedVertexCount(image.width, image.height, fraction), max_error,
                             options, sink, on_step);
    if (options.mesh)
        throw UserError("--mesh does not combine yet with a simplification in tiles (" + std::to_string(image.width) + "×" +
                        std::to_string(image.height) + " in " + std::to_string(side) +
                        "-pixel tiles); in one piece it needs a --memory that holds it and no smaller --tile");
    return simplifyTiled(backend, image, out, fraction, max_error, side, sink, on_step);
}

}  // namespace ddt
