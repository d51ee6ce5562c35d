// A strip of tiles on a backend that hands its surfaces over (app/tiled_upscale.cpp): each
// tile's surface is either kept until the strip is shaped and then rendered band by band, or
// rendered at once into the strip's rows and dropped, whichever holds fewer bytes. Both ways
// give the same rows, and the surfaces alive at once show which way was taken.
#include <catch2/catch.hpp>

#include <algorithm>
#include <atomic>
#include <functional>
#include <memory>
#include <optional>

#include "backend.h"
#include "parallel.h"
#include "sample_quantise.h"
#include "test_support.h"
#include "tiled_upscale.h"

namespace {

using namespace ddt;

// The surfaces alive now and at most, and made so far, over a backend and its twins.
struct SurfaceCount {
    std::atomic<int> alive = 0, most = 0, made = 0;
};

// The bytes the n-th surface made reports: nullopt for its own.
using BytesOf = std::function<std::optional<size_t>(int n)>;

// A surface that counts itself and reports `bytes` instead of its own, if given.
class CountedSurface final : public HostSurface {
public:
    CountedSurface(std::unique_ptr<HostSurface> surface, SurfaceCount& count, std::optional<size_t> bytes)
        : surface_(std::move(surface)), count_(count), bytes_(bytes) {
        const int alive = ++count_.alive;
        int most = count_.most;
        while (alive > most && !count_.most.compare_exchange_weak(most, alive)) {
        }
    }
    ~CountedSurface() override { --count_.alive; }
    void renderWindow(const RenderWindow& window, float* rows, size_t row_stride) const override {
        surface_->renderWindow(window, rows, row_stride);
    }
    size_t bytes() const override { return bytes_ ? *bytes_ : surface_->bytes(); }

private:
    std::unique_ptr<HostSurface> surface_;
    SurfaceCount& count_;
    std::optional<size_t> bytes_;
};

// The CPU backend, its surfaces counted and their bytes as `bytes_of` says.
class CountingBackend final : public Backend {
public:
    CountingBackend(SurfaceCount& count, BytesOf bytes_of)
        : cpu_(makeCpuBackend()), count_(count), bytes_of_(std::move(bytes_of)) {}

    void prepare(const Image& image) override { cpu_->prepare(image); }
    void prepareFrom(const Image& image, Mesh initial) override { cpu_->prepareFrom(image, std::move(initial)); }
    OptimizeStats optimize() override { return cpu_->optimize(); }
    void reconstruct(const DegradationModel& model) override { cpu_->reconstruct(model); }
    void addFallback(float grain_share) override { cpu_->addFallback(grain_share); }
    void renderWindow(const RenderWindow& window, float* rows) override { cpu_->renderWindow(window, rows); }
    bool handsOverSurface() const override { return true; }
    std::unique_ptr<HostSurface> takeSurface() override {
        return std::make_unique<CountedSurface>(cpu_->takeSurface(), count_, bytes_of_(count_.made++));
    }
    Mesh mesh() override { return cpu_->mesh(); }
    ParallelSimplifyStats simplify(Mesh& mesh, Image& values, uint32_t target, double max_error) override {
        return cpu_->simplify(mesh, values, target, max_error);
    }
    uint64_t memoryNeeded(uint32_t width, uint32_t height, uint32_t channels, bool reconstruction) const override {
        return cpu_->memoryNeeded(width, height, channels, reconstruction);
    }
    uint64_t memoryAvailable() const override { return cpu_->memoryAvailable(); }
    const Image& preparedImage() const override { return cpu_->preparedImage(); }
    std::unique_ptr<Backend> twin() const override { return std::make_unique<CountingBackend>(count_, bytes_of_); }

private:
    std::unique_ptr<Backend> cpu_;
    SurfaceCount& count_;
    BytesOf bytes_of_;
};

struct StripRun {
    std::vector<float> rows;     // where they came as floats
    std::vector<uint8_t> bytes;  // where they came as 8-bit codes
    std::vector<uint16_t> words;  // or 16-bit ones
    int most_surfaces;
};

StripRun upscaleWith(const Image& image, double scale, BytesOf bytes_of, uint32_t code_bits) {
    SurfaceCount count;
    CountingBackend backend(count, std::move(bytes_of));
    const OutputSize out = scaledOutputSize(image.width, image.height, scale);
    const size_t row_floats = size_t(out.width) * image.channels;
    StripRun run{std::vector<float>(row_floats * out.height, -1.0f), std::vector<uint8_t>(row_floats * out.height),
                 std::vector<uint16_t>(row_floats * out.height), 0};
    TileOptions options;
    options.tile = 64;
    options.reconstruct = true;
    options.fallback = true;
    options.code_bits = code_bits;
    PackedImage packed(image);
    upscaleRows(backend, packed, out, options, [&](OutputRows&& rows) {
        const size_t first = rows.y_begin * row_floats;
        if (!rows.codes8.empty())
            std::copy(rows.codes8.begin(), rows.codes8.end(), run.bytes.begin() + first);
        else if (!rows.codes16.empty())
            std::copy(rows.codes16.begin(), rows.codes16.end(), run.words.begin() + first);
        else
            std::copy_n(rows.floats.get(), rows.rows() * row_floats, run.rows.begin() + first);
    });
    CHECK(count.alive == 0);
    run.most_surfaces = count.most;
    return run;
}

// Every surface reporting `bytes` (nullopt: its own).
StripRun upscaleCounted(const Image& image, double scale, std::optional<size_t> bytes, uint32_t code_bits = 0) {
    return upscaleWith(image, scale, [bytes](int) { return bytes; }, code_bits);
}

// The first surface reporting 1 byte, so that it is kept, the others a terabyte, so that the
// first strip's other tiles, and every later strip, render at once.
StripRun upscaleMixed(const Image& image, double scale, uint32_t code_bits) {
    return upscaleWith(image, scale, [](int n) { return n == 0 ? size_t(1) : size_t(1) << 40; }, code_bits);
}

// 300 × 200 in tiles of 64: strips of 5 tiles.
const int kStripTiles = 5;

TEST_CASE("strip rendering: surfaces rendered at once give the rows kept surfaces give") {
    const Image image = test::photoCrop();
    REQUIRE(image.width == 300);
    const int threads = int(std::max(1u, threadCount()));
    for (double scale : {2.0, 3.5}) {
        CAPTURE(scale);
        // Surfaces reported huge are rendered at once; reported tiny, kept for the whole strip.
        const StripRun at_once = upscaleCounted(image, scale, size_t(1) << 40);
        const StripRun kept = upscaleCounted(image, scale, size_t(1));
        CHECK(at_once.most_surfaces <= threads);
        CHECK(kept.most_surfaces == kStripTiles);
        CHECK(std::none_of(at_once.rows.begin(), at_once.rows.end(), [](float v) { return v == -1.0f; }));
        CHECK(test::samePixels(at_once.rows, kept.rows));
    }
}

// The real bytes: a 64-pixel tile's crop (96², with its overlap) holds its quadratic surface,
// triangle tables and fallback, over 100 bytes a crop pixel; its core's output at ×2 is 48
// bytes a core pixel (RGB floats), at ×8 768.
TEST_CASE("strip rendering: the measured bytes choose: at once at x2, kept at x8") {
    const Image image = test::photoCrop();
    const int threads = int(std::max(1u, threadCount()));
    CHECK(upscaleCounted(image, 2.0, std::nullopt).most_surfaces <= threads);
    CHECK(upscaleCounted(image, 8.0, std::nullopt).most_surfaces == kStripTiles);
}

// The rows as a writer of `Sample` codes makes them, row by row.
template <typename Sample>
std::vector<Sample> codesOf(const std::vector<float>& rows, size_t row_floats) {
    std::vector<Sample> codes(rows.size());
    for (size_t y = 0; y < rows.size() / row_floats; ++y)
        quantiseRow(rows.data() + y * row_floats, codes.data() + y * row_floats, row_floats);
    return codes;
}

// Kept as codes, the strip's rows go out as the codes the writer makes of the floats rendered,
// whether the tiles render at once or from their kept surfaces band by band.
TEST_CASE("strip rendering: a strip kept as 8- or 16-bit codes gives the writer the codes of its floats") {
    const Image image = test::photoCrop();
    const size_t row_floats = size_t(scaledOutputSize(image.width, image.height, 2.0).width) * image.channels;
    const StripRun floats = upscaleCounted(image, 2.0, size_t(1) << 40);
    const StripRun bytes = upscaleCounted(image, 2.0, size_t(1) << 40, 8);
    const StripRun words = upscaleCounted(image, 2.0, size_t(1) << 40, 16);
    CHECK(std::all_of(bytes.rows.begin(), bytes.rows.end(), [](float v) { return v == -1.0f; }));  // no floats came
    CHECK(bytes.bytes == codesOf<uint8_t>(floats.rows, row_floats));
    CHECK(words.words == codesOf<uint16_t>(floats.rows, row_floats));
    // Strips whose first tile's surface was measured small and kept, and the rest's large and
    // rendered at once: the kept one renders into the codes too.
    const StripRun mixed = upscaleMixed(image, 2.0, 8);
    CHECK(mixed.bytes == codesOf<uint8_t>(floats.rows, row_floats));
    // Every surface measured small: kept, and each band rendered across the tiles as codes.
    const StripRun kept_bytes = upscaleCounted(image, 2.0, size_t(1), 8);
    const StripRun kept_words = upscaleCounted(image, 2.0, size_t(1), 16);
    CHECK(kept_bytes.most_surfaces == kStripTiles);
    CHECK(std::all_of(kept_bytes.rows.begin(), kept_bytes.rows.end(), [](float v) { return v == -1.0f; }));
    CHECK(kept_bytes.bytes == codesOf<uint8_t>(floats.rows, row_floats));
    CHECK(kept_words.words == codesOf<uint16_t>(floats.rows, row_floats));
}

}  // namespace
