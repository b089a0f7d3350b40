// document.hpp — the scene being edited: every edit is a new Scene pushed through here, so undo
// and redo cover all of them; the scene is validated after each edit (scene_io's rules) and the
// problem, if any, is kept as text for the UI instead of being thrown at the user.
//
// Files: save() is scene_io's atomic write (temporary file beside the target, flush, rename);
// autosave() writes this session's recovery file the same way (recovery.hpp offers other
// sessions' files at start and on open).
#pragma once

#include "haptics/scene.hpp"

#include <cstdint>
#include <optional>
#include <string>
#include <vector>

namespace contactlab::editor {

class Document {
public:
    Document();  // a new scene: the default finger and force, no contours
    explicit Document(Scene scene, std::string path = {});

    const Scene& scene() const { return scene_; }
    const std::string& path() const { return path_; }
    bool dirty() const { return dirty_; }
    // New on every change (edit, undo, redo, open), unique across documents: cheap "did anything
    // change" for caches.
    std::uint64_t revision() const { return revision_; }

    // Validation of the current scene: empty when valid, else scene_io's message.
    const std::string& problem() const { return problem_; }
    bool valid() const { return problem_.empty(); }
    // Where closed contours cross (m) when that is the problem (scene_io's ContourCrossingError):
    // a shape may cross while it is being drawn, and the canvas marks the point.
    const std::optional<Vec2>& problem_point() const { return problem_point_; }
    // The last scene that passed validation (what the servo and the drawer use meanwhile).
    const Scene& last_valid() const { return last_valid_; }

    // An edit: `next` replaces the scene; the old one goes on the undo stack; redo is cleared.
    // `label` names it in the UI ("add line", "move vertex", "Ke").
    void edit(Scene next, const std::string& label);
    // Continuous edits (a drag): begin() records the undo point once, update() replaces the scene
    // without growing the stack, end() closes it (nothing is recorded if nothing changed).
    void begin_continuous(const std::string& label);
    void update_continuous(Scene next);
    void end_continuous();
    bool in_continuous() const { return continuous_; }

    bool can_undo() const { return !undo_.empty(); }
    bool can_redo() const { return !redo_.empty(); }
    bool undo();
    bool redo();
    std::string undo_label() const { return undo_.empty() ? std::string() : undo_.back().label; }
    std::string redo_label() const { return redo_.empty() ? std::string() : redo_.back().label; }
    std::size_t undo_depth() const { return undo_.size(); }

    // Replaces everything with the file's scene (throws SceneError; the document is unchanged).
    void open(const std::string& path);
    // Atomic save to `path` (or the current path when empty). Throws SceneError when the scene is
    // invalid or the file cannot be written; afterwards path() is `path` and dirty() is false.
    void save(const std::string& path = {});

    // Recovery files. Each session writes its own: the first free name of PATH.recovery.json,
    // PATH.recovery-2.json, PATH.recovery-3.json, ... (untitled: $TMPDIR/contactlab-untitled.
    // recovery.json and so on), claimed atomically on the first autosave (link(2) refuses a name
    // that exists), so a session never writes over another session's file, crashed or running.
    //
    // The first name for `path` (or for an unnamed scene).
    static std::string recovery_path_for(const std::string& path);
    // Every recovery file for `path` now on disk, oldest first.
    static std::vector<std::string> recovery_files_for(const std::string& path);
    // The file this session claimed ("" before its first autosave).
    const std::string& own_recovery() const { return own_recovery_; }
    // Writes the current scene to this session's recovery file if it changed since the last
    // autosave (whether valid or not is irrelevant: it is the user's work). Returns the file
    // written, or empty when nothing needed writing. Never throws; a failure is reported in the
    // returned text prefixed "error: ".
    std::string autosave();
    // Removes this session's recovery file (after a successful save); never another's.
    void discard_recovery();
    // Recovers another session's file: its scene replaces this one as an undoable edit (undo
    // goes back to what was open), the document is dirty, and the file becomes this session's
    // recovery file (or, if this session already has one, is written there and then removed).
    // Throws SceneError (nothing changed) if the file is not a scene at all.
    void recover(const std::string& file);

private:
    struct Entry {
        Scene scene;
        std::string label;
    };
    void changed();

    Scene scene_;
    Scene last_valid_;
    std::string path_;
    std::string problem_;
    std::optional<Vec2> problem_point_;
    std::vector<Entry> undo_, redo_;
    bool dirty_ = false;
    bool continuous_ = false;
    bool continuous_changed_ = false;
    std::uint64_t revision_ = 0;
    std::uint64_t autosaved_revision_ = 0;
    std::string own_recovery_;
};

}  // namespace contactlab::editor
