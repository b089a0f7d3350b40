// scene_layer_cache.cpp — the kept scene layer: its images, its redraw and its copy (see
// scene_layer_cache.hpp).
#include "engine/editor/scene_layer_cache.hpp"

#include "engine/render/vk_check.hpp"

namespace contactlab::editor {

using render::vk_check;

SceneLayerCache::SceneLayerCache(const render::VulkanContext& ctx, VkFormat stencil_format)
    : ctx_(ctx), stencil_format_(stencil_format) {
    // Render pass: the window's (colour cleared, stencil cleared), ending ready to be copied from;
    // compatible with the window's, so the window's pipelines draw in it.
    render_pass_ = render::create_render_pass(ctx_.device(), render::kColorFormat, stencil_format_,
                                              VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL);
}

SceneLayerCache::~SceneLayerCache() {
    vkDeviceWaitIdle(ctx_.device());
    destroy_images();
    geometry_ = render::FrameBuffers{};
    if (render_pass_) vkDestroyRenderPass(ctx_.device(), render_pass_, nullptr);
}

void SceneLayerCache::destroy_images() {
    if (framebuffer_) vkDestroyFramebuffer(ctx_.device(), framebuffer_, nullptr);
    framebuffer_ = VK_NULL_HANDLE;
    destroy_image_attachment(ctx_.device(), stencil_);
    destroy_image_attachment(ctx_.device(), color_);
    key_ = 0;
}

void SceneLayerCache::resize(VkExtent2D extent) {
    destroy_images();
    extent_ = extent;
    if (extent.width == 0 || extent.height == 0) return;
    // Attachments: colour (drawn, then a copy source) and its own stencil for the solids' fills.
    color_ = render::create_image_attachment(ctx_, extent_, render::kColorFormat,
                                             VK_IMAGE_USAGE_COLOR_ATTACHMENT_BIT | VK_IMAGE_USAGE_TRANSFER_SRC_BIT,
                                             VK_IMAGE_ASPECT_COLOR_BIT, "scene layer colour");
    stencil_ = render::create_image_attachment(ctx_, extent_, stencil_format_, VK_IMAGE_USAGE_DEPTH_STENCIL_ATTACHMENT_BIT,
                                               render::stencil_aspect(stencil_format_), "scene layer stencil");

    // Framebuffer over both.
    VkImageView views[2] = {color_.view, stencil_.view};
    VkFramebufferCreateInfo fb{};
    fb.sType = VK_STRUCTURE_TYPE_FRAMEBUFFER_CREATE_INFO;
    fb.renderPass = render_pass_;
    fb.attachmentCount = 2;
    fb.pAttachments = views;
    fb.width = extent_.width;
    fb.height = extent_.height;
    fb.layers = 1;
    vk_check(vkCreateFramebuffer(ctx_.device(), &fb, nullptr, &framebuffer_), "vkCreateFramebuffer (scene layer)");
}

void SceneLayerCache::record_update(VkCommandBuffer cmd, const render::Pipelines& pipelines, const render::DrawList& list,
                                    render::Color background, std::uint64_t key) {
    // Geometry: the layer's vertices into the cache's own buffers (no frame in flight reads them).
    render::upload_draw_list(ctx_, list, geometry_);

    // Render pass: clear to the background, the layer, ending as a transfer source.
    VkClearValue clear[2]{};
    clear[0].color = {{background.r / 255.0f, background.g / 255.0f, background.b / 255.0f, background.a / 255.0f}};
    clear[1].depthStencil = {1.0f, 0};
    VkRenderPassBeginInfo rp{};
    rp.sType = VK_STRUCTURE_TYPE_RENDER_PASS_BEGIN_INFO;
    rp.renderPass = render_pass_;
    rp.framebuffer = framebuffer_;
    rp.renderArea = {{0, 0}, extent_};
    rp.clearValueCount = 2;
    rp.pClearValues = clear;
    vkCmdBeginRenderPass(cmd, &rp, VK_SUBPASS_CONTENTS_INLINE);
    render::record_draw_list(cmd, pipelines, list, geometry_);
    vkCmdEndRenderPass(cmd);
    key_ = key;
    ++updates_;
}

void SceneLayerCache::record_copy(VkCommandBuffer cmd, VkImage target) const {
    // Barrier: the target's old contents are discarded; it becomes a transfer destination once
    // acquired (the submit waits for the acquisition at the transfer stage too).
    VkImageMemoryBarrier to_dst{};
    to_dst.sType = VK_STRUCTURE_TYPE_IMAGE_MEMORY_BARRIER;
    to_dst.srcAccessMask = 0;
    to_dst.dstAccessMask = VK_ACCESS_TRANSFER_WRITE_BIT;
    to_dst.oldLayout = VK_IMAGE_LAYOUT_UNDEFINED;
    to_dst.newLayout = VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL;
    to_dst.srcQueueFamilyIndex = VK_QUEUE_FAMILY_IGNORED;
    to_dst.dstQueueFamilyIndex = VK_QUEUE_FAMILY_IGNORED;
    to_dst.image = target;
    to_dst.subresourceRange = {VK_IMAGE_ASPECT_COLOR_BIT, 0, 1, 0, 1};
    vkCmdPipelineBarrier(cmd, VK_PIPELINE_STAGE_TRANSFER_BIT, VK_PIPELINE_STAGE_TRANSFER_BIT, 0, 0, nullptr, 0, nullptr, 1,
                         &to_dst);

    // Copy: the whole picture (the render pass that drew it left it a transfer source).
    VkImageCopy region{};
    region.srcSubresource = {VK_IMAGE_ASPECT_COLOR_BIT, 0, 0, 1};
    region.dstSubresource = {VK_IMAGE_ASPECT_COLOR_BIT, 0, 0, 1};
    region.extent = {extent_.width, extent_.height, 1};
    vkCmdCopyImage(cmd, color_.image, VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL, target, VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL, 1,
                   &region);

    // Barrier: the copy done before the render pass loads and blends onto it.
    VkImageMemoryBarrier to_color = to_dst;
    to_color.srcAccessMask = VK_ACCESS_TRANSFER_WRITE_BIT;
    to_color.dstAccessMask = VK_ACCESS_COLOR_ATTACHMENT_READ_BIT | VK_ACCESS_COLOR_ATTACHMENT_WRITE_BIT;
    to_color.oldLayout = VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL;
    to_color.newLayout = VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL;
    vkCmdPipelineBarrier(cmd, VK_PIPELINE_STAGE_TRANSFER_BIT, VK_PIPELINE_STAGE_COLOR_ATTACHMENT_OUTPUT_BIT, 0, 0, nullptr, 0,
                         nullptr, 1, &to_color);
}

}  // namespace contactlab::editor
