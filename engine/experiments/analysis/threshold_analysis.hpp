// threshold_analysis.hpp — thresholds in `experiment analyze`: adds to the analysis JSON
// (analysis.hpp), per condition and per participant within it,
//   "adaptive": {"procedure", "target_p", "estimate", "reversals", "trials", "track"} from an
//               adaptive run's own columns (procedure, target_p, reversal, estimate): the
//               estimate is the one after the participant's last trial in the condition (the
//               mean of the last reversals for a staircase, the threshold at the posterior's mode for QUEST+);
//               per condition the participants' median and each estimate; per participant
//               "converged" (true, false, or null when not judged) and "convergence" (the
//               reason) by kConvergenceRule;
//   "psychometric": {"function", "threshold", "threshold_ci", "scale", "scale_ci", "lapse",
//               "guess", "deviance", "method", "bins"} when a function is asked for: the
//               maximum-likelihood fit of psychometric_fit.hpp to the analysed rows (warm-up and
//               invalid rows left out) binned by stimulus value, pooled over participants per
//               condition and per participant. `threshold` is where F = 0.5 (psychometric.hpp).
//               A value the data do not bound is null with "<key>_undefined" (kBoundsRule).
//   "thresholds_compared": with both, the staircase's target p, its estimate, and the fit read
//               at that p beside the fit's own threshold and the p it sits at.
#pragma once

#include "engine/experiments/analysis/psychometric_fit.hpp"
#include "engine/experiments/base/results_table.hpp"

#include <nlohmann/json_fwd.hpp>

#include <optional>

namespace contactlab::experiments {

// The rule that says whether an adaptive track converged (written into the JSON and report).
extern const char* const kConvergenceRule;
constexpr int kConvergenceReversals = 6;  // the last reversals judged
constexpr double kConvergenceSteps = 4.0; // their span allowed, in final steps

struct ThresholdOptions {
    std::optional<PsyFitOptions> psychometric;  // fit when set
};

void add_threshold_analysis(nlohmann::json& result, const ResultsTable& t, const ThresholdOptions& o);

}  // namespace contactlab::experiments
