// recovery.cpp — offers of other sessions' recovery files (recovery.hpp).
#include "engine/editor/recovery.hpp"

#include "engine/editor/scene_edit.hpp"
#include "haptics/scene_io.hpp"

#include <chrono>
#include <cstdio>
#include <ctime>
#include <filesystem>

namespace contactlab::editor {
namespace {

namespace fs = std::filesystem;

std::time_t to_time_t(fs::file_time_type t) {
    const auto sys = std::chrono::time_point_cast<std::chrono::system_clock::duration>(
        t - fs::file_time_type::clock::now() + std::chrono::system_clock::now());
    return std::chrono::system_clock::to_time_t(sys);
}

// "20261125-061503": the file's own time, so the name says when the work was done.
std::string stamp_of(const std::string& file) {
    std::error_code ec;
    const std::time_t t = to_time_t(fs::last_write_time(file, ec));
    std::tm tm{};
    localtime_r(&t, &tm);
    char buf[32];
    std::strftime(buf, sizeof buf, "%Y%m%d-%H%M%S", &tm);
    return buf;
}

// NAME.recovery[-N].json -> NAME.recovered-STAMP[-K].json, a name nothing else uses.
std::string kept_name(const std::string& file) {
    std::string base = file;
    if (const auto at = base.rfind(".recovery"); at != std::string::npos) base.erase(at);
    if (base.size() > 5 && base.compare(base.size() - 5, 5, ".json") == 0) base.erase(base.size() - 5);
    const std::string stem = base + ".recovered-" + stamp_of(file);
    std::string name = stem + ".json";
    for (int k = 2; fs::exists(name); ++k) name = stem + "-" + std::to_string(k) + ".json";
    return name;
}

}  // namespace

void offer_recovery(EditorState& s) {
    for (const std::string& f : Document::recovery_files_for(s.doc.path())) {
        if (f == s.doc.own_recovery()) continue;
        bool queued = false;
        for (const std::string& q : s.recovery_offers) queued |= q == f;
        if (!queued) s.recovery_offers.push_back(f);
    }
    if (!s.recovery_offers.empty())
        s.say("unsaved work from an earlier session: " + s.recovery_offers.front() + " (Recover, Discard or Keep both)",
              true);
}

std::string recovery_summary(const std::string& file) {
    std::error_code ec;
    const std::time_t t = to_time_t(fs::last_write_time(file, ec));
    std::tm tm{};
    localtime_r(&t, &tm);
    char when[64];
    std::strftime(when, sizeof when, "%Y-%m-%d %H:%M:%S", &tm);
    std::string what;
    try {
        const Scene sc = load_work_in_progress(file);
        char buf[96];
        std::snprintf(buf, sizeof buf, "%zu contour(s), %d segment(s)", sc.contours.size(), segment_count(sc));
        what = buf;
    } catch (const SceneError& e) {
        what = std::string("not a scene: ") + e.what();
    }
    return file + ", written " + when + ": " + what;
}

bool answer_recovery(EditorState& s, RecoveryAnswer answer) {
    if (s.recovery_offers.empty()) {
        s.say("no recovery file is waiting", true);
        return false;
    }
    const std::string file = s.recovery_offers.front();
    s.recovery_offers.erase(s.recovery_offers.begin());
    std::error_code ec;
    switch (answer) {
    case RecoveryAnswer::recover:
        try {
            s.doc.recover(file);
            s.selected.reset();
            s.hovered.reset();
            s.say("recovered " + file + (s.doc.valid() ? "" : " (its geometry does not validate yet)"));
        } catch (const SceneError& e) {
            s.recovery_offers.insert(s.recovery_offers.begin(), file);  // still there: answer again
            s.say(std::string("cannot recover: ") + e.what() + " (Discard or Keep both)", true);
            return false;
        }
        break;
    case RecoveryAnswer::discard:
        fs::remove(file, ec);
        if (ec) {
            s.say("cannot remove " + file + ": " + ec.message(), true);
            return false;
        }
        s.say("discarded " + file);
        break;
    case RecoveryAnswer::keep_both: {
        const std::string kept = kept_name(file);
        fs::rename(file, kept, ec);
        if (ec) {
            s.recovery_offers.insert(s.recovery_offers.begin(), file);
            s.say("cannot keep " + file + " as " + kept + ": " + ec.message(), true);
            return false;
        }
        s.say("kept the earlier work as " + kept + " (File > Open it when you want it)");
        break;
    }
    }
    return true;
}

}  // namespace contactlab::editor
