// test_context.cpp — the Vulkan context: lavapipe chosen when forced, validation on and silent,
// and the messenger really counting what the validation layer reports.
#include "render_fixture.hpp"

#include "engine/render/vk_check.hpp"

#include <doctest/doctest.h>

using namespace render_test;

TEST_CASE("context: tests run on lavapipe with validation layers and a counting messenger") {
    const VulkanContext& ctx = lavapipe();
    CHECK(ctx.is_software());
    CHECK(ctx.device_name().find("llvmpipe") != std::string::npos);
    CHECK(ctx.validation_enabled());
    CHECK(ctx.validation_messages() == 0);
}

TEST_CASE("context: the messenger counts a deliberate validation error") {
    // A separate, quiet context so the deliberate error does not reach the shared one.
    const VulkanContext ctx(ContextOptions{.software = true, .validation = true, .quiet = true});
    REQUIRE(ctx.validation_errors() == 0);
    // Invalid usage: a buffer of size 0 (VUID-VkBufferCreateInfo-size-00912).
    VkBufferCreateInfo info{};
    info.sType = VK_STRUCTURE_TYPE_BUFFER_CREATE_INFO;
    info.size = 0;
    info.usage = VK_BUFFER_USAGE_VERTEX_BUFFER_BIT;
    VkBuffer buffer = VK_NULL_HANDLE;
    const VkResult r = vkCreateBuffer(ctx.device(), &info, nullptr, &buffer);
    if (r == VK_SUCCESS && buffer) vkDestroyBuffer(ctx.device(), buffer, nullptr);
    CHECK(ctx.validation_errors() >= 1);
}

TEST_CASE("context: no Vulkan driver at all is reported as NoVulkanDevice naming mesa-vulkan-drivers") {
    const std::string saved = std::getenv("VK_DRIVER_FILES") ? std::getenv("VK_DRIVER_FILES") : "";
    setenv("VK_DRIVER_FILES", "/nonexistent/contactlab_no_icd.json", 1);
    std::string message;
    try {
        const VulkanContext ctx(ContextOptions{.software = false, .validation = false});
    } catch (const NoVulkanDevice& e) {
        message = e.what();
    }
    setenv("VK_DRIVER_FILES", saved.c_str(), 1);
    CHECK(message.find("mesa-vulkan-drivers") != std::string::npos);
}
