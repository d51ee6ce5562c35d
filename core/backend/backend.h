// A DDT backend runs the three stages the paper times: prepare (build the initial mesh,
// upload), optimize, render, and between the last two, optionally, the consistent
// reconstruction. The serial CPU reference and the Vulkan backend implement it
// with the same step names. Inputs too large for a backend's memory are split into tiles by
// app/tiled_upscale.h, which asks the backend what an input needs and what it has.
#pragma once

#include <memory>
#include <string>
#include <vector>

#include "cost.h"
#include "image.h"
#include "lawson.h"
#include "mesh.h"
#include "parallel_simplify.h"
#include "reconstruct.h"
#include "render.h"

namespace ddt {

// A tile's surface handed over by a backend that renders on the host, able to render windows
// on its own (as Backend::renderWindow does), so that the backend can take the next tile
// while this one waits for its rows to be rendered.
class HostSurface {
public:
    virtual ~HostSurface() = default;
    // Renders `window` on the calling thread into `rows`, `row_stride` floats from one row's
    // start to the next: a strip's tiles render side by side into one band, in parallel.
    virtual void renderWindow(const RenderWindow& window, float* rows, size_t row_stride) const = 0;
    // The bytes it holds: a tiler keeps a strip's surfaces only while they are smaller than the
    // strip's output (app/tiled_upscale.cpp).
    virtual size_t bytes() const = 0;
};

class Backend {
public:
    virtual ~Backend() = default;
    // Builds the initial triangulation of `image` (which must outlive the backend's use).
    virtual void prepare(const Image& image) = 0;
    // Like prepare, from `initial` instead of the grid's triangulation: a triangulation of some
    // of the image's pixels (core/delaunay/, the known ones of a mask), over which optimize
    // runs the same flips. renderWindow and reconstruct need the grid's mesh; such a mesh is
    // rendered on the host from mesh() (core/delaunay/sampled_render.h).
    virtual void prepareFrom(const Image& image, Mesh initial) = 0;
    // The Delaunay triangulations prepareFrom takes (core/delaunay/delaunay.h): of some of a
    // width × height grid's pixels (a mask's known ones), or of points (a point file's). The
    // serial one on the host here; the Vulkan backend runs them on its device where --delaunay
    // says so (compute/delaunay/device_delaunay.h), with the same records.
    virtual Mesh delaunayPixels(uint32_t width, uint32_t height, const std::vector<uint32_t>& pixel_ids);
    virtual Mesh delaunayPoints(uint32_t width, uint32_t height, const std::vector<Position>& points);
    // Whether the last of those two ran on a device (for --stats).
    virtual bool lastDelaunayOnDevice() const { return false; }
    virtual OptimizeStats optimize() = 0;
    // Replaces plain DDT's surface (the input values, linear on each triangle) by the
    // consistent reconstruction under `model` (core/image/reconstruct.h); renderWindow then renders
    // it. prepare returns to the plain surface. The CPU backend gives up its mesh here to
    // lower its peak memory: after reconstruct, only renderWindow and takeSurface until the
    // next prepare.
    virtual void reconstruct(const DegradationModel& model) = 0;
    // Blends the surface towards a Lanczos3 convolution of the prepared image where it has
    // little contrast (core/image/convolution_fallback.h), in renderWindow and in a surface
    // taken over, until the next prepare. After optimize and reconstruct. `grain_share` is
    // grainShareFor the surface's assumed downscale.
    virtual void addFallback(float grain_share) = 0;
    // Renders `window` (see core/image/render.h) of the prepared image, which is the crop at
    // (window.crop_x, window.crop_y) of the whole input: window.width() × channels floats per row.
    virtual void renderWindow(const RenderWindow& window, float* rows) = 0;
    // Whether the backend renders on the host and hands its surfaces over (takeSurface).
    virtual bool handsOverSurface() const { return false; }
    // The surface renderWindow would render (after optimize and, if wanted, reconstruct),
    // taken out of the backend: the next prepare starts afresh. Null unless handsOverSurface().
    virtual std::unique_ptr<HostSurface> takeSurface() { return nullptr; }
    // The current mesh (for tests and checks).
    virtual Mesh mesh() = 0;
    // The current mesh, taken out of the backend, for a caller that goes on without it (it
    // renders or simplifies the mesh itself): a backend that holds it on the host gives it up
    // instead of copying it, and must be prepared again.
    virtual Mesh takeMesh() { return mesh(); }
    // Simplifies `mesh` (this backend's optimized mesh, from mesh()) to `target` vertices or as
    // far as `max_error` allows, `values` holding the vertices' colours (greedy_simplify.h).
    // The CPU backend runs the serial greedy reference, on a CPU both faster and closer to
    // Garland and Heckbert's order than the parallel rule; a device runs the parallel rule
    // (core/simplify/parallel_simplify.h) in its kernels. rounds: 0 for the serial one.
    virtual ParallelSimplifyStats simplify(Mesh& mesh, Image& values, uint32_t target, double max_error) = 0;

    // Bytes prepare, optimize, render and, with `reconstruction`, reconstruct need for a
    // width × height input (UINT64_MAX when one of its buffers exceeds a per-buffer limit of
    // the device), and the bytes available.
    virtual uint64_t memoryNeeded(uint32_t width, uint32_t height, uint32_t channels, bool reconstruction) const = 0;
    virtual uint64_t memoryAvailable() const = 0;
    // The most a job that cannot be tiled (a mask's, a simplification's) may hold: the device's
    // memory, or on the CPU backend the run's budget rather than the working set tiles are sized for.
    virtual uint64_t memoryLimit() const { return memoryAvailable(); }
    // What simplify holds beyond memoryNeeded for a width × height input, in the memory
    // memoryLimit counts: the CPU backend's serial simplification (greedy_simplify.h); 0 where
    // the simplification's buffers are the device's own, which it checks as it allocates them.
    virtual uint64_t simplifyMemoryNeeded(uint32_t /*width*/, uint32_t /*height*/, uint32_t /*channels*/) const {
        return 0;
    }

    // The image given to prepare.
    virtual const Image& preparedImage() const = 0;

    // Another backend of the same kind that can work at the same time as this one, so that
    // tiles are processed in parallel (the CPU backend); null where one device does the work.
    virtual std::unique_ptr<Backend> twin() const { return nullptr; }

    // Renders output rows [y_begin, y_end) of an untiled input (out.width × channels floats per row).
    void renderRows(OutputSize out, uint32_t y_begin, uint32_t y_end, float* rows) {
        const Image& image = preparedImage();
        renderWindow(wholeRows(image.width, image.height, out, y_begin, y_end), rows);
    }
};

// The serial reference; `options` choose the cost (LawsonOptions::cost) and the sweep cap.
// `memory_limit`: the bytes it may hold at once (memoryLimit); 0 = half the machine's memory.
std::unique_ptr<Backend> makeCpuBackend(const LawsonOptions& options = {}, uint64_t memory_limit = 0);

}  // namespace ddt
