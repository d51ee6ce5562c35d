#include "tiled_upscale.h"

#include <algorithm>
#include <memory>
#include <mutex>
#include <new>
#include <optional>
#include <string>
#include <vector>

#include "backend_pool.h"
#include "convolution_fallback.h"
#include "delaunay/sampled_tile.h"
#include "memory_size.h"
#include "parallel.h"
#include "strip_rows.h"
#include "tiling.h"
#include "user_error.h"

namespace ddt {

namespace {

// Output rows are rendered in bands of at most this many floats, which keeps the host's
// memory flat whatever the output size.
const size_t kBandFloats = size_t(2) << 20;  // 8 MiB
// On a backend that keeps its surfaces (a GPU), a strip of several tiles is assembled on the
// host before its rows go out: strips are cut thinner than the tile side where a strip of
// square tiles would exceed this.
const size_t kStripFloats = size_t(128) << 20;  // 512 MiB

using Sink = std::function<void(OutputRows&& rows)>;

// Hands rows to the sink once each: rows already sent before a retry are skipped.
class RowEmitter {
public:
    RowEmitter(const Sink& sink, size_t row_floats) : sink_(sink), row_floats_(row_floats) {}

    void emit(OutputRows&& rows) {
        if (rows.y_end <= next_row_) return;
        if (rows.y_begin < next_row_) rows.dropBefore(next_row_, row_floats_);  // rare: after a retry
        next_row_ = rows.y_end;
        sink_(std::move(rows));
    }

private:
    const Sink& sink_;
    size_t row_floats_;
    uint32_t next_row_ = 0;
};

// Whether a job fits its share of the available memory (1/`sharers` of it) with 1/8 to
// spare: drivers round allocations up and keep their own, and an estimate is only an estimate.
bool fits(const Backend& backend, uint32_t width, uint32_t height, uint32_t channels, bool reconstruction,
          uint32_t sharers = 1) {
    const uint64_t needed = backend.memoryNeeded(width, height, channels, reconstruction);
    const uint64_t available = backend.memoryAvailable() / sharers;
    return needed != UINT64_MAX && needed <= available - available / 8;
}


// Input rows per strip: the tile side, or, where a strip of several tiles is assembled, fewer
// if it would not fit kStripFloats (a strip of one tile, or of surfaces handed over, streams
// its rows out).
uint32_t stripSide(const Image& image, OutputSize out, uint32_t side, bool assembled) {
    if (side >= image.width || !assembled) return side;
    const size_t row_floats = size_t(out.width) * image.channels;
    const uint64_t out_rows = std::max<size_t>(1, kStripFloats / row_floats);
    const uint64_t in_rows = out_rows * image.height / out.height;
    return uint32_t(std::clamp<uint64_t>(in_rows, std::min(kMinTileSide, side), side));
}

uint32_t tilesFrom(uint32_t height, uint32_t y0, uint32_t columns, uint32_t strip_side) {
    uint32_t tiles = 0;
    for (uint32_t y = y0; y < height; y = stripEnd(height, y, strip_side)) tiles += columns;
    return tiles;
}

struct Job {
    BackendPool& backends;
    const PackedImage& input;  // the whole input, made floats a crop at a time
    const Image& image;        // its header (size, channels, sample type)
    OutputSize out;
    bool reconstruct;
    AssumedKernel kernel;
    bool fallback;
    const TileStepCallback& on_step;
    RowEmitter& rows;
    StitchedMesh* strip_mesh;  // the current strip's tiles' meshes, if the caller wants them
    const KnownSamples* known;  // a mask's or a point file's: the tiles are of its samples
    uint32_t code_bits;         // TileOptions::code_bits
    uint32_t overlap;           // TileOptions::overlap, at least 1
    std::mutex step_mutex;  // tiles in parallel report their steps one at a time
    std::mutex mesh_mutex;  // and add their meshes one at a time

    void step(uint32_t tile, uint32_t tiles, TilePhase phase) {
        std::lock_guard lock(step_mutex);
        if (on_step) on_step({tile, tiles, phase});
    }
};

// Optimises one tile's crop on `backend` and, if the job asks, reconstructs its surface. The
// crop is made in `crop`, which the backend reads until it is prepared again.
OptimizeStats shapeTile(Job& job, Backend& backend, const Tile& tile, uint32_t index, uint32_t total, Image& crop) {
    job.step(index, total, TilePhase::Optimize);
    const bool whole = tile.crop.width() == job.image.width && tile.crop.height() == job.image.height;
    const Image* floats = whole ? job.input.floats() : nullptr;  // an untiled float input needs no copy
    if (!floats) crop = job.input.crop(tile.crop);
    backend.prepare(floats ? *floats : crop);
    const OptimizeStats stats = backend.optimize();
    if (job.strip_mesh) {
        const Mesh mesh = backend.mesh();  // before the reconstruction, which may give it up
        std::lock_guard lock(job.mesh_mutex);
        job.strip_mesh->add(mesh, tile.crop, tile.core);
    }
    // The model follows the whole image's factors; each crop is reconstructed on its own, and
    // the overlap keeps the crop's border out of the core's output (test/image/test_tiling.cpp).
    if (job.reconstruct) {
        job.step(index, total, TilePhase::Reconstruct);
        backend.reconstruct(degradationFor(double(job.out.width) / job.image.width,
                                           double(job.out.height) / job.image.height, job.kernel));
    }
    if (job.fallback) backend.addFallback(grainShareFor(job.kernel));
    return stats;
}

// The tile's output rows [y_begin, y_end).
RenderWindow windowOf(const Job& job, const Tile& tile, uint32_t y_begin, uint32_t y_end) {
    RenderWindow window;
    window.input_width = job.image.width;
    window.input_height = job.image.height;
    window.out = job.out;
    window.crop_x = tile.crop.x0;
    window.crop_y = tile.crop.y0;
    window.x_begin = tile.output.x0;
    window.x_end = tile.output.x1;
    window.y_begin = y_begin;
    window.y_end = y_end;
    return window;
}

// Output rows per band for rows of `row_floats` floats.
uint32_t bandRows(size_t row_floats) { return uint32_t(std::max<size_t>(1, kBandFloats / row_floats)); }

// Optimises one tile's crop on `backend` and renders its output, in bands, to `deliver(rows)`.
template <typename Deliver>
OptimizeStats upscaleTile(Job& job, Backend& backend, const Tile& tile, uint32_t index, uint32_t total,
                          Deliver deliver) {
    if (tile.output.width() == 0 || tile.output.height() == 0) return {};  // a core between two samples
    Image crop;
    const OptimizeStats stats = shapeTile(job, backend, tile, index, total, crop);
    job.step(index, total, TilePhase::Render);
    const size_t row_floats = size_t(tile.output.width()) * job.image.channels;
    const uint32_t band_rows = bandRows(row_floats);
    for (uint32_t y = tile.output.y0; y < tile.output.y1; y += band_rows) {
        OutputRows band(y, std::min(tile.output.y1, y + band_rows), row_floats);
        backend.renderWindow(windowOf(job, tile, band.y_begin, band.y_end), band.floats.get());
        deliver(std::move(band));
    }
    return stats;
}

// A strip of several tiles on a backend that hands its surfaces over, or of a mask's tiles.
// The tiles are shaped (in parallel with twins) and each surface is either kept, to render the
// strip's rows band by band across the tiles once all are shaped (a band is then all the
// output held, whatever the scale), or rendered at once into the strip's rows
// (app/strip_rows.h) and dropped. Whichever holds less: at ×2 a photo's surfaces are twice
// its output rows as floats, at ×4 half. The choice is made tile by tile from the surfaces
// measured so far, projected over the strip.
OptimizeStats upscaleStripInBands(Job& job, const std::vector<Tile>& tiles, uint32_t first_index, uint32_t total) {
    const uint32_t c = job.image.channels;
    const size_t row_floats = size_t(job.out.width) * c;
    const uint32_t y0 = tiles[0].output.y0, y1 = tiles[0].output.y1, band_rows = bandRows(row_floats);
    const double strip_bytes = StripRows::bytes(y1 - y0, row_floats, job.code_bits);
    double strip_crop_pixels = 0.0;
    for (const Tile& tile : tiles) strip_crop_pixels += double(tile.crop.width()) * tile.crop.height();

    OptimizeStats stats;
    std::mutex mutex;  // guards stats, the measured surfaces and the making of `strip`
    double measured_bytes = 0.0, measured_pixels = 0.0;
    std::optional<StripRows> strip;  // made when a first tile renders at once
    std::vector<std::unique_ptr<HostSurface>> kept(tiles.size());
    auto shapeOne = [&](size_t i) {
        const Tile& tile = tiles[i];
        if (tile.output.width() == 0 || tile.output.height() == 0) return;  // a core between two samples
        job.backends.withBackend([&](Backend& backend) {
            OptimizeStats tile_stats;
            std::unique_ptr<HostSurface> surface;
            if (job.known) {
                job.step(first_index + uint32_t(i), total, TilePhase::Optimize);
                SampledTile shaped = shapeSampledTile(backend, job.input, *job.known, tile, windowOf(job, tile, 0, 0), job.overlap);
                surface = std::move(shaped.surface);
                tile_stats = shaped.stats;
            } else {
                Image crop;
                tile_stats = shapeTile(job, backend, tile, first_index + uint32_t(i), total, crop);
                surface = backend.takeSurface();
            }
            bool at_once;
            {
                std::lock_guard lock(mutex);
                addStats(stats, tile_stats);
                measured_bytes += double(surface->bytes());
                measured_pixels += double(tile.crop.width()) * tile.crop.height();
                at_once = strip_bytes < measured_bytes / measured_pixels * strip_crop_pixels;
                if (at_once && !strip) strip.emplace(y0, y1, row_floats, band_rows, job.code_bits);
            }
            if (!at_once) {
                kept[i] = std::move(surface);
                return;
            }
            job.step(first_index + uint32_t(i), total, TilePhase::Render);
            strip->render(*surface, windowOf(job, tile, y0, y1), c);
        });
    };
    // At most one tile per backend at once: a device without twins (a mask's tiles on Vulkan)
    // shapes them one by one.
    if (job.backends.size() > 1)
        parallelFor(tiles.size(), 1, [&](size_t begin, size_t end) {
            for (size_t i = begin; i < end; ++i) shapeOne(i);
        });
    else
        for (size_t i = 0; i < tiles.size(); ++i) shapeOne(i);

    std::vector<uint32_t> rendered;  // the kept surfaces
    for (uint32_t i = 0; i < tiles.size(); ++i)
        if (kept[i]) {
            job.step(first_index + i, total, TilePhase::Render);
            rendered.push_back(i);
        }
    if (strip) {
        // The tiles shaped before the strip was made: into it too, then its bands go out.
        parallelFor(rendered.size(), 1, [&](size_t begin, size_t end) {
            for (size_t item = begin; item < end; ++item)
                strip->render(*kept[rendered[item]], windowOf(job, tiles[rendered[item]], y0, y1), c);
        });
        for (uint32_t k = 0; k < strip->bandCount(); ++k) job.rows.emit(strip->takeBand(k));
        return stats;
    }
    for (uint32_t y = y0; y < y1; y += band_rows) {
        const uint32_t y_end = std::min(y1, y + band_rows);
        StripRows band(y, y_end, row_floats, band_rows, job.code_bits);  // one band, as the writer's codes where it takes them
        // Every kept tile's runs of rows at once, each written straight into its columns of the band.
        const uint32_t runs = (y_end - y + kRowsPerRenderBand - 1) / kRowsPerRenderBand;
        parallelFor(rendered.size() * runs, 1, [&](size_t begin, size_t end) {
            for (size_t item = begin; item < end; ++item) {
                const uint32_t i = rendered[item / runs];
                const uint32_t run_begin = y + uint32_t(item % runs) * kRowsPerRenderBand;
                band.render(*kept[i], windowOf(job, tiles[i], run_begin, std::min(y_end, run_begin + kRowsPerRenderBand)), c);
            }
        });
        job.rows.emit(band.takeBand(0));
    }
    return stats;
}

// One strip of tiles: a single tile streams its rows out; several render band by band from
// their surfaces where the backend hands them over, else are assembled first.
OptimizeStats upscaleStrip(Job& job, const std::vector<Tile>& tiles, uint32_t first_index, uint32_t total) {
    OptimizeStats stats;
    const uint32_t c = job.image.channels;
    const size_t row_floats = size_t(job.out.width) * c;
    // A mask's tiles render on the host whatever the backend.
    if (job.known) return upscaleStripInBands(job, tiles, first_index, total);
    if (tiles.size() == 1) {
        addStats(stats, job.backends.withBackend([&](Backend& backend) {
            return upscaleTile(job, backend, tiles[0], first_index, total,
                               [&](OutputRows&& rows) { job.rows.emit(std::move(rows)); });
        }));
        return stats;
    }
    if (job.backends.handOverSurfaces()) return upscaleStripInBands(job, tiles, first_index, total);
    const PixelRect strip = {0, tiles[0].output.y0, job.out.width, tiles[0].output.y1};
    OutputRows strip_rows(strip.y0, strip.y1, row_floats);
    std::mutex stats_mutex;
    auto upscaleTileInStrip = [&](uint32_t i) {
        const Tile& tile = tiles[i];
        const size_t tile_row_floats = size_t(tile.output.width()) * c;
        const OptimizeStats tile_stats = job.backends.withBackend([&](Backend& backend) {
            return upscaleTile(job, backend, tile, first_index + i, total,
                               [&](OutputRows&& rows) {
                                   for (uint32_t y = rows.y_begin; y < rows.y_end; ++y)
                                       std::copy_n(rows.row(y, tile_row_floats), tile_row_floats,
                                                   strip_rows.row(y, row_floats) + size_t(tile.output.x0) * c);
                               });
        });
        std::lock_guard lock(stats_mutex);
        addStats(stats, tile_stats);
    };
    // With twins the tiles run in parallel. Each writes its own columns of the strip, so the
    // order they finish in does not matter: the bytes are those of serial tiles.
    if (job.backends.size() > 1)
        parallelFor(tiles.size(), 1, [&](size_t begin, size_t end) {
            for (size_t i = begin; i < end; ++i) upscaleTileInStrip(uint32_t(i));
        });
    else
        for (uint32_t i = 0; i < tiles.size(); ++i) upscaleTileInStrip(i);
    if (strip.height() > 0) job.rows.emit(std::move(strip_rows));
    return stats;
}

}  // namespace

std::string untiledMemoryProblem(const Backend& backend, uint32_t width, uint32_t height, uint32_t channels,
                                 uint64_t extra) {
    const uint64_t needed = backend.memoryNeeded(width, height, channels, false);
    const uint64_t limit = backend.memoryLimit();
    if (needed != UINT64_MAX && needed + extra <= limit - limit / 8) return "";
    const std::string size = std::to_string(width) + "×" + std::to_string(height);
    if (needed == UINT64_MAX) return size + " is beyond what one piece of the device can hold";
    return size + " needs about " + mebibytes(needed + extra) + ", more than the " +
           mebibytes(limit - limit / 8) + " the backend may use (--memory sets it for the CPU backend)";
}

uint32_t automaticTileSide(const Backend& backend, uint32_t width, uint32_t height, uint32_t channels,
                           uint32_t overlap, bool reconstruction) {
    if (fits(backend, width, height, channels, reconstruction)) return 0;
    // Tiles that run at once share the memory.
    const uint32_t sharers = tilesAtOnce(backend);
    auto crop_fits = [&](uint32_t side) {
        return fits(backend, std::min(width, side + 2 * overlap), std::min(height, side + 2 * overlap), channels,
                    reconstruction, sharers);
    };
    for (uint32_t side = std::max(width, height) / 256 * 256; side >= 256; side -= 256)
        if (crop_fits(side)) return side;
    for (uint32_t side : {128u, 64u})
        if (crop_fits(side)) return side;
    return kMinTileSide;  // the retry below reports that nothing fits
}

OptimizeStats upscaleRows(Backend& backend, PackedImage& input, OutputSize out, const TileOptions& options,
                          const Sink& sink, const TileStepCallback& on_step) {
    const Image& image = input.header();
    // A core's last samples must lie inside its crop's hull, or they would stay unwritten.
    const uint32_t overlap = std::max(1u, options.overlap);
    const uint32_t largest_side = std::max(image.width, image.height);
    uint32_t side =
        options.tile ? options.tile : automaticTileSide(backend, image.width, image.height, image.channels, overlap,
                                                     options.reconstruct);
    // A mask's tiles grow around its holes, and it keeps one piece where that fits.
    if (!options.tile && side == 0 && !options.known && tilesAtOnce(backend) > 1) side = kParallelTileSide;
    if (side == 0 || side > largest_side) side = largest_side;

    RowEmitter rows(sink, size_t(out.width) * image.channels);
    BackendPool backends(backend, side < largest_side ? tilesAtOnce(backend) : 1);
    Job job{backends, input, image, out, options.reconstruct, options.kernel, options.fallback, on_step, rows, nullptr,
            options.known, options.code_bits, overlap, {}, {}};
    OptimizeStats stats;
    uint32_t tiles_done = 0;
    for (uint32_t y0 = 0; y0 < image.height;) {
        const uint32_t strip_side = stripSide(image, out, side, !backends.handOverSurfaces());
        const uint32_t y1 = stripEnd(image.height, y0, strip_side);
        // Automatic tiles: a multiple of the threads a strip (stripColumns); a given --tile is cut as it says.
        const uint32_t columns = stripColumns(image.width, side, options.tile ? 1 : backends.size());
        std::vector<Tile> tiles = planStrip(image.width, image.height, out, y0, y1, side, overlap, columns);
        // Holes wider than a tile may grow a crop by at most the tile side a side.
        if (options.known)
            for (Tile& tile : tiles) tile.crop = options.known->cropFor(tile.crop, side);
        // The input rows the strip's crops reach; a retry's smaller tiles reach no further.
        uint32_t first_row = image.height, end_row = 0;
        for (const Tile& tile : tiles) {
            first_row = std::min(first_row, tile.crop.y0);
            end_row = std::max(end_row, tile.crop.y1);
        }
        input.holdRows(first_row, end_row);
        std::string out_of_memory;
        // A strip's meshes count once it succeeds: a retry gives them again.
        std::optional<StitchedMesh> strip_mesh;
        if (options.mesh) strip_mesh.emplace(image.width, image.height);
        job.strip_mesh = strip_mesh ? &*strip_mesh : nullptr;
        try {
            addStats(stats, upscaleStrip(job, tiles, tiles_done,
                                         tiles_done + tilesFrom(image.height, y0, columns, strip_side)));
        } catch (const DeviceOutOfMemory& error) {
            out_of_memory = error.what();
        } catch (const std::bad_alloc&) {
            out_of_memory = "out of host memory";
        }
        if (!out_of_memory.empty()) {
            // Redo this strip with tiles half as large; rows already sent stay sent.
            if (side <= kMinTileSide)
                throw UserError("not enough device memory even for " + std::to_string(kMinTileSide) + "×" +
                                std::to_string(kMinTileSide) + " tiles (" + out_of_memory + ")");
            side = std::max(kMinTileSide, side / 2);
            continue;
        }
        if (strip_mesh) options.mesh->append(std::move(*strip_mesh));
        tiles_done += uint32_t(tiles.size());
        y0 = y1;
    }
    return stats;
}

}  // namespace ddt
