// haptics_commands.hpp — the editor's commands on the live haptics (device, servo rate,
// recording), shared by the Haptics/Tuning panels and the --script runner. Each reports its
// outcome in the status line (s.say) and returns whether it worked.
#pragma once

#include "engine/editor/editor_state.hpp"

#include <string>

namespace contactlab::editor {

// Points s.servo, s.device and s.pose_input at the host's current ones (after any switch).
void sync_haptics(EditorState& s);
// Switches the servo to `spec` (haptics_host.hpp: mouse, sim-cld, replay:FILE, usb:hapio,
// usb:falcon) at the current rate, through the safety path. The plots restart.
bool cmd_set_device(EditorState& s, const std::string& spec);
// Restarts the servo at `hz` (100..20000 Hz) on the same device, through the safety path.
bool cmd_set_rate(EditorState& s, double hz);
bool cmd_record_start(EditorState& s, const std::string& path);
bool cmd_record_stop(EditorState& s);

// The rolling plots keep 5 s of ticks, at most 25 000 of them (a 1 s window at 20 kHz: ImGui's
// plot of more points costs more frame time than it shows).
std::size_t plot_capacity(double rate_hz);

}  // namespace contactlab::editor
