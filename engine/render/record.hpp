// record.hpp — the last step of the drawing path: a draw list replayed into a command buffer
// inside a render pass that the caller (offscreen target or, later, the window) has begun.
#pragma once

#include "engine/render/draw_list.hpp"
#include "engine/render/gpu_buffer.hpp"
#include "engine/render/pipelines.hpp"

namespace contactlab::render {

// The draw list's vertices and indices, copied into host-visible buffers for one frame.
struct FrameBuffers {
    GpuBuffer vertices;
    GpuBuffer indices;
};

// Copies the draw list into `buffers` (grown as needed).
void upload_draw_list(const VulkanContext& ctx, const DrawList& list, FrameBuffers& buffers);

// Records viewport, push constants and one indexed draw per command.
void record_draw_list(VkCommandBuffer cmd, const Pipelines& pipelines, const DrawList& list,
                      const FrameBuffers& buffers);

}  // namespace contactlab::render
