// panel_parts.cpp — the named parts' registry (see panel_parts.hpp).
#include "engine/editor/panel_parts.hpp"

#include <utility>

namespace contactlab::editor {
namespace {

std::vector<PanelPart>& drawing() {
    static std::vector<PanelPart> v;
    return v;
}
std::vector<PanelPart>& done() {
    static std::vector<PanelPart> v;
    return v;
}
std::vector<PanelPart>& canvas() {
    static std::vector<PanelPart> v;
    return v;
}

}  // namespace

void begin_panel_parts() { drawing().clear(); }
void note_panel_part(std::string name, const Rect& r) { drawing().push_back({std::move(name), r}); }
void end_panel_parts() { done() = drawing(); }
const std::vector<PanelPart>& panel_parts() { return done(); }

void set_canvas_parts(std::vector<PanelPart> parts) { canvas() = std::move(parts); }
const std::vector<PanelPart>& canvas_parts() { return canvas(); }

}  // namespace contactlab::editor
