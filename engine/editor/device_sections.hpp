// device_sections.hpp — the Tuning panel's sections that belong to a device (issue 29: the panels
// show what the attached device has and nothing it lacks): the roller's PID and feed-forward for
// a device with a roller (mouse, sim-cld, hapio), seed 003's platform for sim-wearable (its state,
// both loops' gains, fit mode, FSR noise). Every value goes through set_parameter.
#pragma once

#include "engine/editor/editor_state.hpp"

namespace contactlab::editor {

// What the attached device has (no device yet: the roller, as the default mouse device has one).
bool device_has_roller(const EditorState& s);
bool device_has_platform(const EditorState& s);
// How many plots the Plots panel shows for the device: "roller err" only with a roller.
int live_plot_count(const EditorState& s);

inline constexpr const char* kRollerSection = "Roller PID (live, not in the scene)";
inline constexpr const char* kWearableSection = "Wearable platform (seed 003, live)";

// Each draws its collapsing section (nothing for a device without the part) and notes its header
// as "Tuning > NAME" for the `layout` command (panel_parts.hpp).
void roller_section(EditorState& s);
void wearable_section(EditorState& s);

}  // namespace contactlab::editor
