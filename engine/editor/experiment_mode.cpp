// experiment_mode.cpp — live trials in the editor (experiment_mode.hpp).
#include "engine/editor/experiment_mode.hpp"

#include "engine/editor/canvas.hpp"
#include "engine/editor/editor_state.hpp"
#include "engine/editor/haptics_host.hpp"
#include "drivers/device.hpp"
#include "engine/experiments/runs/run_meta.hpp"

#include <imgui.h>

#include <cmath>
#include <numbers>
#include <cstdio>

namespace contactlab::editor {
namespace {

const Scene& nothing() {
    static const Scene empty;  // no contour: nothing to feel
    return empty;
}

// Seed 003's sweep on the device, when the trial has one and the device takes it (a platform:
// PoseInput::start_sweep); stop_sweep hands the finger back to the cursor.
bool start_sweep(EditorState& s) {
    ExperimentState* e = s.experiment;
    const auto sweep = e->session->sweep();
    e->sweeping = sweep && s.pose_input && s.pose_input->start_sweep(*sweep);
    return e->sweeping;
}

void stop_sweep(EditorState& s) {
    if (!s.experiment || !s.experiment->sweeping) return;
    if (s.pose_input) s.pose_input->stop_sweep();
    s.experiment->sweeping = false;
}

void start_trial(ExperimentState& e) {
    e.trial_start = -1.0;
    e.touched = e.in_contact = e.faulted = false;
    e.contact_breaks = 0;
    e.ticks = e.contact_ticks = 0;
    e.peak_force = 0.0;
}

std::string prompt(const experiments::LiveSession& s, bool sweeping) {
    switch (s.protocol().task) {
        case experiments::Task::contour_following: return "Follow the top to its edge, tip round it and go down the far side; then Enter.";
        case experiments::Task::bump_counting: return "Trace the contour and count the bumps.";
        case experiments::Task::curvature:
            return sweeping ? "The arc passes under the finger (N: again). Which height was it (mm)?" : "Which height was the arc (mm)?";
        case experiments::Task::surface_orientation: return "Press the surface: which shape, A or B?";
        case experiments::Task::edge_sharpness:
            return s.interval() < s.intervals() ? "Edge 1 of 2: slide across it, then Next (N) for edge 2."
                                                : "Edge 2 of 2: slide across it. Which edge felt sharper, the first or the second?";
    }
    return {};
}

// Seed 004's visual templates as pictures (the seed's Fig. 7, bottom): a surface tilted along
// the field's axis of maximum compliance, alpha = 45 deg (template A, the protocol's first answer)
// or 135 deg (B), in side view with its solid below, so the participant matches a shape, not a
// letter. `alpha_deg` from +x, counter-clockwise.
void template_picture(double alpha_deg, const char* label) {
    const float w = 96.0f, h = 72.0f;  // px
    const ImVec2 p = ImGui::GetCursorScreenPos();
    ImDrawList* dl = ImGui::GetWindowDrawList();
    const float a = static_cast<float>(alpha_deg * std::numbers::pi / 180.0);
    const ImVec2 c(p.x + w / 2.0f, p.y + h / 2.0f + 6.0f);
    const float half = 0.42f * w;  // px of the surface either side of the centre
    const ImVec2 d(std::cos(a) * half, -std::sin(a) * half);  // screen y grows downwards
    const ImVec2 e1(c.x - d.x, c.y - d.y), e2(c.x + d.x, c.y + d.y);
    const ImVec2 left = e1.x < e2.x ? e1 : e2, right = e1.x < e2.x ? e2 : e1;
    dl->AddRectFilled(p, ImVec2(p.x + w, p.y + h), IM_COL32(30, 30, 36, 255));
    dl->AddQuadFilled(left, right, ImVec2(right.x, p.y + h - 2.0f), ImVec2(left.x, p.y + h - 2.0f), IM_COL32(205, 160, 120, 140));
    dl->AddLine(left, right, IM_COL32(250, 220, 190, 255), 2.0f);
    dl->AddRect(p, ImVec2(p.x + w, p.y + h), IM_COL32(120, 120, 130, 255));
    dl->AddText(ImVec2(p.x + 5.0f, p.y + 3.0f), IM_COL32(255, 255, 255, 255), label);
    ImGui::Dummy(ImVec2(w, h));
}

// The serial of the device the trial was felt on goes into the results' meta as
// "device_serials": {spec: serial} (a session may switch devices): a real device's own (a hapio
// board's handshake, the Falcon's FTDI chip, the Haply board's USB serial); a simulated one is
// "simulated, seed N" with the session's seed; the mouse and a replay say what they are.
void record_device_serial(EditorState& s) {
    if (!s.device || !s.haptics || !s.experiment || !s.experiment->session) return;
    const std::string spec = s.haptics->spec();
    std::string serial = s.device->serial();
    if (serial.empty()) {
        if (spec.rfind("usb:", 0) == 0) return;  // a real device that has not said (yet)
        serial = spec == "mouse" ? "mouse (no serial)" : spec.rfind("replay:", 0) == 0 ? "replay (no serial)" : "simulated";
    }
    const std::string key = spec + " " + serial;
    if (key == s.experiment->serial_recorded) return;
    try {
        auto meta = experiments::read_meta(s.experiment->session->results_path());
        if (!meta) return;
        std::string value = serial;
        if (value == "simulated" && meta->contains("seed")) value += ", seed " + (*meta)["seed"].dump();
        (*meta)["device_serials"][spec] = value;
        experiments::write_meta(s.experiment->session->results_path(), *meta);
        s.experiment->serial_recorded = key;
    } catch (const std::exception& ex) {
        s.say(std::string("results meta: the device's serial not recorded: ") + ex.what(), true);
    }
}

}  // namespace

bool experiment_running(const EditorState& s) {
    return s.experiment && s.experiment->session && !s.experiment->session->finished();
}

const Scene& experiment_servo_scene(const EditorState& s) {
    const ExperimentState* e = s.experiment;
    if (!e || !e->session || e->paused || e->session->finished()) return nothing();
    return e->session->scene();
}

std::uint64_t experiment_scene_key(const EditorState& s) {
    const ExperimentState* e = s.experiment;
    if (!e || !e->session || e->paused || e->session->finished()) return 0;
    return e->session->scene_version();
}

void experiment_scene_published(EditorState& s, double now) {
    ExperimentState* e = s.experiment;
    if (e && e->session && !e->paused && !e->session->finished() && e->trial_start < 0.0) {
        e->trial_start = now;
        // The stimulus's extent and the finger in view (not the arcs' whole circles: seed 003's
        // arcs are parts of metre-wide circles); the stimulus itself is not drawn.
        Aabb box;
        for (const Contour& c : e->session->scene().contours)
            for (const Segment& seg : c.segments) {
                box.grow(segment_start(seg));
                box.grow(segment_end(seg));
            }
        const double reach = 3.5 * e->session->scene().finger.radius;  // m
        box.grow(s.pose.finger - Vec2(reach));
        box.grow(s.pose.finger + Vec2(reach));
        s.camera.fit(box);
        if (start_sweep(s)) s.say("the arc passes under the finger; N passes it again");
    }
}

void experiment_on_record(EditorState& s, const drivers::TickRecord& r) {
    ExperimentState* e = s.experiment;
    if (!e || e->trial_start < 0.0) return;
    e->peak_force = std::max(e->peak_force, std::hypot(r.force.x, r.force.y));
    if (e->touched && e->in_contact && !r.contact) ++e->contact_breaks;
    e->touched |= r.contact;
    e->in_contact = r.contact;
    ++e->ticks;
    e->contact_ticks += r.contact;
    e->faulted |= r.fault != ServoFault::none;
}

bool cmd_experiment_answer(EditorState& s, const std::string& response, double now) {
    ExperimentState* e = s.experiment;
    if (!e || !e->session || e->session->finished()) {
        s.say("no trial is waiting for an answer", true);
        return false;
    }
    if (e->paused || e->trial_start < 0.0) {
        s.say("the trial has not started (resume first)", true);
        return false;
    }
    experiments::LiveTrialResult r;
    r.response = response;
    r.time_s = now - e->trial_start;
    r.contact_breaks = e->contact_breaks;
    if (e->ticks > 0) r.contact_fraction = static_cast<double>(e->contact_ticks) / static_cast<double>(e->ticks);
    r.peak_force = e->peak_force;
    r.valid = !e->faulted;
    r.touched = e->touched;
    r.device = s.haptics ? s.haptics->spec() : std::string();
    try {
        e->session->answer(r);
    } catch (const std::exception& ex) {
        s.say(ex.what(), true);
        return false;
    }
    stop_sweep(s);  // the next trial's starts when its scene reaches the servo
    start_trial(*e);
    record_device_serial(s);
    char buf[160];
    if (e->session->finished()) {
        // The meta says the run is whole: finished_utc and the row count.
        try {
            if (auto meta = experiments::read_meta(e->session->results_path())) {
                experiments::finish_meta(*meta, e->session->total());
                experiments::write_meta(e->session->results_path(), *meta);
            }
        } catch (const std::exception& ex) {
            s.say(std::string("results meta not finished: ") + ex.what(), true);
        }
    }
    if (e->session->finished())
        std::snprintf(buf, sizeof buf, "experiment finished: %zu trials in %s", e->session->total(), e->session->results_path().c_str());
    else
        std::snprintf(buf, sizeof buf, "trial %zu of %zu recorded%s", e->session->done(), e->session->total(),
                      !r.valid     ? " (invalid: the servo faulted; it comes again at the end of the block)"
                      : !*r.touched ? " (invalid: the stimulus was never touched; it comes again at the end of the block)"
                                    : "");
    s.say(buf);
    return true;
}

void cmd_experiment_pause(EditorState& s, bool paused) {
    ExperimentState* e = s.experiment;
    if (!e || !e->session) return;
    if (e->paused == paused) return;
    e->paused = paused;
    stop_sweep(s);
    start_trial(*e);  // a paused trial starts again from the beginning
    s.say(paused ? "experiment paused: nothing to feel until Resume" : "experiment resumed");
}

bool cmd_experiment_next_interval(EditorState& s) {
    ExperimentState* e = s.experiment;
    if (!e || !e->session || e->session->finished() || e->paused || e->trial_start < 0.0) {
        s.say("no trial is running", true);
        return false;
    }
    if (e->sweeping) {  // seed 003 on the platform: the arc passes again
        start_sweep(s);
        s.say("the arc passes under the finger again");
        return true;
    }
    if (!e->session->next_interval()) {
        s.say(e->session->intervals() > 1 ? "this is the trial's last edge: answer which felt sharper" : "this task has one stimulus per trial",
              true);
        return false;
    }
    char buf[64];
    std::snprintf(buf, sizeof buf, "edge %d of %d", e->session->interval(), e->session->intervals());
    s.say(buf);
    return true;
}

bool experiment_key(EditorState& s, const std::string& key, double now) {
    ExperimentState* e = s.experiment;
    if (!e || !e->session) return false;
    if (key == "p") {
        cmd_experiment_pause(s, !e->paused);
        return true;
    }
    if (key == "n" && (e->session->intervals() > 1 || e->sweeping)) return cmd_experiment_next_interval(s), true;
    const auto& answers = e->session->protocol().answers;
    if (key == "enter" && answers.empty()) return cmd_experiment_answer(s, "", now), true;
    if (key.size() == 1 && key[0] >= '1' && key[0] <= '9') {
        const std::size_t i = static_cast<std::size_t>(key[0] - '1');
        if (i < answers.size()) cmd_experiment_answer(s, answers[i], now);
        return true;  // the tool keys are off during an experiment
    }
    return false;
}

void experiment_window(EditorState& s, double now) {
    ExperimentState* e = s.experiment;
    if (!e || !e->session) return;
    const experiments::LiveSession& x = *e->session;
    ImGui::SetNextWindowPos(ImVec2(ImGui::GetIO().DisplaySize.x * 0.5f - 200.0f, 70.0f), ImGuiCond_FirstUseEver);
    ImGui::SetNextWindowSize(ImVec2(400.0f, 0.0f), ImGuiCond_FirstUseEver);
    if (!ImGui::Begin("Experiment")) {
        ImGui::End();
        return;
    }
    ImGui::PushTextWrapPos(0.0f);
    ImGui::TextDisabled("%s, participant %s", x.protocol().name.c_str(), x.participant().c_str());
    char progress[64];
    if (x.adaptive() && !x.finished())
        std::snprintf(progress, sizeof progress, "%zu trials (%s: at most %zu)", x.done(), x.protocol().procedure.label().c_str(), x.total());
    else
        std::snprintf(progress, sizeof progress, "%zu / %zu trials", x.done(), x.total());
    ImGui::ProgressBar(x.total() ? static_cast<float>(x.done()) / static_cast<float>(x.total()) : 1.0f, ImVec2(-1.0f, 0.0f), progress);
    if (x.finished()) {
        ImGui::Text("Finished. Results: %s", x.results_path().c_str());
    } else if (e->paused) {
        ImGui::TextColored(ImVec4(1, 0.8f, 0.4f, 1), "Paused: nothing to feel.");
        if (ImGui::Button("Resume (P)")) cmd_experiment_pause(s, false);
    } else {
        ImGui::Text("Trial %d (%s)%s", x.trial().trial, x.condition().name.c_str(), x.trial().warmup ? ", warm-up" : "");
        ImGui::TextUnformatted(prompt(x, e->sweeping).c_str());
        const auto& answers = x.interval() < x.intervals() ? std::vector<std::string>{} : x.protocol().answers;
        if (x.interval() < x.intervals()) {
            if (ImGui::Button("Next edge (N)")) cmd_experiment_next_interval(s);
        } else if (e->sweeping) {
            if (ImGui::Button("Again (N)")) cmd_experiment_next_interval(s);
        } else if (answers.empty()) {
            if (ImGui::Button("Done (Enter)")) cmd_experiment_answer(s, "", now);
        }
        const bool templates = x.protocol().task == experiments::Task::surface_orientation && answers.size() == 2;
        for (std::size_t i = 0; i < answers.size(); ++i) {
            if (i) ImGui::SameLine();
            char label[48];
            std::snprintf(label, sizeof label, "%s (%zu)", answers[i].c_str(), i + 1);
            ImGui::BeginGroup();
            if (templates) template_picture(i == 0 ? 45.0 : 135.0, answers[i].c_str());
            if (ImGui::Button(label)) cmd_experiment_answer(s, answers[i], now);
            ImGui::EndGroup();
        }
        if (ImGui::Button("Pause (P)")) cmd_experiment_pause(s, true);
    }
    ImGui::PopTextWrapPos();
    ImGui::End();
}

}  // namespace contactlab::editor
