// attachment.cpp — device-local image attachments (see attachment.hpp).
#include "engine/render/attachment.hpp"

#include "engine/render/vk_check.hpp"

#include <string>

namespace contactlab::render {

ImageAttachment create_image_attachment(const VulkanContext& ctx, VkExtent2D extent, VkFormat format,
                                        VkImageUsageFlags usage, VkImageAspectFlags aspect, const char* what) {
    const VkDevice dev = ctx.device();
    const std::string suffix = std::string(" (") + what + ")";
    ImageAttachment a;
    // Image: 2-D, one mip level and layer, not multisampled.
    VkImageCreateInfo info{};
    info.sType = VK_STRUCTURE_TYPE_IMAGE_CREATE_INFO;
    info.imageType = VK_IMAGE_TYPE_2D;
    info.format = format;
    info.extent = {extent.width, extent.height, 1};
    info.mipLevels = 1;
    info.arrayLayers = 1;
    info.samples = VK_SAMPLE_COUNT_1_BIT;
    info.tiling = VK_IMAGE_TILING_OPTIMAL;
    info.usage = usage;
    info.sharingMode = VK_SHARING_MODE_EXCLUSIVE;
    info.initialLayout = VK_IMAGE_LAYOUT_UNDEFINED;
    try {
        vk_check(vkCreateImage(dev, &info, nullptr, &a.image), ("vkCreateImage" + suffix).c_str());
        // Memory: device-local, bound whole.
        VkMemoryRequirements req;
        vkGetImageMemoryRequirements(dev, a.image, &req);
        VkMemoryAllocateInfo alloc{};
        alloc.sType = VK_STRUCTURE_TYPE_MEMORY_ALLOCATE_INFO;
        alloc.allocationSize = req.size;
        alloc.memoryTypeIndex = ctx.memory_type(req.memoryTypeBits, VK_MEMORY_PROPERTY_DEVICE_LOCAL_BIT);
        vk_check(vkAllocateMemory(dev, &alloc, nullptr, &a.memory), ("vkAllocateMemory" + suffix).c_str());
        vk_check(vkBindImageMemory(dev, a.image, a.memory, 0), ("vkBindImageMemory" + suffix).c_str());
        // View: the whole image over `aspect`.
        VkImageViewCreateInfo view{};
        view.sType = VK_STRUCTURE_TYPE_IMAGE_VIEW_CREATE_INFO;
        view.image = a.image;
        view.viewType = VK_IMAGE_VIEW_TYPE_2D;
        view.format = format;
        view.subresourceRange = {aspect, 0, 1, 0, 1};
        vk_check(vkCreateImageView(dev, &view, nullptr, &a.view), ("vkCreateImageView" + suffix).c_str());
    } catch (...) {
        destroy_image_attachment(dev, a);
        throw;
    }
    return a;
}

void destroy_image_attachment(VkDevice dev, ImageAttachment& a) {
    if (a.view) vkDestroyImageView(dev, a.view, nullptr);
    if (a.image) vkDestroyImage(dev, a.image, nullptr);
    if (a.memory) vkFreeMemory(dev, a.memory, nullptr);
    a = ImageAttachment{};
}

}  // namespace contactlab::render
