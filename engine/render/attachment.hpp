// attachment.hpp — a device-local 2-D image with its memory and view: the colour and stencil
// attachments of the offscreen target, the editor's kept scene layer and the swapchain's stencil.
#pragma once

#include "engine/render/context.hpp"

namespace contactlab::render {

struct ImageAttachment {
    VkImage image = VK_NULL_HANDLE;
    VkDeviceMemory memory = VK_NULL_HANDLE;
    VkImageView view = VK_NULL_HANDLE;
};

// An extent-sized image of `format` and `usage` (1 mip, 1 layer, 1x sampling, optimal tiling) in
// device-local memory, with a view over `aspect`. `what` names it in errors ("vkCreateImage
// (what)"). On failure whatever was made is destroyed before the error is thrown.
ImageAttachment create_image_attachment(const VulkanContext& ctx, VkExtent2D extent, VkFormat format,
                                        VkImageUsageFlags usage, VkImageAspectFlags aspect, const char* what);
// Destroys what `a` holds (any part may be null) and leaves it empty.
void destroy_image_attachment(VkDevice dev, ImageAttachment& a);

// The aspects a stencil attachment of `format` has: stencil, and depth unless it is S8_UINT.
inline VkImageAspectFlags stencil_aspect(VkFormat format) {
    VkImageAspectFlags aspect = VK_IMAGE_ASPECT_STENCIL_BIT;
    if (format != VK_FORMAT_S8_UINT) aspect |= VK_IMAGE_ASPECT_DEPTH_BIT;
    return aspect;
}

}  // namespace contactlab::render
