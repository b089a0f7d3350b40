// editor_state.hpp — everything the editor's UI, canvas tools and script runner share (UI thread
// only; the servo side is reached through LiveServo and MouseDevice).
#pragma once

#include "engine/editor/camera.hpp"
#include "engine/editor/document.hpp"
#include "engine/editor/live_servo.hpp"
#include "engine/editor/mouse_device.hpp"
#include "engine/editor/plot_history.hpp"
#include "engine/editor/scene_edit.hpp"
#include "engine/render/frame.hpp"

#include <optional>
#include <string>
#include <vector>

namespace contactlab::editor {

enum class Tool { finger, select, line, quad, arc };
const char* to_string(Tool t);

struct EditorState {
    Document doc;
    Camera camera;
    Tool tool = Tool::finger;

    // The finger as the mouse device reports it (m, rad).
    MousePose pose;
    double phi_step = 2.0 * 3.14159265358979323846 / 180.0;  // rad per wheel notch / key press

    // Canvas interaction.
    Vec2 cursor{0.0};                  // m, world point under the cursor
    std::optional<Handle> hovered, selected;
    bool dragging = false;             // a handle is being moved (select tool)
    Vec2 grab_offset{0.0};             // m, handle position minus cursor when grabbed
    // Drawing tools: the points placed so far for the next segment (m). Line: start; quad: start,
    // control; arc: start, through. The segment's end starts the next one (a chain).
    std::vector<Vec2> pending;
    bool panning = false;
    double pan_last_x = 0.0, pan_last_y = 0.0;  // px
    bool snap_grid = false;
    double grid_mm = 1.0;              // mm, snapping grid

    // Live haptics.
    LiveServo* servo = nullptr;
    MouseDevice* device = nullptr;
    RollerGains roller;                // published with the scene's Ke and max force
    PlotHistory history;
    // The most recent fault the servo reported (kept after it recovers), from the tick records.
    ServoFault last_fault = ServoFault::none;
    double last_fault_t = 0.0;  // s, device time

    // View options.
    render::Overlays overlays;
    bool labels = true;

    // Messages for the status bar: the last action's outcome.
    std::string message;
    bool message_is_error = false;
    void say(std::string m, bool error = false) {
        message = std::move(m);
        message_is_error = error;
    }

    bool quit = false;
};

}  // namespace contactlab::editor
