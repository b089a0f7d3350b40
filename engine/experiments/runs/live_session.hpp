// live_session.hpp — an experiment run with a person at the device (`contactlab edit
// --experiment PROTOCOL --participant ID`): the trial order (trial_plan.hpp, from the seed and
// the participant's id), the current trial's stimulus scene, and the results file written row by
// row (each write atomic: the whole file to a temporary, then renamed), so a crash loses at most
// the trial in progress. Started again with the same protocol, participant, seed and file, it
// resumes after the last row it finds for that participant. An invalid trial (the servo
// faulted, or the finger never touched the stimulus: `touched` 0) is presented again at the end
// of its block, as in `experiment run`, when the protocol's repeat_invalid says so.
//
// An adaptive procedure (staircase, QUEST+) chooses each trial's stimulus from the answers so far
// (adaptive_plan.hpp), and a resumed session replays this participant's stored answers to rebuild
// it. A two-interval task (edge sharpness) shows its trial's two edges one after the other
// (next_interval()); the answer names the interval.
//
// The editor stays thin: it shows the prompt, publishes current_scene() to the servo with the
// contact element held (roller_held()) in force-only conditions, and calls answer().
#pragma once

#include "engine/experiments/procedures/adaptive_plan.hpp"
#include "engine/experiments/protocol/protocol.hpp"
#include "engine/experiments/protocol/trial_plan.hpp"
#include "drivers/finger_sweep.hpp"
#include "haptics/scene.hpp"

#include <cmath>
#include <cstdint>
#include <memory>
#include <optional>
#include <string>
#include <vector>

namespace contactlab::experiments {

struct LiveTrialResult {
    std::string response;     // one of the protocol's answers ("" for the timed task)
    double time_s = 0.0;      // s, from the trial's start to the answer
    int contact_breaks = 0;
    double peak_force = 0.0;  // N
    bool valid = true;        // false: the servo faulted during the trial
    // The finger contacted the stimulus during the trial; when the editor does not say, a
    // trial with a peak force above zero touched (the servo renders force only in contact).
    std::optional<bool> touched;
    std::string device;       // the device the trial was felt on ("" when not known)
    // Last, so the brace-initialised results written before it still mean what they meant.
    double contact_fraction = NAN;  // share of the trial's ticks in contact, 0..1; NaN: not known
};

class LiveSession {
public:
    // Throws ExperimentError for a results file it cannot read or that has other columns.
    LiveSession(Protocol protocol, std::string participant, std::uint64_t seed, std::string results_path);

    const Protocol& protocol() const { return protocol_; }
    const std::string& participant() const { return participant_; }
    const std::string& results_path() const { return results_path_; }
    bool finished() const { return plan_ ? plan_->done() : next_ >= queue_.size(); }
    std::size_t done() const { return plan_ ? adaptive_done_ : next_; }
    // The trials in all: with an adaptive procedure, the most it can take until it has finished
    // (then the trials it took).
    std::size_t total() const;
    bool adaptive() const { return plan_ != nullptr; }
    std::size_t resumed() const { return resumed_; }  // rows found in the file at start

    // The trial in progress (finished() must be false).
    const PlannedTrial& trial() const { return plan_ ? current_ : queue_[next_]; }
    // Two-interval tasks: which of the trial's intervals the scene is (1 or 2), of intervals().
    int interval() const { return interval_; }
    int intervals() const { return protocol_.task == Task::edge_sharpness ? 2 : 1; }
    // To the trial's next interval (its scene replaces this one); false on the last.
    bool next_interval();
    const Condition& condition() const;
    const Scene& scene() const { return scene_; }
    // Force-only condition: the contact element is held at the pad's centre.
    bool roller_held() const { return !condition().contact_location; }
    // Seed 003's trial on a display that moves no hand (the wearable platform): the finger held
    // still and the arc passing under it is the finger passing over the still arc, left to right
    // for motion A and right to left for B, from 2 cm before the arc to 2 cm after it at the
    // protocol's hand speed, as the simulated trial (drivers/finger_sweep.hpp). Empty for the
    // other tasks and when finished.
    std::optional<drivers::FingerSweep> sweep() const;
    // Number of the scene's build: changes with every trial (for "publish when it changed").
    std::uint64_t scene_version() const { return version_; }

    // Records the trial (one row, written at once) and moves to the next. An answer outside
    // the protocol's set, or before the last interval was felt, is refused (ExperimentError;
    // nothing written).
    void answer(const LiveTrialResult& r);

private:
    void build_scene();
    void write();
    // The current trial, invalid, is presented again at the end of its block.
    void queue_repeat();

    Protocol protocol_;
    std::string participant_, results_path_;
    std::vector<PlannedTrial> queue_;     // every block in order, repeats appended to their block's end
    std::vector<std::size_t> block_end_;  // index one past each block in queue_
    std::size_t next_ = 0, resumed_ = 0;
    std::vector<std::string> lines_;      // the file's lines, header first
    Scene scene_;
    int small_bumps_ = 0, large_bumps_ = 0;  // the current stimulus's (seed 002)
    std::uint64_t version_ = 0;
    int interval_ = 1;
    // Adaptive procedures: the plan, its trial in progress and the trials recorded.
    std::unique_ptr<AdaptivePlan> plan_;
    PlannedTrial current_;
    std::size_t adaptive_done_ = 0;
};

}  // namespace contactlab::experiments
