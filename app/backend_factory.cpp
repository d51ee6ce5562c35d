#include "backend_factory.h"

#include <OpenImageIO/strutil.h>

#include <cstdlib>
#include <filesystem>

#include "parallel.h"
#include "vulkan_backend.h"

namespace ddt {

namespace {

// The first word of the device type, lower case: "discrete", "integrated", "cpu", …
std::string deviceKind(VkPhysicalDeviceType type) {
    const std::string name = deviceTypeName(type);
    return OIIO::Strutil::lower(name.substr(0, name.find(' ')));
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
    return {makeCpuBackend(options), {"cpu", "", "", threadCount(), std::move(reason)}};
}

ChosenBackend vulkanBackend(const Settings& settings, int device_index, std::string reason) {
    VulkanOptions options;
    if (!settings.variant.empty()) options.rule = settings.variant;
    options.active_set = settings.active_set;
    options.cost = costOf(settings);
    options.device_index = device_index;
    auto backend = std::make_unique<VulkanBackend>(options);
    const DeviceInfo& device = backend->device();
    BackendChoice choice{"vulkan", device.name, deviceKind(device.type), 0, std::move(reason)};
    return {std::move(backend), std::move(choice)};
}

// --backend auto without --device: Vulkan on the device Vulkan would choose, when that is a GPU.
ChosenBackend automaticBackend(const Settings& settings) {
    if (!mayHaveGpu()) return cpuBackend(settings, "this machine has no GPU device (/dev/dri/renderD*, /dev/nvidiactl)");
    std::vector<DeviceInfo> devices;
    uint32_t best = 0;
    try {
        devices = listDevices();
        best = chooseDevice(devices, -1);
    } catch (const UserError&) {
        return cpuBackend(settings, "no usable Vulkan device (a GPU driver would give one)");
    }
    const DeviceInfo& device = devices[best];
    if (device.isCpu())
        return cpuBackend(settings, "the only Vulkan device, " + device.name +
                          ", runs on the CPU, where the CPU backend is faster (--backend vulkan uses it anyway)");
    return vulkanBackend(settings, int(best), "");
}

}  // namespace

ChosenBackend makeBackend(const Settings& settings) {
    if (settings.backend == "cpu") return cpuBackend(settings, "");
    if (settings.backend == "vulkan" || settings.device >= 0) return vulkanBackend(settings, settings.device, "");
    return automaticBackend(settings);
}

}  // namespace ddt
