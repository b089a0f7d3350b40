// context.hpp — a Vulkan instance and device with no surface: enough to render offscreen.
//
// The window (a later issue) creates its surface from the same instance. Device choice: a GPU
// (discrete, then integrated, then virtual) unless `software` asks for the CPU implementation
// (lavapipe, Debian package mesa-vulkan-drivers), which gives bit-stable pictures.
#pragma once

#include <vulkan/vulkan.h>

#include <atomic>
#include <string>
#include <vector>

namespace contactlab::render {

struct ContextOptions {
    bool software = false;    // force the CPU device (lavapipe)
    bool validation = false;  // VK_LAYER_KHRONOS_validation + a messenger counting its messages
    bool quiet = false;       // do not print validation messages (they are still counted)
};

// What a window target adds: the instance extensions the window system needs (e.g. from
// glfwGetRequiredInstanceExtensions) and VK_KHR_swapchain on the device. Offscreen contexts go
// without (and create exactly what they did before).
struct WindowSupport {
    std::vector<std::string> instance_extensions;
    bool swapchain = false;
};

// Counts of the validation messages seen since the context was created.
struct ValidationCounts {
    std::atomic<int> errors{0};
    std::atomic<int> warnings{0};
    bool quiet = false;
};

class VulkanContext {
public:
    // Throws NoVulkanDevice when there is no Vulkan implementation or no device of the kind asked
    // for; VulkanError for other failures (and when validation is asked for but not installed).
    explicit VulkanContext(const ContextOptions& options = {}, const WindowSupport& window = {});
    ~VulkanContext();
    VulkanContext(const VulkanContext&) = delete;
    VulkanContext& operator=(const VulkanContext&) = delete;

    VkInstance instance() const { return instance_; }
    VkPhysicalDevice physical_device() const { return physical_; }
    VkDevice device() const { return device_; }
    VkQueue queue() const { return queue_; }
    uint32_t queue_family() const { return queue_family_; }
    VkCommandPool command_pool() const { return pool_; }
    const std::string& device_name() const { return device_name_; }
    bool is_software() const { return software_; }
    bool validation_enabled() const { return messenger_ != VK_NULL_HANDLE; }

    int validation_errors() const { return counts_.errors.load(); }
    int validation_warnings() const { return counts_.warnings.load(); }
    // Errors + warnings: what the tests require to be zero.
    int validation_messages() const { return validation_errors() + validation_warnings(); }

    // Index of a memory type allowed by `type_bits` with all of `flags`; throws if none.
    uint32_t memory_type(uint32_t type_bits, VkMemoryPropertyFlags flags) const;

private:
    void create_instance(const ContextOptions& options, const WindowSupport& window);
    void pick_device(bool software);
    void create_device(bool swapchain);
    void destroy();  // releases whatever was created (also after a failed constructor)

    VkInstance instance_ = VK_NULL_HANDLE;
    VkDebugUtilsMessengerEXT messenger_ = VK_NULL_HANDLE;
    VkPhysicalDevice physical_ = VK_NULL_HANDLE;
    VkDevice device_ = VK_NULL_HANDLE;
    VkQueue queue_ = VK_NULL_HANDLE;
    uint32_t queue_family_ = 0;
    VkCommandPool pool_ = VK_NULL_HANDLE;
    VkPhysicalDeviceMemoryProperties memory_{};
    std::string device_name_;
    bool software_ = false;
    ValidationCounts counts_;
};

// The message for "no Vulkan device": names the Debian package that provides one.
std::string no_vulkan_device_hint();

}  // namespace contactlab::render
