#include "vulkan_error.h"

#include <string>

namespace ddt {

const char* vulkanResultName(VkResult result) {
    switch (result) {
#define DDT_RESULT(name) \
    case name:           \
        return #name;
        DDT_RESULT(VK_SUCCESS)
        DDT_RESULT(VK_NOT_READY)
        DDT_RESULT(VK_TIMEOUT)
        DDT_RESULT(VK_INCOMPLETE)
        DDT_RESULT(VK_ERROR_OUT_OF_HOST_MEMORY)
        DDT_RESULT(VK_ERROR_OUT_OF_DEVICE_MEMORY)
        DDT_RESULT(VK_ERROR_INITIALIZATION_FAILED)
        DDT_RESULT(VK_ERROR_DEVICE_LOST)
        DDT_RESULT(VK_ERROR_MEMORY_MAP_FAILED)
        DDT_RESULT(VK_ERROR_LAYER_NOT_PRESENT)
        DDT_RESULT(VK_ERROR_EXTENSION_NOT_PRESENT)
        DDT_RESULT(VK_ERROR_FEATURE_NOT_PRESENT)
        DDT_RESULT(VK_ERROR_INCOMPATIBLE_DRIVER)
        DDT_RESULT(VK_ERROR_TOO_MANY_OBJECTS)
        DDT_RESULT(VK_ERROR_FORMAT_NOT_SUPPORTED)
        DDT_RESULT(VK_ERROR_FRAGMENTED_POOL)
        DDT_RESULT(VK_ERROR_OUT_OF_POOL_MEMORY)
        DDT_RESULT(VK_ERROR_INVALID_SHADER_NV)
        DDT_RESULT(VK_ERROR_FRAGMENTATION)
        DDT_RESULT(VK_ERROR_INVALID_OPAQUE_CAPTURE_ADDRESS)
        DDT_RESULT(VK_ERROR_UNKNOWN)
#undef DDT_RESULT
        default:
            return "an unknown VkResult";
    }
}

void checkVulkan(VkResult result, const char* call) {
    if (result == VK_SUCCESS) return;
    std::string name(call);
    name = name.substr(0, name.find('('));  // "vkCreateDevice(physical, …)" -> "vkCreateDevice"
    const std::string message =
        "Vulkan: " + name + " failed with " + vulkanResultName(result) + " (" + std::to_string(int(result)) + ")";
    if (result == VK_ERROR_OUT_OF_DEVICE_MEMORY || result == VK_ERROR_OUT_OF_HOST_MEMORY)
        throw DeviceOutOfMemory(message);
    throw UserError(message);
}

}  // namespace ddt
