// window_target.hpp — the window's end of the one drawing path: a draw list (plus an overlay such
// as ImGui) recorded into the acquired swapchain image and presented. Frames in flight, their
// fences and semaphores, swapchain recreation on resize / out-of-date / suboptimal, and a
// screenshot read back from the swapchain image itself.
#pragma once

#include "engine/editor/swapchain.hpp"
#include "engine/render/draw_list.hpp"
#include "engine/render/image.hpp"
#include "engine/render/pipelines.hpp"
#include "engine/render/record.hpp"

#include <array>
#include <functional>
#include <memory>

namespace contactlab::editor {

enum class FrameOutcome { presented, skipped };

class WindowTarget {
public:
    static constexpr int kFramesInFlight = 2;

    WindowTarget(const render::VulkanContext& ctx, VkSurfaceKHR surface, bool vsync);
    ~WindowTarget();
    WindowTarget(const WindowTarget&) = delete;
    WindowTarget& operator=(const WindowTarget&) = delete;

    VkRenderPass render_pass() const { return render_pass_; }
    uint32_t min_image_count() const { return swapchain_.min_image_count(); }
    uint32_t image_count() const { return static_cast<uint32_t>(swapchain_.images().size()); }
    VkPresentModeKHR present_mode() const { return swapchain_.present_mode(); }

    // Makes the swapchain match a framebuffer of width x height px (recreating it after a resize
    // or an out-of-date report). False while the window is minimised (0x0): draw nothing.
    bool prepare(int width, int height);
    VkExtent2D extent() const { return swapchain_.extent(); }
    // Swapchain recreations so far (resize, out-of-date, suboptimal).
    int recreations() const { return recreations_; }

    // Records the list (its size should be extent()), then `overlay` inside the same render pass,
    // and presents. With `screenshot`, the presented image is copied out and returned there (RGBA).
    FrameOutcome render(const render::DrawList& list, render::Color background,
                        const std::function<void(VkCommandBuffer)>& overlay, render::Image* screenshot);

private:
    struct Frame {
        VkCommandBuffer cmd = VK_NULL_HANDLE;
        VkFence done = VK_NULL_HANDLE;           // signalled when the frame's commands finished
        VkSemaphore acquired = VK_NULL_HANDLE;   // image acquired -> rendering may write it
        render::FrameBuffers geometry;           // the draw list's vertices and indices
    };
    void recreate(int width, int height);
    void record_readback(VkCommandBuffer cmd, VkImage image);
    void destroy();

    const render::VulkanContext& ctx_;
    bool vsync_;
    VkFormat stencil_format_;
    VkRenderPass render_pass_ = VK_NULL_HANDLE;
    std::unique_ptr<render::Pipelines> pipelines_;
    Swapchain swapchain_;
    std::array<Frame, kFramesInFlight> frames_{};
    std::vector<VkSemaphore> rendered_;  // per swapchain image: rendering done -> present
    uint32_t frame_index_ = 0;
    bool out_of_date_ = false;
    int width_ = 0, height_ = 0, recreations_ = 0;
    render::GpuBuffer readback_;
};

}  // namespace contactlab::editor
