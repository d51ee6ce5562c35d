// The Vulkan context: instance (no surface), device choice, logical device, the compute
// queue and a command pool. Optionally the Khronos validation layer with synchronization
// validation, whose messages are printed and counted (tests require zero).
#pragma once

#include <vulkan/vulkan.h>

#include <atomic>
#include <cstdint>
#include <memory>
#include <string>
#include <vector>

namespace ddt {

struct DeviceInfo {
    uint32_t index = 0;        // position in the instance's device list (--device N)
    std::string name;
    VkPhysicalDeviceType type = VK_PHYSICAL_DEVICE_TYPE_OTHER;
    std::string driver;        // driver name and version info
    uint64_t memory_bytes = 0; // largest device-local heap
    std::string unusable;      // "" if ddtup can run on it, else why not

    bool isCpu() const { return type == VK_PHYSICAL_DEVICE_TYPE_CPU; }
};

const char* deviceTypeName(VkPhysicalDeviceType type);

struct ContextOptions {
    int device_index = -1;    // -1: choose (discrete, then integrated, then the rest)
    bool validation = false;  // also on when DDTUP_VALIDATION=1 is set
};

struct VulkanContext {
    VkInstance instance = VK_NULL_HANDLE;
    VkDebugUtilsMessengerEXT messenger = VK_NULL_HANDLE;
    VkPhysicalDevice physical = VK_NULL_HANDLE;
    VkDevice device = VK_NULL_HANDLE;
    VkQueue queue = VK_NULL_HANDLE;
    uint32_t queue_family = 0;
    VkCommandPool command_pool = VK_NULL_HANDLE;
    VkPhysicalDeviceProperties properties{};
    VkPhysicalDeviceMemoryProperties memory{};
    DeviceInfo info;
    bool timestamps = false;  // the queue supports timestamp queries
    bool memory_budget = false;  // VK_EXT_memory_budget is enabled
    std::atomic<uint32_t> validation_messages{0};

    VulkanContext() = default;
    VulkanContext(const VulkanContext&) = delete;
    VulkanContext& operator=(const VulkanContext&) = delete;
    ~VulkanContext();
};

// Every Vulkan device the loader reports, with why ddtup cannot use it where it cannot.
// Throws UserError when no Vulkan driver is installed at all.
std::vector<DeviceInfo> listDevices();
// The index of the device to use: `requested` (an index, checked) or, for -1, the first
// usable discrete GPU, then integrated, then the rest. Throws UserError when there is none.
uint32_t chooseDevice(const std::vector<DeviceInfo>& devices, int requested);

// Throws UserError naming the fix when no usable device exists.
std::unique_ptr<VulkanContext> createContext(const ContextOptions& options);

// Bytes of the largest device-local heap this process may still use: its budget where the
// device reports one (VK_EXT_memory_budget), else the heap's size.
uint64_t memoryAvailable(const VulkanContext& context);

}  // namespace ddt
