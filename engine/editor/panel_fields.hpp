// panel_fields.hpp — the Tuning panel's field widgets, shared by its sections (panels.cpp,
// device_sections.cpp). Every change goes through set_parameter (parameter_edit.hpp): a refused
// value never shows as if it were in effect, and its reason stays under the field.
#pragma once

#include "engine/editor/editor_state.hpp"

namespace contactlab::editor {

// The refused value's message under its field, until the field is set again.
void field_error_line(const EditorState& s, const char* name);
// A grey explanatory line, wrapped to the panel (never cut at its edge).
void wrapped_hint(const char* text);
// A slider bound to one tunable parameter: one undoable edit per drag or entry. The value is
// printed beside the slider, not on it, so the slider's handle never covers its digits (issue
// 29: the finger-R handle hid them); Ctrl+click types a value. `scale` converts the SI value to
// the displayed unit (e.g. 1e3 for mm).
void edit_field(EditorState& s, const char* label, const char* name, double lo, double hi, const char* fmt,
                double scale = 1.0, bool log = false);
// A live parameter outside the scene (roller and platform gains): typed, Enter or the step
// buttons apply it.
void edit_live(EditorState& s, const char* label, const char* name, double step, double fast, const char* fmt);

}  // namespace contactlab::editor
