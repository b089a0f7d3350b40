// editor.hpp — `contactlab edit`: the interactive editor's entry point.
#pragma once

#include <string>

namespace contactlab::editor {

struct EditorOptions {
    std::string scene_path;       // empty: a new, untitled scene
    int width = 1280, height = 720;  // px, initial window size
    long frames = 0;              // > 0: render this many frames, then exit 0
    std::string screenshot;       // with frames: PNG of the last frame, read back from the swapchain
    std::string script;           // --script FILE (script.hpp); exits when it ends
    double timeout = 0.0;         // s, > 0: give up (exit 1) if still running after this long
    bool software = false;        // force lavapipe
    bool validation = false;      // Vulkan validation layers; any message makes the exit code 1
    bool vsync = true;            // FIFO presentation; off: MAILBOX/IMMEDIATE (for frame timing)
    double rate = 1000.0;         // Hz, servo rate
    std::string device = "mouse"; // the device the servo starts on (haptics_host.hpp specs); one
                                  // that does not open leaves the mouse running and says why
    double autosave_interval = 30.0;  // s between recovery-file writes
    // --experiment PROTOCOL --participant ID [--seed N] [--results FILE]: live trials
    // (experiment_mode.hpp); results default to PROTOCOL-NAME-ID.csv in the working directory.
    std::string experiment, participant, results;
    unsigned long long experiment_seed = 1;
};

// Runs the editor; returns the process exit code. No display: prints the message naming xvfb-run
// and the headless subcommands, returns 2. A scene file that does not load opens an empty scene
// with the error shown in the window (with --frames or --script it throws SceneError: exit 2).
int run_editor(const EditorOptions& options);

}  // namespace contactlab::editor
