// experiment_mode.hpp — `contactlab edit --experiment PROTOCOL --participant ID`: live trials
// with a person at the device (issue 16). The editor stays thin: the session
// (engine/experiments/runs/live_session.hpp) holds the order and writes the results; this file puts
// the trial's stimulus on the servo (felt, never drawn: the canvas shows only the finger), holds
// the contact element at the pad's centre in force-only conditions, counts contact breaks, peak
// force and servo faults during the trial, and takes the answer from the Experiment panel's
// buttons, the keys 1..9 (the protocol's answers in order; Enter ends a timed trial), or a
// script's `answer X`. A two-interval trial (edge sharpness) shows its first edge, then its second
// after Next (N, or `key n`); the answer comes after the second. Pause (P, or `pause`) takes the
// stimulus away until Resume. An adaptive procedure's progress reads "n trials (at most N)".
// Seed 003 on a display that moves no hand (sim-wearable, a hapio model 2 board): each trial's
// arc passes under the held finger once when the trial starts (the device takes the finger from
// LiveSession::sweep() instead of the cursor), and again after N.
#pragma once

#include "drivers/tick_record.hpp"
#include "engine/experiments/runs/live_session.hpp"

#include <memory>
#include <string>

namespace contactlab::editor {

struct EditorState;

struct ExperimentState {
    std::unique_ptr<experiments::LiveSession> session;
    bool paused = false;
    // The trial in progress: when it began (s of editor time), what happened since.
    double trial_start = -1.0;
    bool touched = false, in_contact = false, faulted = false;
    // Seed 003 on the wearable platform: the trial's sweep is playing on the device (the finger
    // passing over the still arc, LiveSession::sweep()).
    bool sweeping = false;
    int contact_breaks = 0;
    long ticks = 0, contact_ticks = 0;  // servo ticks recorded in the trial, and those in contact
    double peak_force = 0.0;  // N
    // "spec serial" last written to the results' meta: the meta is read and rewritten only when
    // the device (or its serial) changes, not after every answer.
    std::string serial_recorded;
};

// A live experiment is on with trials left: the trial's values are fixed (Tuning shows them
// read-only, and parameter edits are refused).
bool experiment_running(const EditorState& s);

// The scene the servo should feel now: the trial's, or an empty one while paused or finished.
const Scene& experiment_servo_scene(const EditorState& s);
// A number that changes whenever experiment_servo_scene changes.
std::uint64_t experiment_scene_key(const EditorState& s);
// Starts the trial's clock the first time its scene reaches the servo.
void experiment_scene_published(EditorState& s, double now);
// Every servo tick record while a trial runs.
void experiment_on_record(EditorState& s, const drivers::TickRecord& r);

// The answer (or, for the timed task, "" to end the trial): one row written, the next trial
// ready. Says the outcome; false (with an error message) when refused.
bool cmd_experiment_answer(EditorState& s, const std::string& response, double now);
void cmd_experiment_pause(EditorState& s, bool paused);
// A two-interval trial: its next interval's stimulus on the servo. False (with a message) on the
// last interval or with no trial running.
bool cmd_experiment_next_interval(EditorState& s);
// Keys 1..9 answer, p pauses or resumes, enter ends a timed trial; true if it was one of them.
bool experiment_key(EditorState& s, const std::string& key, double now);

// The Experiment panel (ImGui): trial n of N with a progress bar, the prompt, the answers,
// pause and resume.
void experiment_window(EditorState& s, double now);

}  // namespace contactlab::editor
