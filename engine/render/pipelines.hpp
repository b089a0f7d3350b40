// pipelines.hpp — the render pass layout and the three graphics pipelines of the drawing path
// (blended triangles, stencil mark, stencil cover), all from shaders/solid.{vert,frag}.
#pragma once

#include "engine/render/context.hpp"
#include "engine/render/draw_list.hpp"

namespace contactlab::render {

// UNORM colour (never SRGB) so the window and offscreen targets share one pipeline set and the
// bytes written are exactly the blended values.
inline constexpr VkFormat kColorFormat = VK_FORMAT_B8G8R8A8_UNORM;

// A stencil (or depth-stencil) format the device can attach: S8, D24S8 or D32S8.
VkFormat pick_stencil_format(const VulkanContext& ctx);

// One subpass: colour cleared then stored and left in `color_final_layout`; stencil cleared, not
// stored. 1x sampling. With `keep_color` the colour is loaded instead of cleared and must be in
// COLOR_ATTACHMENT_OPTIMAL when the pass begins (the editor copies its cached scene layer in
// first); the two kinds are compatible, so one pipeline set and framebuffer serve both.
VkRenderPass create_render_pass(VkDevice device, VkFormat color, VkFormat stencil, VkImageLayout color_final_layout,
                                bool keep_color = false);

class Pipelines {
public:
    Pipelines(const VulkanContext& ctx, VkRenderPass render_pass);
    ~Pipelines();
    Pipelines(const Pipelines&) = delete;
    Pipelines& operator=(const Pipelines&) = delete;

    VkPipeline pipeline(DrawKind kind) const { return pipelines_[static_cast<int>(kind)]; }
    VkPipelineLayout layout() const { return layout_; }

private:
    void destroy();

    VkDevice device_;
    VkPipelineLayout layout_ = VK_NULL_HANDLE;
    VkPipeline pipelines_[3] = {VK_NULL_HANDLE, VK_NULL_HANDLE, VK_NULL_HANDLE};
};

// Push constants of solid.vert (std430 layout: one vec2 at offset 0).
struct PushConstants {
    float px_to_ndc[2];
};

}  // namespace contactlab::render
