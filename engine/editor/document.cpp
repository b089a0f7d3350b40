// document.cpp — edits, undo/redo, validation, atomic save, autosave (see document.hpp).
#include "engine/editor/document.hpp"

#include "haptics/scene_io.hpp"

#include <algorithm>
#include <cerrno>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <tuple>

#include <unistd.h>

namespace contactlab::editor {

Document::Document() : Document(Scene{}) {}

Document::Document(Scene scene, std::string path) : scene_(std::move(scene)), path_(std::move(path)) {
    last_valid_ = Scene{};
    changed();
    dirty_ = false;
}

namespace {
std::uint64_t next_revision() {
    static std::uint64_t counter = 0;  // UI thread only: unique across documents (File > New)
    return ++counter;
}
}  // namespace

void Document::changed() {
    revision_ = next_revision();
    problem_point_.reset();
    try {
        validate_scene(scene_);
        problem_.clear();
        last_valid_ = scene_;
    } catch (const ContourCrossingError& e) {
        problem_ = e.what();
        problem_point_ = e.point;
    } catch (const SceneError& e) {
        problem_ = e.what();
    }
}

void Document::edit(Scene next, const std::string& label) {
    if (continuous_) end_continuous();
    undo_.push_back({std::move(scene_), label});
    redo_.clear();
    scene_ = std::move(next);
    dirty_ = true;
    changed();
}

void Document::begin_continuous(const std::string& label) {
    if (continuous_) end_continuous();
    undo_.push_back({scene_, label});
    continuous_ = true;
    continuous_changed_ = false;
}

void Document::update_continuous(Scene next) {
    if (!continuous_) begin_continuous("edit");
    if (!continuous_changed_) redo_.clear();
    scene_ = std::move(next);
    continuous_changed_ = true;
    dirty_ = true;
    changed();
}

void Document::end_continuous() {
    if (!continuous_) return;
    continuous_ = false;
    if (!continuous_changed_) undo_.pop_back();  // a click without a move records nothing
}

bool Document::undo() {
    if (continuous_) end_continuous();
    if (undo_.empty()) return false;
    redo_.push_back({std::move(scene_), undo_.back().label});
    scene_ = std::move(undo_.back().scene);
    undo_.pop_back();
    dirty_ = true;
    changed();
    return true;
}

bool Document::redo() {
    if (continuous_) end_continuous();
    if (redo_.empty()) return false;
    undo_.push_back({std::move(scene_), redo_.back().label});
    scene_ = std::move(redo_.back().scene);
    redo_.pop_back();
    dirty_ = true;
    changed();
    return true;
}

void Document::open(const std::string& path) {
    Scene s = load_scene_file(path);  // throws SceneError, leaving the document as it was
    if (continuous_) end_continuous();
    scene_ = std::move(s);
    path_ = path;
    undo_.clear();
    redo_.clear();
    changed();
    dirty_ = false;
    autosaved_revision_ = revision_;
}

void Document::save(const std::string& path) {
    const std::string target = path.empty() ? path_ : path;
    if (target.empty()) throw SceneError("no file name to save to (use Save As)");
    if (!problem_.empty()) throw SceneError("not saved: the scene is invalid: " + problem_);
    save_scene_file(scene_, target);
    path_ = target;
    dirty_ = false;
    discard_recovery();  // this session's only: other sessions' files wait to be offered
    autosaved_revision_ = revision_;
}

namespace {

namespace fs = std::filesystem;

// PATH.recovery.json for n = 1, PATH.recovery-N.json after it.
std::string recovery_name(const std::string& path, int n) {
    const std::string base = path.empty() ? (fs::temp_directory_path() / "contactlab-untitled").string() : path;
    return n == 1 ? base + ".recovery.json" : base + ".recovery-" + std::to_string(n) + ".json";
}

// Writes `text` to a new temporary file beside `near`, flushed; returns its name or "".
std::string write_temporary(const std::string& near, const std::string& text) {
    std::string tmp = near + ".XXXXXX";
    const int fd = ::mkstemp(tmp.data());
    if (fd < 0) return {};
    std::size_t done = 0;
    while (done < text.size()) {
        const ssize_t n = ::write(fd, text.data() + done, text.size() - done);
        if (n <= 0) break;
        done += static_cast<std::size_t>(n);
    }
    const bool ok = done == text.size() && ::fsync(fd) == 0;
    ::close(fd);
    if (!ok) {
        ::unlink(tmp.c_str());
        return {};
    }
    return tmp;
}

}  // namespace

std::string Document::recovery_path_for(const std::string& path) { return recovery_name(path, 1); }

std::vector<std::string> Document::recovery_files_for(const std::string& path) {
    // Names are claimed in order, but a discarded one leaves a gap: look a little past it.
    std::vector<std::tuple<fs::file_time_type, int, std::string>> found;  // time, then claim order
    for (int n = 1, misses = 0; misses < 16 && n < 10000; ++n) {
        const std::string f = recovery_name(path, n);
        std::error_code ec;
        const auto t = fs::last_write_time(f, ec);
        if (ec) {
            ++misses;
            continue;
        }
        misses = 0;
        found.emplace_back(t, n, f);
    }
    std::sort(found.begin(), found.end());
    std::vector<std::string> files;
    for (auto& [t, n, f] : found) files.push_back(f);
    return files;
}

std::string Document::autosave() {
    if (revision_ == autosaved_revision_ || !dirty_) return {};
    try {
        // The recovery file holds the user's work even when it does not validate yet, so it is
        // written as plain JSON text (atomically: temporary file, then rename or link).
        const std::string text = scene_to_json_text(scene_);
        const std::string near = own_recovery_.empty() ? recovery_name(path_, 1) : own_recovery_;
        const std::string tmp = write_temporary(near, text);
        if (tmp.empty()) return "error: cannot write beside " + near;
        if (!own_recovery_.empty()) {
            if (::rename(tmp.c_str(), own_recovery_.c_str()) != 0) {
                ::unlink(tmp.c_str());
                return "error: cannot write " + own_recovery_ + " (" + std::strerror(errno) + ")";
            }
        } else {
            // Claim the first free name: link() fails with EEXIST where another session's file
            // is, so that file is never replaced.
            for (int n = 1;; ++n) {
                const std::string candidate = recovery_name(path_, n);
                if (::link(tmp.c_str(), candidate.c_str()) == 0) {
                    own_recovery_ = candidate;
                    break;
                }
                if (errno != EEXIST || n >= 10000) {
                    const std::string why = std::strerror(errno);
                    ::unlink(tmp.c_str());
                    return "error: cannot write " + candidate + " (" + why + ")";
                }
            }
            ::unlink(tmp.c_str());
        }
    } catch (const std::exception& e) {
        return std::string("error: ") + e.what();
    }
    autosaved_revision_ = revision_;
    return own_recovery_;
}

void Document::discard_recovery() {
    if (own_recovery_.empty()) return;
    std::error_code ec;
    fs::remove(own_recovery_, ec);
    own_recovery_.clear();
}

void Document::recover(const std::string& file) {
    Scene recovered = load_work_in_progress(file);  // throws SceneError: nothing changed
    edit(std::move(recovered), "recover " + fs::path(file).filename().string());
    if (own_recovery_.empty()) {
        own_recovery_ = file;  // this session carries on writing it
        autosaved_revision_ = revision_;
        return;
    }
    // This session already has a file: the recovered work goes there first, then the other goes.
    if (autosave().rfind("error: ", 0) != 0) {
        std::error_code ec;
        fs::remove(file, ec);
    }
}

}  // namespace contactlab::editor
