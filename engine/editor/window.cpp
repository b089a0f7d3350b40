// window.cpp — GLFW window and Vulkan surface (see window.hpp).
#include "engine/editor/window.hpp"

#include "engine/render/vk_check.hpp"

#define GLFW_INCLUDE_VULKAN
#include <GLFW/glfw3.h>

#include <stdexcept>

namespace contactlab::editor {
namespace {

void count_event(GLFWwindow* w) {
    if (auto* self = static_cast<Window*>(glfwGetWindowUserPointer(w))) self->note_event();
}

}  // namespace

std::vector<std::string> window_instance_extensions() {
    uint32_t n = 0;
    const char** names = glfwGetRequiredInstanceExtensions(&n);
    std::vector<std::string> out;
    for (uint32_t i = 0; names && i < n; ++i) out.emplace_back(names[i]);
    return out;
}

Window::Window(int width, int height, const std::string& title) {
    glfwWindowHint(GLFW_CLIENT_API, GLFW_NO_API);  // Vulkan, not OpenGL
    glfwWindowHint(GLFW_RESIZABLE, GLFW_TRUE);
    window_ = glfwCreateWindow(width, height, title.c_str(), nullptr, nullptr);
    if (!window_) throw std::runtime_error("could not create a " + std::to_string(width) + "x" + std::to_string(height) + " window");
    // Event callbacks: each only counts (Window::events); ImGui's backend, installed later, keeps
    // them as its "previous" callbacks and calls them after its own.
    glfwSetWindowUserPointer(window_, this);
    glfwSetCursorPosCallback(window_, [](GLFWwindow* w, double, double) { count_event(w); });
    glfwSetMouseButtonCallback(window_, [](GLFWwindow* w, int, int, int) { count_event(w); });
    glfwSetScrollCallback(window_, [](GLFWwindow* w, double, double) { count_event(w); });
    glfwSetKeyCallback(window_, [](GLFWwindow* w, int, int, int, int) { count_event(w); });
    glfwSetCharCallback(window_, [](GLFWwindow* w, unsigned int) { count_event(w); });
    glfwSetWindowFocusCallback(window_, [](GLFWwindow* w, int) { count_event(w); });
    glfwSetCursorEnterCallback(window_, [](GLFWwindow* w, int) { count_event(w); });
    glfwSetFramebufferSizeCallback(window_, [](GLFWwindow* w, int, int) { count_event(w); });
    glfwSetWindowRefreshCallback(window_, [](GLFWwindow* w) { count_event(w); });
    glfwSetWindowIconifyCallback(window_, [](GLFWwindow* w, int) { count_event(w); });
}

Window::~Window() {
    if (window_) glfwDestroyWindow(window_);
}

bool Window::should_close() const { return glfwWindowShouldClose(window_) == GLFW_TRUE; }
void Window::request_close() { glfwSetWindowShouldClose(window_, GLFW_TRUE); }
void Window::framebuffer_size(int& width, int& height) const { glfwGetFramebufferSize(window_, &width, &height); }
void Window::set_size(int width, int height) { glfwSetWindowSize(window_, width, height); }
void Window::set_title(const std::string& title) { glfwSetWindowTitle(window_, title.c_str()); }

Surface::Surface(VkInstance instance, const Window& window) : instance_(instance) {
    render::vk_check(glfwCreateWindowSurface(instance, window.handle(), nullptr, &surface_), "glfwCreateWindowSurface");
}

Surface::~Surface() {
    if (surface_) vkDestroySurfaceKHR(instance_, surface_, nullptr);
}

}  // namespace contactlab::editor
