// statistics.hpp — the seeds' analyses as pure functions: confusion matrices, proportion correct,
// information transfer (seed 002 eq. 6), Cramer's phi (seed 004), the chi-square test of
// independence, and t tests with confidence intervals (seed 000: a t test with its 99 % interval;
// seed 002: paired t tests across participants). The t and chi-square distributions come from
// Boost.Math, not from hand-written series.
#pragma once

#include <cstddef>
#include <string>
#include <vector>

namespace contactlab::experiments {

// Stimulus x response counts: rows are stimuli, columns responses, each in sorted label order
// (labels that read as numbers sort numerically: "2" before "10").
struct Confusion {
    std::vector<std::string> stimuli, responses;
    std::vector<std::vector<long>> counts;  // counts[i][j]: stimulus i answered with response j
    long total() const;
};

// From paired lists (the same length).
Confusion make_confusion(const std::vector<std::string>& stimuli, const std::vector<std::string>& responses);

// Share of trials whose response label equals the stimulus label; NaN with no trials.
double proportion_correct(const Confusion& c);

// Seed 002 eq. 6, the maximum-likelihood estimate of information transfer (bits):
//   IT_est = sum_ij (n_ij / n) log2(n_ij n / (n_i n_j)),
// empty cells contribute nothing. It is biased upward for small n (seed 002 reports it per
// participant, 125 trials each, and averages).
double it_est_bits(const Confusion& c);

struct ChiSquare {
    double statistic = 0.0;  // Pearson's X^2
    double df = 0.0;         // (r - 1)(c - 1) over the rows and columns with any count
    double p = 1.0;          // upper tail
};
// Pearson's test of independence of stimulus and response (rows or columns with no count are
// dropped; fewer than two of either: X^2 = 0, p = 1).
ChiSquare chi_square(const Confusion& c);

// Cramer's phi = sqrt(X^2 / (n (min(r, c) - 1))), 0 (no dependence) to 1 (complete); seed 004
// Table I, [[41, 9], [3, 47]], gives 0.766.
double cramers_phi(const Confusion& c);

struct Summary {
    std::size_t n = 0;
    double mean = 0.0;
    double sd = 0.0;  // sample standard deviation (n - 1); 0 for n < 2
};
// Shifted by the first value before summing, so identical values give exactly that value and sd
// 0 (a plain sum of n copies of 3.401 divided by n is not 3.401, and the round-off then reads
// as variance).
Summary summarize(const std::vector<double>& x);

// Round-off tolerance for a spread of values computed from inputs of magnitude `magnitude`: 32
// units of double epsilon times the magnitude. Why 32: each input may carry a few ulps from its
// own computation (decimal parsing 0.5 ulp, a shifted mean about 2), each difference a_i - b_i
// of two inputs up to about 10 eps M with its own rounding, and a spread of two differences
// twice that: 20 eps M from round-off alone; 32 is the power of two above it.
double roundoff_tolerance(double magnitude);

struct TTest {
    bool paired = false;
    std::size_t n_a = 0, n_b = 0;
    double mean_difference = 0.0;  // mean(a) - mean(b) (paired: mean of a_i - b_i)
    double t = 0.0;
    double df = 0.0;               // Welch-Satterthwaite for two samples, n - 1 paired
    double p = 1.0;                // two-sided
    double confidence = 0.95;
    double ci_low = 0.0, ci_high = 0.0;  // for the mean difference
    bool valid = false;            // false when there are too few values or no variance
    // Why t is undefined when !valid ("the differences are all equal to within round-off ..."):
    // a t test on no variance has no p value, and one from round-off would be a made-up number.
    std::string undefined;
};
// Two independent samples, unequal variances (Welch). Undefined when both samples' spreads are
// within roundoff_tolerance of their magnitude.
TTest welch_t_test(const std::vector<double>& a, const std::vector<double>& b, double confidence = 0.95);
// Paired samples (a[i] with b[i], the same length). Undefined when the differences' spread is
// within roundoff_tolerance of the values' magnitude.
TTest paired_t_test(const std::vector<double>& a, const std::vector<double>& b, double confidence = 0.95);

}  // namespace contactlab::experiments
