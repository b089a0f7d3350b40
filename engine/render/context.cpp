// context.cpp — instance, validation messenger, physical device choice, logical device, pool.
#include "engine/render/context.hpp"

#include "engine/render/vk_check.hpp"

#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <vector>

namespace contactlab::render {
namespace {

constexpr const char* kValidationLayer = "VK_LAYER_KHRONOS_validation";
// Debian's lavapipe ICD manifest: pointing the loader at it alone skips probing other drivers.
constexpr const char* kLavapipeIcd = "/usr/share/vulkan/icd.d/lvp_icd.x86_64.json";

VKAPI_ATTR VkBool32 VKAPI_CALL on_validation_message(VkDebugUtilsMessageSeverityFlagBitsEXT severity,
                                                     VkDebugUtilsMessageTypeFlagsEXT,
                                                     const VkDebugUtilsMessengerCallbackDataEXT* data,
                                                     void* user) {
    auto* counts = static_cast<ValidationCounts*>(user);
    const bool error = (severity & VK_DEBUG_UTILS_MESSAGE_SEVERITY_ERROR_BIT_EXT) != 0;
    if (error) ++counts->errors;
    else ++counts->warnings;
    if (!counts->quiet)
        std::fprintf(stderr, "vulkan validation %s: %s\n", error ? "error" : "warning",
                     data && data->pMessage ? data->pMessage : "(no message)");
    return VK_FALSE;  // never abort the call
}

VkDebugUtilsMessengerCreateInfoEXT messenger_info(ValidationCounts* counts) {
    VkDebugUtilsMessengerCreateInfoEXT info{};
    info.sType = VK_STRUCTURE_TYPE_DEBUG_UTILS_MESSENGER_CREATE_INFO_EXT;
    info.messageSeverity = VK_DEBUG_UTILS_MESSAGE_SEVERITY_WARNING_BIT_EXT | VK_DEBUG_UTILS_MESSAGE_SEVERITY_ERROR_BIT_EXT;
    info.messageType = VK_DEBUG_UTILS_MESSAGE_TYPE_GENERAL_BIT_EXT | VK_DEBUG_UTILS_MESSAGE_TYPE_VALIDATION_BIT_EXT |
                       VK_DEBUG_UTILS_MESSAGE_TYPE_PERFORMANCE_BIT_EXT;
    info.pfnUserCallback = on_validation_message;
    info.pUserData = counts;
    return info;
}

bool layer_available(const char* name) {
    uint32_t n = 0;
    vkEnumerateInstanceLayerProperties(&n, nullptr);
    std::vector<VkLayerProperties> layers(n);
    vkEnumerateInstanceLayerProperties(&n, layers.data());
    for (const auto& l : layers)
        if (std::strcmp(l.layerName, name) == 0) return true;
    return false;
}

// Preference of a device type: lower is better. CPU devices are last unless asked for.
int type_rank(VkPhysicalDeviceType t, bool software) {
    if (software) return t == VK_PHYSICAL_DEVICE_TYPE_CPU ? 0 : -1;
    switch (t) {
        case VK_PHYSICAL_DEVICE_TYPE_DISCRETE_GPU: return 0;
        case VK_PHYSICAL_DEVICE_TYPE_INTEGRATED_GPU: return 1;
        case VK_PHYSICAL_DEVICE_TYPE_VIRTUAL_GPU: return 2;
        case VK_PHYSICAL_DEVICE_TYPE_CPU: return 3;
        default: return 4;
    }
}

}  // namespace

std::string no_vulkan_device_hint() {
    return "no Vulkan device found; install a Vulkan driver, e.g. Debian's mesa-vulkan-drivers "
           "(lavapipe, a CPU implementation: apt-get install mesa-vulkan-drivers)";
}

VulkanContext::VulkanContext(const ContextOptions& options, const WindowSupport& window) {
    counts_.quiet = options.quiet;
    software_ = options.software;
    // --software: unless the user chose drivers, load only lavapipe's manifest (faster start,
    // and no GPU driver is even probed).
    if (options.software && !std::getenv("VK_DRIVER_FILES") && !std::getenv("VK_ICD_FILENAMES") &&
        std::filesystem::exists(kLavapipeIcd))
        setenv("VK_DRIVER_FILES", kLavapipeIcd, 0);
    try {
        create_instance(options, window);
        pick_device(options.software);
        create_device(window.swapchain);
    } catch (...) {
        destroy();
        throw;
    }
}

VulkanContext::~VulkanContext() { destroy(); }

void VulkanContext::destroy() {
    if (device_) {
        vkDeviceWaitIdle(device_);
        if (pool_) vkDestroyCommandPool(device_, pool_, nullptr);
        vkDestroyDevice(device_, nullptr);
    }
    if (messenger_) {
        auto destroy = reinterpret_cast<PFN_vkDestroyDebugUtilsMessengerEXT>(
            vkGetInstanceProcAddr(instance_, "vkDestroyDebugUtilsMessengerEXT"));
        if (destroy) destroy(instance_, messenger_, nullptr);
    }
    if (instance_) vkDestroyInstance(instance_, nullptr);
    pool_ = VK_NULL_HANDLE;
    device_ = VK_NULL_HANDLE;
    messenger_ = VK_NULL_HANDLE;
    instance_ = VK_NULL_HANDLE;
}

void VulkanContext::create_instance(const ContextOptions& options, const WindowSupport& window) {
    // Instance: Vulkan 1.1; surface extensions only when a window asks for them; debug utils only
    // with validation.
    VkApplicationInfo app{};
    app.sType = VK_STRUCTURE_TYPE_APPLICATION_INFO;
    app.pApplicationName = "ContactLab";
    app.pEngineName = "ContactLab";
    app.apiVersion = VK_API_VERSION_1_1;

    std::vector<const char*> layers, extensions;
    VkDebugUtilsMessengerCreateInfoEXT debug = messenger_info(&counts_);
    VkInstanceCreateInfo info{};
    info.sType = VK_STRUCTURE_TYPE_INSTANCE_CREATE_INFO;
    info.pApplicationInfo = &app;
    if (options.validation) {
        if (!layer_available(kValidationLayer))
            throw VulkanError("validation requested but VK_LAYER_KHRONOS_validation is not installed "
                              "(Debian package vulkan-validationlayers)");
        layers.push_back(kValidationLayer);
        extensions.push_back(VK_EXT_DEBUG_UTILS_EXTENSION_NAME);
        info.pNext = &debug;  // also reports problems in vkCreateInstance itself
    }
    for (const std::string& e : window.instance_extensions) extensions.push_back(e.c_str());
    info.enabledLayerCount = static_cast<uint32_t>(layers.size());
    info.ppEnabledLayerNames = layers.data();
    info.enabledExtensionCount = static_cast<uint32_t>(extensions.size());
    info.ppEnabledExtensionNames = extensions.data();
    const VkResult r = vkCreateInstance(&info, nullptr, &instance_);
    if (r == VK_ERROR_INCOMPATIBLE_DRIVER) throw NoVulkanDevice(no_vulkan_device_hint());
    vk_check(r, "vkCreateInstance");

    // Debug messenger: counts validation errors and warnings for the whole context's life.
    if (options.validation) {
        auto create = reinterpret_cast<PFN_vkCreateDebugUtilsMessengerEXT>(
            vkGetInstanceProcAddr(instance_, "vkCreateDebugUtilsMessengerEXT"));
        if (!create) throw VulkanError("vkCreateDebugUtilsMessengerEXT is not available");
        vk_check(create(instance_, &debug, nullptr, &messenger_), "vkCreateDebugUtilsMessengerEXT");
    }
}

void VulkanContext::pick_device(bool software) {
    // Physical device: best-ranked type with a graphics queue (the first such, in loader order).
    uint32_t n = 0;
    const VkResult r = vkEnumeratePhysicalDevices(instance_, &n, nullptr);
    if (r == VK_ERROR_INITIALIZATION_FAILED || n == 0) throw NoVulkanDevice(no_vulkan_device_hint());
    vk_check(r, "vkEnumeratePhysicalDevices");
    std::vector<VkPhysicalDevice> devices(n);
    vk_check(vkEnumeratePhysicalDevices(instance_, &n, devices.data()), "vkEnumeratePhysicalDevices");

    int best_rank = 1 << 30;
    for (VkPhysicalDevice d : devices) {
        VkPhysicalDeviceProperties props;
        vkGetPhysicalDeviceProperties(d, &props);
        const int rank = type_rank(props.deviceType, software);
        if (rank < 0 || rank >= best_rank) continue;
        uint32_t qn = 0;
        vkGetPhysicalDeviceQueueFamilyProperties(d, &qn, nullptr);
        std::vector<VkQueueFamilyProperties> families(qn);
        vkGetPhysicalDeviceQueueFamilyProperties(d, &qn, families.data());
        for (uint32_t q = 0; q < qn; ++q) {
            if (!(families[q].queueFlags & VK_QUEUE_GRAPHICS_BIT)) continue;
            physical_ = d;
            queue_family_ = q;
            best_rank = rank;
            device_name_ = props.deviceName;
            software_ = props.deviceType == VK_PHYSICAL_DEVICE_TYPE_CPU;
            break;
        }
    }
    if (!physical_) {
        if (software)
            throw NoVulkanDevice("no CPU Vulkan device (lavapipe) found for --software; install Debian's "
                                 "mesa-vulkan-drivers (apt-get install mesa-vulkan-drivers)");
        throw NoVulkanDevice(no_vulkan_device_hint());
    }
    vkGetPhysicalDeviceMemoryProperties(physical_, &memory_);
}

void VulkanContext::create_device(bool swapchain) {
    // Logical device: one graphics queue, no optional features; VK_KHR_swapchain for a window.
    const float priority = 1.0f;
    VkDeviceQueueCreateInfo queue{};
    queue.sType = VK_STRUCTURE_TYPE_DEVICE_QUEUE_CREATE_INFO;
    queue.queueFamilyIndex = queue_family_;
    queue.queueCount = 1;
    queue.pQueuePriorities = &priority;
    VkDeviceCreateInfo info{};
    info.sType = VK_STRUCTURE_TYPE_DEVICE_CREATE_INFO;
    info.queueCreateInfoCount = 1;
    info.pQueueCreateInfos = &queue;
    const char* swapchain_extension = VK_KHR_SWAPCHAIN_EXTENSION_NAME;
    if (swapchain) {
        info.enabledExtensionCount = 1;
        info.ppEnabledExtensionNames = &swapchain_extension;
    }
    vk_check(vkCreateDevice(physical_, &info, nullptr, &device_), "vkCreateDevice");
    vkGetDeviceQueue(device_, queue_family_, 0, &queue_);

    // Command pool: buffers are re-recorded every frame.
    VkCommandPoolCreateInfo pool{};
    pool.sType = VK_STRUCTURE_TYPE_COMMAND_POOL_CREATE_INFO;
    pool.flags = VK_COMMAND_POOL_CREATE_RESET_COMMAND_BUFFER_BIT;
    pool.queueFamilyIndex = queue_family_;
    vk_check(vkCreateCommandPool(device_, &pool, nullptr, &pool_), "vkCreateCommandPool");
}

uint32_t VulkanContext::memory_type(uint32_t type_bits, VkMemoryPropertyFlags flags) const {
    for (uint32_t i = 0; i < memory_.memoryTypeCount; ++i)
        if ((type_bits & (1u << i)) && (memory_.memoryTypes[i].propertyFlags & flags) == flags) return i;
    throw VulkanError("no Vulkan memory type with the required properties");
}

}  // namespace contactlab::render
