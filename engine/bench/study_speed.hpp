// study_speed.hpp — how fast a simulated study runs: one simulated participant of a shipped
// protocol through `contactlab experiment run`'s own code (run_experiment, one job, no traces,
// files in a temporary folder), with the stages timed (engine/experiments/base/trial_profile.hpp).
// The figure is x real time per core: the results rows' time_s (what each trial's row measures:
// seed 002's slide, from its start to its end) over wall seconds, the goal's figure, beside the
// trials' whole virtual time over wall seconds; the stages say where the wall time went. `contactlab bench` runs two: seed 002 on the CLD rig, against the
// goal of 500x, and seed 003 on the wearable platform (its plant's equilibrium every 0.1 ms, the
// slowest protocol). `--quick` runs 10 trials per condition instead of seed 002's 135 (and no
// warm-up), and one presentation of each stimulus instead of seed 003's 4.
#pragma once

#include "engine/experiments/base/trial_profile.hpp"

#include <string>

namespace contactlab::bench {

inline constexpr double kStudySpeedGoal = 500.0;  // x real time per core (seed 002)

struct StudySpeed {
    std::string skipped = "not run";  // why it did not run (no protocol file, or it failed); empty when it ran
    std::string protocol;  // the protocol's name
    experiments::TrialProfile profile;
    // s: the results rows' time_s summed (what the protocol times of each trial: seed 002's slide).
    // The goal is read by this; a trial's virtual time also holds what comes before it (the reach
    // for the surface and 0.3 s of settling on it), simulated but not counted in the rows.
    double rows_time_s = 0.0;
    // x real time by the whole virtual time of the trials, and by the rows' time_s (the goal's).
    double x_real_time() const { return profile.wall > 0.0 ? profile.virtual_s / profile.wall : 0.0; }
    double x_real_time_by_rows() const { return profile.wall > 0.0 ? rows_time_s / profile.wall : 0.0; }
};

// `protocol_path`: the protocol file (the CLI passes the installed one); empty skips.
StudySpeed study_speed(const std::string& protocol_path, bool quick);

}  // namespace contactlab::bench
