#include "backend_factory.h"

#include <cctype>
#include <cstdlib>
#include <filesystem>

#include "parallel.h"
#include "volume/tet_device.h"
#include "volume/tet_resample_device.h"
#include "vulkan_backend.h"

namespace ddt {

namespace {

// The first word of the device type, lower case: "discrete", "integrated", "cpu", …
std::string deviceKind(VkPhysicalDeviceType type) {
    const std::string name = deviceTypeName(type);
    std::string kind = name.substr(0, name.find(' '));
    for (char& c : kind) c = char(std::tolower(uint8_t(c)));
    return kind;
}

// Whether the machine may have a GPU for Vulkan: every one needs a kernel device node (DRM
// render nodes for Mesa's drivers and virtual GPUs, NVIDIA's own nodes, WSL's /dev/dxg).
// Without one, loading the Vulkan drivers only to list CPU devices would cost about 0.25 s
// and 50 MB (lavapipe brings LLVM) on every run. A loader pointed at drivers on purpose
// (VK_DRIVER_FILES, VK_ICD_FILENAMES) is asked anyway.
bool mayHaveGpu() {
    if (std::getenv("VK_DRIVER_FILES") || std::getenv("VK_ICD_FILENAMES")) return true;
    std::error_code error;
    for (const char* node : {"/dev/nvidiactl", "/dev/dxg"})
        if (std::filesystem::exists(node, error)) return true;
    for (const auto& entry : std::filesystem::directory_iterator("/dev/dri", error))
        if (entry.path().filename().string().starts_with("renderD")) return true;
    return false;
}

// --cost for images: Sederberg's unless named.
CostFunction costOf(const Settings& settings) {
    return settings.cost.empty() ? CostFunction::sederberg : *parseCostFunction(settings.cost);
}

ChosenBackend cpuBackend(const Settings& settings, std::string reason) {
    LawsonOptions options;
    options.cost = costOf(settings);
    return {makeCpuBackend(options, settings.memory), {"cpu", "", "", threadCount(), std::move(reason)}};
}

// --delaunay on a Vulkan backend: auto takes the device unless it is a CPU implementation,
// where the serial triangulation is the faster (bench/README.md, "Scattered samples").
DelaunayPlace delaunayPlace(const std::string& delaunay, bool cpu_device) {
    if (delaunay == "cpu") return DelaunayPlace::host;
    if (delaunay == "device") return DelaunayPlace::device;
    return cpu_device ? DelaunayPlace::host : DelaunayPlace::device_where_fits;
}

ChosenBackend vulkanBackend(const Settings& settings, int device_index, std::string reason) {
    VulkanOptions options;
    if (!settings.variant.empty()) options.rule = settings.variant;
    options.active_set = settings.active_set;
    options.cost = costOf(settings);
    options.device_index = device_index;
    auto backend = std::make_unique<VulkanBackend>(options);
    const DeviceInfo& device = backend->device();
    backend->setDelaunayPlace(delaunayPlace(settings.delaunay, device.isCpu()));
    BackendChoice choice{"vulkan", device.name, deviceKind(device.type), 0, std::move(reason)};
    return {std::move(backend), std::move(choice)};
}

}  // namespace

AutomaticDevice automaticDevice() {
    if (!mayHaveGpu()) return {-1, "this machine has no GPU device (/dev/dri/renderD*, /dev/nvidiactl)"};
    std::vector<DeviceInfo> devices;
    uint32_t best = 0;
    try {
        devices = listDevices();
        best = chooseDevice(devices, -1);
    } catch (const UserError&) {
        return {-1, "no usable Vulkan device (a GPU driver would give one)"};
    }
    const DeviceInfo& device = devices[best];
    if (device.isCpu())
        return {-1, "the only Vulkan device, " + device.name +
                        ", runs on the CPU, where the CPU backend is faster (--backend vulkan uses it anyway)"};
    return {int(best), ""};
}

ChosenBackend makeBackend(const Settings& settings) {
    if (settings.backend == "cpu") return cpuBackend(settings, "");
    if (settings.backend == "vulkan" || settings.device >= 0 || settings.delaunay == "device")
        return vulkanBackend(settings, settings.device, "");
    const AutomaticDevice device = automaticDevice();
    if (device.index < 0)
        return cpuBackend(settings, device.cpu_reason + (settings.active_set ? "" : "; --no-active-set, which applies "
                                                                                    "to the Vulkan flips, does nothing"));
    return vulkanBackend(settings, device.index, "");
}

VolumeEngine makeVolumeEngine(const Settings& settings) {
    VolumeEngine engine;
    engine.choice = {"cpu", "", "", threadCount(), ""};
    int device_index = settings.device;
    if (settings.backend == "auto" && settings.device < 0) {
        const AutomaticDevice device = automaticDevice();
        if (device.index < 0) {
            engine.choice.reason = device.cpu_reason;
            return engine;
        }
        device_index = device.index;
    } else if (settings.backend == "cpu") {
        return engine;
    }
    std::shared_ptr<VulkanContext> context = createContext({device_index, false});
    engine.choice = {"vulkan", context->info.name, deviceKind(context->info.type), 0, ""};
    engine.context = context;
    engine.optimize = [context](TetMesh& mesh, TetCostField&& field, TetWeight weight) {
        const std::string problem = tetDeviceProblem(*context, mesh.slotCount(), mesh.vertexCount(), weight);
        if (!problem.empty()) throw UserError(problem + " (a smaller --tile makes smaller bricks)");
        TetParallelOptions options;
        options.weight = weight;
        // The host's copies of the field and of the neighbours would only add to the peak.
        TetDeviceOptions device;
        device.return_neighbours = false;
        const TetParallelStats rule = optimizeTetMeshVulkan(*context, mesh, std::move(field), options, device);
        TetLawsonStats stats;
        stats.cost_before = rule.cost_before;
        stats.cost_after = rule.cost_after;
        stats.flips = rule.flips;
        stats.iterations = rule.rounds;
        stats.capped = rule.capped;
        return stats;
    };
    // A window the kernel cannot take (an output row longer than a slab, more slots than a texel
    // buffer holds) goes to core whole: the same voxels, on the CPU.
    engine.resample = [context](const TetMesh& mesh, const std::vector<float>& values, const TetResampleWindow& window,
                                float* out) {
        if (tetResampleDeviceProblem(*context, mesh, window).empty())
            resampleTetsVulkan(*context, mesh, values, window, out);
        else
            resampleTetsInto(mesh, values, window, out);
    };
    return engine;
}

}  // namespace ddt
