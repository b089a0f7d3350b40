// imgui_layer.cpp — ImGui context and backends (see imgui_layer.hpp).
#include "engine/editor/imgui_layer.hpp"

#include "engine/render/vk_check.hpp"

#include <imgui.h>
#include <backends/imgui_impl_glfw.h>
#include <backends/imgui_impl_vulkan.h>

#include <cstdio>

namespace contactlab::editor {

using render::vk_check;

namespace {

void check_imgui_vk(VkResult r) {
    if (r != VK_SUCCESS) std::fprintf(stderr, "imgui vulkan backend: %s\n", render::vk_result_name(r));
}

}  // namespace

ImGuiLayer::ImGuiLayer(const render::VulkanContext& ctx, GLFWwindow* window, VkRenderPass render_pass,
                       uint32_t min_images, uint32_t images)
    : ctx_(ctx) {
    const VkDevice dev = ctx_.device();
    IMGUI_CHECKVERSION();
    ImGui::CreateContext();
    ImGuiIO& io = ImGui::GetIO();
    io.IniFilename = nullptr;  // no imgui.ini beside the user's files
    ImGui::StyleColorsDark();
    try {
        // Descriptor pool: the font texture's combined image sampler (and a few spare).
        VkDescriptorPoolSize sizes[1] = {{VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER, 8}};
        VkDescriptorPoolCreateInfo pool{};
        pool.sType = VK_STRUCTURE_TYPE_DESCRIPTOR_POOL_CREATE_INFO;
        pool.flags = VK_DESCRIPTOR_POOL_CREATE_FREE_DESCRIPTOR_SET_BIT;
        pool.maxSets = 8;
        pool.poolSizeCount = 1;
        pool.pPoolSizes = sizes;
        vk_check(vkCreateDescriptorPool(dev, &pool, nullptr, &pool_), "vkCreateDescriptorPool (imgui)");

        glfw_ = ImGui_ImplGlfw_InitForVulkan(window, true);
        ImGui_ImplVulkan_InitInfo info{};
        info.Instance = ctx_.instance();
        info.PhysicalDevice = ctx_.physical_device();
        info.Device = dev;
        info.QueueFamily = ctx_.queue_family();
        info.Queue = ctx_.queue();
        info.DescriptorPool = pool_;
        info.Subpass = 0;
        info.MinImageCount = min_images < 2 ? 2 : min_images;
        info.ImageCount = images < info.MinImageCount ? info.MinImageCount : images;
        info.MSAASamples = VK_SAMPLE_COUNT_1_BIT;
        info.CheckVkResultFn = check_imgui_vk;
        // ImGui pipeline: built for the window's render pass (1.86 has no dynamic rendering).
        vulkan_ = ImGui_ImplVulkan_Init(&info, render_pass);
        if (!glfw_ || !vulkan_) throw render::VulkanError("Dear ImGui backends failed to initialise");

        // Font atlas upload: one-shot command buffer, submit, wait, free the staging buffer.
        VkCommandBufferAllocateInfo alloc{};
        alloc.sType = VK_STRUCTURE_TYPE_COMMAND_BUFFER_ALLOCATE_INFO;
        alloc.commandPool = ctx_.command_pool();
        alloc.level = VK_COMMAND_BUFFER_LEVEL_PRIMARY;
        alloc.commandBufferCount = 1;
        VkCommandBuffer cmd;
        vk_check(vkAllocateCommandBuffers(dev, &alloc, &cmd), "vkAllocateCommandBuffers (fonts)");
        VkCommandBufferBeginInfo begin{};
        begin.sType = VK_STRUCTURE_TYPE_COMMAND_BUFFER_BEGIN_INFO;
        begin.flags = VK_COMMAND_BUFFER_USAGE_ONE_TIME_SUBMIT_BIT;
        vk_check(vkBeginCommandBuffer(cmd, &begin), "vkBeginCommandBuffer (fonts)");
        ImGui_ImplVulkan_CreateFontsTexture(cmd);
        vk_check(vkEndCommandBuffer(cmd), "vkEndCommandBuffer (fonts)");
        VkSubmitInfo submit{};
        submit.sType = VK_STRUCTURE_TYPE_SUBMIT_INFO;
        submit.commandBufferCount = 1;
        submit.pCommandBuffers = &cmd;
        vk_check(vkQueueSubmit(ctx_.queue(), 1, &submit, VK_NULL_HANDLE), "vkQueueSubmit (fonts)");
        vk_check(vkQueueWaitIdle(ctx_.queue()), "vkQueueWaitIdle (fonts)");
        vkFreeCommandBuffers(dev, ctx_.command_pool(), 1, &cmd);
        ImGui_ImplVulkan_DestroyFontUploadObjects();
    } catch (...) {
        shutdown();
        throw;
    }
}

ImGuiLayer::~ImGuiLayer() { shutdown(); }

void ImGuiLayer::shutdown() {
    if (ctx_.device()) vkDeviceWaitIdle(ctx_.device());
    if (vulkan_) ImGui_ImplVulkan_Shutdown();
    if (glfw_) ImGui_ImplGlfw_Shutdown();
    vulkan_ = glfw_ = false;
    if (ImGui::GetCurrentContext()) ImGui::DestroyContext();
    if (pool_) vkDestroyDescriptorPool(ctx_.device(), pool_, nullptr);
    pool_ = VK_NULL_HANDLE;
}

void ImGuiLayer::new_frame() {
    ImGui_ImplVulkan_NewFrame();
    ImGui_ImplGlfw_NewFrame();
    ImGui::NewFrame();
}

void ImGuiLayer::render() { ImGui::Render(); }

void ImGuiLayer::record(VkCommandBuffer cmd) {
    ImDrawData* data = ImGui::GetDrawData();
    if (data) ImGui_ImplVulkan_RenderDrawData(data, cmd);
}

void ImGuiLayer::set_min_image_count(uint32_t n) { ImGui_ImplVulkan_SetMinImageCount(n < 2 ? 2 : n); }

}  // namespace contactlab::editor
