#include "context.h"

#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <cstring>

#include "vulkan_error.h"

namespace ddt {

namespace {

const char* kValidationLayer = "VK_LAYER_KHRONOS_validation";
const char* kNoDeviceHint =
    "install a Vulkan driver (Debian: mesa-vulkan-drivers provides lavapipe, a CPU device) or use --backend cpu";

bool validationRequested(const ContextOptions& options) {
    const char* env = std::getenv("DDTUP_VALIDATION");
    return options.validation || (env && std::strcmp(env, "1") == 0);
}

VKAPI_ATTR VkBool32 VKAPI_CALL onValidationMessage(VkDebugUtilsMessageSeverityFlagBitsEXT,
                                                   VkDebugUtilsMessageTypeFlagsEXT,
                                                   const VkDebugUtilsMessengerCallbackDataEXT* data, void* user) {
    auto* context = static_cast<VulkanContext*>(user);
    context->validation_messages.fetch_add(1);
    std::fprintf(stderr, "ddtup: validation: %s\n", data->pMessage);
    return VK_FALSE;
}

VkDebugUtilsMessengerCreateInfoEXT messengerInfo(VulkanContext* context) {
    VkDebugUtilsMessengerCreateInfoEXT info{VK_STRUCTURE_TYPE_DEBUG_UTILS_MESSENGER_CREATE_INFO_EXT};
    info.messageSeverity = VK_DEBUG_UTILS_MESSAGE_SEVERITY_WARNING_BIT_EXT | VK_DEBUG_UTILS_MESSAGE_SEVERITY_ERROR_BIT_EXT;
    info.messageType = VK_DEBUG_UTILS_MESSAGE_TYPE_GENERAL_BIT_EXT | VK_DEBUG_UTILS_MESSAGE_TYPE_VALIDATION_BIT_EXT |
                       VK_DEBUG_UTILS_MESSAGE_TYPE_PERFORMANCE_BIT_EXT;
    info.pfnUserCallback = onValidationMessage;
    info.pUserData = context;
    return info;
}

VkInstance createInstance(bool validation, VulkanContext* context_for_messages) {
    VkApplicationInfo app{VK_STRUCTURE_TYPE_APPLICATION_INFO};
    app.pApplicationName = "ddtup";
    app.apiVersion = VK_API_VERSION_1_2;
    VkInstanceCreateInfo info{VK_STRUCTURE_TYPE_INSTANCE_CREATE_INFO};
    info.pApplicationInfo = &app;

    // Synchronization validation catches missing barriers, which lavapipe forgives.
    VkValidationFeatureEnableEXT enables[] = {VK_VALIDATION_FEATURE_ENABLE_SYNCHRONIZATION_VALIDATION_EXT};
    VkValidationFeaturesEXT features{VK_STRUCTURE_TYPE_VALIDATION_FEATURES_EXT};
    features.enabledValidationFeatureCount = 1;
    features.pEnabledValidationFeatures = enables;
    VkDebugUtilsMessengerCreateInfoEXT messenger = messengerInfo(context_for_messages);
    const char* extensions[] = {VK_EXT_DEBUG_UTILS_EXTENSION_NAME};
    if (validation) {
        info.enabledLayerCount = 1;
        info.ppEnabledLayerNames = &kValidationLayer;
        info.enabledExtensionCount = 1;
        info.ppEnabledExtensionNames = extensions;
        features.pNext = &messenger;  // also reports problems during instance creation
        info.pNext = &features;
    }
    VkInstance instance = VK_NULL_HANDLE;
    VkResult result = vkCreateInstance(&info, nullptr, &instance);
    if (result == VK_ERROR_INCOMPATIBLE_DRIVER)
        throw UserError(std::string("Vulkan: no Vulkan 1.2 driver found; ") + kNoDeviceHint);
    if (result == VK_ERROR_LAYER_NOT_PRESENT)
        throw UserError("Vulkan: validation layer missing; install vulkan-validationlayers");
    VK_CHECK(result);
    return instance;
}

std::vector<VkPhysicalDevice> physicalDevices(VkInstance instance) {
    uint32_t count = 0;
    VK_CHECK(vkEnumeratePhysicalDevices(instance, &count, nullptr));
    std::vector<VkPhysicalDevice> devices(count);
    VK_CHECK(vkEnumeratePhysicalDevices(instance, &count, devices.data()));
    devices.resize(count);
    return devices;
}

// A queue family with compute, or UINT32_MAX.
uint32_t computeQueueFamily(VkPhysicalDevice physical) {
    uint32_t count = 0;
    vkGetPhysicalDeviceQueueFamilyProperties(physical, &count, nullptr);
    std::vector<VkQueueFamilyProperties> families(count);
    vkGetPhysicalDeviceQueueFamilyProperties(physical, &count, families.data());
    for (uint32_t i = 0; i < count; ++i)
        if (families[i].queueFlags & VK_QUEUE_COMPUTE_BIT) return i;
    return UINT32_MAX;
}

DeviceInfo describe(VkPhysicalDevice physical, uint32_t index) {
    VkPhysicalDeviceDriverProperties driver{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_DRIVER_PROPERTIES};
    VkPhysicalDeviceProperties2 properties{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_PROPERTIES_2};
    properties.pNext = &driver;
    vkGetPhysicalDeviceProperties2(physical, &properties);
    VkPhysicalDeviceFeatures2 features{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_FEATURES_2};
    vkGetPhysicalDeviceFeatures2(physical, &features);
    VkPhysicalDeviceMemoryProperties memory;
    vkGetPhysicalDeviceMemoryProperties(physical, &memory);

    DeviceInfo info;
    info.index = index;
    info.name = properties.properties.deviceName;
    info.type = properties.properties.deviceType;
    info.driver = std::string(driver.driverName) + " " + driver.driverInfo;
    for (uint32_t i = 0; i < memory.memoryHeapCount; ++i)
        if (memory.memoryHeaps[i].flags & VK_MEMORY_HEAP_DEVICE_LOCAL_BIT)
            info.memory_bytes = std::max<uint64_t>(info.memory_bytes, memory.memoryHeaps[i].size);

    if (properties.properties.apiVersion < VK_API_VERSION_1_2) info.unusable = "needs Vulkan 1.2";
    else if (!features.features.shaderFloat64) info.unusable = "no shaderFloat64 (gains are computed in fp64)";
    else if (!features.features.shaderInt64) info.unusable = "no shaderInt64";
    else if (computeQueueFamily(physical) == UINT32_MAX) info.unusable = "no compute queue";
    return info;
}

bool hasDeviceExtension(VkPhysicalDevice physical, const char* name) {
    uint32_t count = 0;
    VK_CHECK(vkEnumerateDeviceExtensionProperties(physical, nullptr, &count, nullptr));
    std::vector<VkExtensionProperties> extensions(count);
    VK_CHECK(vkEnumerateDeviceExtensionProperties(physical, nullptr, &count, extensions.data()));
    for (uint32_t i = 0; i < count; ++i)
        if (std::strcmp(extensions[i].extensionName, name) == 0) return true;
    return false;
}

int typePreference(VkPhysicalDeviceType type) {
    switch (type) {
        case VK_PHYSICAL_DEVICE_TYPE_DISCRETE_GPU:
            return 0;
        case VK_PHYSICAL_DEVICE_TYPE_INTEGRATED_GPU:
            return 1;
        case VK_PHYSICAL_DEVICE_TYPE_VIRTUAL_GPU:
            return 2;
        case VK_PHYSICAL_DEVICE_TYPE_CPU:
            return 3;
        default:
            return 4;
    }
}

}  // namespace

uint32_t chooseDevice(const std::vector<DeviceInfo>& devices, int requested) {
    if (devices.empty()) throw UserError(std::string("Vulkan: no devices found; ") + kNoDeviceHint);
    if (requested >= 0) {
        if (size_t(requested) >= devices.size())
            throw UserError("--device " + std::to_string(requested) + ": no such device (" +
                            std::to_string(devices.size()) + " found; see --list-devices)");
        const DeviceInfo& chosen = devices[requested];
        if (!chosen.unusable.empty())
            throw UserError("--device " + std::to_string(requested) + ": " + chosen.name + " cannot run ddtup (" +
                            chosen.unusable + ")");
        return uint32_t(requested);
    }
    int best = -1;
    for (const DeviceInfo& d : devices)
        if (d.unusable.empty() && (best < 0 || typePreference(d.type) < typePreference(devices[best].type)))
            best = int(d.index);
    if (best < 0)
        throw UserError("Vulkan: no usable device (" + devices[0].name + ": " + devices[0].unusable + "); " +
                        kNoDeviceHint);
    return uint32_t(best);
}


const char* deviceTypeName(VkPhysicalDeviceType type) {
    switch (type) {
        case VK_PHYSICAL_DEVICE_TYPE_DISCRETE_GPU:
            return "discrete GPU";
        case VK_PHYSICAL_DEVICE_TYPE_INTEGRATED_GPU:
            return "integrated GPU";
        case VK_PHYSICAL_DEVICE_TYPE_VIRTUAL_GPU:
            return "virtual GPU";
        case VK_PHYSICAL_DEVICE_TYPE_CPU:
            return "CPU";
        default:
            return "other";
    }
}

std::vector<DeviceInfo> listDevices() {
    VkInstance instance = createInstance(false, nullptr);
    std::vector<DeviceInfo> devices;
    try {
        std::vector<VkPhysicalDevice> physical = physicalDevices(instance);
        for (uint32_t i = 0; i < physical.size(); ++i) devices.push_back(describe(physical[i], i));
    } catch (...) {
        vkDestroyInstance(instance, nullptr);
        throw;
    }
    vkDestroyInstance(instance, nullptr);
    return devices;
}

std::unique_ptr<VulkanContext> createContext(const ContextOptions& options) {
    auto context = std::make_unique<VulkanContext>();
    VulkanContext& c = *context;
    const bool validation = validationRequested(options);
    c.instance = createInstance(validation, &c);
    if (validation) {
        VkDebugUtilsMessengerCreateInfoEXT info = messengerInfo(&c);
        auto create = reinterpret_cast<PFN_vkCreateDebugUtilsMessengerEXT>(
            vkGetInstanceProcAddr(c.instance, "vkCreateDebugUtilsMessengerEXT"));
        if (create) VK_CHECK(create(c.instance, &info, nullptr, &c.messenger));
    }

    std::vector<VkPhysicalDevice> physical = physicalDevices(c.instance);
    std::vector<DeviceInfo> devices;
    for (uint32_t i = 0; i < physical.size(); ++i) devices.push_back(describe(physical[i], i));
    const uint32_t chosen = chooseDevice(devices, options.device_index);
    c.physical = physical[chosen];
    c.info = devices[chosen];
    vkGetPhysicalDeviceProperties(c.physical, &c.properties);
    vkGetPhysicalDeviceMemoryProperties(c.physical, &c.memory);
    c.queue_family = computeQueueFamily(c.physical);

    uint32_t family_count = 0;
    vkGetPhysicalDeviceQueueFamilyProperties(c.physical, &family_count, nullptr);
    std::vector<VkQueueFamilyProperties> families(family_count);
    vkGetPhysicalDeviceQueueFamilyProperties(c.physical, &family_count, families.data());
    c.timestamps = families[c.queue_family].timestampValidBits > 0 && c.properties.limits.timestampPeriod > 0.0f;

    c.memory_budget = hasDeviceExtension(c.physical, VK_EXT_MEMORY_BUDGET_EXTENSION_NAME);

    // Enable exactly what the kernels use.
    VkPhysicalDeviceFeatures2 features{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_FEATURES_2};
    features.features.shaderFloat64 = VK_TRUE;
    features.features.shaderInt64 = VK_TRUE;
    const float priority = 1.0f;
    VkDeviceQueueCreateInfo queue{VK_STRUCTURE_TYPE_DEVICE_QUEUE_CREATE_INFO};
    queue.queueFamilyIndex = c.queue_family;
    queue.queueCount = 1;
    queue.pQueuePriorities = &priority;
    VkDeviceCreateInfo info{VK_STRUCTURE_TYPE_DEVICE_CREATE_INFO};
    info.pNext = &features;
    info.queueCreateInfoCount = 1;
    info.pQueueCreateInfos = &queue;
    const char* budget_extension = VK_EXT_MEMORY_BUDGET_EXTENSION_NAME;
    if (c.memory_budget) {
        info.enabledExtensionCount = 1;
        info.ppEnabledExtensionNames = &budget_extension;
    }
    VK_CHECK(vkCreateDevice(c.physical, &info, nullptr, &c.device));
    vkGetDeviceQueue(c.device, c.queue_family, 0, &c.queue);

    VkCommandPoolCreateInfo pool{VK_STRUCTURE_TYPE_COMMAND_POOL_CREATE_INFO};
    pool.flags = VK_COMMAND_POOL_CREATE_RESET_COMMAND_BUFFER_BIT;
    pool.queueFamilyIndex = c.queue_family;
    VK_CHECK(vkCreateCommandPool(c.device, &pool, nullptr, &c.command_pool));
    return context;
}

uint64_t memoryAvailable(const VulkanContext& context) {
    VkPhysicalDeviceMemoryBudgetPropertiesEXT budget{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_MEMORY_BUDGET_PROPERTIES_EXT};
    VkPhysicalDeviceMemoryProperties2 memory{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_MEMORY_PROPERTIES_2};
    if (context.memory_budget) memory.pNext = &budget;
    vkGetPhysicalDeviceMemoryProperties2(context.physical, &memory);
    uint64_t largest = 0;
    for (uint32_t i = 0; i < memory.memoryProperties.memoryHeapCount; ++i) {
        if (!(memory.memoryProperties.memoryHeaps[i].flags & VK_MEMORY_HEAP_DEVICE_LOCAL_BIT)) continue;
        const uint64_t size = memory.memoryProperties.memoryHeaps[i].size;
        // heapBudget includes what this process holds now, which the next prepare releases.
        const uint64_t usable = context.memory_budget ? std::min<uint64_t>(size, budget.heapBudget[i]) : size;
        largest = std::max(largest, usable);
    }
    return largest;
}

VulkanContext::~VulkanContext() {
    if (device) {
        vkDeviceWaitIdle(device);
        if (command_pool) vkDestroyCommandPool(device, command_pool, nullptr);
        vkDestroyDevice(device, nullptr);
    }
    if (messenger) {
        auto destroy = reinterpret_cast<PFN_vkDestroyDebugUtilsMessengerEXT>(
            vkGetInstanceProcAddr(instance, "vkDestroyDebugUtilsMessengerEXT"));
        if (destroy) destroy(instance, messenger, nullptr);
    }
    if (instance) vkDestroyInstance(instance, nullptr);
}

}  // namespace ddt
