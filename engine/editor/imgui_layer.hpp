// imgui_layer.hpp — Dear ImGui 1.86 on the window: its context, the GLFW platform backend and the
// Vulkan renderer backend drawing into the window target's render pass (after the scene).
#pragma once

#include "engine/render/context.hpp"

#include <vulkan/vulkan.h>

struct GLFWwindow;

namespace contactlab::editor {

class ImGuiLayer {
public:
    ImGuiLayer(const render::VulkanContext& ctx, GLFWwindow* window, VkRenderPass render_pass, uint32_t min_images,
               uint32_t images);
    ~ImGuiLayer();
    ImGuiLayer(const ImGuiLayer&) = delete;
    ImGuiLayer& operator=(const ImGuiLayer&) = delete;

    void new_frame();                       // backends + ImGui::NewFrame
    void render();                          // ImGui::Render (draw data ready)
    void record(VkCommandBuffer cmd);       // the draw data into an open render pass
    void set_min_image_count(uint32_t n);   // after a swapchain recreation

private:
    void shutdown();

    const render::VulkanContext& ctx_;
    VkDescriptorPool pool_ = VK_NULL_HANDLE;
    bool glfw_ = false, vulkan_ = false;
};

}  // namespace contactlab::editor
