// window.hpp — the GLFW window (no client API: Vulkan draws into it) and its Vulkan surface.
#pragma once

#include <vulkan/vulkan.h>

#include <cstdint>
#include <string>
#include <vector>

struct GLFWwindow;

namespace contactlab::editor {

// The instance extensions GLFW needs for a window surface (VK_KHR_surface + the platform's).
std::vector<std::string> window_instance_extensions();

class Window {
public:
    Window(int width, int height, const std::string& title);  // throws std::runtime_error
    ~Window();
    Window(const Window&) = delete;
    Window& operator=(const Window&) = delete;

    GLFWwindow* handle() const { return window_; }
    bool should_close() const;
    void request_close();
    void framebuffer_size(int& width, int& height) const;  // px; 0x0 while minimised
    void set_title(const std::string& title);
    void set_size(int width, int height);  // screen coordinates (px without scaling)
    // Input and window events so far (cursor, buttons, wheel, keys, text, focus, resize, expose):
    // the editor draws on demand and compares this with the count at its last frame. Counted by
    // GLFW callbacks installed here, before Dear ImGui's backend, which chains to them.
    std::uint64_t events() const { return events_; }
    void note_event() { ++events_; }  // the callbacks' (window.cpp)

private:
    GLFWwindow* window_ = nullptr;
    std::uint64_t events_ = 0;
};

// A VkSurfaceKHR for the window, destroyed before the instance.
class Surface {
public:
    Surface(VkInstance instance, const Window& window);
    ~Surface();
    Surface(const Surface&) = delete;
    Surface& operator=(const Surface&) = delete;
    VkSurfaceKHR handle() const { return surface_; }

private:
    VkInstance instance_;
    VkSurfaceKHR surface_ = VK_NULL_HANDLE;
};

}  // namespace contactlab::editor
