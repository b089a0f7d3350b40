// swapchain.cpp — swapchain, image views, stencil attachment, framebuffers (see swapchain.hpp).
#include "engine/editor/swapchain.hpp"

#include "engine/render/pipelines.hpp"
#include "engine/render/vk_check.hpp"

#include <algorithm>

namespace contactlab::editor {

using render::vk_check;
using render::VulkanError;

Swapchain::Swapchain(const render::VulkanContext& ctx, VkSurfaceKHR surface) : ctx_(ctx), surface_(surface) {
    // Presentation support of the graphics queue family: asked before any swapchain exists.
    VkBool32 supported = VK_FALSE;
    vk_check(vkGetPhysicalDeviceSurfaceSupportKHR(ctx_.physical_device(), ctx_.queue_family(), surface_, &supported),
             "vkGetPhysicalDeviceSurfaceSupportKHR");
    if (!supported) throw VulkanError(ctx_.device_name() + " cannot present to this window's surface");
}

Swapchain::~Swapchain() {
    destroy();
}

void Swapchain::destroy_images() {
    const VkDevice dev = ctx_.device();
    for (SwapchainImage& im : images_) {
        if (im.framebuffer) vkDestroyFramebuffer(dev, im.framebuffer, nullptr);
        if (im.view) vkDestroyImageView(dev, im.view, nullptr);
    }
    images_.clear();
    render::destroy_image_attachment(dev, stencil_);
}

void Swapchain::destroy() {
    destroy_images();
    if (swapchain_) vkDestroySwapchainKHR(ctx_.device(), swapchain_, nullptr);
    swapchain_ = VK_NULL_HANDLE;
}

bool Swapchain::create(VkRenderPass render_pass, VkFormat stencil_format, int width, int height, bool vsync) {
    const VkDevice dev = ctx_.device();
    const VkPhysicalDevice phys = ctx_.physical_device();

    // Surface capabilities: extent (the surface's own when it fixes one) and image count.
    VkSurfaceCapabilitiesKHR caps;
    vk_check(vkGetPhysicalDeviceSurfaceCapabilitiesKHR(phys, surface_, &caps), "vkGetPhysicalDeviceSurfaceCapabilitiesKHR");
    VkExtent2D extent = caps.currentExtent;
    if (extent.width == 0xFFFFFFFFu) {
        extent.width = std::clamp(static_cast<uint32_t>(std::max(width, 0)), caps.minImageExtent.width, caps.maxImageExtent.width);
        extent.height = std::clamp(static_cast<uint32_t>(std::max(height, 0)), caps.minImageExtent.height, caps.maxImageExtent.height);
    }
    destroy_images();
    if (extent.width == 0 || extent.height == 0 || width == 0 || height == 0) return false;  // minimised

    // Format: B8G8R8A8_UNORM (sRGB non-linear colour space), the renderer's colour format.
    uint32_t nf = 0;
    vkGetPhysicalDeviceSurfaceFormatsKHR(phys, surface_, &nf, nullptr);
    std::vector<VkSurfaceFormatKHR> formats(nf);
    vkGetPhysicalDeviceSurfaceFormatsKHR(phys, surface_, &nf, formats.data());
    const auto fmt = std::find_if(formats.begin(), formats.end(),
                                  [](const VkSurfaceFormatKHR& f) { return f.format == render::kColorFormat; });
    if (fmt == formats.end()) throw VulkanError("the window surface does not offer B8G8R8A8_UNORM");

    // Present mode: FIFO (always available) with vsync; otherwise MAILBOX, then IMMEDIATE.
    present_mode_ = VK_PRESENT_MODE_FIFO_KHR;
    if (!vsync) {
        uint32_t nm = 0;
        vkGetPhysicalDeviceSurfacePresentModesKHR(phys, surface_, &nm, nullptr);
        std::vector<VkPresentModeKHR> modes(nm);
        vkGetPhysicalDeviceSurfacePresentModesKHR(phys, surface_, &nm, modes.data());
        for (VkPresentModeKHR want : {VK_PRESENT_MODE_MAILBOX_KHR, VK_PRESENT_MODE_IMMEDIATE_KHR})
            if (std::find(modes.begin(), modes.end(), want) != modes.end()) {
                present_mode_ = want;
                break;
            }
    }

    // Swapchain: colour attachment + transfer source (screenshots read the presented image).
    if (!(caps.supportedUsageFlags & VK_IMAGE_USAGE_TRANSFER_SRC_BIT))
        throw VulkanError("the window surface's images cannot be read back (no TRANSFER_SRC usage)");
    min_images_ = std::max(2u, caps.minImageCount);
    uint32_t want_images = std::max(caps.minImageCount + 1, 3u);
    if (caps.maxImageCount > 0) want_images = std::min(want_images, caps.maxImageCount);
    VkSwapchainCreateInfoKHR info{};
    info.sType = VK_STRUCTURE_TYPE_SWAPCHAIN_CREATE_INFO_KHR;
    info.surface = surface_;
    info.minImageCount = want_images;
    info.imageFormat = fmt->format;
    info.imageColorSpace = fmt->colorSpace;
    info.imageExtent = extent;
    info.imageArrayLayers = 1;
    // Transfer destination too where the surface allows it: the cached scene layer is copied in.
    copy_target_ = (caps.supportedUsageFlags & VK_IMAGE_USAGE_TRANSFER_DST_BIT) != 0;
    info.imageUsage = VK_IMAGE_USAGE_COLOR_ATTACHMENT_BIT | VK_IMAGE_USAGE_TRANSFER_SRC_BIT |
                      (copy_target_ ? VkImageUsageFlags{VK_IMAGE_USAGE_TRANSFER_DST_BIT} : VkImageUsageFlags{0});
    info.imageSharingMode = VK_SHARING_MODE_EXCLUSIVE;
    info.preTransform = caps.currentTransform;
    info.compositeAlpha = (caps.supportedCompositeAlpha & VK_COMPOSITE_ALPHA_OPAQUE_BIT_KHR)
                              ? VK_COMPOSITE_ALPHA_OPAQUE_BIT_KHR
                              : static_cast<VkCompositeAlphaFlagBitsKHR>(caps.supportedCompositeAlpha & -caps.supportedCompositeAlpha);
    info.presentMode = present_mode_;
    info.clipped = VK_TRUE;
    info.oldSwapchain = swapchain_;
    VkSwapchainKHR created = VK_NULL_HANDLE;
    vk_check(vkCreateSwapchainKHR(dev, &info, nullptr, &created), "vkCreateSwapchainKHR");
    if (swapchain_) vkDestroySwapchainKHR(dev, swapchain_, nullptr);
    swapchain_ = created;
    extent_ = extent;

    // Stencil attachment: device-local, the size of the swapchain images.
    stencil_ = render::create_image_attachment(ctx_, extent, stencil_format, VK_IMAGE_USAGE_DEPTH_STENCIL_ATTACHMENT_BIT,
                                               render::stencil_aspect(stencil_format), "stencil");

    // Image views and framebuffers: one per swapchain image, sharing the stencil attachment.
    uint32_t n = 0;
    vk_check(vkGetSwapchainImagesKHR(dev, swapchain_, &n, nullptr), "vkGetSwapchainImagesKHR");
    std::vector<VkImage> images(n);
    vk_check(vkGetSwapchainImagesKHR(dev, swapchain_, &n, images.data()), "vkGetSwapchainImagesKHR");
    images_.resize(n);
    for (uint32_t i = 0; i < n; ++i) {
        SwapchainImage& im = images_[i];
        im.image = images[i];
        VkImageViewCreateInfo v{};
        v.sType = VK_STRUCTURE_TYPE_IMAGE_VIEW_CREATE_INFO;
        v.image = im.image;
        v.viewType = VK_IMAGE_VIEW_TYPE_2D;
        v.format = fmt->format;
        v.subresourceRange = {VK_IMAGE_ASPECT_COLOR_BIT, 0, 1, 0, 1};
        vk_check(vkCreateImageView(dev, &v, nullptr, &im.view), "vkCreateImageView (swapchain)");
        VkImageView attachments[2] = {im.view, stencil_.view};
        VkFramebufferCreateInfo fb{};
        fb.sType = VK_STRUCTURE_TYPE_FRAMEBUFFER_CREATE_INFO;
        fb.renderPass = render_pass;
        fb.attachmentCount = 2;
        fb.pAttachments = attachments;
        fb.width = extent.width;
        fb.height = extent.height;
        fb.layers = 1;
        vk_check(vkCreateFramebuffer(dev, &fb, nullptr, &im.framebuffer), "vkCreateFramebuffer (swapchain)");
    }
    return true;
}

}  // namespace contactlab::editor
