// record.cpp — draw list -> Vulkan commands.
#include "engine/render/record.hpp"

#include <cstring>

namespace contactlab::render {

void upload_draw_list(const VulkanContext& ctx, const DrawList& list, FrameBuffers& buffers) {
    const VkDeviceSize vbytes = list.vertices().size() * sizeof(Vertex);
    const VkDeviceSize ibytes = list.indices().size() * sizeof(uint32_t);
    ensure_buffer(ctx, buffers.vertices, vbytes > 0 ? vbytes : 1, VK_BUFFER_USAGE_VERTEX_BUFFER_BIT);
    ensure_buffer(ctx, buffers.indices, ibytes > 0 ? ibytes : 1, VK_BUFFER_USAGE_INDEX_BUFFER_BIT);
    if (vbytes) std::memcpy(buffers.vertices.data(), list.vertices().data(), vbytes);
    if (ibytes) std::memcpy(buffers.indices.data(), list.indices().data(), ibytes);
}

void record_draw_list(VkCommandBuffer cmd, const Pipelines& pipelines, const DrawList& list,
                      const FrameBuffers& buffers) {
    // Viewport and scissor: the whole target, y down (pixel coordinates map straight through).
    const VkViewport viewport{0.0f, 0.0f, static_cast<float>(list.width()), static_cast<float>(list.height()), 0.0f, 1.0f};
    const VkRect2D scissor{{0, 0}, {static_cast<uint32_t>(list.width()), static_cast<uint32_t>(list.height())}};
    vkCmdSetViewport(cmd, 0, 1, &viewport);
    vkCmdSetScissor(cmd, 0, 1, &scissor);
    if (list.commands().empty()) return;

    // Push constants: px -> NDC scale (std430: vec2 at offset 0).
    const PushConstants push{{2.0f / static_cast<float>(list.width()), 2.0f / static_cast<float>(list.height())}};
    vkCmdPushConstants(cmd, pipelines.layout(), VK_SHADER_STAGE_VERTEX_BIT, 0, sizeof(push), &push);

    // Geometry: one vertex and one index buffer for the whole frame.
    const VkDeviceSize offset = 0;
    const VkBuffer vb = buffers.vertices.buffer();
    vkCmdBindVertexBuffers(cmd, 0, 1, &vb, &offset);
    vkCmdBindIndexBuffer(cmd, buffers.indices.buffer(), 0, VK_INDEX_TYPE_UINT32);

    // Draws in list order; the pipeline changes only where the command kind does.
    VkPipeline bound = VK_NULL_HANDLE;
    for (const DrawCommand& c : list.commands()) {
        const VkPipeline p = pipelines.pipeline(c.kind);
        if (p != bound) {
            vkCmdBindPipeline(cmd, VK_PIPELINE_BIND_POINT_GRAPHICS, p);
            bound = p;
        }
        vkCmdDrawIndexed(cmd, c.index_count, 1, c.first_index, 0, 0);
    }
}

}  // namespace contactlab::render
