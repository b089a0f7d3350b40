// vk_check.hpp — turning Vulkan result codes into exceptions.
#pragma once

#include <vulkan/vulkan.h>

#include <stdexcept>
#include <string>

namespace contactlab::render {

// A Vulkan call failed (anything but VK_SUCCESS where success was required).
struct VulkanError : std::runtime_error {
    using std::runtime_error::runtime_error;
};

// No Vulkan implementation or no suitable device: the user can fix it by installing a driver.
struct NoVulkanDevice : std::runtime_error {
    using std::runtime_error::runtime_error;
};

const char* vk_result_name(VkResult r);

inline void vk_check(VkResult r, const char* what) {
    if (r != VK_SUCCESS) throw VulkanError(std::string(what) + " failed: " + vk_result_name(r));
}

}  // namespace contactlab::render
