// display.cpp — glfwInit with its failure turned into a message (see display.hpp).
#include "engine/editor/display.hpp"

#include <GLFW/glfw3.h>

#include <cstdlib>

namespace contactlab::editor {
namespace {

std::string g_last_error;  // set by the GLFW error callback during glfwInit (main thread only)

void on_glfw_error(int code, const char* text) {
    g_last_error = "GLFW error " + std::to_string(code) + ": " + (text ? text : "(no description)");
}

}  // namespace

std::string no_display_message(const std::string& reason) {
    const char* display = std::getenv("DISPLAY");
    const char* wayland = std::getenv("WAYLAND_DISPLAY");
    std::string m = "contactlab edit: no display: the editor needs a window (X11 or Wayland)";
    if ((!display || !*display) && (!wayland || !*wayland)) m += "; DISPLAY is not set";
    if (!reason.empty()) m += " (" + reason + ")";
    m +=
        ".\n"
        "  On a machine without a screen, run it under a virtual X server:\n"
        "      xvfb-run -a contactlab edit [SCENE.json]\n"
        "  (Debian package xvfb). Or use the headless subcommands:\n"
        "      contactlab trace     proxy trace of a finger path through a scene (CSV)\n"
        "      contactlab simulate  the servo loop against the simulated CLD rig or a recording\n"
        "      contactlab render    a scene drawn offscreen with Vulkan into a PNG\n"
        "      contactlab generate  stimulus scenes (bumps, block, arc)\n"
        "  `contactlab --help` lists them all.\n";
    return m;
}

GlfwSession::GlfwSession() {
    glfwSetErrorCallback(on_glfw_error);
    ok_ = glfwInit() == GLFW_TRUE;
    if (!ok_) reason_ = g_last_error.empty() ? "glfwInit failed" : g_last_error;
    else if (!glfwVulkanSupported()) {
        ok_ = false;
        glfwTerminate();
        reason_ = "GLFW found no Vulkan loader (Debian package libvulkan1)";
    }
}

GlfwSession::~GlfwSession() {
    if (ok_) glfwTerminate();
}

}  // namespace contactlab::editor
