// swapchain.hpp — the window's images: a VkSwapchainKHR of B8G8R8A8_UNORM images (the format the
// offscreen target uses, so the one pipeline set serves both), a stencil attachment of the same
// size, and a framebuffer per image for the window's render pass. Recreated on resize or when
// the surface reports out-of-date; never created at 0x0 (a minimised window).
#pragma once

#include "engine/render/attachment.hpp"
#include "engine/render/context.hpp"

#include <vulkan/vulkan.h>

#include <vector>

namespace contactlab::editor {

struct SwapchainImage {
    VkImage image = VK_NULL_HANDLE;     // owned by the swapchain
    VkImageView view = VK_NULL_HANDLE;
    VkFramebuffer framebuffer = VK_NULL_HANDLE;
};

class Swapchain {
public:
    Swapchain(const render::VulkanContext& ctx, VkSurfaceKHR surface);
    ~Swapchain();
    Swapchain(const Swapchain&) = delete;
    Swapchain& operator=(const Swapchain&) = delete;

    // (Re)creates everything for a framebuffer of width x height px (the surface's current extent
    // wins when it has one). The old swapchain is handed to the new one and then destroyed; the
    // caller waits for the device to be idle first. Returns false for a 0x0 surface.
    bool create(VkRenderPass render_pass, VkFormat stencil_format, int width, int height, bool vsync);
    void destroy();

    bool valid() const { return swapchain_ != VK_NULL_HANDLE; }
    VkSwapchainKHR handle() const { return swapchain_; }
    VkExtent2D extent() const { return extent_; }
    uint32_t min_image_count() const { return min_images_; }
    const std::vector<SwapchainImage>& images() const { return images_; }
    VkPresentModeKHR present_mode() const { return present_mode_; }
    // Whether images may be a copy's destination (the cached scene layer goes in that way).
    bool copy_target() const { return copy_target_; }

private:
    void destroy_images();

    const render::VulkanContext& ctx_;
    VkSurfaceKHR surface_;
    VkSwapchainKHR swapchain_ = VK_NULL_HANDLE;
    VkExtent2D extent_{0, 0};
    uint32_t min_images_ = 2;
    VkPresentModeKHR present_mode_ = VK_PRESENT_MODE_FIFO_KHR;
    bool copy_target_ = false;
    std::vector<SwapchainImage> images_;
    // Stencil attachment (one: frames are recorded one after another on one queue).
    render::ImageAttachment stencil_;
};

}  // namespace contactlab::editor
