// The CPU backend: core's mesh and serial Lawson sweeps (the reference), the reconstruction
// and the rasteriser on the host, the last two on the shared thread pool.
#include <algorithm>
#include <optional>
#include <stdexcept>

#include "backend.h"
#include "convolution_fallback.h"
#include "parallel.h"
#include "physical_memory.h"

namespace ddt {

namespace {

// What the CPU backend may hold at once: by memoryNeeded's estimate enough for a 512² RGB
// input's consistent reconstruction and fallback in one piece (about 149 MB, with the 1/8
// that tiling keeps spare), which a run on one thread keeps. On more threads every image
// beyond 256 pixels goes in 256-pixel tiles, one per thread at a time (kParallelTileSide,
// app/tiled_upscale.h): a 512² PNG to ×8 and a 1600×1112 JPEG to ×4 peak at 79 and 90 MiB
// resident (`/usr/bin/time`), the idle process 7 MB.
const uint64_t kWorkingMemory = uint64_t(160) << 20;

// A surface taken out of the backend with its triangle tables: it owns what the renderer reads.
class TakenSurface final : public HostSurface {
public:
    TakenSurface(Surface surface, MeshRenderer&& tables, std::optional<ConvolutionFallback> fallback)
        : surface_(std::move(surface)),
          renderer_(std::move(tables), surface_.values, surface_.bubbles.empty() ? nullptr : surface_.bubbles.data()),
          fallback_(std::move(fallback)) {}
    TakenSurface(const TakenSurface&) = delete;  // renderer_ refers to surface_
    TakenSurface& operator=(const TakenSurface&) = delete;

    void renderWindow(const RenderWindow& window, float* rows, size_t row_stride) const override {
        renderer_.renderWindow(window, rows, row_stride);
        if (fallback_) fallback_->blend(window, rows, row_stride);
    }
    size_t bytes() const override {
        return (surface_.values.pixels.capacity() + surface_.bubbles.capacity()) * sizeof(float) + renderer_.bytes() +
               (fallback_ ? fallback_->bytes() : 0);
    }

private:
    Surface surface_;
    MeshRenderer renderer_;
    std::optional<ConvolutionFallback> fallback_;
};

class CpuBackend final : public Backend {
public:
    CpuBackend(const LawsonOptions& options, uint64_t memory_limit)
        : options_(options), memory_limit_(memory_limit ? memory_limit : physicalMemory() / 2) {}

    void prepare(const Image& image) override { prepareFrom(image, buildGridMesh(image.width, image.height)); }

    // `image` is a point mesh's n × 1 values image, not a grid, where `initial` has positions.
    void prepareFrom(const Image& image, Mesh initial) override {
        image_ = &image;
        renderer_.reset();
        surface_.reset();
        fallback_.reset();
        field_ = costFieldOf(image);
        mesh_ = std::move(initial);
        mesh_released_ = false;
    }

    OptimizeStats optimize() override {
        requireMesh();
        renderer_.reset();
        surface_.reset();
        return optimizeSerial(mesh_, field_, options_);
    }

    void reconstruct(const DegradationModel& model) override {
        requireMesh();
        // One set of triangle tables serves the reconstruction, then renders the result.
        MeshRenderer locator = renderer_ ? MeshRenderer(std::move(*renderer_), *image_) : MeshRenderer(mesh_, *image_);
        renderer_.reset();
        surface_.reset();
        // The reconstruction is the mesh's last use: rendering reads the triangle tables.
        surface_ = reconstructSurface(std::move(mesh_), *image_, model, locator.triangles());
        mesh_released_ = true;
        renderer_.emplace(std::move(locator), surface_->values, surface_->bubbles.data());
    }

    void addFallback(float grain_share) override { fallback_.emplace(*image_, grain_share); }

    void renderWindow(const RenderWindow& window, float* rows) override {
        BandFinish blend;
        if (fallback_) blend = [&](const RenderWindow& band, float* band_rows) { fallback_->blend(band, band_rows); };
        renderInParallel(renderer(), window, image_->channels, rows, blend);
    }

    bool handsOverSurface() const override { return true; }

    std::unique_ptr<HostSurface> takeSurface() override {
        renderer();  // builds the triangle tables if reconstruct did not
        // The plain surface is the prepared image's values, which its caller may drop: copied.
        Surface surface = surface_ ? std::move(*surface_) : Surface{*image_, {}};
        auto taken = std::make_unique<TakenSurface>(std::move(surface), std::move(*renderer_), std::move(fallback_));
        renderer_.reset();
        surface_.reset();
        fallback_.reset();
        mesh_ = {};
        mesh_released_ = true;
        field_ = {};
        return taken;
    }

    Mesh mesh() override {
        requireMesh();
        return mesh_;
    }
    Mesh takeMesh() override {
        requireMesh();
        renderer_.reset();
        surface_.reset();
        fallback_.reset();
        mesh_released_ = true;
        return std::move(mesh_);
    }
    ParallelSimplifyStats simplify(Mesh& mesh, Image& values, uint32_t target, double max_error) override {
        ParallelSimplifyStats stats;
        static_cast<SimplifyStats&>(stats) = simplifySerial(mesh, values, target, max_error);
        return stats;
    }
    std::unique_ptr<Backend> twin() const override { return std::make_unique<CpuBackend>(options_, memory_limit_); }
    const Image& preparedImage() const override { return *image_; }

    // A rough count of the host arrays at their peak, per vertex. Optimizing: the mesh's two
    // 32-byte records per edge and the sweeps' state (16 bytes per edge, about three edges per
    // vertex), the renderer's triangle list (about two 24-byte triangles), the cost field (4)
    // and the input (4 per channel). Reconstructing (core/image/reconstruct.cpp), after the sweeps
    // and the mesh's neighbour records are released: the triangle list, the mesh's 16-byte
    // edge records (the lattice's now), the lattice's lists of each vertex's shares (32), the
    // cost field, each unknown's step scale (one float per vertex and per edge, 16), and per
    // channel 92 bytes of floats (the supersamples, 36; the edges' shares of their vertices'
    // projections, 24; the vertex values and bubbles, 16; the residuals and the bounds, 12;
    // the input). The convolution fallback, with either surface, adds its copy of the input and
    // its weights, and while it makes them the structure tensor and its pass along x, three
    // floats per pixel each (4 · channels + 4 + 24).
    uint64_t memoryNeeded(uint32_t width, uint32_t height, uint32_t channels, bool reconstruction) const override {
        const uint64_t vertices = uint64_t(width) * height;
        const uint64_t fallback = 4 * channels + 4 + 24;
        const uint64_t optimizing = 3 * (32 + 16) + 2 * 24 + 4 + 4 * channels + fallback;
        const uint64_t reconstructing = 2 * 24 + 3 * 16 + 32 + 4 + 16 + 92 * channels + fallback;
        return vertices * (reconstruction ? std::max(optimizing, reconstructing) : optimizing);
    }

    // A fixed working set, within the limit: larger inputs go in tiles (app/tiled_upscale.h),
    // so the process's size does not grow with the input.
    uint64_t memoryAvailable() const override { return std::min(kWorkingMemory, memory_limit_); }
    uint64_t memoryLimit() const override { return memory_limit_; }
    uint64_t simplifyMemoryNeeded(uint32_t width, uint32_t height, uint32_t channels) const override {
        return uint64_t(width) * height * simplifyBytesPerPixel(channels);
    }

private:
    void requireMesh() const {
        if (mesh_released_) throw std::logic_error("CpuBackend: the mesh was given up (reconstruct, takeSurface); prepare again");
    }

    // The renderer of the current surface, built on first use.
    const MeshRenderer& renderer() {
        if (!renderer_) {
            requireMesh();
            if (surface_)
                renderer_.emplace(mesh_, surface_->values, surface_->bubbles.data());
            else
                renderer_.emplace(mesh_, *image_);
        }
        return *renderer_;
    }

    LawsonOptions options_;
    uint64_t memory_limit_;
    const Image* image_ = nullptr;
    CostField field_;
    Mesh mesh_;
    bool mesh_released_ = false;  // by reconstruct
    std::optional<Surface> surface_;  // set by reconstruct
    std::optional<MeshRenderer> renderer_;
    std::optional<ConvolutionFallback> fallback_;  // set by addFallback
};

}  // namespace

std::unique_ptr<Backend> makeCpuBackend(const LawsonOptions& options, uint64_t memory_limit) {
    return std::make_unique<CpuBackend>(options, memory_limit);
}

}  // namespace ddt
