// recovery.hpp — offering the work of sessions that ended without saving (a crash, a kill, a
// power cut) when the same scene, or an untitled one, is started or opened again.
//
// Every start (a named scene, a new file name, or untitled) and every File > Open / New lists the
// recovery files on disk for that scene (Document::recovery_files_for) and offers them one at a
// time, in the window (a modal: Recover / Discard / Keep both) and to scripts (`recovery ANSWER`).
// Nothing is written over a file before the user answers: this session's autosave claims a name
// of its own (document.hpp), so offered or not, another session's work stays on disk.
#pragma once

#include "engine/editor/editor_state.hpp"

#include <string>

namespace contactlab::editor {

enum class RecoveryAnswer {
    recover,    // its scene replaces the one open (undo goes back), and the file becomes ours
    discard,    // the file is deleted
    keep_both,  // the file is kept as a scene beside it (NAME.recovered-DATE.json); nothing opened
};

// Queues the recovery files for the document's path that are not this session's own.
void offer_recovery(EditorState& s);
// One line for the offer at the front: its file, when it was written, and what it holds.
std::string recovery_summary(const std::string& file);
// Answers the offer at the front; the outcome is said in the status line. False if none.
bool answer_recovery(EditorState& s, RecoveryAnswer answer);

}  // namespace contactlab::editor
