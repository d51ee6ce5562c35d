#include "upscale_job.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <optional>

#include "delaunay.h"
#include "delaunay/sampled_tile.h"
#include "delaunay/sampled_upscale.h"
#include "image_metadata.h"
#include "indexed_mesh.h"
#include "known_pixels.h"
#include "known_points.h"
#include "mesh_file.h"
#include "point_file.h"
#include "delaunay/point_mesh.h"
#include "simplified_upscale.h"
#include "tiled_upscale.h"

namespace ddt {

namespace {

namespace fs = std::filesystem;

double secondsSince(std::chrono::steady_clock::time_point start) {
    return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

void checkMagnifiable(const std::string& input, const Image& header) {
    if (header.width < 2 || header.height < 2)
        throw UserError(inputName(input) + ": DDT needs at least 2×2 pixels (got " + std::to_string(header.width) + "×" +
                        std::to_string(header.height) + ")");
}

void checkOutputLimit(const std::string& output, OutputSize out) {
    if (uint64_t(out.width) * out.height <= kMaxOutputPixels) return;
    // Sides beyond 32 bits arrive saturated (render.h): say "more than" rather than a false size.
    const bool saturated = out.width == UINT32_MAX || out.height == UINT32_MAX;
    const std::string size = saturated ? "more than 4294967295 pixels a side"
                                       : std::to_string(out.width) + "×" + std::to_string(out.height) + " pixels";
    throw UserError(outputName(output) + ": the output would be " + size + "; ddtup writes at most " +
                    std::to_string(kMaxOutputPixels) + " pixels (4 gigapixels)");
}

// The output size the settings ask for, for an input of width × height.
OutputSize requestedOutputSize(const Settings& settings, uint32_t width, uint32_t height) {
    if (settings.width && settings.height) return {settings.width, settings.height};
    if (settings.width) return outputSizeForWidth(width, height, settings.width);
    if (settings.height) return outputSizeForHeight(width, height, settings.height);
    return scaledOutputSize(width, height, settings.scale);
}

// The pixels `mask_path` marks as known in `image`, checked to have a Delaunay triangulation.
// The mask is read as kept in its file and made floats a band of rows at a time.
KnownPixels knownPixelsOf(const std::string& mask_path, const Image& image) {
    const PackedImage mask = ImageReader(mask_path).readPacked();
    const Image& header = mask.header();
    if (header.width != image.width || header.height != image.height)
        throw UserError(mask_path + ": the mask is " + std::to_string(header.width) + "×" + std::to_string(header.height) +
                        ", the input " + std::to_string(image.width) + "×" + std::to_string(image.height));
    if (image.width > kMaxDelaunaySide || image.height > kMaxDelaunaySide)
        throw UserError(mask_path + ": masks apply to images of at most " + std::to_string(kMaxDelaunaySide) +
                        " pixels a side (the exact in-circle test's range)");
    std::vector<uint8_t> bytes(size_t(image.width) * image.height, 0);
    const uint32_t band = 64;
    for (uint32_t y = 0; y < image.height; y += band) {
        const PixelRect rows{0, y, image.width, std::min(image.height, y + band)};
        for (uint32_t id : knownPixels(mask.crop(rows))) bytes[size_t(y) * image.width + id] = 1;
    }
    KnownPixels known(image.width, image.height, std::move(bytes));
    if (std::string problem = known.problemIn({0, 0, image.width, image.height}); !problem.empty())
        throw UserError(mask_path + ": the known pixels cannot be triangulated (" + problem + ")");
    return known;
}

}  // namespace

struct ImageJob::State {
    std::optional<ImageReader> reader;  // from open() to decode()
    std::optional<PointSamples> points;  // a point file's, from open() to decode()
    std::optional<SampleSet> merged;     // a point file's, from decode() to render()
    std::optional<KnownPixels> known;    // a mask's known pixels (or pixel-centred points in tiles), to render()
    std::optional<KnownPoints> known_points;  // a point file's points in tiles, in render()
    Frame frame;                         // a point file's
    uint32_t channels = 0;
    PackedImage input;            // the input; for a point file, its vertex values (point_mesh.h)
    std::optional<Mesh> samples;  // --mask or a point file: the known samples' triangulation, in render()
    std::optional<ImageWriter> writer;
    std::optional<BandStream> bands;  // from process() to write()
    std::chrono::steady_clock::time_point rendered;  // when process() sent the last band
    std::chrono::steady_clock::time_point started = std::chrono::steady_clock::now();
};

ImageJob::ImageJob(size_t index, const ImageTask& task, const Settings& settings, Reporter& reporter)
    : index_(index), task_(task), settings_(settings), reporter_(reporter), state_(std::make_unique<State>()) {}

ImageJob::~ImageJob() = default;

AssumedKernel ImageJob::assumedKernel() const {
    if (settings_.assume != kAutomaticAssumption) return *parseAssumedKernel(settings_.assume);  // checked by the command line
    const auto& metadata = state_->input.header().metadata;
    return automaticAssumption(metadata ? metadata->format_name : "");
}

WriteOptions ImageJob::writeOptions() const {
    WriteOptions options;
    options.quality = settings_.quality;
    if (!settings_.depth.empty()) options.depth = parseSampleType(settings_.depth);
    options.format = settings_.format;
    // Standard output has no extension to go by: follow the input's (the CLI made sure of one).
    if (task_.output == kStandardStream && options.format.empty())
        options.format = fs::path(task_.input).extension().string().substr(1);
    return options;
}

void ImageJob::open() {
    reporter_.stage(index_, task_.input, Stage::Read);
    const auto start = std::chrono::steady_clock::now();
    const Image header = isPointFilePath(task_.input) ? openPoints() : state_->reader.emplace(task_.input).header();
    state_->channels = header.channels;
    checkMagnifiable(task_.input, header);
    report_.out = requestedOutputSize(settings_, header.width, header.height);
    checkOutputLimit(task_.output, report_.out);
    if (std::string problem = checkOutputSize(header.width, header.height, report_.out); !problem.empty())
        throw UserError(inputName(task_.input) + ": " + problem);
    if (!task_.mesh.empty() && !(settings_.max_error > 0.0 && settings_.simplify == 0.0)) {
        // A simplified mesh of V vertices has fewer than 2V triangles (a triangulated disk),
        // plus its ring's, at most two per hull pixel and corner.
        // With --max-error alone the count is known only at the end, where it is checked again.
        // A point file's mesh has fewer than 2 triangles a point; a mask's, fewer than the grid's.
        const uint64_t faces = state_->points ? 2 * uint64_t(state_->points->size())
                               : settings_.simplifies()
                                   ? 2 * simplifiedVertexCount(header.width, header.height, settings_.simplify) +
                                         4 * (uint64_t(header.width) + header.height) + 8
                                   : indexedFaceCount(header.width, header.height);
        if (std::string problem = checkMeshSize(*meshFormatOf(task_.mesh), faces); !problem.empty())
            throw UserError(task_.mesh + ": " + problem);
    }
    // A batch writes into sub-folders that mirror the input folder's.
    if (task_.output != kStandardStream) {
        std::error_code error;
        const fs::path folder = fs::path(task_.output).parent_path();
        if (!folder.empty() && !fs::exists(folder, error) && !settings_.singleForm())
            fs::create_directories(folder, error);
    }
    // Open the output before decoding the input: an unwritable path, or a size the format
    // cannot hold, fails before any of the long parts.
    state_->writer.emplace(task_.output, report_.out.width, report_.out.height, header, writeOptions());
    report_.times.init_s = secondsSince(start);
}

// Reads the point file and returns the header of an image of its frame.
Image ImageJob::openPoints() {
    PointSamples& points = state_->points.emplace(readPointFile(task_.input));
    state_->frame = settings_.frame_width ? Frame{settings_.frame_width, settings_.frame_height} : frameOfPoints(points);
    if (state_->frame.width > kMaxDelaunaySide || state_->frame.height > kMaxDelaunaySide)
        throw UserError(inputName(task_.input) + ": the points span a frame of " + std::to_string(state_->frame.width) +
                        "×" + std::to_string(state_->frame.height) + " pixels; at most " +
                        std::to_string(kMaxDelaunaySide) + " a side (the exact in-circle test's range)");
    Image header;
    header.width = state_->frame.width;
    header.height = state_->frame.height;
    header.channels = points.channels;
    header.sample_type = points.sample_type;
    return header;
}

uint64_t ImageJob::hostMemory() const {
    if (state_->points) {
        // The values image, twice (the file's and the merged copy), and the mesh: about 3
        // edges a point of 32 bytes each, with the triangulation's scratch as much again; in
        // tiles, the points kept by block and their gaps' measure.
        const uint64_t n = state_->points->size();
        return n * (2 * sizeof(float) * state_->channels + 2 * 3 * 32 + KnownPoints::bytesPerPoint(state_->channels));
    }
    const Image& header = state_->reader->header();
    const uint64_t samples = uint64_t(header.width) * header.height * header.channels;
    // The image as kept and a tile's crop of it in floats, at most as large; the output's bands
    // have a budget of their own. A mask: its known pixels, a byte each, and while its holes
    // are measured, 4 bytes a pixel (core/delaunay/known_pixels.h).
    const uint64_t mask = task_.mask.empty() ? 0 : 5 * uint64_t(header.width) * header.height;
    return (state_->reader->keptSampleBytes() + sizeof(float)) * samples + mask;
}

void ImageJob::decode() {
    const auto start = std::chrono::steady_clock::now();
    if (state_->points) {
        try {
            state_->merged = mergePoints(*state_->points, state_->frame);
        } catch (const UserError& error) {
            throw UserError(inputName(task_.input) + ": " + error.what());
        }
        state_->points.reset();
        report_.times.init_s += secondsSince(start);
        return;
    }
    // Only the plain tiled path takes the input a strip at a time; a mask, a simplification and
    // a mesh file read it whole.
    const bool rows_as_needed = task_.mask.empty() && task_.mesh.empty() && !settings_.simplifies();
    state_->input = state_->reader->readPacked(rows_as_needed);
    for (const std::string& note : state_->reader->notes()) reporter_.notice(task_.input, note);
    state_->reader.reset();
    if (!task_.mask.empty()) state_->known = knownPixelsOf(task_.mask, state_->input.header());
    report_.times.init_s += secondsSince(start);
}

const Image& ImageJob::inputFloats() {
    if (const Image* floats = state_->input.floats()) return *floats;
    state_->input = PackedImage(std::move(state_->input).unpack());
    return state_->input.header();
}

void ImageJob::streamOutput(MemoryBudget& budget) { state_->bands.emplace(budget); }

void ImageJob::process(Backend& backend) {
    try {
        render(backend);
    } catch (...) {
        state_->bands->abandon();
        throw;
    }
    state_->rendered = std::chrono::steady_clock::now();
    state_->bands->finish();  // publishes `rendered` to the writer
}

void ImageJob::triangulateSamples(Backend& backend) {
    try {
        if (state_->merged) {
            state_->samples = triangulateMerged(*state_->merged, state_->frame, backend);
            state_->input = PackedImage(std::move(state_->merged->values));
            state_->merged.reset();
        } else if (state_->known) {
            const Image& header = state_->input.header();
            state_->samples =
                backend.delaunayPixels(header.width, header.height, state_->known->idsIn({0, 0, header.width, header.height}));
            state_->known.reset();
        } else {
            return;
        }
        report_.delaunay_on_device = backend.lastDelaunayOnDevice();
    } catch (const UserError& error) {
        throw UserError(inputName(task_.input) + ": " + error.what());
    }
}

uint32_t ImageJob::sampledTileSide(const Backend& backend) const {
    // A mesh file is of the whole triangulation, and so is a simplification (its collapses
    // reach across any tile's crop).
    if (!task_.mesh.empty() || settings_.simplifies()) return 0;
    if (state_->known) {
        const Image& header = state_->input.header();
        const uint32_t side = settings_.tile ? settings_.tile
                                             : automaticTileSide(backend, header.width, header.height, header.channels,
                                                                 kDefaultOverlap, false);
        return side >= std::max(header.width, header.height) ? 0 : side;
    }
    if (!state_->merged) return 0;
    const Frame frame = state_->frame;
    const uint32_t largest = std::max(frame.width, frame.height);
    if (settings_.tile) return settings_.tile >= largest ? 0 : settings_.tile;
    // In one piece while the mesh and the whole output fit, as upscaleFromSamples checks.
    const Image& values = state_->merged->values;
    const OutputSize out = report_.out;
    const uint64_t output_bytes = uint64_t(out.width) * out.height * values.channels * sizeof(float);
    if (untiledMemoryProblem(backend, values.width, values.height, values.channels, output_bytes).empty()) return 0;
    // Crops holding about as many points as automatic tiling's crops of an image hold pixels:
    // sides scaled by the square root of the pixels a point, in steps of kMinTileSide.
    const uint32_t overlap = kPointTileOverlap;
    const uint32_t pixel_side = automaticTileSide(backend, frame.width, frame.height, values.channels, overlap, false);
    const uint64_t points = state_->merged->places.empty() ? state_->merged->pixel_ids.size() : values.width;
    const double crop_side = double(pixel_side ? pixel_side + 2 * overlap : largest) *
                             std::sqrt(double(frame.width) * frame.height / double(points));
    const double side = std::max(0.0, crop_side - 2 * overlap);
    // Whole frames at once where the crop would hold it: tiles still keep the output in bands.
    return uint32_t(std::clamp(std::floor(side / kMinTileSide) * kMinTileSide, double(kMinTileSide), double(largest)));
}

void ImageJob::keepPointsForTiles() {
    SampleSet& merged = *state_->merged;
    const Frame frame = state_->frame;
    if (!merged.places.empty()) {
        Image header;
        header.width = frame.width;
        header.height = frame.height;
        header.channels = merged.values.channels;
        header.sample_type = merged.values.sample_type;
        header.metadata = merged.values.metadata;
        state_->known_points.emplace(frame.width, frame.height, merged.places, merged.values);
        state_->input = PackedImage(std::move(header));
    } else {
        // Points on pixel centres, as a mask's known pixels of the frame-sized values.
        std::vector<uint8_t> bytes(size_t(frame.width) * frame.height, 0);
        for (uint32_t id : merged.pixel_ids) bytes[id] = 1;
        state_->known.emplace(frame.width, frame.height, std::move(bytes));
        state_->input = PackedImage(std::move(merged.values));
    }
    state_->merged.reset();
}

void ImageJob::render(Backend& backend) {
    const uint32_t sample_tile = sampledTileSide(backend);
    // Building the mesh counts as optimizing's (time-comp), as the grid's does; tiles of
    // samples triangulate theirs as they go.
    const auto triangulating = std::chrono::steady_clock::now();
    if (sample_tile) {
        if (state_->merged) keepPointsForTiles();
        if (state_->known) state_->known->measureHoles();
        else state_->known_points->measureHoles();
    } else {
        triangulateSamples(backend);
    }
    report_.times.comp_s += secondsSince(triangulating);
    const bool sampled = state_->samples || sample_tile;
    const OutputSize out = report_.out;
    const Image& header = state_->input.header();
    const size_t row_floats = size_t(out.width) * header.channels;
    auto sink = [&](OutputRows&& rows) {
        const size_t bytes = rows.bytes(row_floats);
        state_->bands->send(std::move(rows), bytes);
    };
    // Time spent in each phase, for --stats: optimize (with building and uploading each
    // tile's mesh), reconstruct and render.
    auto mark = std::chrono::steady_clock::now();
    TilePhase phase = TilePhase::Optimize;
    auto timeOf = [&](TilePhase p) -> double& {
        return p == TilePhase::Optimize      ? report_.times.comp_s
               : p == TilePhase::Reconstruct ? report_.times.reconstruct_s
                                             : report_.times.final_s;
    };
    // The note is for tiles that memory asks for; an image that fits goes in tiles on several
    // threads for speed (kParallelTileSide), which needs no note.
    const bool fits_whole = !sampled && automaticTileSide(backend, header.width, header.height, header.channels,
                                                          kDefaultOverlap, settings_.reconstruct == "consistent") == 0;
    bool told_tiles = false;
    auto on_step = [&](const TileStep& step) {
        timeOf(phase) += secondsSince(mark);
        mark = std::chrono::steady_clock::now();
        phase = step.phase;
        // Progress shows the reconstruction as part of optimizing: both shape the surface.
        if (phase == TilePhase::Reconstruct) return;
        reporter_.stage(index_, task_.input, phase == TilePhase::Render ? Stage::Render : Stage::Optimize, step.tile,
                        step.tiles);
        if (step.tiles > 1 && !fits_whole && !told_tiles && !settings_.tile) {
            reporter_.notice(task_.input, inputName(task_.input) + ": larger than the backend's memory in one piece; " +
                                              "processed in " + std::to_string(step.tiles) + " tiles");
            told_tiles = true;
        }
    };
    std::optional<StitchedMesh> mesh;  // the tiles' meshes, for --mesh
    if (!task_.mesh.empty() && !sampled) mesh.emplace(header.width, header.height);
    std::optional<Mesh> sample_mesh;  // the optimised sample mesh, for --mesh
    try {
        TileOptions options;
        options.tile = settings_.tile;
        options.reconstruct = settings_.reconstruct == "consistent";
        options.kernel = assumedKernel();
        if (options.reconstruct && !sampled && !settings_.simplifies()) report_.assumed = options.kernel;
        options.fallback = settings_.fallsBack();
        options.mesh = mesh ? &*mesh : nullptr;
        options.code_bits = state_->writer->codeBits();
        // The default surface is the consistent one; where it cannot apply, say so rather than
        // change it without a word (a --reconstruct consistent given here was refused).
        if (options.reconstruct && (sampled || settings_.simplifies()))
            reporter_.notice(task_.input, inputName(task_.input) + ": rendered with the linear surface (the consistent "
                                              "one, the default, needs " +
                                              (sampled ? "every pixel's value)" : "the full mesh)"));
        if (sample_tile) {
            options.tile = sample_tile;
            if (!state_->known) options.overlap = kPointTileOverlap;
            options.reconstruct = options.fallback = false;
            options.known = state_->known ? static_cast<const KnownSamples*>(&*state_->known) : &*state_->known_points;
            report_.stats = upscaleRows(backend, state_->input, out, options, sink, on_step);
            report_.delaunay_on_device = backend.lastDelaunayOnDevice();
            state_->known.reset();
            state_->known_points.reset();
        } else if (state_->samples) {
            if (!task_.mesh.empty()) sample_mesh.emplace();
            std::optional<SampleSimplification> simplification;
            if (settings_.simplifies()) {
                simplification.emplace();
                simplification->fraction = settings_.simplify;
                simplification->max_error = settings_.max_error;
            }
            report_.stats = upscaleFromSamples(backend, inputFloats(), std::move(*state_->samples), out, sink, on_step,
                                               sample_mesh ? &*sample_mesh : nullptr,
                                               simplification ? &*simplification : nullptr);
            state_->samples.reset();
            if (simplification) {  // the mesh file's colours are the kept vertices'
                report_.simplify = simplification->stats;
                state_->input = PackedImage(std::move(simplification->values));
            }
        } else if (settings_.simplifies()) {
            SimplifiedUpscale simplified = upscaleSimplified(backend, inputFloats(), out, settings_.simplify,
                                                             settings_.max_error, options, sink, on_step);
            report_.stats = simplified.optimize;
            report_.simplify = simplified.simplify;
            if (!simplified.values.pixels.empty())  // the mesh file's colours (none when tiled); the input is not read again
                state_->input = PackedImage(std::move(simplified.values));
        } else
            report_.stats = upscaleRows(backend, state_->input, out, options, sink, on_step);
    } catch (const InputError&) {
        throw;  // it names the input
    } catch (const UserError& error) {
        throw UserError(inputName(task_.input) + ": " + error.what());
    }
    timeOf(phase) += secondsSince(mark);
    if (mesh) writeTiledMesh(mesh->take(), mesh->takePositions());
    if (sample_mesh) {
        // A point file's frame, else the image's.
        const OutputSize frame = state_->frame.width ? OutputSize{state_->frame.width, state_->frame.height}
                                                     : OutputSize{header.width, header.height};
        writeMesh(indexedSampleMeshOf(*sample_mesh, inputFloats(), frame, out, settings_.mesh_height), frame,
                  "; the known samples' hull only: outside it the image takes the nearest rendered pixel");
    }
    state_->input.release();  // the next image may need the memory
}

void ImageJob::writeTiledMesh(std::vector<uint32_t> triangles, std::vector<Position> positions) {
    const Image& image = inputFloats();
    if (std::string problem = StitchedMesh::check(triangles, image.width, image.height, positions); !problem.empty())
        throw UserError(task_.mesh + ": the tiles' meshes do not join (" + problem +
                        "); a larger --tile, or none, avoids it");
    writeMesh(indexedMeshOf(triangles, positions, image, report_.out, settings_.mesh_height),
              {image.width, image.height}, "");
}

void ImageJob::writeMesh(const IndexedMesh& indexed, OutputSize frame, const std::string& coverage) {
    const Image& image = inputFloats();
    const OutputSize out = report_.out;
    char details[256];
    std::snprintf(details, sizeof(details),
                  "sx = %.9g, sy = %.9g; y up in PLY and OBJ (y = %u - that), down in SVG; colours straight, %s "
                  "samples; z = luma * %.9g",
                  double(out.width) / frame.width, double(out.height) / frame.height, out.height,
                  sampleTypeName(image.sample_type), settings_.mesh_height);
    const std::string comment = std::string("ddtup ") + DDTUP_VERSION + ": the optimised DDT mesh of " +
                                inputName(task_.input) + " for a " + std::to_string(out.width) + "x" +
                                std::to_string(out.height) + " output; x, y in output pixels, the vertex at input " +
                                "position (x, y) (pixel centres at integers) at ((x + 0.5) sx, (y + 0.5) sy) from the top left; " + details +
                                coverage;
    writeMeshFile(task_.mesh, indexed, comment);
}

bool ImageJob::write() {
    try {
        while (std::optional<Band> band = state_->bands->receive()) {
            const OutputRows& rows = band->rows;
            if (!rows.codes8.empty())
                state_->writer->writeCodes(rows.y_begin, rows.y_end, rows.codes8.data());
            else if (!rows.codes16.empty())
                state_->writer->writeCodes(rows.y_begin, rows.y_end, rows.codes16.data());
            else
                state_->writer->writeRows(rows.y_begin, rows.y_end, rows.floats.get());
        }
    } catch (...) {
        state_->bands->refuse();
        throw;
    }
    if (!state_->bands->complete()) return false;
    // The last rows are encoded: what is left is finishing and renaming the file.
    reporter_.stage(index_, task_.input, Stage::Write);
    state_->writer->commit();
    // Encoding overlaps rendering, which process() timed: add what came after it.
    report_.times.final_s += secondsSince(state_->rendered);
    for (const std::string& note : state_->writer->notes()) reporter_.notice(task_.input, note);
    reporter_.done(index_, task_, report_.out, secondsSince(state_->started));
    return true;
}

}  // namespace ddt
