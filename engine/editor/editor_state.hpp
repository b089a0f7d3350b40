// editor_state.hpp — everything the editor's UI, canvas tools and script runner share (UI thread
// only; the servo side is reached through HapticsHost: LiveServo, the device, its pose input).
#pragma once

#include "engine/editor/camera.hpp"
#include "engine/editor/document.hpp"
#include "engine/editor/frame_stages.hpp"
#include "engine/editor/haptics_host.hpp"
#include "engine/editor/live_servo.hpp"
#include "engine/editor/pose_input.hpp"
#include "engine/editor/plot_history.hpp"
#include "engine/editor/scene_edit.hpp"
#include "engine/render/frame.hpp"
#include "haptics/wearable/rig_tuning.hpp"

#include <optional>
#include <string>
#include <vector>

namespace contactlab::editor {

enum class Tool { finger, select, line, quad, arc, arc_center, cubic };
const char* to_string(Tool t);

struct ExperimentState;  // experiment_mode.hpp

struct EditorState {
    Document doc;
    Camera camera;
    Tool tool = Tool::finger;

    // The cursor's finger pose (m, rad): the mouse device's finger, sim-cld's hand target.
    MousePose pose;
    double phi_step = 2.0 * 3.14159265358979323846 / 180.0;  // rad per wheel notch / key press

    // Canvas interaction.
    Vec2 cursor{0.0};                  // m, world point under the cursor
    std::optional<Handle> hovered, selected;
    bool dragging = false;             // a handle is being moved (select tool)
    Vec2 grab_offset{0.0};             // m, handle position minus cursor when grabbed
    // The scene when the drag began: every move applies to it, so an arc dragged by its end keeps
    // passing through its halfway point as it was then (not as each step moved it).
    Scene drag_base;
    // Drawing tools: the points placed so far for the next segment (m). Line: start; quad: start,
    // control; arc: start, through; centre-radius arc: start, centre; cubic: start, control 1,
    // control 2. The segment's end starts the next one (a chain).
    std::vector<Vec2> pending;
    bool panning = false;
    double pan_last_x = 0.0, pan_last_y = 0.0;  // px
    bool snap_grid = false;
    double grid_mm = 1.0;              // mm, snapping grid
    // Tangent continuation: a segment started on an open chain's end leaves along the chain's
    // tangent there (G1 joint): its first control point / a line's end is put on that ray, an
    // arc is made tangent, a centre-radius arc's centre is put on the normal.
    bool snap_tangent = false;

    // Live haptics. `servo`, `device` and `pose_input` are the host's current ones (they change
    // when the device or the rate does: sync_haptics()).
    HapticsHost* haptics = nullptr;
    LiveServo* servo = nullptr;
    drivers::Device* device = nullptr;
    PoseInput* pose_input = nullptr;  // null: the device ignores the cursor (replay); the Falcon and 2DIY take only phi
    // The panel's recording and replay files: different names, so that a recording started while
    // a replay runs never writes over the file being played (cmd_record_start refuses that too).
    char record_path[512] = "recording.csv";
    char replay_path[512] = "replay.csv";
    RollerGains roller;                // published with the scene's Ke and max force
    double roller_travel = 0.0;        // m of roller travel l_d may use (0: the device's whole)
    // Seed 003's platform, when the device is sim-wearable: its live gains, fit mode and FSR
    // noise (the Wearable section), sent to the device whenever they differ from its own.
    wearable::RigTuning wearable = wearable::tuning_of(wearable::seed_fit_rig());
    PlotHistory history;
    // The most recent fault the servo reported (kept after it recovers), from the tick records.
    ServoFault last_fault = ServoFault::none;
    double last_fault_t = 0.0;  // s, device time

    // `--experiment`: live trials (experiment_mode.hpp); null otherwise. Owned by run_editor.
    ExperimentState* experiment = nullptr;
    double now = 0.0;  // s since the frame loop began, set each frame (trial times)

    // Other sessions' recovery files waiting for an answer (recovery.hpp), the front one shown.
    std::vector<std::string> recovery_offers;

    // Where the drawn frames' time goes (frame_stages.hpp); the panels time their plots into it.
    // Its frames() counts the frames drawn (a script's `idle` reads it).
    FrameStages* stages = nullptr;
    // The kept scene layer (scene_layer_cache.hpp), for scripts: pictures drawn so far, and the
    // pixels that differed between a frame drawn with it and the same frame drawn fresh at the
    // last `check_layer` (-1: none yet).
    long scene_layer_updates = 0;
    long layer_mismatch = -1;

    // View options.
    render::Overlays overlays;
    bool labels = true;

    // Messages for the status bar: the last action's outcome.
    std::string message;
    bool message_is_error = false;
    // The last refused parameter edit (parameter_edit.hpp): its name and why, shown beside the
    // field until that field is set again.
    std::string field_error_name, field_error;
    void say(std::string m, bool error = false) {
        message = std::move(m);
        message_is_error = error;
    }

    bool quit = false;
};

}  // namespace contactlab::editor
