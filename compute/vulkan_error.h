// The one checking path for Vulkan results: a failed call reaches the user as one line
// naming the call and the error code.
#pragma once

#include <vulkan/vulkan.h>

#include "user_error.h"

namespace ddt {

const char* vulkanResultName(VkResult result);

// Throws UserError("Vulkan: vkCall failed with VK_ERROR_…") unless result is VK_SUCCESS;
// DeviceOutOfMemory (core/user_error.h) for the out-of-memory results, which smaller tiles may avoid.
void checkVulkan(VkResult result, const char* call);

}  // namespace ddt

#define VK_CHECK(call) ::ddt::checkVulkan((call), #call)
