#include "backend_factory.h"

#include "vulkan_backend.h"

namespace ddt {

namespace {

const char* deviceKind(VkPhysicalDeviceType type) {
    switch (type) {
        case VK_PHYSICAL_DEVICE_TYPE_DISCRETE_GPU:
            return "discrete";
        case VK_PHYSICAL_DEVICE_TYPE_INTEGRATED_GPU:
            return "integrated";
        case VK_PHYSICAL_DEVICE_TYPE_VIRTUAL_GPU:
            return "virtual";
        case VK_PHYSICAL_DEVICE_TYPE_CPU:
            return "cpu";
        default:
            return "other";
    }
}

}  // namespace

ChosenBackend makeBackend(const Settings& settings) {
    if (settings.backend == "cpu") return {makeCpuBackend(), "", ""};
    VulkanOptions options;
    if (!settings.variant.empty()) options.rule = settings.variant;
    options.active_set = settings.active_set;
    options.device_index = settings.device;
    auto backend = std::make_unique<VulkanBackend>(options);
    const DeviceInfo& device = backend->device();
    return {std::move(backend), device.name, deviceKind(device.type)};
}

}  // namespace ddt
