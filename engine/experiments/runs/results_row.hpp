// results_row.hpp — one trial as a results row, the same for the batch runner (experiment_run)
// and the editor's live session (live_session), so both write the same columns with the same
// units and grading (scenes/README.md, "Experiments: results").
#pragma once

#include "engine/experiments/protocol/protocol.hpp"
#include "engine/experiments/protocol/trial_plan.hpp"

#include <cmath>
#include <string>
#include <vector>

namespace contactlab::experiments {

struct TrialRecord {
    std::string participant;
    PlannedTrial trial;
    std::string response;        // "" for the timed task
    bool valid = true;
    bool failed = false;
    double time_s = 0.0;         // NaN: not measured (an empty cell)
    int contact_breaks = 0;
    double contact_fraction = NAN;  // share of the timed window in contact, 0..1; NaN: not measured (empty cell)
    double peak_force = 0.0;     // N
    bool touched = false;        // the finger contacted the stimulus during the trial
    std::string device;          // the device's name ("sim-cld"); "" when not known
    int small_bumps = 0, large_bumps = 0;  // seed 002: the stimulus's bumps by size
    // Adaptive procedures: whether this trial's answer made the staircase reverse, and the
    // procedure's estimate after it (NaN: none yet).
    bool reversal = false;
    double estimate = NAN;
};

// The results file's columns, in order: the common ones, the task's (seed 002 small_bumps and
// large_bumps, 003 motion, 004 e and k, edge sharpness reference_mm and comparison_interval),
// then, for an adaptive procedure, procedure, target_p, reversal and estimate.
const std::vector<std::string>& results_columns(const Protocol& p);

// The row's cells, as results_columns(p) names them.
std::vector<std::string> results_row(const Protocol& p, const TrialRecord& r);

}  // namespace contactlab::experiments
