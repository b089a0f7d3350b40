// window_target.hpp — the window's end of the one drawing path: a draw list (plus an overlay such
// as ImGui) recorded into the acquired swapchain image and presented. Frames in flight, their
// fences and semaphores, swapchain recreation on resize / out-of-date / suboptimal, and a
// screenshot read back from the swapchain image itself.
#pragma once

#include "engine/editor/frame_stages.hpp"
#include "engine/editor/scene_layer_cache.hpp"
#include "engine/editor/swapchain.hpp"
#include "engine/render/draw_list.hpp"
#include "engine/render/image.hpp"
#include "engine/render/pipelines.hpp"
#include "engine/render/record.hpp"

#include <array>
#include <functional>
#include <memory>
#include <span>
#include <vector>

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
    // With stage timing on, render() waits for the queue right after submitting, so the time the
    // rasteriser takes (lavapipe: on the UI's own core) is timed as Stage::rasterise instead of
    // hiding in the next present or fence wait. Off for interactive use: it would stop a GPU's
    // work overlapping the next frame's CPU work.
    void set_stage_timing(bool on) { stage_timing_ = on; }
    // Pictures of the base layer drawn so far (scene_layer_cache.hpp).
    long base_layer_updates() const { return cache_ ? cache_->updates() : 0; }
    // Swapchain recreations so far (resize, out-of-date, suboptimal).
    int recreations() const { return recreations_; }

    // One draw list of a frame. `revision` names its contents: a frame slot whose buffers already
    // hold that revision does not copy the list again (0: copy it every frame).
    struct Layer {
        const render::DrawList* list = nullptr;
        std::uint64_t revision = 0;
    };
    // The bottom of the frame. With a `cache_key` (not 0) it is kept as a picture between frames
    // (scene_layer_cache.hpp) and drawn again only when the key changes; with 0, or where the
    // swapchain's images cannot be copied into, it is drawn in the render pass like a Layer.
    struct BaseLayer {
        const render::DrawList* list = nullptr;
        std::uint64_t cache_key = 0;
    };
    // Records the base, then the layers in order (their size should be extent()), then `overlay`
    // inside the same render pass, and presents. With `screenshot`, the presented image is copied
    // out and returned there (RGBA). With `stages`, the time of each step is added there
    // (frame_stages.hpp).
    FrameOutcome render(const BaseLayer& base, std::span<const Layer> layers, render::Color background,
                        const std::function<void(VkCommandBuffer)>& overlay, render::Image* screenshot,
                        FrameStages* stages = nullptr);

private:
    struct Frame {
        VkCommandBuffer cmd = VK_NULL_HANDLE;
        VkFence done = VK_NULL_HANDLE;           // signalled when the frame's commands finished
        VkSemaphore acquired = VK_NULL_HANDLE;   // image acquired -> rendering may write it
        std::vector<render::FrameBuffers> geometry;  // each layer's vertices and indices
        std::vector<std::uint64_t> uploaded;         // the revision each layer's buffers hold
    };
    void recreate(int width, int height);
    void record_readback(VkCommandBuffer cmd, VkImage image);
    void destroy();

    const render::VulkanContext& ctx_;
    bool vsync_;
    VkFormat stencil_format_;
    VkRenderPass render_pass_ = VK_NULL_HANDLE;
    VkRenderPass load_pass_ = VK_NULL_HANDLE;  // render_pass_, loading the copied base layer
    std::unique_ptr<SceneLayerCache> cache_;
    std::unique_ptr<render::Pipelines> pipelines_;
    Swapchain swapchain_;
    std::array<Frame, kFramesInFlight> frames_{};
    std::vector<VkSemaphore> rendered_;  // per swapchain image: rendering done -> present
    uint32_t frame_index_ = 0;
    bool out_of_date_ = false;
    bool stage_timing_ = false;
    int width_ = 0, height_ = 0, recreations_ = 0;
    render::GpuBuffer readback_;
};

}  // namespace contactlab::editor
