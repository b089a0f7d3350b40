// document.cpp — edits, undo/redo, validation, atomic save, autosave (see document.hpp).
#include "engine/editor/document.hpp"

#include "haptics/scene_io.hpp"

#include <cstdio>
#include <filesystem>

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
    try {
        validate_scene(scene_);
        problem_.clear();
        last_valid_ = scene_;
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
    const std::string old_recovery = recovery_path_for(path_);
    path_ = target;
    dirty_ = false;
    std::error_code ec;
    std::filesystem::remove(old_recovery, ec);
    discard_recovery();
    autosaved_revision_ = revision_;
}

std::string Document::recovery_path_for(const std::string& path) {
    if (path.empty()) return (std::filesystem::temp_directory_path() / "contactlab-untitled.recovery.json").string();
    return path + ".recovery.json";
}

std::string Document::autosave() {
    if (revision_ == autosaved_revision_ || !dirty_) return {};
    const std::string target = recovery_path_for(path_);
    try {
        // The recovery file holds the user's work even when it does not validate yet, so it is
        // written as plain JSON text (atomically: temporary file, then rename).
        const std::string text = scene_to_json_text(scene_);
        const std::string tmp = target + ".tmp";
        std::FILE* f = std::fopen(tmp.c_str(), "wb");
        if (!f) return "error: cannot write " + tmp;
        const bool ok = std::fwrite(text.data(), 1, text.size(), f) == text.size() && std::fflush(f) == 0;
        std::fclose(f);
        if (!ok) return "error: cannot write " + tmp;
        std::filesystem::rename(tmp, target);
    } catch (const std::exception& e) {
        return std::string("error: ") + e.what();
    }
    autosaved_revision_ = revision_;
    return target;
}

void Document::discard_recovery() const {
    std::error_code ec;
    std::filesystem::remove(recovery_path_for(path_), ec);
}

}  // namespace contactlab::editor
