// panel_parts.hpp — named parts drawn inside the panels (a device section, each plot) and on the
// canvas (the scale bars), as rectangles in ImGui's px, for the `layout` script command: a test
// sees a "Wearable" section on screen, and that every plot and scale bar lies whole inside the
// window with nothing over it (issue 29). UI thread only.
#pragma once

#include "engine/editor/layout.hpp"

#include <string>
#include <vector>

namespace contactlab::editor {

struct PanelPart {
    std::string name;  // "Tuning > Wearable ...", "Plots (last 5 s) > |F| (N)", "force-scale bar"
    Rect rect;
};

// Panels: begin_panel_parts() at the start of the panels' frame, note_panel_part() as each is
// drawn (only when on screen: ImGui::IsItemVisible), end_panel_parts() at the end (the list then replaces the last frame's).
void begin_panel_parts();
void note_panel_part(std::string name, const Rect& r);
void end_panel_parts();
const std::vector<PanelPart>& panel_parts();  // the last complete frame's

// Canvas: the parts drawn on the canvas this frame (under the panels, so a panel must not cover them).
void set_canvas_parts(std::vector<PanelPart> parts);
const std::vector<PanelPart>& canvas_parts();

}  // namespace contactlab::editor
