// The consistent reconstruction on the device: the initial surface and the SART steps of
// compute/image/reconstruct/, over the supersampled grid as a window of the renderer.
#include <algorithm>

#include "reconstruct/surface_passes.h"
#include "vulkan_backend_state.h"

namespace ddt {

void VulkanBackend::reconstruct(const DegradationModel& model) {
    static_assert(kSupersamplingFactor == kSupersampling && kSartRelaxation == kRelaxation,
                  "glsl/layout.h follows core/image/reconstruct.h");
    State& s = *state_;
    VulkanContext& c = *s.context;
    s.checkMemory(s.width, s.height, true);
    if (s.spans.empty()) s.computeRowSpans();
    // The taps are a few numbers from core's own formula: computed here and uploaded.
    const std::vector<float> taps_x = degradationTaps(model.kernel, model.width_x),
                             taps_y = degradationTaps(model.kernel, model.width_y);
    std::vector<float> taps = taps_x;
    taps.insert(taps.end(), taps_y.begin(), taps_y.end());
    destroySurfaceBuffers(c, s.surface);
    s.surface = createSurfaceBuffers(c, s.width, s.height, s.edge_count, uint32_t(taps.size()));
    s.writeDescriptors();
    uploadToBuffer(c, s.surface.taps, taps.data(), taps.size() * 4);

    // The supersampled grid as a window of the renderer: an output of 3w × 3h, crop 0.
    const RenderWindow grid = wholeRows(s.width, s.height, {kSupersampling * s.width, kSupersampling * s.height}, 0,
                                        kSupersampling * s.height);
    const State::PartShape part = s.partShape(grid);
    CommandBatch batch(c);
    SurfacePassJob job;
    job.commands = batch.buffer();
    job.kernels = &s.kernels.reconstruction;
    job.bindings = s.bindings();
    job.push = s.push();
    job.push.taps_x_radius = uint32_t(taps_x.size() / 2);
    job.push.taps_y_radius = uint32_t(taps_y.size() / 2);
    const SampleType type = s.image->sample_type;
    job.push.integer_samples = boundedToUnit(type) ? 1 : 0;
    job.push.quantisation_tolerance = quantisationTolerance(type);
    job.pixels = &s.pixels;
    job.triangle_pass = [&](VkPipeline kernel) {
        for (uint32_t y = 0; y < grid.y_end; y += part.rows)
            for (uint32_t x = 0; x < grid.x_end; x += part.cols)
                s.recordTrianglePart(batch.buffer(), kernel, grid, y, std::min(grid.y_end, y + part.rows), x,
                                     std::min(grid.x_end, x + part.cols));
    };
    recordInitialSurface(job, s.surface);
    if (!model.identity()) recordSartSteps(job, s.surface, kReconstructIterations);
    batch.submitAndWait();
    s.quadratic = true;
}

}  // namespace ddt
