// analysis.hpp — `contactlab experiment analyze`: a results table (results_table.hpp) to the
// figures the seeds report, as JSON (scenes/README.md, "Experiments: analysis" has the schema).
//
// Rows with valid = 0 or warmup = 1 are left out (a table without those columns: every row
// counts). Per condition (the `condition` column; "all" without one): n; with stimulus and
// response columns the confusion matrix (rows stimuli, columns responses), proportion correct
// (the `correct` column when there is one, else response = stimulus), IT_est (seed 002 eq. 6)
// and Cramer's phi, per stimulus too; with a `participant` column the same per participant and
// their means (seed 002 computes IT per participant, then averages: IT_est is biased upward for
// small n, so the pooled and the averaged figures differ); with `time_s`, the mean and sd of the
// successful trials' times and, with `failed`, the failure proportion (seed 000). Two conditions
// are compared by t tests: paired across participants when both have the same two or more
// participants, else Welch over trials.
#pragma once

#include "engine/experiments/results_table.hpp"

#include <nlohmann/json_fwd.hpp>

namespace contactlab::experiments {

struct AnalyzeOptions {
    double confidence = 0.95;  // of the t tests' intervals (seed 000 used 0.99)
};

nlohmann::json analyze_results(const ResultsTable& table, const AnalyzeOptions& options = {});

}  // namespace contactlab::experiments
