// device_sections.cpp — the roller's and the wearable platform's Tuning sections (see
// device_sections.hpp).
#include "engine/editor/device_sections.hpp"

#include "engine/editor/cursor_wearable_device.hpp"
#include "engine/editor/panel_fields.hpp"
#include "engine/editor/panel_parts.hpp"
#include "engine/editor/parameter_edit.hpp"

#include <imgui.h>

#include <cstdio>
#include <string>

namespace contactlab::editor {
namespace {

constexpr double kRadToDeg = 180.0 / 3.14159265358979323846;

// A section's header, noted for the layout check.
bool section(const char* name) {
    const bool open = ImGui::CollapsingHeader(name, ImGuiTreeNodeFlags_DefaultOpen);
    const ImVec2 a = ImGui::GetItemRectMin(), b = ImGui::GetItemRectMax();
    // Only what is on screen (a header scrolled out of the panel's sight is not).
    if (ImGui::IsItemVisible()) note_panel_part(std::string("Tuning > ") + name, Rect{a.x, a.y, b.x - a.x, b.y - a.y});
    return open;
}

// The roller travel l_d may use (live, not in the scene): centred in the device's travel.
void edit_roller_travel(EditorState& s) {
    edit_live(s, "usable travel (mm)", "travel_mm", 0.0, 0.0, "%.1f");
    if (ImGui::SmallButton("all")) set_parameter(s, "travel_mm", 0.0);
    ImGui::SameLine();
    if (ImGui::SmallButton("18 mm")) set_parameter(s, "travel_mm", 18.0);  // seed 002's CLD
    if (s.roller_travel == 0.0) {
        ImGui::SameLine();
        ImGui::TextDisabled("(0: all of it)");
    }
}

// The platform's state from the simulation's view (sim_wearable_device.hpp): pose, the three
// cable tensions against the motors' stall force, and the loop's status.
void wearable_state(const EditorState& s) {
    const auto* wd = dynamic_cast<const CursorWearableDevice*>(s.device);
    if (!wd) return;
    const drivers::sim::WearablePlatformView v = wd->platform_view();
    if (!v.valid) {
        ImGui::TextDisabled("platform: not running yet");
        return;
    }
    ImGui::Text("roll %+.2f deg  pitch %+.2f deg  press %.3f mm", v.roll * kRadToDeg, v.pitch * kRadToDeg, v.press * 1e3);
    for (int i = 0; i < 3; ++i) {
        char overlay[64];
        std::snprintf(overlay, sizeof overlay, "cable %d: %.3f of %.2f N", i + 1, v.tension[i], v.tension_limit);
        const float frac = v.tension_limit > 0.0 ? static_cast<float>(v.tension[i] / v.tension_limit) : 0.0f;
        // The cables' own colour (the canvas and `render --wearable` draw them in it), not the force's red.
        ImGui::PushStyleColor(ImGuiCol_PlotHistogram, ImVec4(0.95f, 0.65f, 0.15f, 1.0f));
        ImGui::ProgressBar(frac, ImVec2(-1.0f, 0.0f), overlay);
        ImGui::PopStyleColor();
    }
    const bool fault = wearable::is_fault(v.control);
    ImGui::TextColored(fault ? ImVec4(1, 0.35f, 0.3f, 1) : ImVec4(0.7f, 0.9f, 0.7f, 1), "%s loop: %s",
                       v.position_mode ? "position (Fig. 6)" : "force (Fig. 5)", wearable::to_string(v.control));
    const drivers::DeviceFault f = s.device->fault();
    if (f.code != drivers::DeviceFaultCode::none)
        ImGui::TextColored(ImVec4(1, 0.35f, 0.3f, 1), "fault: %s - %s", drivers::to_string(f.code), f.detail);
    else
        ImGui::TextDisabled("fault: none");
}

}  // namespace

bool device_has_roller(const EditorState& s) { return !s.device || s.device->capabilities().roller; }
bool device_has_platform(const EditorState& s) { return s.device && s.device->capabilities().platform; }
int live_plot_count(const EditorState& s) { return device_has_roller(s) ? 6 : 5; }

void roller_section(EditorState& s) {
    if (!device_has_roller(s) || !section(kRollerSection)) return;
    edit_live(s, "Kp (V/m)", "kp", 1000.0, 10000.0, "%.0f");
    edit_live(s, "Ki (V/(m s))", "ki", 1e4, 1e5, "%.0f");
    edit_live(s, "Kd (V s/m)", "kd", 1.0, 10.0, "%.1f");
    edit_live(s, "max drive (V)", "max_drive", 0.5, 1.0, "%.1f");
    // Velocity feed-forward (roller_controller.hpp, RollerGains::kff): Kd + back-EMF cancels the
    // lag on a moving target; 0 is seed 000's eq. 2 alone.
    edit_live(s, "kff (V s/m)", "roller_kff", 10.0, 100.0, "%.2f");
    if (ImGui::IsItemHovered()) ImGui::SetTooltip("velocity feed-forward: 864.88 = Kd + back-EMF (default), 0 = eq. 2 alone");
    edit_live(s, "ff cutoff (Hz)", "ff_cutoff_hz", 1.0, 10.0, "%.1f");
    edit_roller_travel(s);
}

void wearable_section(EditorState& s) {
    if (!device_has_platform(s) || !section(kWearableSection)) return;
    wearable_state(s);
    ImGui::TextDisabled("force loop (Fig. 5), N m of torque per N");
    edit_live(s, "force Kp (N m/N)", "wearable_force_kp", 5e-4, 5e-3, "%.3g");
    edit_live(s, "force Kd (N m s/N)", "wearable_force_kd", 1e-6, 1e-5, "%.3g");
    ImGui::TextDisabled("position loop (Fig. 6), N m of torque per m of cable");
    edit_live(s, "position Kp (N m/m)", "wearable_position_kp", 0.1, 1.0, "%.3g");
    edit_live(s, "position Kd (N m s/m)", "wearable_position_kd", 5e-4, 5e-3, "%.3g");
    int fit = s.wearable.seed_fit ? 0 : 1;
    if (ImGui::Combo("fit mode", &fit, "seed (45 ms response)\0none (Table 1's motor)\0"))
        set_parameter(s, "wearable_fit", fit == 0 ? 1.0 : 0.0);
    if (ImGui::IsItemHovered())
        ImGui::SetTooltip("seed: references shaped to the seed's measured 3.5 Hz\nnone: the motors' own ~10 ms response");
    field_error_line(s, "wearable_fit");
    edit_live(s, "FSR noise (N)", "fsr_noise", 1e-3, 1e-2, "%.4f");
}

}  // namespace contactlab::editor
