// parameter_edit.hpp — the one path every edit of a tunable parameter takes, from the Tuning panel
// and from `--script` (`set NAME V`) alike: the value is checked against the limits scene files
// and the servo share (haptics/parameter_limits.hpp, through scene_io's validation and
// servo_params_check), and
//   - accepted: it is applied (scene parameters as one undoable edit, or as a step of a drag),
//     the status line says so, and the field's error is cleared;
//   - refused: nothing changes, so the field shows the value still in effect; the status line
//     and the field's own error line say what was refused and why, e.g.
//     "ke: force.stiffness: must lie in (0, 1e+07] N/m, got 1e+09".
// Before this, a refused value stayed in its field while the servo kept the old one: the user
// believed in a stiffness that was not there.
#pragma once

#include "engine/editor/editor_state.hpp"

#include <optional>
#include <string>
#include <string_view>
#include <vector>

namespace contactlab::editor {

struct ParameterInfo {
    const char* name;  // as `set NAME V` and `expect NAME V` take it
    const char* unit;  // of V (SI, except travel_mm)
    const char* what;  // for messages and the README
    bool in_scene;     // saved with the scene and undoable; else live only (roller gains, travel)
};

// Every tunable parameter, in the Tuning panel's order.
const std::vector<ParameterInfo>& tunable_parameters();
bool is_tunable_parameter(std::string_view name);

// How an accepted value is recorded: one undoable edit, or a step of a drag the caller opened
// with Document::begin_continuous (closed with end_continuous; nothing is recorded if no step was
// accepted). Parameters outside the scene (roller gains, travel) are live and not undoable.
enum class EditKind { single, drag_step };

// The value the user sees for `name` (what is in effect for the scene once valid): ke N/m,
// max_force N, damping N s/m, mu_s, mu_d, k_t N/m, k_n N/m, eccentricity, total_k N/m,
// tolerance m, finger_r m, pad_l m, kp V/m, ki V/(m s), kd V s/m, max_drive V, roller_kff V s/m, ff_cutoff_hz Hz, travel_mm mm,
// wearable_force_kp N m/N, wearable_force_kd N m s/N, wearable_position_kp N m/m,
// wearable_position_kd N m s/m, wearable_fit 1|0, fsr_noise N.
// Empty for an unknown name.
std::optional<double> parameter_value(const EditorState& s, std::string_view name);

// The problem with setting `name` to `value` now ("" when it would be accepted), without
// changing anything.
std::string parameter_problem(const EditorState& s, std::string_view name, double value);

// Sets `name` to `value` through the checks above. Returns whether it was accepted.
bool set_parameter(EditorState& s, std::string_view name, double value, EditKind kind = EditKind::single);

}  // namespace contactlab::editor
