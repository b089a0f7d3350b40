// trial_outcome.hpp — what a participant's trial gave: the answer, its grading, the movement's
// measures and what the device displayed. Every kind of participant fills it (the simulated person
// through the servo, sim_participant.hpp, or on the wearable platform, wearable_trial.hpp; the
// model observer, model_observer.hpp), and the run turns it into a results row (runs/).
#pragma once

#include "drivers/sim/wearable_tasks.hpp"
#include "drivers/tick_record.hpp"

#include <cmath>
#include <string>
#include <vector>

namespace contactlab::experiments {

struct TrialOutcome {
    std::string response;    // one of Protocol::answers; empty for timed tasks
    bool correct = false;
    bool valid = true;       // false when the servo faulted (the trial is presented again)
    double time_s = 0.0;     // seed 000: start line to finish line; others: the slide's duration
    bool failed = false;     // seed 000: contact broken, or the finish line not reached
    int contact_breaks = 0;  // contact lost after it was first made
    // Share of the timed part of the trial (the window time_s measures) spent in contact, 0..1;
    // NaN where nothing was timed against a contour (a model observer).
    double contact_fraction = NAN;
    bool touched = false;    // the finger contacted the stimulus at any tick of the trial
    int small_bumps = 0, large_bumps = 0;  // seed 002: the stimulus's bumps by size
    double peak_force = 0.0; // N
    // What the device displayed in the trial as performed, every 10th tick (100 Hz), for the
    // per-trial trace files.
    std::vector<drivers::TickRecord> shown;
    // On the wearable platform (Protocol::device "sim-wearable") instead: the platform's tilt,
    // press force and cable tensions at the link's 100 Hz (wearable_trial.hpp).
    std::vector<drivers::sim::CurvatureSample> platform;
};

}  // namespace contactlab::experiments
