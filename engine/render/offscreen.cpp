// offscreen.cpp — offscreen target: attachments, framebuffer, record, submit, read back.
#include "engine/render/offscreen.hpp"

#include "engine/render/vk_check.hpp"

#include <cstring>
#include <stdexcept>

namespace contactlab::render {

OffscreenTarget::OffscreenTarget(const VulkanContext& ctx, int width, int height)
    : ctx_(ctx), width_(width), height_(height) {
    if (width <= 0 || height <= 0 || width > 16384 || height > 16384)
        throw std::invalid_argument("offscreen target size must be in 1..16384 px");
    const VkDevice dev = ctx_.device();
    try {
        // Attachments: colour (also a copy source for readback) and stencil.
        const VkFormat stencil_format = pick_stencil_format(ctx_);
        const VkExtent2D extent{static_cast<uint32_t>(width_), static_cast<uint32_t>(height_)};
        color_ = create_image_attachment(ctx_, extent, kColorFormat,
                                         VK_IMAGE_USAGE_COLOR_ATTACHMENT_BIT | VK_IMAGE_USAGE_TRANSFER_SRC_BIT,
                                         VK_IMAGE_ASPECT_COLOR_BIT, "offscreen colour");
        stencil_ = create_image_attachment(ctx_, extent, stencil_format, VK_IMAGE_USAGE_DEPTH_STENCIL_ATTACHMENT_BIT,
                                           stencil_aspect(stencil_format), "offscreen stencil");

        // Render pass: the colour ends ready to be copied out.
        render_pass_ = create_render_pass(dev, kColorFormat, stencil_format, VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL);

        // Framebuffer over both attachments.
        VkImageView views[2] = {color_.view, stencil_.view};
        VkFramebufferCreateInfo fb{};
        fb.sType = VK_STRUCTURE_TYPE_FRAMEBUFFER_CREATE_INFO;
        fb.renderPass = render_pass_;
        fb.attachmentCount = 2;
        fb.pAttachments = views;
        fb.width = static_cast<uint32_t>(width_);
        fb.height = static_cast<uint32_t>(height_);
        fb.layers = 1;
        vk_check(vkCreateFramebuffer(dev, &fb, nullptr, &framebuffer_), "vkCreateFramebuffer");

        // Pipelines for this render pass.
        pipelines_ = std::make_unique<Pipelines>(ctx_, render_pass_);

        // Readback buffer: 4 bytes per pixel, tightly packed rows.
        readback_ = GpuBuffer(ctx_, static_cast<VkDeviceSize>(width_) * height_ * 4, VK_BUFFER_USAGE_TRANSFER_DST_BIT);

        // Command buffer and fence, reused for every render.
        VkCommandBufferAllocateInfo alloc{};
        alloc.sType = VK_STRUCTURE_TYPE_COMMAND_BUFFER_ALLOCATE_INFO;
        alloc.commandPool = ctx_.command_pool();
        alloc.level = VK_COMMAND_BUFFER_LEVEL_PRIMARY;
        alloc.commandBufferCount = 1;
        vk_check(vkAllocateCommandBuffers(dev, &alloc, &cmd_), "vkAllocateCommandBuffers");
        VkFenceCreateInfo fence{};
        fence.sType = VK_STRUCTURE_TYPE_FENCE_CREATE_INFO;
        vk_check(vkCreateFence(dev, &fence, nullptr, &fence_), "vkCreateFence");
    } catch (...) {
        destroy();
        throw;
    }
}

OffscreenTarget::~OffscreenTarget() { destroy(); }

void OffscreenTarget::destroy() {
    const VkDevice dev = ctx_.device();
    vkDeviceWaitIdle(dev);
    if (fence_) vkDestroyFence(dev, fence_, nullptr);
    if (cmd_) vkFreeCommandBuffers(dev, ctx_.command_pool(), 1, &cmd_);
    fence_ = VK_NULL_HANDLE;
    cmd_ = VK_NULL_HANDLE;
    geometry_ = FrameBuffers{};
    readback_.reset();
    pipelines_.reset();
    if (framebuffer_) vkDestroyFramebuffer(dev, framebuffer_, nullptr);
    if (render_pass_) vkDestroyRenderPass(dev, render_pass_, nullptr);
    framebuffer_ = VK_NULL_HANDLE;
    render_pass_ = VK_NULL_HANDLE;
    destroy_image_attachment(dev, stencil_);
    destroy_image_attachment(dev, color_);
}

Image OffscreenTarget::render(const DrawList& list, Color background) {
    if (list.width() != width_ || list.height() != height_)
        throw std::invalid_argument("draw list size does not match the offscreen target");
    const VkDevice dev = ctx_.device();
    upload_draw_list(ctx_, list, geometry_);

    // Command buffer: one-shot recording of the whole frame.
    vk_check(vkResetCommandBuffer(cmd_, 0), "vkResetCommandBuffer");
    VkCommandBufferBeginInfo begin{};
    begin.sType = VK_STRUCTURE_TYPE_COMMAND_BUFFER_BEGIN_INFO;
    begin.flags = VK_COMMAND_BUFFER_USAGE_ONE_TIME_SUBMIT_BIT;
    vk_check(vkBeginCommandBuffer(cmd_, &begin), "vkBeginCommandBuffer");

    // Render pass: clear colour to the theme background and stencil to 0, then the draw list.
    VkClearValue clear[2]{};
    clear[0].color = {{background.r / 255.0f, background.g / 255.0f, background.b / 255.0f, background.a / 255.0f}};
    clear[1].depthStencil = {1.0f, 0};
    VkRenderPassBeginInfo rp{};
    rp.sType = VK_STRUCTURE_TYPE_RENDER_PASS_BEGIN_INFO;
    rp.renderPass = render_pass_;
    rp.framebuffer = framebuffer_;
    rp.renderArea = {{0, 0}, {static_cast<uint32_t>(width_), static_cast<uint32_t>(height_)}};
    rp.clearValueCount = 2;
    rp.pClearValues = clear;
    vkCmdBeginRenderPass(cmd_, &rp, VK_SUBPASS_CONTENTS_INLINE);
    record_draw_list(cmd_, *pipelines_, list, geometry_);
    vkCmdEndRenderPass(cmd_);  // colour now in TRANSFER_SRC_OPTIMAL

    // Readback: copy the colour image into the host-visible buffer.
    VkBufferImageCopy region{};
    region.imageSubresource = {VK_IMAGE_ASPECT_COLOR_BIT, 0, 0, 1};
    region.imageExtent = {static_cast<uint32_t>(width_), static_cast<uint32_t>(height_), 1};
    vkCmdCopyImageToBuffer(cmd_, color_.image, VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL, readback_.buffer(), 1, &region);

    // Barrier: the transfer's writes visible to the host.
    VkBufferMemoryBarrier to_host{};
    to_host.sType = VK_STRUCTURE_TYPE_BUFFER_MEMORY_BARRIER;
    to_host.srcAccessMask = VK_ACCESS_TRANSFER_WRITE_BIT;
    to_host.dstAccessMask = VK_ACCESS_HOST_READ_BIT;
    to_host.srcQueueFamilyIndex = VK_QUEUE_FAMILY_IGNORED;
    to_host.dstQueueFamilyIndex = VK_QUEUE_FAMILY_IGNORED;
    to_host.buffer = readback_.buffer();
    to_host.size = VK_WHOLE_SIZE;
    vkCmdPipelineBarrier(cmd_, VK_PIPELINE_STAGE_TRANSFER_BIT, VK_PIPELINE_STAGE_HOST_BIT, 0, 0, nullptr, 1, &to_host,
                         0, nullptr);
    vk_check(vkEndCommandBuffer(cmd_), "vkEndCommandBuffer");

    // Submit and wait: offscreen frames are synchronous.
    VkSubmitInfo submit{};
    submit.sType = VK_STRUCTURE_TYPE_SUBMIT_INFO;
    submit.commandBufferCount = 1;
    submit.pCommandBuffers = &cmd_;
    vk_check(vkResetFences(dev, 1, &fence_), "vkResetFences");
    vk_check(vkQueueSubmit(ctx_.queue(), 1, &submit, fence_), "vkQueueSubmit");
    vk_check(vkWaitForFences(dev, 1, &fence_, VK_TRUE, UINT64_MAX), "vkWaitForFences");

    // BGRA -> RGBA.
    Image img;
    img.width = width_;
    img.height = height_;
    img.rgba.resize(static_cast<size_t>(width_) * height_ * 4);
    const auto* src = static_cast<const uint8_t*>(readback_.data());
    for (size_t i = 0; i < img.rgba.size(); i += 4) {
        img.rgba[i + 0] = src[i + 2];
        img.rgba[i + 1] = src[i + 1];
        img.rgba[i + 2] = src[i + 0];
        img.rgba[i + 3] = src[i + 3];
    }
    return img;
}

}  // namespace contactlab::render
