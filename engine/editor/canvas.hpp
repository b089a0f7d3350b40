// canvas.hpp — the scene canvas: mouse and keyboard on the world (tools, pan, zoom, finger,
// emergency stop) and the editor's own marks drawn over the frame (handles, selection, the line
// being drawn). The real mouse (through ImGui's IO) and the --script runner call the same
// functions, so scripted tests exercise the code a user does.
#pragma once

#include "engine/editor/editor_state.hpp"
#include "engine/render/draw_list.hpp"

#include <string>

namespace contactlab::editor {

enum class Button { left, right, middle };

// Pointer at (x, y) px in the canvas (framebuffer pixels, origin top-left).
void canvas_move(EditorState& s, double x, double y);
void canvas_press(EditorState& s, Button b, double x, double y);
void canvas_release(EditorState& s, Button b, double x, double y);
// Wheel: zoom about the cursor; with `rotate` (Shift or Ctrl held) it turns the finger instead.
void canvas_wheel(EditorState& s, double x, double y, double notches, bool rotate);

// Commands shared by keys, menus and scripts.
void cmd_undo(EditorState& s);
void cmd_redo(EditorState& s);
void cmd_delete(EditorState& s);
void cmd_fit(EditorState& s);
// Zooms on the fingertip (render::fingertip_box: the pad's middle and R / 2 around it), where
// seed 003's platform, its tension arrows and the contact frame show; F goes back to the scene.
void cmd_zoom_fingertip(EditorState& s);
void cmd_toggle_stop(EditorState& s);
void cmd_set_tool(EditorState& s, Tool t);
void cmd_rotate_finger(EditorState& s, double dphi);  // rad
void cmd_save(EditorState& s, const std::string& path);  // empty: the document's own path
// Replaces the contours with a seed stimulus ("block", "bumps", "arc"; haptics/stimuli.hpp),
// keeping the finger, force and contact rule: one undoable edit. False for an unknown name.
bool cmd_generate(EditorState& s, const std::string& name);

// A key by name ("space", "delete", "ctrl+z", "ctrl+y", "ctrl+s", "escape", "f", "1".."7" for
// the tools, "q", "e"); false for a name that means nothing to the canvas.
bool canvas_key(EditorState& s, const std::string& name);

// The editor's marks for the current tool, over the frame.
void draw_canvas_marks(const EditorState& s, const render::Theme& theme, render::DrawList& out);

}  // namespace contactlab::editor
