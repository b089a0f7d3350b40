// window_target.cpp — acquire, record, submit, present, read back (see window_target.hpp).
#include "engine/editor/window_target.hpp"

#include "engine/render/vk_check.hpp"

#include <cstring>

namespace contactlab::editor {

using render::vk_check;

WindowTarget::WindowTarget(const render::VulkanContext& ctx, VkSurfaceKHR surface, bool vsync)
    : ctx_(ctx), vsync_(vsync), stencil_format_(render::pick_stencil_format(ctx)), swapchain_(ctx, surface) {
    const VkDevice dev = ctx_.device();
    try {
        // Render pass: the renderer's layout (colour cleared and stored, stencil cleared), ending
        // ready for presentation.
        render_pass_ = render::create_render_pass(dev, render::kColorFormat, stencil_format_,
                                                  VK_IMAGE_LAYOUT_PRESENT_SRC_KHR);
        // The same render pass loading its colour: frames whose base layer was copied in.
        load_pass_ = render::create_render_pass(dev, render::kColorFormat, stencil_format_,
                                                VK_IMAGE_LAYOUT_PRESENT_SRC_KHR, true);
        // Pipelines: the same three the offscreen target builds, for this render pass.
        pipelines_ = std::make_unique<render::Pipelines>(ctx_, render_pass_);
        cache_ = std::make_unique<SceneLayerCache>(ctx_, stencil_format_);

        // Per frame in flight: a command buffer, a fence (created signalled: the first wait passes)
        // and the image-acquired semaphore.
        for (Frame& f : frames_) {
            VkCommandBufferAllocateInfo alloc{};
            alloc.sType = VK_STRUCTURE_TYPE_COMMAND_BUFFER_ALLOCATE_INFO;
            alloc.commandPool = ctx_.command_pool();
            alloc.level = VK_COMMAND_BUFFER_LEVEL_PRIMARY;
            alloc.commandBufferCount = 1;
            vk_check(vkAllocateCommandBuffers(dev, &alloc, &f.cmd), "vkAllocateCommandBuffers");
            VkFenceCreateInfo fence{};
            fence.sType = VK_STRUCTURE_TYPE_FENCE_CREATE_INFO;
            fence.flags = VK_FENCE_CREATE_SIGNALED_BIT;
            vk_check(vkCreateFence(dev, &fence, nullptr, &f.done), "vkCreateFence");
            VkSemaphoreCreateInfo sem{};
            sem.sType = VK_STRUCTURE_TYPE_SEMAPHORE_CREATE_INFO;
            vk_check(vkCreateSemaphore(dev, &sem, nullptr, &f.acquired), "vkCreateSemaphore");
        }
    } catch (...) {
        destroy();
        throw;
    }
}

WindowTarget::~WindowTarget() { destroy(); }

void WindowTarget::destroy() {
    const VkDevice dev = ctx_.device();
    vkDeviceWaitIdle(dev);
    for (VkSemaphore s : rendered_) vkDestroySemaphore(dev, s, nullptr);
    rendered_.clear();
    for (Frame& f : frames_) {
        if (f.acquired) vkDestroySemaphore(dev, f.acquired, nullptr);
        if (f.done) vkDestroyFence(dev, f.done, nullptr);
        if (f.cmd) vkFreeCommandBuffers(dev, ctx_.command_pool(), 1, &f.cmd);
        f = Frame{};
    }
    readback_.reset();
    cache_.reset();
    swapchain_.destroy();
    pipelines_.reset();
    if (load_pass_) vkDestroyRenderPass(dev, load_pass_, nullptr);
    if (render_pass_) vkDestroyRenderPass(dev, render_pass_, nullptr);
    load_pass_ = VK_NULL_HANDLE;
    render_pass_ = VK_NULL_HANDLE;
}

void WindowTarget::recreate(int width, int height) {
    const VkDevice dev = ctx_.device();
    // Swapchain recreation: nothing may still use the old images.
    vkDeviceWaitIdle(dev);
    for (VkSemaphore s : rendered_) vkDestroySemaphore(dev, s, nullptr);
    rendered_.clear();
    const bool had = swapchain_.valid();
    if (!swapchain_.create(render_pass_, stencil_format_, width, height, vsync_)) return;
    if (had) ++recreations_;
    // The kept base layer: the new size, drawn again at the next frame.
    cache_->resize(swapchain_.extent());
    // Render-finished semaphores: one per swapchain image (presentation has no fence to tell
    // when a semaphore may be reused, the image's next acquisition does).
    rendered_.resize(swapchain_.images().size(), VK_NULL_HANDLE);
    for (VkSemaphore& s : rendered_) {
        VkSemaphoreCreateInfo sem{};
        sem.sType = VK_STRUCTURE_TYPE_SEMAPHORE_CREATE_INFO;
        vk_check(vkCreateSemaphore(dev, &sem, nullptr, &s), "vkCreateSemaphore");
    }
    width_ = width;
    height_ = height;
    out_of_date_ = false;
}

bool WindowTarget::prepare(int width, int height) {
    if (width <= 0 || height <= 0) return false;  // minimised: keep the old swapchain, draw nothing
    if (!swapchain_.valid() || rendered_.empty() || out_of_date_ || width != width_ || height != height_)
        recreate(width, height);
    return swapchain_.valid() && !rendered_.empty();
}

void WindowTarget::record_readback(VkCommandBuffer cmd, VkImage image) {
    const VkExtent2D e = swapchain_.extent();
    // Barrier: the presentable image (colour writes done) becomes a transfer source.
    VkImageMemoryBarrier to_src{};
    to_src.sType = VK_STRUCTURE_TYPE_IMAGE_MEMORY_BARRIER;
    to_src.srcAccessMask = VK_ACCESS_COLOR_ATTACHMENT_WRITE_BIT;
    to_src.dstAccessMask = VK_ACCESS_TRANSFER_READ_BIT;
    to_src.oldLayout = VK_IMAGE_LAYOUT_PRESENT_SRC_KHR;
    to_src.newLayout = VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL;
    to_src.srcQueueFamilyIndex = VK_QUEUE_FAMILY_IGNORED;
    to_src.dstQueueFamilyIndex = VK_QUEUE_FAMILY_IGNORED;
    to_src.image = image;
    to_src.subresourceRange = {VK_IMAGE_ASPECT_COLOR_BIT, 0, 1, 0, 1};
    vkCmdPipelineBarrier(cmd, VK_PIPELINE_STAGE_COLOR_ATTACHMENT_OUTPUT_BIT, VK_PIPELINE_STAGE_TRANSFER_BIT, 0, 0,
                         nullptr, 0, nullptr, 1, &to_src);

    // Copy: the whole image into the host-visible buffer, tightly packed BGRA rows.
    VkBufferImageCopy region{};
    region.imageSubresource = {VK_IMAGE_ASPECT_COLOR_BIT, 0, 0, 1};
    region.imageExtent = {e.width, e.height, 1};
    vkCmdCopyImageToBuffer(cmd, image, VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL, readback_.buffer(), 1, &region);

    // Barriers: the image back to the presentation layout; the copy visible to the host.
    VkImageMemoryBarrier to_present = to_src;
    to_present.srcAccessMask = VK_ACCESS_TRANSFER_READ_BIT;
    to_present.dstAccessMask = 0;
    to_present.oldLayout = VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL;
    to_present.newLayout = VK_IMAGE_LAYOUT_PRESENT_SRC_KHR;
    VkBufferMemoryBarrier to_host{};
    to_host.sType = VK_STRUCTURE_TYPE_BUFFER_MEMORY_BARRIER;
    to_host.srcAccessMask = VK_ACCESS_TRANSFER_WRITE_BIT;
    to_host.dstAccessMask = VK_ACCESS_HOST_READ_BIT;
    to_host.srcQueueFamilyIndex = VK_QUEUE_FAMILY_IGNORED;
    to_host.dstQueueFamilyIndex = VK_QUEUE_FAMILY_IGNORED;
    to_host.buffer = readback_.buffer();
    to_host.size = VK_WHOLE_SIZE;
    vkCmdPipelineBarrier(cmd, VK_PIPELINE_STAGE_TRANSFER_BIT, VK_PIPELINE_STAGE_HOST_BIT | VK_PIPELINE_STAGE_BOTTOM_OF_PIPE_BIT,
                         0, 0, nullptr, 1, &to_host, 1, &to_present);
}

FrameOutcome WindowTarget::render(const BaseLayer& base, std::span<const Layer> layers, render::Color background,
                                  const std::function<void(VkCommandBuffer)>& overlay, render::Image* screenshot,
                                  FrameStages* stages) {
    const VkDevice dev = ctx_.device();
    if (!swapchain_.valid() || rendered_.empty()) return FrameOutcome::skipped;
    Frame& f = frames_[frame_index_];

    // Wait for this slot's previous frame: its command buffer, geometry and semaphore are free.
    StageTimer waiting(stages, Stage::frame_wait);
    vk_check(vkWaitForFences(dev, 1, &f.done, VK_TRUE, UINT64_MAX), "vkWaitForFences");
    // A new picture of the base layer: the other frame in flight may still copy the old one.
    const bool keep_base = base.cache_key != 0 && swapchain_.copy_target();
    const bool redraw_base = keep_base && !cache_->holds(base.cache_key);
    if (redraw_base)
        for (Frame& other : frames_) vk_check(vkWaitForFences(dev, 1, &other.done, VK_TRUE, UINT64_MAX), "vkWaitForFences");
    waiting.stop();
    StageTimer recording(stages, Stage::record);

    // Acquire: out-of-date means recreate and skip; suboptimal still signalled the semaphore.
    uint32_t image_index = 0;
    VkResult r = vkAcquireNextImageKHR(dev, swapchain_.handle(), UINT64_MAX, f.acquired, VK_NULL_HANDLE, &image_index);
    if (r == VK_ERROR_OUT_OF_DATE_KHR) {
        out_of_date_ = true;
        return FrameOutcome::skipped;
    }
    if (r == VK_SUBOPTIMAL_KHR) out_of_date_ = true;
    else vk_check(r, "vkAcquireNextImageKHR");
    vk_check(vkResetFences(dev, 1, &f.done), "vkResetFences");

    const SwapchainImage& target = swapchain_.images()[image_index];
    const VkExtent2D e = swapchain_.extent();
    // Geometry: each layer copied into this slot's buffers unless they already hold its revision
    // (slot 0: the base layer when it is drawn in the pass).
    if (f.geometry.size() < layers.size() + 1) {
        f.geometry.resize(layers.size() + 1);
        f.uploaded.resize(layers.size() + 1, 0);
    }
    if (!keep_base) render::upload_draw_list(ctx_, *base.list, f.geometry[0]);
    for (std::size_t i = 0; i < layers.size(); ++i) {
        if (layers[i].revision != 0 && f.uploaded[i + 1] == layers[i].revision) continue;
        render::upload_draw_list(ctx_, *layers[i].list, f.geometry[i + 1]);
        f.uploaded[i + 1] = layers[i].revision;
    }
    if (screenshot)
        render::ensure_buffer(ctx_, readback_, static_cast<VkDeviceSize>(e.width) * e.height * 4,
                              VK_BUFFER_USAGE_TRANSFER_DST_BIT);

    // Command buffer: re-recorded every frame.
    vk_check(vkResetCommandBuffer(f.cmd, 0), "vkResetCommandBuffer");
    VkCommandBufferBeginInfo begin{};
    begin.sType = VK_STRUCTURE_TYPE_COMMAND_BUFFER_BEGIN_INFO;
    begin.flags = VK_COMMAND_BUFFER_USAGE_ONE_TIME_SUBMIT_BIT;
    vk_check(vkBeginCommandBuffer(f.cmd, &begin), "vkBeginCommandBuffer");

    // Base layer kept as a picture: drawn again if its key changed, then copied into the image.
    if (redraw_base) cache_->record_update(f.cmd, *pipelines_, *base.list, background, base.cache_key);
    if (keep_base) cache_->record_copy(f.cmd, target.image);

    // Render pass: the copied base loaded, or a clear to the theme background and the base drawn;
    // the layers, then the overlay (ImGui).
    VkClearValue clear[2]{};
    clear[0].color = {{background.r / 255.0f, background.g / 255.0f, background.b / 255.0f, background.a / 255.0f}};
    clear[1].depthStencil = {1.0f, 0};
    VkRenderPassBeginInfo rp{};
    rp.sType = VK_STRUCTURE_TYPE_RENDER_PASS_BEGIN_INFO;
    rp.renderPass = keep_base ? load_pass_ : render_pass_;
    rp.framebuffer = target.framebuffer;
    rp.renderArea = {{0, 0}, e};
    rp.clearValueCount = 2;
    rp.pClearValues = clear;
    vkCmdBeginRenderPass(f.cmd, &rp, VK_SUBPASS_CONTENTS_INLINE);
    if (!keep_base) render::record_draw_list(f.cmd, *pipelines_, *base.list, f.geometry[0]);
    for (std::size_t i = 0; i < layers.size(); ++i)
        render::record_draw_list(f.cmd, *pipelines_, *layers[i].list, f.geometry[i + 1]);
    if (overlay) overlay(f.cmd);
    vkCmdEndRenderPass(f.cmd);  // the image is now in PRESENT_SRC_KHR

    // Screenshot: copy the very image that is presented.
    if (screenshot) record_readback(f.cmd, target.image);
    vk_check(vkEndCommandBuffer(f.cmd), "vkEndCommandBuffer");
    recording.stop();

    // Submit: wait for the acquisition before writing colour (or copying the base layer in);
    // signal the image's semaphore.
    const VkPipelineStageFlags wait_stage = VK_PIPELINE_STAGE_COLOR_ATTACHMENT_OUTPUT_BIT | VK_PIPELINE_STAGE_TRANSFER_BIT;
    VkSubmitInfo submit{};
    submit.sType = VK_STRUCTURE_TYPE_SUBMIT_INFO;
    submit.waitSemaphoreCount = 1;
    submit.pWaitSemaphores = &f.acquired;
    submit.pWaitDstStageMask = &wait_stage;
    submit.commandBufferCount = 1;
    submit.pCommandBuffers = &f.cmd;
    submit.signalSemaphoreCount = 1;
    submit.pSignalSemaphores = &rendered_[image_index];
    StageTimer submitting(stages, Stage::submit);
    vk_check(vkQueueSubmit(ctx_.queue(), 1, &submit, f.done), "vkQueueSubmit");
    submitting.stop();
    if (stage_timing_ && stages) {
        // Measuring: wait for the queue here, so the rasteriser's work is not counted as present.
        StageTimer rasterising(stages, Stage::rasterise);
        vk_check(vkWaitForFences(dev, 1, &f.done, VK_TRUE, UINT64_MAX), "vkWaitForFences (timed)");
    }

    // Present: out-of-date or suboptimal marks the swapchain for recreation before the next frame.
    VkSwapchainKHR sc = swapchain_.handle();
    VkPresentInfoKHR present{};
    present.sType = VK_STRUCTURE_TYPE_PRESENT_INFO_KHR;
    present.waitSemaphoreCount = 1;
    present.pWaitSemaphores = &rendered_[image_index];
    present.swapchainCount = 1;
    present.pSwapchains = &sc;
    present.pImageIndices = &image_index;
    StageTimer presenting(stages, Stage::present);
    r = vkQueuePresentKHR(ctx_.queue(), &present);
    presenting.stop();
    if (r == VK_ERROR_OUT_OF_DATE_KHR || r == VK_SUBOPTIMAL_KHR) out_of_date_ = true;
    else vk_check(r, "vkQueuePresentKHR");
    frame_index_ = (frame_index_ + 1) % kFramesInFlight;

    // Readback: wait for this frame, then BGRA -> RGBA.
    if (screenshot) {
        vk_check(vkWaitForFences(dev, 1, &f.done, VK_TRUE, UINT64_MAX), "vkWaitForFences (screenshot)");
        screenshot->width = static_cast<int>(e.width);
        screenshot->height = static_cast<int>(e.height);
        screenshot->rgba.resize(static_cast<size_t>(e.width) * e.height * 4);
        const auto* src = static_cast<const uint8_t*>(readback_.data());
        for (size_t i = 0; i < screenshot->rgba.size(); i += 4) {
            screenshot->rgba[i + 0] = src[i + 2];
            screenshot->rgba[i + 1] = src[i + 1];
            screenshot->rgba[i + 2] = src[i + 0];
            screenshot->rgba[i + 3] = 255;  // the window is opaque
        }
    }
    return FrameOutcome::presented;
}

}  // namespace contactlab::editor
