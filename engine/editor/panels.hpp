// panels.hpp — the editor's Dear ImGui windows: menu bar (File, Edit, View, Tools, Generate),
// tuning (force model, Ke, max force, friction, damping, contact rule, finger, roller gains),
// status (device, servo state and fault, emergency stop, period statistics, scene problems) and
// rolling plots of the last 5 s.
#pragma once

#include "engine/editor/editor_state.hpp"
#include "engine/editor/layout.hpp"
#include "engine/render/frame.hpp"

#include <optional>
#include <vector>

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

// The fixed layout for this frame's size (layout.hpp), in ImGui's units, for a Plots panel of
// `plots` plots (device_sections.hpp: live_plot_count).
EditorLayout current_layout(int plots = 6);

// What is on screen, for the layout check (`layout` in scripts): the rulers and every visible
// Dear ImGui window as drawn last frame, and whether its content is wider than its inside; then
// the named parts inside the panels ("PANEL > PART", not tiled: a device section's header, each
// plot, the emergency stop) and the canvas's scale bars (tiled: no panel may cover them).
struct LaidOut {
    std::string name;
    Rect rect;
    bool overflow = false;  // a label or text cut at the right edge
    bool tiled = true;      // false for popups, which float over the rest by design
    float content_w = 0.0f, inside_w = 0.0f;  // px: the widest item, the room for it
};
std::vector<LaidOut> laid_out();
// Menus, the status row (the proxy's state, `proxy`, when there is one), the Tuning, Haptics and
// Plots panels, the recovery offer, and the message row.
void draw_panels(EditorState& s, const FrameInfo& info, const std::optional<ProxyOutput>& proxy);

}  // namespace contactlab::editor
