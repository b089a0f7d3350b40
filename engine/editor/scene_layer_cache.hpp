// scene_layer_cache.hpp — the frame's scene layer (grid and solids, render::build_scene_layer)
// kept as a picture between frames. On lavapipe rasterising it was 6 ms of a block's frame and
// more on a long terrain (the solids' stencil fills cover the screen several times over) while
// only the finger moved; copying the kept picture into the swapchain image costs a memcpy.
//
// The picture is drawn with the window's pipelines into an image of its own (colour + stencil,
// the swapchain's formats and size), then copied into each frame's image before the render pass,
// which loads it instead of clearing. The bytes are the ones drawing the layer in the pass would
// give: same formats, same blending onto the same background, and the stencil left at zero by
// every cover pass. It is drawn again only when its key (the editor's document revision, view
// and theme, see editor.cpp) changes.
#pragma once

#include "engine/render/attachment.hpp"
#include "engine/render/context.hpp"
#include "engine/render/draw_list.hpp"
#include "engine/render/pipelines.hpp"
#include "engine/render/record.hpp"

#include <cstdint>

namespace contactlab::editor {

class SceneLayerCache {
public:
    SceneLayerCache(const render::VulkanContext& ctx, VkFormat stencil_format);
    ~SceneLayerCache();
    SceneLayerCache(const SceneLayerCache&) = delete;
    SceneLayerCache& operator=(const SceneLayerCache&) = delete;

    // Makes the images width x height (the device must be idle: the swapchain is being
    // recreated); forgets the picture.
    void resize(VkExtent2D extent);
    // Whether the picture is that of `key` (never of 0).
    bool holds(std::uint64_t key) const { return key != 0 && key_ == key; }
    // Records drawing `list` on `background` into the cache's image and remembers `key`. Nothing
    // in flight may still read the image or the list's buffers (the caller waits for its frames).
    void record_update(VkCommandBuffer cmd, const render::Pipelines& pipelines, const render::DrawList& list,
                       render::Color background, std::uint64_t key);
    // Records copying the picture into `target` (any layout before: its contents are replaced),
    // leaving `target` in COLOR_ATTACHMENT_OPTIMAL for a render pass that loads it.
    void record_copy(VkCommandBuffer cmd, VkImage target) const;
    // Pictures drawn so far (tests: a scene edit or a view change draws a new one).
    long updates() const { return updates_; }

private:
    void destroy_images();

    const render::VulkanContext& ctx_;
    VkFormat stencil_format_;
    VkRenderPass render_pass_ = VK_NULL_HANDLE;
    VkExtent2D extent_{0, 0};
    render::ImageAttachment color_, stencil_;
    VkFramebuffer framebuffer_ = VK_NULL_HANDLE;
    render::FrameBuffers geometry_;
    std::uint64_t key_ = 0;
    long updates_ = 0;
};

}  // namespace contactlab::editor
