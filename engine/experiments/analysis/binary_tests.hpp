// binary_tests.hpp — tests made for binary outcomes (a trial failed or not, was answered right or
// not), reported beside the seeds' paired t tests on per-participant proportions. The t test
// treats a proportion as a normal mean, so its interval can leave [-1, 1] (0.63 .. 1.09 in a
// report); these cannot:
//   - an exact paired permutation test: under "the condition makes no difference" each
//     participant's two labels are exchangeable, so each per-participant difference
//     d_i = p_a,i - p_b,i is as likely with either sign; p is the share of the 2^n sign
//     assignments whose |mean| is at least the observed one (all of them up to
//     kExactPermutationMax participants, else kMonteCarloDraws seeded draws, p = (1 + hits) /
//     (1 + draws), Phipson & Smyth 2010, never 0);
//   - a participant-level bootstrap percentile interval of the mean difference: participants
//     resampled with replacement (the trials within one are not independent of each other),
//     each resample's mean of d_i; every d_i lies in [-1, 1], so does every mean and the interval.
// Per participant the proportion is pooled over their trials in the condition (k / n).
#pragma once

#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

namespace contactlab::experiments {

struct BinaryPair {
    long k_a = 0, n_a = 0, k_b = 0, n_b = 0;  // one participant: successes of trials, per condition
};

constexpr std::size_t kExactPermutationMax = 20;   // 2^20 sign assignments: about a second at worst
constexpr int kMonteCarloDraws = 100000;          // beyond it; the p value's Monte-Carlo sd is below 0.0016
constexpr int kParticipantBootstrap = 4000;        // resamples of participants
constexpr std::size_t kMinBootstrapParticipants = 5;  // fewer: the percentile interval is not reported

struct BinaryComparison {
    std::size_t participants = 0;
    double mean_difference = 0.0;  // mean over participants of p_a,i - p_b,i
    double p = 1.0;                // two-sided, sign-flip permutation
    bool exact = true;             // all 2^n assignments (else Monte Carlo)
    long assignments = 0;          // enumerated or drawn
    double min_p = 0.0;            // the smallest p this test can give with these participants
    double confidence = 0.95;
    double ci_low = 0.0, ci_high = 0.0;
    std::string undefined;         // why there is no test at all ("" when there is one)
    std::string ci_undefined;      // why there is no interval ("" when there is one)
};

// Sign-flip permutation p value of the mean of `d` (exact up to kExactPermutationMax values).
double sign_flip_p(const std::vector<double>& d, std::uint64_t seed, bool& exact, long& assignments);

BinaryComparison compare_binary(const std::vector<BinaryPair>& pairs, double confidence = 0.95, std::uint64_t seed = 1);

extern const char* const kBinaryRule;

}  // namespace contactlab::experiments
