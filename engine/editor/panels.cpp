// panels.cpp — menus, tuning, status and plots (see panels.hpp).
#include "engine/editor/panels.hpp"

#include "engine/editor/canvas.hpp"
#include "engine/editor/haptics_commands.hpp"
#include "engine/editor/parameter_edit.hpp"
#include "engine/editor/panel_fields.hpp"
#include "engine/editor/device_sections.hpp"
#include "engine/editor/live_plot.hpp"
#include "engine/editor/panel_parts.hpp"
#include "engine/editor/experiment_mode.hpp"
#include "engine/editor/recovery.hpp"
#include "engine/render/frame.hpp"
#include "haptics/scene_io.hpp"

#include <imgui.h>
#include <imgui_internal.h>  // the window list, for laid_out()

#include <cfloat>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <iterator>

namespace contactlab::editor {
namespace {

// Seed 004's other way to set the ellipsoid field: eccentricity e = k_normal / k_tangential and
// total stiffness k (printed formula, force_law.hpp). Both sliders write k_tangential and
// k_normal, one undoable edit per drag.
void edit_ellipsoid_ek(EditorState& s) {
    edit_field(s, "eccentricity e", "eccentricity", 0.01, 100.0, "%.3f", 1.0, true);
    edit_field(s, "total k (N/m)", "total_k", 10.0, 5000.0, "%.0f", 1.0, true);
}

// How curves become what the proxy touches (scene.hpp, CurveDef): exact arc splines, or chords
// within a tolerance (faster, with the error `contactlab bench` measures).
void edit_accuracy(EditorState& s) {
    const Scene& sc = s.doc.scene();
    int mode = sc.curves.mode == CurveMode::exact ? 0 : 1;
    if (ImGui::Combo("curves", &mode, "exact (arc spline)\0flatten (chords)\0")) {
        Scene c = sc;
        c.curves.mode = mode == 0 ? CurveMode::exact : CurveMode::flatten;
        s.doc.edit(std::move(c), "curve accuracy");
    }
    if (ImGui::IsItemHovered())
        ImGui::SetTooltip("exact: curves become arc splines within 2e-8 m\nflatten: chords within the tolerance below");
    if (sc.curves.mode == CurveMode::flatten)
        edit_field(s, "chord tolerance (um)", "tolerance", 1e-7, 1e-3, "%.2f", 1e6, true);
}

void menu_bar(EditorState& s) {
    static char path_buf[1024] = "";
    bool open_popup = false, save_popup = false;
    if (ImGui::BeginMainMenuBar()) {
        if (ImGui::BeginMenu("File")) {
            if (ImGui::MenuItem("New")) {
                s.doc = Document();
                s.say("new scene");
                offer_recovery(s);  // an untitled session's unsaved work, if one ended badly
            }
            if (ImGui::MenuItem("Open...")) open_popup = true;
            if (ImGui::MenuItem("Save", "Ctrl+S", false, !s.doc.path().empty())) {
                try {
                    s.doc.save();
                    s.say("saved " + s.doc.path());
                } catch (const std::exception& e) {
                    s.say(e.what(), true);
                }
            }
            if (ImGui::MenuItem("Save As...")) save_popup = true;
            ImGui::Separator();
            if (ImGui::MenuItem("Quit", "Ctrl+Q")) s.quit = true;
            ImGui::EndMenu();
        }
        if (ImGui::BeginMenu("Edit")) {
            const std::string u = "Undo " + s.doc.undo_label(), r = "Redo " + s.doc.redo_label();
            if (ImGui::MenuItem(u.c_str(), "Ctrl+Z", false, s.doc.can_undo())) cmd_undo(s);
            if (ImGui::MenuItem(r.c_str(), "Ctrl+Y", false, s.doc.can_redo())) cmd_redo(s);
            if (ImGui::MenuItem("Delete segment", "Del", false, s.selected.has_value())) cmd_delete(s);
            if (ImGui::MenuItem("Flip solid side", nullptr, false, s.selected.has_value())) {
                s.doc.edit(reverse_contour(s.doc.scene(), s.selected->contour), "flip solid side");
                s.selected.reset();
            }
            const bool closed = s.selected && s.selected->contour < static_cast<int>(s.doc.scene().contours.size()) &&
                                s.doc.scene().contours[s.selected->contour].closed;
            if (ImGui::MenuItem(closed ? "Open contour (at its seam)" : "Close contour (join its ends)", nullptr, false,
                                s.selected.has_value())) {
                s.doc.edit(toggle_closed(s.doc.scene(), s.selected->contour), closed ? "open contour" : "close contour");
                s.selected.reset();
            }
            ImGui::MenuItem("Snap to grid", nullptr, &s.snap_grid);
            ImGui::MenuItem("Snap tangent (G1 at chain ends)", nullptr, &s.snap_tangent);
            ImGui::EndMenu();
        }
        if (ImGui::BeginMenu("View")) {
            if (ImGui::MenuItem("Fit to scene", "F")) cmd_fit(s);
            if (ImGui::MenuItem("Zoom to fingertip", "Z")) cmd_zoom_fingertip(s);
            ImGui::MenuItem("C-space boundary", nullptr, &s.overlays.cspace);
            ImGui::MenuItem("Anticipation zones", nullptr, &s.overlays.zones);
            ImGui::MenuItem("Labels", nullptr, &s.labels);
            ImGui::EndMenu();
        }
        if (ImGui::BeginMenu("Tools")) {
            if (ImGui::MenuItem("Finger (cursor drives x_f)", "1", s.tool == Tool::finger)) cmd_set_tool(s, Tool::finger);
            if (ImGui::MenuItem("Select / move", "2", s.tool == Tool::select)) cmd_set_tool(s, Tool::select);
            if (ImGui::MenuItem("Line", "3", s.tool == Tool::line)) cmd_set_tool(s, Tool::line);
            if (ImGui::MenuItem("Quadratic curve (start, control, end)", "4", s.tool == Tool::quad)) cmd_set_tool(s, Tool::quad);
            if (ImGui::MenuItem("Arc (start, through, end)", "5", s.tool == Tool::arc)) cmd_set_tool(s, Tool::arc);
            if (ImGui::MenuItem("Arc (start, centre, end)", "6", s.tool == Tool::arc_center)) cmd_set_tool(s, Tool::arc_center);
            if (ImGui::MenuItem("Cubic curve (start, control, control, end)", "7", s.tool == Tool::cubic))
                cmd_set_tool(s, Tool::cubic);
            ImGui::EndMenu();
        }
        if (ImGui::BeginMenu("Generate")) {
            if (ImGui::MenuItem("Block (seed 000, d = 6 cm)")) cmd_generate(s, "block");
            if (ImGui::MenuItem("Bumps (seed 002)")) cmd_generate(s, "bumps");
            if (ImGui::MenuItem("Arc (seed 003, 30 cm / 20 mm)")) cmd_generate(s, "arc");
            ImGui::EndMenu();
        }
        ImGui::TextDisabled("  tool: %s  |  %s%s", to_string(s.tool),
                            s.doc.path().empty() ? "(untitled)" : s.doc.path().c_str(), s.doc.dirty() ? " *" : "");
        ImGui::EndMainMenuBar();
    }
    if (open_popup) {
        std::snprintf(path_buf, sizeof path_buf, "%s", s.doc.path().c_str());
        ImGui::OpenPopup("Open scene");
    }
    if (save_popup) {
        std::snprintf(path_buf, sizeof path_buf, "%s", s.doc.path().c_str());
        ImGui::OpenPopup("Save scene as");
    }
    for (const bool opening : {true, false}) {
        if (ImGui::BeginPopupModal(opening ? "Open scene" : "Save scene as", nullptr, ImGuiWindowFlags_AlwaysAutoResize)) {
            ImGui::InputText("file", path_buf, sizeof path_buf);
            if (ImGui::Button("OK")) {
                try {
                    if (opening) {
                        s.doc.open(path_buf);
                        cmd_fit(s);
                        s.say("opened " + s.doc.path());
                        offer_recovery(s);
                    } else {
                        s.doc.save(path_buf);
                        s.say("saved " + s.doc.path());
                    }
                } catch (const std::exception& e) {
                    s.say(e.what(), true);
                }
                ImGui::CloseCurrentPopup();
            }
            ImGui::SameLine();
            if (ImGui::Button("Cancel")) ImGui::CloseCurrentPopup();
            ImGui::EndPopup();
        }
    }
}

// Exact numeric editing of the selected point, in mm (one undoable edit per entry).
void selection_editor(EditorState& s) {
    if (s.selected && !valid_handle(s.doc.scene(), *s.selected)) s.selected.reset();  // scene replaced
    if (s.hovered && !valid_handle(s.doc.scene(), *s.hovered)) s.hovered.reset();
    if (!s.selected) return;
    ImGui::Separator();
    const Handle h = *s.selected;
    ImGui::TextDisabled("selected point: contour %d, segment %d, point %d", h.contour, h.segment, h.point);
    const Vec2 p = handle_position(s.doc.scene(), h);
    double mm[2] = {p.x * 1e3, p.y * 1e3};
    if (ImGui::InputScalarN("x, y (mm)", ImGuiDataType_Double, mm, 2, nullptr, nullptr, "%.3f",
                            ImGuiInputTextFlags_EnterReturnsTrue)) {
        s.doc.edit(move_handle(s.doc.scene(), h, Vec2(mm[0] * 1e-3, mm[1] * 1e-3)), "point position");
    }
}

// Device menu (USB models listed, disabled with the reason when they cannot be used), the
// device's state and fault reason (always shown), and recording start/stop.
void device_controls(EditorState& s) {
    if (!s.haptics) return;
    HapticsHost& h = *s.haptics;
    const std::string current = h.spec();
    std::string next;  // switched after the combo closes (the switch replaces s.servo)
    if (ImGui::BeginCombo("device", current.c_str())) {
        for (const DeviceOption& o : h.options()) {
            const bool replay = o.spec == "replay:";
            const bool selected = replay ? current.rfind("replay:", 0) == 0 : current == o.spec;
            const std::string label = o.available ? o.label : o.label + " - " + o.why;
            if (ImGui::Selectable(label.c_str(), selected, o.available ? 0 : ImGuiSelectableFlags_Disabled))
                next = replay ? std::string("replay:") + s.replay_path : o.spec;
        }
        if (ImGui::Selectable("(scan the USB bus again)", false, ImGuiSelectableFlags_DontClosePopups)) h.options(true);
        ImGui::EndCombo();
    }
    ImGui::InputText("replay file", s.replay_path, sizeof s.replay_path);
    if (!next.empty()) cmd_set_device(s, next);
    if (!s.device) return;
    const drivers::DeviceFault f = s.device->fault();
    ImGui::Text("device: %s, %s", s.device->name(), drivers::to_string(s.device->state()));
    if (f.code != drivers::DeviceFaultCode::none)
        ImGui::TextColored(ImVec4(1, 0.35f, 0.3f, 1), "device fault: %s - %s", drivers::to_string(f.code), f.detail);
    else
        ImGui::TextDisabled("device fault: none");
    if (!h.recording()) {
        ImGui::InputText("record to", s.record_path, sizeof s.record_path);
        if (ImGui::Button("Start recording")) cmd_record_start(s, s.record_path);
    } else {
        ImGui::TextColored(ImVec4(1, 0.5f, 0.4f, 1), "REC %s: %llu ticks, %llu dropped", h.recording_path().c_str(),
                           static_cast<unsigned long long>(h.recorded()),
                           static_cast<unsigned long long>(h.recording_dropped()));
        if (ImGui::Button("Stop recording")) cmd_record_stop(s);
    }
}

// Servo rate: typed (Enter applies) or a preset; each change restarts the servo safely.
void rate_controls(EditorState& s) {
    if (!s.haptics) return;
    wrapped_hint("A change restarts the servo: zero force, then the force ramps in.");
    double hz = s.haptics->rate();
    if (ImGui::InputDouble("rate (Hz)", &hz, 0.0, 0.0, "%.0f", ImGuiInputTextFlags_EnterReturnsTrue) &&
        hz != s.haptics->rate())
        cmd_set_rate(s, hz);
    static const double presets[] = {100, 500, 1000, 2000, 5000, 10000, 20000};
    for (std::size_t i = 0; i < std::size(presets); ++i) {
        char label[16];
        std::snprintf(label, sizeof label, presets[i] >= 1000 ? "%.0fk" : "%.0f",
                      presets[i] >= 1000 ? presets[i] / 1000 : presets[i]);
        if (i > 0) ImGui::SameLine();
        if (ImGui::SmallButton(label) && presets[i] != s.haptics->rate()) cmd_set_rate(s, presets[i]);
    }
}

// During a live experiment: the trial's force and finger values, read-only. Nothing that gives the
// stimulus away (the scene is not drawn either).
void trial_values(EditorState& s) {
    const Scene& sc = experiment_servo_scene(s);
    ImGui::TextColored(ImVec4(1.0f, 0.8f, 0.4f, 1.0f), "Experiment running: the trial's values (read-only)");
    const ForceLaw& law = sc.force.law;
    if (law.model == ForceModel::spring) {
        ImGui::Text("model        spring");
        ImGui::Text("Ke           %.0f N/m", sc.force.stiffness);
    } else {
        ImGui::Text("model        ellipsoid");
        // Not the field angle: in seed 004 it is the stimulus the participant judges.
        ImGui::Text("k_t, k_n     %.0f, %.0f N/m", law.k_tangential, law.k_normal);
    }
    ImGui::Text("max force    %.2f N", sc.force.max_force);
    ImGui::Text("damping      %.2f N s/m", law.damping);
    ImGui::Text("mu s, d      %.2f, %.2f", law.mu_static, law.mu_dynamic);
    ImGui::Text("finger R, L  %.1f, %.1f mm", sc.finger.radius * 1e3, sc.finger.length * 1e3);
    if (s.haptics) ImGui::Text("servo        %.0f Hz", s.haptics->rate());
    // The device's own live values, shown as the trial runs with them (not editable either).
    if (device_has_roller(s))
        ImGui::Text("roller kff   %.2f V s/m, cutoff %.1f Hz", s.roller.kff, s.roller.ff_cutoff_hz);
    if (device_has_platform(s)) {
        const wearable::RigTuning& w = s.wearable;
        ImGui::Text("wearable     force Kp %.3g, Kd %.3g; position Kp %.3g, Kd %.3g", w.force_kp, w.force_kd,
                    w.position_kp, w.position_kd);
        ImGui::Text("             fit %s, FSR noise %.4f N", w.seed_fit ? "seed" : "none", w.fsr_noise);
    }
}

void tuning_window(EditorState& s, const EditorLayout& layout, ImGuiCond cond) {
    // As tall as its open sections, at most the column (then it scrolls): the canvas's legend
    // below it stays in sight.
    const Rect& r = layout.tuning;
    ImGui::SetNextWindowPos(ImVec2(r.x, r.y), cond);
    ImGui::SetNextWindowSizeConstraints(ImVec2(r.w, 0.0f), ImVec2(r.w, std::max(r.h, 100.0f)));
    if (!ImGui::Begin("Tuning", nullptr, ImGuiWindowFlags_AlwaysAutoResize)) {
        ImGui::End();
        return;
    }
    ImGui::PushTextWrapPos(0.0f);  // long lines wrap, never cut
    if (experiment_running(s)) {
        // A live trial's values are the protocol's: what the servo renders now, shown, not edited
        // (an edit here used to change the field and not the servo).
        trial_values(s);
        ImGui::PopTextWrapPos();
        ImGui::End();
        return;
    }
    ImGui::PushItemWidth(170);
    wearable_section(s);  // the attached platform first: what this device has (device_sections.hpp)
    if (ImGui::CollapsingHeader("Force (scene, undoable)", ImGuiTreeNodeFlags_DefaultOpen)) {
        const Scene& sc = s.doc.scene();
        int model = sc.force.law.model == ForceModel::spring ? 0 : 1;
        if (ImGui::Combo("model", &model, "spring\0ellipsoid\0")) {
            Scene c = sc;
            set_force_model(c.force, model == 0 ? ForceModel::spring : ForceModel::ellipsoid);
            s.doc.edit(std::move(c), "force model");
            s.say(model == 0 ? "model = spring (Ke = k_n)" : "model = ellipsoid (k_n = Ke)");
        }
        const double kmax = s.device ? s.device->limits().max_stable_stiffness : 2000.0;
        edit_field(s, "Ke (N/m)", "ke", 10.0, 5000.0, "%.0f", 1.0, true);
        if (s.servo && s.device) {
            // Discrete stability bound for a spring through the device's damping: K < 2 b / T.
            const double bound = 2.0 * s.device->limits().damping / s.servo->period();
            ImGui::TextColored(s.doc.scene().force.stiffness > kmax ? ImVec4(1, 0.4f, 0.3f, 1) : ImVec4(0.6f, 0.8f, 0.6f, 1),
                               "stable up to: device %.0f N/m, 2b/T %.0f N/m", kmax, bound);
        }
        edit_field(s, "max force (N)", "max_force", 0.01, 5.0, "%.2f");
        if (s.doc.scene().force.law.model == ForceModel::ellipsoid) {
            edit_field(s, "k tangential (N/m)", "k_t", 10.0, 5000.0, "%.0f", 1.0, true);
            edit_field(s, "k normal (N/m)", "k_n", 10.0, 5000.0, "%.0f", 1.0, true);
            edit_ellipsoid_ek(s);
        }
        edit_field(s, "damping (N s/m)", "damping", 0.0, 10.0, "%.2f");
        edit_field(s, "mu static", "mu_s", 0.0, 2.0, "%.2f");
        edit_field(s, "mu dynamic", "mu_d", 0.0, 2.0, "%.2f");
        int rule = s.doc.scene().contact_location.rule == ContactRule::centroid ? 0 : 1;
        if (ImGui::Combo("contact rule", &rule, "centroid (seed 000)\0least displacement\0")) {
            Scene c = s.doc.scene();
            c.contact_location.rule = rule == 0 ? ContactRule::centroid : ContactRule::least_displacement;
            s.doc.edit(std::move(c), "contact rule");
        }
        if (ImGui::IsItemHovered()) ImGui::SetTooltip("centroid: seed 000\nleast displacement: seed 002");
    }
    if (ImGui::CollapsingHeader("Finger and curves (scene)", ImGuiTreeNodeFlags_DefaultOpen)) {
        edit_field(s, "finger R (mm)", "finger_r", 0.005, 0.05, "%.1f", 1e3);
        edit_field(s, "pad L (mm)", "pad_l", 0.002, 0.06, "%.1f", 1e3);
        edit_accuracy(s);
    }
    if (ImGui::CollapsingHeader("Servo rate", ImGuiTreeNodeFlags_DefaultOpen)) rate_controls(s);
    roller_section(s);  // with a roller only (device_sections.hpp)
    selection_editor(s);  // also drops a selection the scene no longer has, so always called
    ImGui::PopItemWidth();
    ImGui::PopTextWrapPos();
    ImGui::End();
}

// The Haptics panel's text (status_window), each item starting on a whole line of `line` px.
void haptics_text(EditorState& s, const FrameInfo& info, float line) {
    // Wrapped text is a few lines tall without their spacing: the next item goes to the next line.
    auto next_row = [line] { ImGui::SetCursorPosY(std::ceil(ImGui::GetCursorPosY() / line - 1e-3f) * line); };
    ImGui::PushTextWrapPos(0.0f);
    if (s.servo) {
        const ServoSnapshot snap = s.servo->snapshot();
        const bool stopped = s.servo->stopped();
        const bool fault = snap.state == ServoState::fault;
        ImGui::TextColored(fault ? ImVec4(1, 0.35f, 0.3f, 1) : ImVec4(0.7f, 0.9f, 0.7f, 1), "servo: %s%s%s",
                           stopped ? "STOPPED (idle)" : to_string(snap.state), fault ? " - " : "",
                           fault ? to_string(snap.fault) : "");
        next_row();
        if (snap.fault_count) {
            ImGui::Text("faults: %u, last: %s at %.1f s", snap.fault_count, to_string(s.last_fault), s.last_fault_t);
            ImGui::SameLine();
            if (ImGui::SmallButton("clear fault")) s.servo->clear_fault();
            next_row();
        }
        ImGui::Text("x_f (%.2f, %.2f) mm  phi %.1f deg", snap.finger.x * 1e3, snap.finger.y * 1e3, snap.phi * 180.0 / kPi);
        next_row();
        ImGui::Text("%s  |F| %.3f N  depth %.3f mm", snap.contact ? "CONTACT" : "free",
                    std::hypot(snap.force.x, snap.force.y), snap.depth * 1e3);
        next_row();
        ImGui::Text("l_d %.2f mm  roller %.2f mm", snap.l_d * 1e3, snap.roller_l * 1e3);
        next_row();
        ImGui::Text("Ke in effect %.0f N/m, max %.2f N", snap.stiffness, snap.max_force);
        next_row();
        // The passivity observer's budget (haptics/safety.hpp): the energy the loop generated, net
        // of what the device dissipated, against the threshold of a report. A user raising Ke sees
        // the margin shrink here before anything faults.
        const double used = std::max(0.0, snap.observer_used);
        ImGui::TextColored(used > 0.5 ? ImVec4(1, 0.6f, 0.3f, 1) : ImVec4(0.7f, 0.9f, 0.7f, 1),
                           "passivity budget used %.0f %% (%.0f of %.0f uJ)%s", 100.0 * used,
                           snap.observer_used * snap.observer_threshold * 1e6, snap.observer_threshold * 1e6,
                           snap.passivity_damping > 0.0 ? ", damping added" : "");
        next_row();
        const auto ps = s.history.period_stats(s.servo->period());
        ImGui::Text("servo %.0f Hz (T = %.0f us)", s.servo->rate(), s.servo->period() * 1e6);
        next_row();
        ImGui::Text("period p50 %.0f us  p99 %.0f us  max %.0f us", ps.p50 * 1e6, ps.p99 * 1e6, ps.max * 1e6);
        next_row();
        ImGui::Text("late ticks (>1.5 T) %zu / %zu (5 s), overruns %llu", ps.late, ps.count,
                    static_cast<unsigned long long>(s.servo->overruns()));
        next_row();
        ImGui::TextDisabled("%s", s.servo->scheduling().c_str());
        next_row();
    }
    ImGui::SetCursorPosY(ImGui::GetCursorPosY() + line);  // a blank line between the servo and the frame
    ImGui::Text("%s, %dx%d, %.1f ms/frame, %.0f fps", info.present_mode.c_str(), info.width, info.height, info.frame_ms,
                info.fps);
    next_row();
    ImGui::TextDisabled("%s", info.gpu.c_str());
    next_row();
    if (info.validation_messages) {
        ImGui::TextColored(ImVec4(1, 0.3f, 0.3f, 1), "validation messages: %d", info.validation_messages);
        next_row();
    }
    ImGui::Text("%d contours, %d segments, undo %zu", static_cast<int>(s.doc.scene().contours.size()),
                segment_count(s.doc.scene()), s.doc.undo_depth());
    next_row();
    if (!s.doc.valid()) {
        ImGui::TextColored(ImVec4(1, 0.4f, 0.3f, 1), "Invalid geometry (not sent to the servo, not saved): %s",
                           s.doc.problem().c_str());
        next_row();
    }
    ImGui::Dummy(ImVec2(0.0f, 0.0f));  // the content ends on a line: the last scroll is whole lines too
    ImGui::PopTextWrapPos();
}

void status_window(EditorState& s, const FrameInfo& info, const EditorLayout& layout, ImGuiCond cond) {
    ImGui::SetNextWindowPos(ImVec2(layout.haptics.x, layout.haptics.y), cond);
    ImGui::SetNextWindowSize(ImVec2(layout.haptics.w, layout.haptics.h), cond);
    if (!ImGui::Begin("Haptics")) {
        ImGui::End();
        return;
    }
    ImGui::PushTextWrapPos(0.0f);  // long lines (a device fault, the scheduling) wrap, never cut
    if (s.servo) {
        // First, so that it stays in sight however short the panel (its text below scrolls).
        const bool stopped = s.servo->stopped();
        ImGui::PushStyleColor(ImGuiCol_Button, stopped ? ImVec4(0.3f, 0.5f, 0.3f, 1) : ImVec4(0.8f, 0.1f, 0.1f, 1));
        if (ImGui::Button(stopped ? "RELEASE STOP (space)" : "EMERGENCY STOP (space)", ImVec2(-1, 34))) cmd_toggle_stop(s);
        ImGui::PopStyleColor();
        const ImVec2 a = ImGui::GetItemRectMin(), b = ImGui::GetItemRectMax();
        if (ImGui::IsItemVisible()) note_panel_part("Haptics > emergency stop", Rect{a.x, a.y, b.x - a.x, b.y - a.y});
    }
    device_controls(s);
    // The text below scrolls in whole lines: a child as tall as the lines that fit, each item
    // starting on a line, its scroll snapped to a line. So no line is ever cut by the panel's
    // edge (at 1280x720 the Plots panel below cut the last one in half).
    const float line = ImGui::GetTextLineHeightWithSpacing();  // px
    const int rows = static_cast<int>(std::floor(ImGui::GetContentRegionAvail().y / line));
    if (rows >= 1 && ImGui::BeginChild("##haptics text", ImVec2(0.0f, static_cast<float>(rows) * line), false)) {
        haptics_text(s, info, line);
        const ImVec2 a = ImGui::GetWindowPos(), size = ImGui::GetWindowSize();
        note_panel_part("Haptics > text", Rect{a.x, a.y, size.x, size.y});
        note_panel_part("Haptics > text row", Rect{a.x, a.y, size.x, line});
        const float sy = ImGui::GetScrollY(), snapped = std::round(sy / line) * line;
        if (std::abs(snapped - sy) > 0.5f) ImGui::SetScrollY(std::min(snapped, ImGui::GetScrollMaxY()));
    }
    if (rows >= 1) ImGui::EndChild();
    ImGui::PopTextWrapPos();
    ImGui::End();
}

// Another session's unsaved work (recovery.hpp): one modal per file, until answered.
void recovery_window(EditorState& s) {
    const char* title = "Recover unsaved work";
    if (s.recovery_offers.empty()) return;
    if (!ImGui::IsPopupOpen(title)) ImGui::OpenPopup(title);
    if (!ImGui::BeginPopupModal(title, nullptr, ImGuiWindowFlags_AlwaysAutoResize)) return;
    ImGui::TextUnformatted("A session ended without saving this work:");
    ImGui::PushTextWrapPos(560.0f);
    ImGui::TextColored(ImVec4(1, 0.85f, 0.5f, 1), "%s", recovery_summary(s.recovery_offers.front()).c_str());
    ImGui::PopTextWrapPos();
    if (s.recovery_offers.size() > 1) ImGui::TextDisabled("(%zu more after this one)", s.recovery_offers.size() - 1);
    if (ImGui::Button("Recover")) answer_recovery(s, RecoveryAnswer::recover);
    if (ImGui::IsItemHovered()) ImGui::SetTooltip("Open it in place of the current scene (undo goes back)");
    ImGui::SameLine();
    if (ImGui::Button("Discard")) answer_recovery(s, RecoveryAnswer::discard);
    if (ImGui::IsItemHovered()) ImGui::SetTooltip("Delete the recovery file");
    ImGui::SameLine();
    if (ImGui::Button("Keep both")) answer_recovery(s, RecoveryAnswer::keep_both);
    if (ImGui::IsItemHovered()) ImGui::SetTooltip("Keep it as NAME.recovered-DATE.json beside the scene");
    if (s.recovery_offers.empty()) ImGui::CloseCurrentPopup();
    ImGui::EndPopup();
}

void plots_window(EditorState& s, const EditorLayout& layout, ImGuiCond cond) {
    ImGui::SetNextWindowPos(ImVec2(layout.plots.x, layout.plots.y), cond);
    ImGui::SetNextWindowSize(ImVec2(layout.plots.w, layout.plots.h), cond);
    const char* title = "Plots (last 5 s)";
    if (!ImGui::Begin(title)) {
        ImGui::End();
        return;
    }
    // The values' time span: one per servo tick, up to the history's 5 s.
    const double rate = s.servo ? s.servo->rate() : 1000.0;
    const double span = static_cast<double>(s.history.size()) / rate;
    const double window = std::min(5.0, static_cast<double>(s.history.capacity()) / rate);
    const auto plot = [&](const char* name, const char* unit, PlotHistory::Column c, float lo, float hi) {
        const Rect r = draw_live_plot(name, s.history.column(c), span, window, LivePlotSpec{name, unit, lo, hi});
        if (ImGui::IsItemVisible()) note_panel_part(std::string(title) + " > " + name, r);  // on screen only
    };
    const float fmax = static_cast<float>(std::max(0.1, s.doc.scene().force.max_force));
    const float nan = std::nanf("");
    plot("|F|", "N", PlotHistory::force_n, 0.0f, fmax * 1.05f);
    plot("depth", "mm", PlotHistory::depth_mm, 0.0f, nan);
    plot("l_d", "mm", PlotHistory::l_d_mm, -10.0f, 10.0f);
    if (device_has_roller(s)) plot("roller err", "mm", PlotHistory::roller_error_mm, nan, nan);
    plot("period", "us", PlotHistory::period_us, 0.0f, nan);
    // The passivity observer's budget (haptics/safety.hpp): the share of its threshold the loop
    // generated, net of what the device dissipated; a user raising Ke sees it climb.
    plot("budget used", "%", PlotHistory::budget_pct, 0.0f, 100.0f);
    const Rect axis = draw_time_axis(window);
    if (ImGui::IsItemVisible()) note_panel_part(std::string(title) + " > time axis", axis);
    ImGui::End();
}

// A fixed, undecorated row the width of the window (the status and message rows).
bool begin_row(const char* id, const Rect& r) {
    ImGui::SetNextWindowPos(ImVec2(r.x, r.y));
    ImGui::SetNextWindowSize(ImVec2(r.w, r.h));
    ImGui::SetNextWindowBgAlpha(1.0f);  // opaque: the canvas does not show through a row
    ImGui::PushStyleVar(ImGuiStyleVar_WindowPadding, ImVec2(8.0f, 3.0f));
    ImGui::PushStyleVar(ImGuiStyleVar_WindowBorderSize, 0.0f);
    ImGui::PushStyleVar(ImGuiStyleVar_WindowMinSize, ImVec2(1.0f, 1.0f));  // a row, not a 32 px window
    const bool open = ImGui::Begin(id, nullptr,
                                   ImGuiWindowFlags_NoDecoration | ImGuiWindowFlags_NoInputs | ImGuiWindowFlags_NoSavedSettings |
                                       ImGuiWindowFlags_NoFocusOnAppearing | ImGuiWindowFlags_NoNav |
                                       ImGuiWindowFlags_NoBringToFrontOnFocus);
    ImGui::PopStyleVar(3);
    return open;
}

}  // namespace

EditorLayout current_layout(int plots) {
    const ImVec2 size = ImGui::GetIO().DisplaySize;
    return editor_layout(static_cast<int>(size.x), static_cast<int>(size.y), ImGui::GetFrameHeight(), plots);
}

std::vector<LaidOut> laid_out() {
    std::vector<LaidOut> parts;
    const EditorLayout l = current_layout();
    for (const auto& [name, r] : {std::pair{"top ruler", l.top_ruler}, std::pair{"left ruler", l.left_ruler}})
        parts.push_back({name, r, false, true});
    // Dear ImGui's windows as drawn last frame (imgui_internal.h: the public API has no list).
    for (ImGuiWindow* w : GImGui->Windows) {
        if (!w->WasActive || w->Hidden || (w->Flags & (ImGuiWindowFlags_ChildWindow | ImGuiWindowFlags_Tooltip))) continue;
        // Content wider than the room inside the padding: something is cut at the right edge.
        const bool overflow = w->ContentSize.x > w->ContentRegionRect.GetWidth() + 0.5f;
        const bool popup = (w->Flags & ImGuiWindowFlags_Popup) != 0;
        parts.push_back({w->Name, Rect{w->Pos.x, w->Pos.y, w->Size.x, w->Size.y}, overflow, !popup, w->ContentSize.x,
                         w->ContentRegionRect.GetWidth()});
    }
    // Parts inside the panels ("Tuning > Wearable ...", each plot): inside their window by design.
    for (const PanelPart& p : panel_parts()) parts.push_back({p.name, p.rect, false, false});
    // The canvas's scale bars: drawn under the panels, so no panel may cover them (tiled).
    for (const PanelPart& p : canvas_parts()) parts.push_back({p.name, p.rect, false, true});
    return parts;
}

void draw_panels(EditorState& s, const FrameInfo& info, const std::optional<ProxyOutput>& proxy) {
    const int plots = live_plot_count(s);
    const EditorLayout layout = current_layout(plots);
    // Panels go where the layout says on the first frame and again whenever the window's size
    // or the device's set of plots changes (a panel left where it was could end up off screen or
    // over another, or leave a plot out of sight); in between they stay where the user moved them.
    static ImVec2 laid_out_for(0.0f, 0.0f);
    static int laid_out_plots = 0;
    const ImVec2 size = ImGui::GetIO().DisplaySize;
    const ImGuiCond cond = size.x != laid_out_for.x || size.y != laid_out_for.y || plots != laid_out_plots
                               ? ImGuiCond_Always
                               : ImGuiCond_FirstUseEver;
    laid_out_for = size;
    laid_out_plots = plots;
    begin_panel_parts();
    menu_bar(s);
    // Status row under the menu bar: the proxy's state, never over the canvas or the rulers.
    if (begin_row("##proxy status", layout.status_row) && proxy)
        ImGui::TextUnformatted(render::proxy_status_text(*proxy).c_str());
    ImGui::End();
    tuning_window(s, layout, cond);
    status_window(s, info, layout, cond);
    {
        StageTimer timing(s.stages, Stage::plots);
        plots_window(s, layout, cond);
    }
    experiment_window(s, s.now);
    recovery_window(s);
    // Message row along the bottom edge: the last action's outcome.
    if (begin_row("##status", layout.message_row))
        ImGui::TextColored(s.message_is_error ? ImVec4(1, 0.4f, 0.3f, 1) : ImVec4(0.8f, 0.85f, 0.9f, 1), "%s",
                           s.message.c_str());
    ImGui::End();
    end_panel_parts();
}

}  // namespace contactlab::editor
