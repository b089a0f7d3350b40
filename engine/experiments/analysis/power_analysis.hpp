// power_analysis.hpp — `contactlab experiment power`: how many participants a study needs.
//
// A pool of simulated participants runs the protocol once through the real servo (the results
// file of `experiment run`); `experiment analyze` gives each participant's value of a measure in
// each of two conditions. For each group size n, `resamples` groups of n participants are drawn
// from the pool with replacement (the pool stands for the population; with replacement so that a
// group may be larger than the pool and draws are independent), the protocol's comparison, the
// two-sided paired t test between the two conditions (statistics.hpp), is applied to each group,
// and the power is the share of groups where p < alpha. A group whose t test is undefined (no
// variance: every difference equal to within round-off) counts as not significant and is counted
// apart. The power's interval is Wilson's at 95 % over the resamples (the Monte Carlo error, not
// the pool's sampling error: a larger pool narrows that).
#pragma once

#include "engine/experiments/analysis/intervals.hpp"

#include <nlohmann/json_fwd.hpp>

#include <cstdint>
#include <string>
#include <vector>

namespace contactlab::experiments {

struct PowerOptions {
    // A per-participant figure of the analysis (analysis.hpp): it_est_bits, proportion_correct,
    // cramers_phi, failure_proportion, or time_s (its mean).
    std::string measure = "it_est_bits";
    std::vector<int> sizes;        // group sizes, each >= 2
    int resamples = 1000;          // groups drawn per size
    double alpha = 0.05;           // two-sided significance level
    std::uint64_t seed = 1;        // of the draws
    std::string condition_a, condition_b;  // empty: the analysis's two conditions, in its order
};

struct PowerPoint {
    int participants = 0;
    long resamples = 0, significant = 0;
    long undefined = 0;            // groups whose t test was undefined (counted not significant)
    double power = 0.0;            // significant / resamples
    Interval power_ci;             // Wilson, 95 %
    double median_p = 1.0;         // of the defined tests
};

// The power at each size from paired values: a[i] and b[i] are participant i's values in the
// two conditions (the same length, finite). Deterministic in options.seed.
std::vector<PowerPoint> resampled_power(const std::vector<double>& a, const std::vector<double>& b, const PowerOptions& o);

// From an analysis of the pool's results (analyze_results): picks the two conditions and each
// participant's value of the measure in both (a participant without one in either is left out
// and named), runs resampled_power, and returns the JSON `experiment power` writes:
//   {"measure", "alpha", "pool", "resamples", "seed", "conditions": [a, b], "test", "sampling",
//    "pool_effect": {"mean_difference", "sd_difference", "dz"}, "left_out": [...],
//    "points": [{"participants", "power", "power_ci", "significant", "undefined", "median_p"}]}
// Throws ExperimentError naming what is missing (a measure the analysis has no per-participant
// value of, conditions that are not two, fewer than 2 usable participants).
nlohmann::json power_analysis(const nlohmann::json& analysis, const PowerOptions& o);

}  // namespace contactlab::experiments
