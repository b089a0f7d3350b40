// offscreen.hpp — render a draw list into an image with no window, and read it back.
//
// The target: a B8G8R8A8_UNORM colour image and a stencil image (1x sampling), a framebuffer,
// the pipelines, and a host-visible readback buffer. One render at a time; each waits for the GPU.
#pragma once

#include "engine/render/attachment.hpp"
#include "engine/render/context.hpp"
#include "engine/render/draw_list.hpp"
#include "engine/render/image.hpp"
#include "engine/render/pipelines.hpp"
#include "engine/render/record.hpp"

#include <memory>

namespace contactlab::render {

class OffscreenTarget {
public:
    OffscreenTarget(const VulkanContext& ctx, int width, int height);
    ~OffscreenTarget();
    OffscreenTarget(const OffscreenTarget&) = delete;
    OffscreenTarget& operator=(const OffscreenTarget&) = delete;

    int width() const { return width_; }
    int height() const { return height_; }

    // Clears to `background`, draws the list (its size must match the target), waits, and returns
    // the pixels as RGBA.
    Image render(const DrawList& list, Color background);

private:
    void destroy();

    const VulkanContext& ctx_;
    int width_, height_;
    ImageAttachment color_, stencil_;
    VkRenderPass render_pass_ = VK_NULL_HANDLE;
    VkFramebuffer framebuffer_ = VK_NULL_HANDLE;
    std::unique_ptr<Pipelines> pipelines_;
    GpuBuffer readback_;
    FrameBuffers geometry_;
    VkCommandBuffer cmd_ = VK_NULL_HANDLE;
    VkFence fence_ = VK_NULL_HANDLE;
};

}  // namespace contactlab::render
