// script.cpp — the --script runner (see script.hpp).
#include "engine/editor/script.hpp"
#include "engine/editor/cursor_wearable_device.hpp"

#include "engine/editor/canvas.hpp"
#include "engine/editor/haptics_commands.hpp"
#include "engine/editor/panels.hpp"
#include "engine/editor/parameter_edit.hpp"
#include "engine/editor/experiment_mode.hpp"
#include "engine/editor/recovery.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <map>
#include <sstream>

namespace contactlab::editor {
namespace {

// Command -> (min, max) argument count.
const std::map<std::string, std::pair<int, int>>& arity() {
    static const std::map<std::string, std::pair<int, int>> a = {
        {"tool", {1, 1}},   {"click", {2, 2}},       {"rclick", {2, 2}},     {"drag", {4, 4}},
        {"finger", {2, 3}}, {"key", {1, 1}},         {"set", {2, 2}},        {"undo", {0, 0}},
        {"redo", {0, 0}},   {"fit", {0, 0}},         {"save", {1, 1}},       {"open", {1, 1}},
        {"screenshot", {1, 1}}, {"estop", {1, 1}},   {"wait", {1, 1}},       {"frames", {1, 1}},
        {"wait_contact", {1, 1}}, {"resize", {2, 2}}, {"generate", {1, 1}}, {"wait_state", {2, 2}}, {"expect", {2, 3}}, {"quit", {0, 0}},
        {"device", {1, 2}}, {"rate", {1, 1}}, {"record", {1, 1}}, {"report", {1, 1}}, {"devices", {0, 0}}, {"recovery", {1, 1}}, {"layout", {0, 0}}, {"answer", {1, 1}}, {"pause", {0, 0}}, {"resume", {0, 0}},
        {"idle", {1, 1}}, {"check_layer", {0, 0}},
    };
    return a;
}

double number(const std::string& w) {
    std::size_t used = 0;
    double v = 0.0;
    try {
        v = std::stod(w, &used);
    } catch (const std::exception&) {
        used = 0;
    }
    if (used != w.size() || !std::isfinite(v)) throw ScriptError("not a number: \"" + w + "\"");
    return v;
}

// World mm -> canvas px (double precision, so a scripted finger lands where it was asked).
void px_of(const EditorState& s, double x_mm, double y_mm, double& px, double& py) {
    const render::View& v = s.camera.view();
    px = 0.5 * v.width + (x_mm * 1e-3 - v.center.x) * v.px_per_m;
    py = 0.5 * v.height - (y_mm * 1e-3 - v.center.y) * v.px_per_m;
}

}  // namespace

Script Script::load(const std::string& path) {
    std::ifstream in(path, std::ios::binary);
    if (!in) throw ScriptError("cannot read script " + path);
    std::ostringstream text;
    text << in.rdbuf();
    return parse(text.str(), path);
}

Script Script::parse(const std::string& text, const std::string& origin) {
    Script sc;
    sc.origin_ = origin;
    std::istringstream lines(text);
    std::string raw;
    int number = 0;
    while (std::getline(lines, raw)) {
        ++number;
        std::istringstream ws(raw);
        Line line;
        line.number = number;
        for (std::string w; ws >> w;) line.words.push_back(w);
        if (line.words.empty() || line.words[0][0] == '#') continue;
        const auto it = arity().find(line.words[0]);
        if (it == arity().end())
            throw ScriptError(origin + ":" + std::to_string(number) + ": unknown command \"" + line.words[0] + "\"");
        const int n = static_cast<int>(line.words.size()) - 1;
        if (n < it->second.first || n > it->second.second)
            throw ScriptError(origin + ":" + std::to_string(number) + ": " + line.words[0] + " takes " +
                              std::to_string(it->second.first) +
                              (it->second.first == it->second.second ? "" : ".." + std::to_string(it->second.second)) +
                              " argument(s), got " + std::to_string(n));
        sc.lines_.push_back(std::move(line));
    }
    return sc;
}

std::optional<std::pair<int, int>> Script::take_resize_request() {
    auto r = resize_;
    resize_.reset();
    return r;
}

std::optional<std::string> Script::take_screenshot_request() {
    auto r = std::move(screenshot_);
    screenshot_.reset();
    return r;
}

void Script::fail(const Line& line, const std::string& why) {
    ++failures_;
    std::fprintf(stderr, "script %s:%d: FAILED: %s\n", origin_.c_str(), line.number, why.c_str());
}

void Script::step(EditorState& s, double now) {
    while (next_ < lines_.size()) {
        const Line& line = lines_[next_];
        bool done = true;
        try {
            done = run(s, line, now);
        } catch (const std::exception& e) {
            fail(line, e.what());
        }
        if (!done) return;
        ++next_;
        wait_until_ = -1.0;
        frames_left_ = -1;
        // One visible action per frame so the window shows each step (and screenshots see it).
        if (line.words[0] == "screenshot" || line.words[0] == "resize") return;
    }
}

bool Script::run(EditorState& s, const Line& line, double now) {
    const auto& w = line.words;
    const std::string& c = w[0];
    double px = 0.0, py = 0.0;
    if (c == "tool") {
        if (w[1] == "finger") cmd_set_tool(s, Tool::finger);
        else if (w[1] == "select") cmd_set_tool(s, Tool::select);
        else if (w[1] == "line") cmd_set_tool(s, Tool::line);
        else if (w[1] == "quad") cmd_set_tool(s, Tool::quad);
        else if (w[1] == "arc") cmd_set_tool(s, Tool::arc);
        else if (w[1] == "arc_center") cmd_set_tool(s, Tool::arc_center);
        else if (w[1] == "cubic") cmd_set_tool(s, Tool::cubic);
        else throw ScriptError("unknown tool \"" + w[1] + "\" (finger, select, line, quad, arc, arc_center, cubic)");
    } else if (c == "click" || c == "rclick") {
        px_of(s, number(w[1]), number(w[2]), px, py);
        const Button b = c == "click" ? Button::left : Button::right;
        canvas_press(s, b, px, py);
        canvas_release(s, b, px, py);
    } else if (c == "drag") {
        px_of(s, number(w[1]), number(w[2]), px, py);
        canvas_press(s, Button::left, px, py);
        double qx = 0.0, qy = 0.0;
        px_of(s, number(w[3]), number(w[4]), qx, qy);
        for (int i = 1; i <= 4; ++i) canvas_move(s, px + (qx - px) * i / 4.0, py + (qy - py) * i / 4.0);
        canvas_release(s, Button::left, qx, qy);
    } else if (c == "finger") {
        if (s.tool != Tool::finger) cmd_set_tool(s, Tool::finger);
        if (w.size() > 3) {
            s.pose.phi = number(w[3]) * kPi / 180.0;
        }
        px_of(s, number(w[1]), number(w[2]), px, py);
        canvas_move(s, px, py);
    } else if (c == "key") {
        if (!experiment_key(s, w[1], now) && !canvas_key(s, w[1])) throw ScriptError("unknown key \"" + w[1] + "\"");
    } else if (c == "answer") {
        if (!s.experiment) throw ScriptError("answer: no experiment (edit --experiment PROTOCOL --participant ID)");
        cmd_experiment_answer(s, w[1] == "-" ? std::string() : w[1], now);  // `answer -` ends a timed trial
    } else if (c == "pause" || c == "resume") {
        if (!s.experiment) throw ScriptError(c + ": no experiment");
        cmd_experiment_pause(s, c == "pause");
    } else if (c == "set") {
        Scene sc = s.doc.scene();
        const std::string& n = w[1];
        if (n == "model") {
            if (w[2] != "spring" && w[2] != "ellipsoid") throw ScriptError("model: spring or ellipsoid");
            set_force_model(sc.force, w[2] == "spring" ? ForceModel::spring : ForceModel::ellipsoid);
        } else if (n == "rule") {
            if (w[2] != "centroid" && w[2] != "least_displacement") throw ScriptError("rule: centroid or least_displacement");
            sc.contact_location.rule = w[2] == "centroid" ? ContactRule::centroid : ContactRule::least_displacement;
        } else if (n == "snap_tangent") {
            if (w[2] != "0" && w[2] != "1") throw ScriptError("snap_tangent: 0 or 1");
            s.snap_tangent = w[2] == "1";
            return true;
        } else if (n == "snap_mm") {
            s.grid_mm = number(w[2]);
            s.snap_grid = s.grid_mm > 0.0;
            return true;
        } else if (n == "curves") {
            const std::optional<CurveMode> named = curve_mode_named(w[2]);
            if (!named) throw ScriptError("curves: exact or flatten");
            sc.curves.mode = *named;
        } else if (is_tunable_parameter(n)) {
            // The Tuning panel's path (parameter_edit.hpp): a refused value changes nothing and
            // is said in the status line; check the outcome with `expect error 0|1`.
            set_parameter(s, n, number(w[2]));
            return true;
        } else {
            throw ScriptError("unknown parameter \"" + n + "\"");
        }
        s.doc.edit(std::move(sc), n);
        s.say(n + " = " + w[2]);
    } else if (c == "recovery") {
        const std::string& a = w[1];
        if (a != "recover" && a != "discard" && a != "keep") throw ScriptError("recovery recover|discard|keep");
        answer_recovery(s, a == "recover" ? RecoveryAnswer::recover
                           : a == "discard" ? RecoveryAnswer::discard
                                            : RecoveryAnswer::keep_both);  // outcome: `expect error 0|1`
    } else if (c == "undo") {
        cmd_undo(s);
    } else if (c == "redo") {
        cmd_redo(s);
    } else if (c == "fit") {
        cmd_fit(s);
    } else if (c == "save") {
        cmd_save(s, w[1]);  // the outcome is checked with `expect error 0|1`
    } else if (c == "open") {
        s.doc.open(w[1]);
        cmd_fit(s);
    } else if (c == "generate") {
        if (!cmd_generate(s, w[1])) throw ScriptError("unknown generator \"" + w[1] + "\" (block, bumps, arc)");
    } else if (c == "resize") {
        const double rw = number(w[1]), rh = number(w[2]);
        if (rw < 64 || rh < 64 || rw > 8192 || rh > 8192) throw ScriptError("resize: 64..8192 px");
        resize_ = std::make_pair(static_cast<int>(rw), static_cast<int>(rh));
        return true;
    } else if (c == "screenshot") {
        screenshot_ = w[1];
    } else if (c == "estop") {
        if (w[1] != "on" && w[1] != "off") throw ScriptError("estop on|off");
        if (s.servo && s.servo->stopped() != (w[1] == "on")) cmd_toggle_stop(s);
    } else if (c == "wait") {
        if (wait_until_ < 0.0) wait_until_ = now + number(w[1]);
        return now >= wait_until_;
    } else if (c == "idle") {
        // Drawing on demand for a while; the frames drawn meanwhile are counted.
        const long drawn = s.stages ? s.stages->frames() : 0;
        if (idle_until_ < 0.0) {
            const double seconds = number(w[1]);
            if (seconds < 0.0) throw ScriptError("idle: the time must not be negative");
            idle_until_ = now + seconds;
            idle_frames_at_ = drawn;
            return false;
        }
        if (now < idle_until_) return false;
        idle_frames_ = drawn - idle_frames_at_;
        idle_until_ = -1.0;
        std::fprintf(stderr, "script idle: %ld frame(s) drawn in %s s\n", idle_frames_, w[1].c_str());
    } else if (c == "check_layer") {
        // Asked this frame, answered (s.layer_mismatch) by the editor before the next one.
        if (!layer_check_sent_) {
            layer_check_ = layer_check_sent_ = true;
            return false;
        }
        layer_check_sent_ = false;
        std::fprintf(stderr, "script check_layer: %ld pixel(s) differ between the kept scene layer and a fresh draw\n",
                     s.layer_mismatch);
    } else if (c == "frames") {
        if (frames_left_ < 0) frames_left_ = static_cast<long>(number(w[1]));
        return frames_left_-- <= 0;
    } else if (c == "wait_contact" || c == "wait_state") {
        const double timeout = number(w[c == "wait_contact" ? 1 : 2]);
        if (wait_until_ < 0.0) wait_until_ = now + timeout;
        const ServoSnapshot snap = s.servo ? s.servo->snapshot() : ServoSnapshot{};
        const bool ok = c == "wait_contact" ? snap.contact : std::string(to_string(snap.state)) == w[1];
        if (ok) return true;
        if (now < wait_until_) return false;
        fail(line, c == "wait_contact" ? "no contact within " + w[1] + " s"
                                       : "servo state is " + std::string(to_string(snap.state)) + ", not " + w[1] +
                                             " after " + w[2] + " s");
    } else if (c == "expect") {
        const ServoSnapshot snap = s.servo ? s.servo->snapshot() : ServoSnapshot{};
        const std::string& n = w[1];
        const double f = std::hypot(snap.force.x, snap.force.y);
        std::string got;
        bool ok = false;
        if (n == "state" || n == "device" || n == "device_state") {
            if (w.size() > 3) throw ScriptError("expect " + n + " takes no tolerance");
            got = n == "state"    ? std::string(to_string(snap.state))
                  : n == "device" ? (s.haptics ? s.haptics->spec() : std::string("none"))
                                  : std::string(s.device ? drivers::to_string(s.device->state()) : "none");
            ok = got == w[2];
        } else {
            const double want = number(w[2]);
            double v = 0.0;
            if (n == "contact") v = snap.contact ? 1 : 0;
            else if (n == "segments") v = segment_count(s.doc.scene());
            else if (n == "contours") v = static_cast<double>(s.doc.scene().contours.size());
            else if (n == "ke_effective") v = snap.stiffness;
            else if (n == "stopped") v = s.servo && s.servo->stopped() ? 1 : 0;
            else if (n == "valid") v = s.doc.valid() ? 1 : 0;
            else if (n == "undo_depth") v = static_cast<double>(s.doc.undo_depth());
            else if (n == "dirty") v = s.doc.dirty() ? 1 : 0;
            else if (n == "recovery_offers") v = static_cast<double>(s.recovery_offers.size());
            else if (n == "experiment_done") v = s.experiment && s.experiment->session ? static_cast<double>(s.experiment->session->done()) : 0;
            else if (n == "experiment_total") v = s.experiment && s.experiment->session ? static_cast<double>(s.experiment->session->total()) : 0;
            else if (n == "experiment_paused") v = s.experiment && s.experiment->paused ? 1 : 0;
            else if (n == "experiment_sweeping") v = s.experiment && s.experiment->sweeping ? 1 : 0;
            else if (n == "experiment_interval") v = s.experiment && s.experiment->session && !s.experiment->session->finished() ? s.experiment->session->interval() : 0;
            else if (n == "error") v = s.message_is_error ? 1 : 0;
            else if (n == "idle_frames") v = static_cast<double>(idle_frames_);
            else if (n == "layer_mismatch") v = static_cast<double>(s.layer_mismatch);
            else if (n == "force_above" || n == "force_below" || n == "force") v = f;
            else if (n == "rate") v = s.servo ? s.servo->rate() : 0.0;
            else if (n == "recording") v = s.haptics && s.haptics->recording() ? 1 : 0;
            else if (n == "finger_x") v = snap.finger.x * 1e3;  // mm
            else if (n == "finger_y") v = snap.finger.y * 1e3;  // mm
            else if (n == "finger_phi") v = snap.phi * 180.0 / 3.14159265358979323846;  // deg
            else if (n == "depth") v = snap.depth * 1e3;        // mm
            else if (n == "l_d") v = snap.l_d * 1e3;            // mm
            else if (n == "roller_target") v = snap.roller_target * 1e3;  // mm
            else if (n == "budget_threshold") v = snap.observer_threshold * 1e6;  // uJ, the passivity observer's
            else if (n == "budget_used")  // % of it the loop has generated (the Haptics panel's plot)
                v = 100.0 * std::max(0.0, snap.observer_used);
            else if (const auto p = parameter_value(s, n)) v = *p;  // the value shown in its field
            else throw ScriptError("unknown expectation \"" + n + "\"");
            const double tol = w.size() > 3 ? number(w[3]) : 0.0;
            if (tol < 0.0) throw ScriptError("expect: the tolerance must not be negative");
            if (n == "force_above") ok = v > want;
            else if (n == "force_below") ok = v < want;
            else if (n == "ke_effective") ok = std::abs(v - want) <= std::max(1.0, tol);
            else ok = std::abs(v - want) <= tol;
            char buf[64];
            std::snprintf(buf, sizeof buf, "%.6g", v);
            got = buf;
        }
        if (!ok) fail(line, "expected " + n + " " + w[2] + ", got " + got);
        else std::fprintf(stderr, "script %s:%d: ok: %s = %s\n", origin_.c_str(), line.number, n.c_str(), got.c_str());
    } else if (c == "device") {
        // `device replay FILE` is `device replay:FILE`, so a path with a colon needs no quoting.
        std::string spec = w[1];
        if (spec == "replay") {
            if (w.size() < 3) throw ScriptError("device replay FILE: name the recording");
            spec = "replay:" + w[2];
        } else if (w.size() > 2) {
            throw ScriptError("device " + w[1] + " takes no file (only replay FILE does)");
        }
        if (!cmd_set_device(s, spec)) throw ScriptError(s.message);
    } else if (c == "rate") {
        if (!cmd_set_rate(s, number(w[1]))) throw ScriptError(s.message);
    } else if (c == "record") {
        const bool ok = w[1] == "stop" ? cmd_record_stop(s) : cmd_record_start(s, w[1]);
        if (!ok) throw ScriptError(s.message);
        // What the status line says (on stop: the ticks written and those the ring dropped).
        std::fprintf(stderr, "script record: %s\n", s.message.c_str());
    } else if (c == "devices") {
        // The device menu as the Haptics panel shows it (USB scanned again), one line each.
        if (s.haptics)
            for (const DeviceOption& o : s.haptics->options(true))
                std::fprintf(stderr, "script device option %s: %s%s\n", o.spec.c_str(),
                             o.available ? "available" : "unavailable: ", o.why.c_str());
    } else if (c == "report") {
        // One machine-readable line for tests to parse (SI but lengths in mm, as the UI shows).
        const ServoSnapshot snap = s.servo ? s.servo->snapshot() : ServoSnapshot{};
        const auto ps = s.history.period_stats(s.servo ? s.servo->period() : 1e-3);
        std::fprintf(stderr,
                     "script report %s: device=%s device_state=%s rate_hz=%.17g cursor_x_mm=%.17g cursor_y_mm=%.17g "
                     "finger_x_mm=%.17g finger_y_mm=%.17g phi_deg=%.17g contact=%d depth_mm=%.17g force_n=%.17g "
                     "ke=%.17g servo_state=%s fault=%s ticks=%llu p50_us=%.6g p99_us=%.6g max_us=%.6g late=%zu count=%zu "
                     "scene_layer_updates=%ld frames_drawn=%ld",
                     w[1].c_str(), s.haptics ? s.haptics->spec().c_str() : "none",
                     s.device ? drivers::to_string(s.device->state()) : "none", s.servo ? s.servo->rate() : 0.0,
                     s.pose.finger.x * 1e3, s.pose.finger.y * 1e3, snap.finger.x * 1e3, snap.finger.y * 1e3,
                     snap.phi * 180.0 / kPi, snap.contact ? 1 : 0, snap.depth * 1e3, std::hypot(snap.force.x, snap.force.y),
                     snap.stiffness, to_string(snap.state), to_string(snap.fault), static_cast<unsigned long long>(snap.ticks), ps.p50 * 1e6,
                     ps.p99 * 1e6, ps.max * 1e6, ps.late, ps.count, s.scene_layer_updates,
                     s.stages ? s.stages->frames() : 0L);
        // Seed 003's platform, when the device is the simulated wearable.
        if (const auto* wd = dynamic_cast<const CursorWearableDevice*>(s.device)) {
            const drivers::sim::WearablePlatformView v = wd->platform_view();
            std::fprintf(stderr, " platform_roll_rad=%.17g platform_press_mm=%.17g platform_tension_n=%.17g",
                         v.roll, v.press * 1e3, v.tension[0] + v.tension[1] + v.tension[2]);
            // The tuning the device holds (the Wearable section sends it when it differs).
            const wearable::RigTuning t = wd->tuning();
            std::fprintf(stderr,
                         " platform_force_kp=%.17g platform_force_kd=%.17g platform_position_kp=%.17g "
                         "platform_position_kd=%.17g platform_seed_fit=%d platform_fsr_noise_n=%.17g",
                         t.force_kp, t.force_kd, t.position_kp, t.position_kd, t.seed_fit ? 1 : 0, t.fsr_noise);
        }
        std::fprintf(stderr, "\n");
    } else if (c == "layout") {
        // One line per part on screen (panels.hpp, laid_out), for the layout test.
        for (const LaidOut& p : laid_out())
            std::fprintf(stderr, "script layout: x=%.1f y=%.1f w=%.1f h=%.1f overflow=%d content_w=%.1f inside_w=%.1f tiled=%d name=%s\n",
                         p.rect.x, p.rect.y, p.rect.w, p.rect.h, p.overflow ? 1 : 0, p.content_w, p.inside_w, p.tiled ? 1 : 0,
                         p.name.c_str());
    } else if (c == "quit") {
        s.quit = true;
    }
    return true;
}

}  // namespace contactlab::editor
