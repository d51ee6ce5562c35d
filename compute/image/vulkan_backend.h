// The Vulkan backend: the paper's parallel Lawson optimisation (Sec. 3–5) in compute
// kernels over the edge arrays of core/image/mesh.h, and rendering on the device, with the
// consistent reconstruction and the convolution fallback. Each iteration runs the same steps
// as the paper: candidates, accept/reject rounds (select), flip.
#pragma once

#include <functional>
#include <memory>
#include <string>
#include <vector>

#include "backend.h"
#include "context.h"
#include "flip_rule.h"

namespace ddt {

// Where the backend runs the Delaunay triangulations of samples (--delaunay; Backend::delaunayPixels).
enum class DelaunayPlace {
    host,              // the serial one: on a CPU device it is the faster one
    device,            // the device's; too many points for it is the user's error
    device_where_fits, // the device's, the host's for more points than its texel buffers hold
};

struct VulkanOptions {
    std::string rule = kDefaultFlipRule;
    CostFunction cost = CostFunction::sederberg;  // the cost the flips lower (core/image/cost.h)
    bool active_set = true;  // after the first iteration, test only edges a flip may have changed
    int device_index = -1;   // -1: choose
    bool validation = false;
    uint32_t max_iterations = 100000;  // safety caps, reported in OptimizeStats::capped
    uint32_t max_rounds = 100000;      // accept/reject rounds per iteration
    bool profile = false;              // time every dispatch (kernelTimes); costs a little
    DelaunayPlace delaunay = DelaunayPlace::host;
};

// Device time spent in one kernel, summed over an optimisation (profile on).
struct KernelTime {
    uint64_t dispatches = 0;
    double ms = 0.0;
    std::vector<double> iteration_ms;  // the same split by iteration of the optimisations (0 first)
};

// One iteration's decisions, just before its flips (for tests).
struct IterationSnapshot {
    uint32_t iteration = 0;
    uint32_t rounds = 0;
    Mesh mesh;                             // before the flips
    std::vector<uint32_t> candidates;      // sorted
    std::vector<double> candidate_gains;   // gains from the candidate step, same order
    std::vector<uint32_t> accepted;        // sorted
    std::vector<uint32_t> undecided;       // left undecided (local-max, or a round cap)
};

class VulkanBackend final : public Backend {
public:
    explicit VulkanBackend(const VulkanOptions& options);
    ~VulkanBackend() override;

    void prepare(const Image& image) override;
    void prepareFrom(const Image& image, Mesh initial) override;
    // On the device where VulkanOptions::delaunay (or setDelaunayPlace, once the device is
    // known) says so (backend_delaunay.cpp).
    void setDelaunayPlace(DelaunayPlace place);
    Mesh delaunayPixels(uint32_t width, uint32_t height, const std::vector<uint32_t>& pixel_ids) override;
    Mesh delaunayPoints(uint32_t width, uint32_t height, const std::vector<Position>& points) override;
    bool lastDelaunayOnDevice() const override;
    OptimizeStats optimize() override;
    void reconstruct(const DegradationModel& model) override;
    // The surface's weights made on the device; renderWindow blends each band there (device_fallback.cpp).
    void addFallback(float grain_share) override;
    void renderWindow(const RenderWindow& window, float* rows) override;
    Mesh mesh() override;
    ParallelSimplifyStats simplify(Mesh& mesh, Image& values, uint32_t target, double max_error) override;
    uint64_t memoryNeeded(uint32_t width, uint32_t height, uint32_t channels, bool reconstruction) const override;
    uint64_t memoryAvailable() const override;
    const Image& preparedImage() const override;

    // Like optimize(), one submit per step, showing each iteration before its flips.
    OptimizeStats optimizeStepwise(const std::function<void(const IterationSnapshot&)>& inspect);
    // The mesh cost, and every edge's cost, as the kernels compute them.
    double deviceMeshCost();
    std::vector<double> deviceEdgeCosts();
    // Per-kernel device time of the optimisations so far (VulkanOptions::profile).
    std::vector<std::pair<std::string, KernelTime>> kernelTimes() const;
    const DeviceInfo& device() const;
    uint32_t validationMessages() const;

private:
    struct State;
    std::unique_ptr<State> state_;
};

std::unique_ptr<Backend> makeVulkanBackend(const VulkanOptions& options);

}  // namespace ddt
