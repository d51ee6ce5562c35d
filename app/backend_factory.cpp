#include "backend_factory.h"

#include <OpenImageIO/strutil.h>

#include "parallel.h"
#include "vulkan_backend.h"

namespace ddt {

namespace {

// The first word of the device type, lower case: "discrete", "integrated", "cpu", …
std::string deviceKind(VkPhysicalDeviceType type) {
    const std::string name = deviceTypeName(type);
    return OIIO::Strutil::lower(name.substr(0, name.find(' ')));
}

ChosenBackend cpuBackend(std::string reason) {
    return {makeCpuBackend(), {"cpu", "", "", threadCount(), std::move(reason)}};
}

ChosenBackend vulkanBackend(const Settings& settings, int device_index, std::string reason) {
    VulkanOptions options;
    if (!settings.variant.empty()) options.rule = settings.variant;
    options.active_set = settings.active_set;
    options.device_index = device_index;
    auto backend = std::make_unique<VulkanBackend>(options);
    const DeviceInfo& device = backend->device();
    BackendChoice choice{"vulkan", device.name, deviceKind(device.type), 0, std::move(reason)};
    return {std::move(backend), std::move(choice)};
}

// --backend auto without --device: Vulkan on the device Vulkan would choose, when that is a GPU.
ChosenBackend automaticBackend(const Settings& settings) {
    std::vector<DeviceInfo> devices;
    uint32_t best = 0;
    try {
        devices = listDevices();
        best = chooseDevice(devices, -1);
    } catch (const UserError&) {
        return cpuBackend("no usable Vulkan device (a GPU driver would give one)");
    }
    const DeviceInfo& device = devices[best];
    if (device.isCpu())
        return cpuBackend("the only Vulkan device, " + device.name +
                          ", runs on the CPU, where the CPU backend is faster (--backend vulkan uses it anyway)");
    return vulkanBackend(settings, int(best), "");
}

}  // namespace

ChosenBackend makeBackend(const Settings& settings) {
    if (settings.backend == "cpu") return cpuBackend("");
    if (settings.backend == "vulkan" || settings.device >= 0) return vulkanBackend(settings, settings.device, "");
    return automaticBackend(settings);
}

}  // namespace ddt
