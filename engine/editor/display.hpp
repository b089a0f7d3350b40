// display.hpp — GLFW start-up and the message a user sees when there is no display.
//
// GLFW 3.3 cannot initialise without an X11/Wayland display (there is no null platform before
// 3.4), so the editor says so clearly and points at xvfb-run and the headless subcommands.
#pragma once

#include <string>

namespace contactlab::editor {

// Exit code of `contactlab edit` when there is no display (the same as other bad-input cases).
inline constexpr int kExitNoDisplay = 2;

// What to print when glfwInit fails: names `xvfb-run -a contactlab edit ...` and the headless
// subcommands. `reason` is GLFW's own description (may be empty).
std::string no_display_message(const std::string& reason);

// RAII for glfwInit/glfwTerminate. ok() is false (and reason() says why) when there is no display.
class GlfwSession {
public:
    GlfwSession();
    ~GlfwSession();
    GlfwSession(const GlfwSession&) = delete;
    GlfwSession& operator=(const GlfwSession&) = delete;

    bool ok() const { return ok_; }
    const std::string& reason() const { return reason_; }

private:
    bool ok_ = false;
    std::string reason_;
};

}  // namespace contactlab::editor
