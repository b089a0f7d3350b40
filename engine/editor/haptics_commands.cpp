// haptics_commands.cpp — device, rate and recording commands (see haptics_commands.hpp).
#include "engine/editor/haptics_commands.hpp"

#include "engine/editor/servo_view.hpp"

#include <algorithm>
#include <filesystem>
#include <cstdio>

namespace contactlab::editor {
namespace {

// Stops (zero force) and starts the host on `spec` at `rate` with the editor's scene, gains and
// cursor; the emergency stop, if engaged, stays engaged on the new servo.
bool restart(EditorState& s, const std::string& spec, double rate, const char* what) {
    if (!s.haptics) return false;
    const bool stopped = s.servo && s.servo->stopped();
    const bool was_recording = s.haptics->recording();
    const std::string rec = s.haptics->recording_path();
    const ServoParams params = servo_params_for(s.doc.last_valid(), s.roller, s.haptics->watchdog_timeout(), s.roller_travel);
    const std::string err = s.haptics->start(spec, rate, s.doc.last_valid(), params, s.pose, stopped);
    sync_haptics(s);
    s.history = PlotHistory(plot_capacity(s.haptics->rate()));
    char buf[160];
    std::snprintf(buf, sizeof buf, "%s: %s at %.0f Hz (force ramps in once small)%s%s", what, s.haptics->spec().c_str(),
                  s.haptics->rate(), was_recording ? "; recording ended: " : "", was_recording ? rec.c_str() : "");
    if (!err.empty()) s.say(err, true);
    else s.say(buf);
    return err.empty();
}

}  // namespace

std::size_t plot_capacity(double rate_hz) {
    return static_cast<std::size_t>(std::clamp(5.0 * rate_hz, 500.0, 25000.0));
}

void sync_haptics(EditorState& s) {
    if (!s.haptics) return;
    s.servo = s.haptics->servo();
    s.device = s.haptics->device();
    s.pose_input = s.haptics->pose_input();
}

bool cmd_set_device(EditorState& s, const std::string& spec) {
    if (!s.haptics) return false;
    return restart(s, spec, s.haptics->rate(), "device");
}

bool cmd_set_rate(EditorState& s, double hz) {
    if (!s.haptics) return false;
    return restart(s, s.haptics->spec(), hz, "servo rate");
}

bool cmd_record_start(EditorState& s, const std::string& path) {
    if (!s.haptics) return false;
    // Recording over the recording being replayed would destroy the take while it plays.
    if (const std::string& spec = s.haptics->spec(); spec.rfind("replay:", 0) == 0) {
        namespace fs = std::filesystem;
        std::error_code ec;
        const fs::path playing = fs::weakly_canonical(spec.substr(7), ec), target = fs::weakly_canonical(path, ec);
        if (playing == target) {
            s.say("refused: " + path + " is the file being replayed; record to another file", true);
            return false;
        }
    }
    const std::string err = s.haptics->start_recording(path);
    if (!err.empty()) {
        s.say(err, true);
        return false;
    }
    s.say("recording every servo tick to " + path);
    return true;
}

bool cmd_record_stop(EditorState& s) {
    if (!s.haptics || !s.haptics->recording()) {
        s.say("not recording", true);
        return false;
    }
    const std::string path = s.haptics->recording_path();
    const std::uint64_t dropped = s.haptics->recording_dropped();
    const drivers::RecordSummary sum = s.haptics->stop_recording();
    char buf[96];
    std::snprintf(buf, sizeof buf, " (%llu ticks, %llu dropped)", static_cast<unsigned long long>(sum.rows),
                  static_cast<unsigned long long>(dropped));
    s.say("recording written to " + path + buf, dropped > 0);
    return true;
}

}  // namespace contactlab::editor
