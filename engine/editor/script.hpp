// script.hpp — `contactlab edit --script FILE`: UI actions and checks, one command per line, run
// through the same canvas functions the mouse and keys use. Coordinates are world mm; angles deg.
//
//   tool finger|select|line|quad|arc|arc_center|cubic   click X Y        rclick X Y       drag X0 Y0 X1 Y1
//   finger X Y [PHI]               key NAME (space, delete, ctrl+z, ctrl+y, f, 1, 2, 3, q, e)
//   set NAME VALUE   a tunable parameter (parameter_edit.hpp, the Tuning panel's one path):
//                     ke N/m, max_force N, k_t N/m, k_n N/m, eccentricity E and total_k N/m
//                     (seed 004's pair, the other kept), damping N s/m, mu_s, mu_d, finger_r m,
//                     pad_l m, tolerance m, kp V/m, ki V/(m s), kd V s/m, max_drive V,
//                     travel_mm MM (usable roller travel, 0 = all). A refused value changes
//                     nothing and is said as an error (`expect error 1`).
//                   also: curves exact|flatten; model spring|ellipsoid; rule centroid|least_displacement;
//                     snap_mm MM: grid snapping for the authoring tools, 0 = off;
//                     snap_tangent 0|1: G1 tangent continuation at open chain ends
//   answer X         (--experiment: the trial's answer, one of the protocol's; `answer -` ends a
//                     timed trial)   pause   resume   (`expect experiment_done N`,
//                     `expect experiment_total N`, `expect experiment_paused 0|1`)
//   recovery recover|discard|keep   (answers the first offer of an earlier session's unsaved work,
//                     recovery.hpp; `expect recovery_offers N` counts those waiting)
//   layout           (one line per part on screen on stderr: "script layout: x= y= w= h= overflow=0|1
//                     tiled=0|1 name=NAME", the rulers and every visible panel; panels.hpp laid_out)
//   undo  redo  fit  save PATH  open PATH  screenshot PATH  estop on|off  resize W H (px)
//   generate block|bumps|arc
//   wait SECONDS     frames N     wait_contact TIMEOUT_S     wait_state STATE TIMEOUT_S
//   idle SECONDS     (the editor draws on demand as it does interactively, redraw_policy.hpp, for
//                     that long; then "script idle: N frame(s) drawn in S s" on stderr and
//                     `expect idle_frames N [TOL]`)
//   check_layer      (the next frame is drawn twice, with the kept scene layer and fresh, and the
//                     pixels compared: `expect layer_mismatch 0`; `report` has scene_layer_updates)
//   device mouse|sim-cld|sim-wearable|usb:hapio|usb:falcon   device replay FILE   (switch, through the safety path)
//   rate HZ          (servo rate, 100..20000; restarts the servo safely)
//   record PATH      record stop      (every servo tick to a "contactlab recording v1" file)
//   devices          (the device menu on stderr: "script device option SPEC: available" or
//                     "...: unavailable: WHY"; the USB bus is scanned again)
//   report LABEL     (one line "script report LABEL: key=value ..." on stderr: device, rate, cursor,
//                     finger, depth, force, servo state, period statistics, and with sim-wearable
//                     platform_roll_rad, platform_press_mm, platform_tension_n; for tests to parse)
//   expect NAME VALUE [TOL]  (contact 0|1, segments N, contours N, any `set` parameter above (the
//                       value its field shows), ke_effective N/m (what the servo uses, within 1),
//                       state NAME, stopped 0|1, valid 0|1, force_above N, force_below N, undo_depth N, dirty 0|1, error 0|1: the last action's message was an error,
//                       device SPEC, device_state NAME, rate HZ, recording 0|1, force N,
//                       finger_x MM, finger_y MM, depth MM, l_d MM, roller_target MM,
//                       budget_used % and budget_threshold uJ (the passivity observer's budget, as
//                       the Haptics panel shows it);
//                       numbers equal within TOL, default 0)
//   quit
// Blank lines and lines starting with # are ignored. A failed expectation is reported with its
// line number and the run goes on; the editor exits 1 if any failed.
#pragma once

#include "engine/editor/editor_state.hpp"

#include <optional>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

namespace contactlab::editor {

struct ScriptError : std::runtime_error {
    using std::runtime_error::runtime_error;
};

class Script {
public:
    // Reads and checks every line (command name and argument count); throws ScriptError.
    static Script load(const std::string& path);
    static Script parse(const std::string& text, const std::string& origin = "script");

    // Runs commands until one has to wait for later frames (or the end). `now`: s, monotonic.
    void step(EditorState& s, double now);
    bool finished() const { return next_ >= lines_.size(); }
    int failures() const { return failures_; }
    // A screenshot the script asked for this frame (the editor takes it and writes the PNG).
    std::optional<std::string> take_screenshot_request();
    // A window size (px) the script asked for this frame.
    std::optional<std::pair<int, int>> take_resize_request();
    // Whether an `idle` is under way at `now`: the editor then draws on demand.
    bool idling(double now) const { return idle_until_ >= 0.0 && now < idle_until_; }
    // A `check_layer` asked for this frame (the editor compares and sets layer_mismatch).
    bool take_layer_check_request() { return std::exchange(layer_check_, false); }

private:
    struct Line {
        int number = 0;
        std::vector<std::string> words;
    };
    // One command; false when it must be retried next frame (a wait not yet over).
    bool run(EditorState& s, const Line& line, double now);
    void fail(const Line& line, const std::string& why);

    std::string origin_;
    std::vector<Line> lines_;
    std::size_t next_ = 0;
    int failures_ = 0;
    double wait_until_ = -1.0;
    long frames_left_ = -1;
    std::optional<std::string> screenshot_;
    std::optional<std::pair<int, int>> resize_;
    double idle_until_ = -1.0;
    long idle_frames_at_ = 0, idle_frames_ = -1;
    bool layer_check_ = false, layer_check_sent_ = false;
};

}  // namespace contactlab::editor
