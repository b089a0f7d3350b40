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
// successful trials' times and, with `failed`, the failure proportion (seed 000). With
// `small_bumps` and `large_bumps` (seed 002): per count of small bumps the proportion correct and
// eq. 7's average error, and accuracy on small-only and large-only stimuli (Fig. 6).
//
// Two conditions are compared by t tests chosen by one stated rule (kPairingRule, written into
// each comparison's "test"): paired across the participants who have rows in both conditions,
// the others left out and named in "warnings"; Welch over trials only without a participant
// column or with fewer than two pairs, and then the comparison says so. A t test with no
// variance, or variance at round-off level, is undefined ("undefined": the reason), never a p
// value. A comparison of proportions (failures, answers correct) also gets, under "binary", the
// tests made for binary outcomes (binary_tests.hpp, kBinaryRule) when its t test is paired.
// Labels are bounded (a column of thousands of distinct stimuli is refused) and a label
// that reads as a number out of a double's range is refused with its file and line.
//
// Room engine/experiments/analysis/: what the results say: `experiment analyze` (here), statistics, binary-outcome tests, intervals,
// psychometric fits and thresholds, pooling results files, power. Includes runs/ and below.
// The rooms and their arrows: docs/ARCHITECTURE.md, "The experiments' rooms".
#pragma once

#include "engine/experiments/base/results_table.hpp"

#include <nlohmann/json_fwd.hpp>

namespace contactlab::experiments {

struct AnalyzeOptions {
    double confidence = 0.95;  // of the t tests' intervals (seed 000 used 0.99)
};

extern const char* const kPairingRule;

nlohmann::json analyze_results(const ResultsTable& table, const AnalyzeOptions& options = {});

}  // namespace contactlab::experiments
