// panel_fields.cpp — the Tuning panel's field widgets (see panel_fields.hpp).
#include "engine/editor/panel_fields.hpp"

#include "engine/editor/panel_parts.hpp"
#include "engine/editor/parameter_edit.hpp"

#include <imgui.h>

#include <algorithm>
#include <cstdio>
#include <string>

namespace contactlab::editor {

void field_error_line(const EditorState& s, const char* name) {
    if (s.field_error_name != name) return;
    ImGui::PushTextWrapPos(0.0f);
    ImGui::TextColored(ImVec4(1, 0.4f, 0.3f, 1), "refused: %s", s.field_error.c_str());
    ImGui::PopTextWrapPos();
}

void wrapped_hint(const char* text) {
    ImGui::PushStyleColor(ImGuiCol_Text, ImGui::GetStyleColorVec4(ImGuiCol_TextDisabled));
    ImGui::TextWrapped("%s", text);
    ImGui::PopStyleColor();
}

void edit_field(EditorState& s, const char* label, const char* name, double lo, double hi, const char* fmt, double scale,
                bool log) {
    // The item width (170 px in Tuning) is split: the slider, then its value in a box of its own.
    constexpr float kValueWidth = 58.0f;  // px: "5000" or "0.025" in the default font
    const float total = ImGui::CalcItemWidth();
    const float slider_w = std::max(40.0f, total - kValueWidth - ImGui::GetStyle().ItemInnerSpacing.x);
    double shown = parameter_value(s, name).value_or(0.0) * scale;
    const double slo = lo * scale, shi = hi * scale;
    ImGui::PushID(name);
    const float x0 = ImGui::GetCursorPosX();
    ImGui::SetNextItemWidth(slider_w);
    // No text on the slider: an empty format draws none (and rounds nothing).
    const bool changed = ImGui::SliderScalar("##slider", ImGuiDataType_Double, &shown, &slo, &shi, "",
                                             (log ? ImGuiSliderFlags_Logarithmic : 0) | ImGuiSliderFlags_NoRoundToFormat);
    if (ImGui::IsItemActivated()) s.doc.begin_continuous(label);
    if (changed) set_parameter(s, name, shown / scale, EditKind::drag_step);
    if (ImGui::IsItemDeactivated()) s.doc.end_continuous();
    if (ImGui::IsItemHovered()) ImGui::SetTooltip("drag, or Ctrl+click to type a value");
    const bool visible = ImGui::IsItemVisible();
    const ImVec2 s0 = ImGui::GetItemRectMin(), s1 = ImGui::GetItemRectMax();
    char value[32];
    std::snprintf(value, sizeof value, fmt, parameter_value(s, name).value_or(0.0) * scale);
    ImGui::SameLine(0.0f, ImGui::GetStyle().ItemInnerSpacing.x);
    ImGui::AlignTextToFramePadding();
    ImGui::TextUnformatted(value);
    if (visible) {  // for the layout test: the value's box never meets the slider's
        const ImVec2 v0 = ImGui::GetItemRectMin(), v1 = ImGui::GetItemRectMax();
        note_panel_part(std::string("Tuning > slider ") + label, Rect{s0.x, s0.y, s1.x - s0.x, s1.y - s0.y});
        note_panel_part(std::string("Tuning > value ") + label, Rect{v0.x, v0.y, v1.x - v0.x, v1.y - v0.y});
    }
    ImGui::SameLine(x0 + total + ImGui::GetStyle().ItemInnerSpacing.x);
    ImGui::TextUnformatted(label);
    ImGui::PopID();
    field_error_line(s, name);
}

void edit_live(EditorState& s, const char* label, const char* name, double step, double fast, const char* fmt) {
    double v = parameter_value(s, name).value_or(0.0);
    if (ImGui::InputDouble(label, &v, step, fast, fmt, ImGuiInputTextFlags_EnterReturnsTrue)) set_parameter(s, name, v);
    field_error_line(s, name);
}

}  // namespace contactlab::editor
