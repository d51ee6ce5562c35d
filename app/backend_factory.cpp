#include "backend_factory.h"

#include <OpenImageIO/strutil.h>

#include "vulkan_backend.h"

namespace ddt {

namespace {

// The first word of the device type, lower case: "discrete", "integrated", "cpu", …
std::string deviceKind(VkPhysicalDeviceType type) {
    const std::string name = deviceTypeName(type);
    return OIIO::Strutil::lower(name.substr(0, name.find(' ')));
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
