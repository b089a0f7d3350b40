// panels.hpp — the editor's Dear ImGui windows: menu bar (File, Edit, View, Tools, Generate),
// tuning (force model, Ke, max force, friction, damping, contact rule, finger, roller gains),
// status (device, servo state and fault, emergency stop, period statistics, scene problems) and
// rolling plots of the last 5 s.
#pragma once

#include "engine/editor/editor_state.hpp"

#include <string>

namespace contactlab::editor {

// Facts about the window and renderer shown in the status window.
struct FrameInfo {
    std::string gpu;            // Vulkan device name
    std::string present_mode;
    double frame_ms = 0.0;      // mean over the last second (CPU time from poll to present)
    double fps = 0.0;
    int width = 0, height = 0;  // px
    int validation_messages = 0;
};

void draw_panels(EditorState& s, const FrameInfo& info);

}  // namespace contactlab::editor
