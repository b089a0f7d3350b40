// grading.hpp — which answer to a trial is right, from the protocol and the planned trial alone:
// the results row's `correct` column (results_row.hpp), and the simulated participant and the model
// observer, who grade their own answers, all ask here.
#pragma once

#include "engine/experiments/protocol/protocol.hpp"
#include "engine/experiments/protocol/trial_plan.hpp"

#include <string>

namespace contactlab::experiments {

// Whether `response` is the right answer to the trial: the stimulus's label (002, 003), the
// template of its field angle (004, orientation_template), or (edge sharpness) the interval
// that held the reference, the sharper edge. False for the timed task.
bool graded_correct(const Protocol& p, const PlannedTrial& t, const std::string& response);
// Edge sharpness: the answer that names the interval holding the reference (the right one).
const std::string& sharper_answer(const Protocol& p, const PlannedTrial& t);

}  // namespace contactlab::experiments
