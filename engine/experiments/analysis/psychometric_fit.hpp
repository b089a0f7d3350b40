// psychometric_fit.hpp — maximum-likelihood fit of a psychometric function (psychometric.hpp)
// to binomial data, with the lapse rate free within bounds (Wichmann & Hill 2001a: a fixed
// lapse of 0 biases threshold and slope when an observer lapses), and confidence intervals by
// parametric bootstrap, percentile method (Wichmann & Hill 2001b): data sets are drawn from the
// fitted function at the observed levels and trial counts, each refitted, and the interval is
// the (1 - c) / 2 and (1 + c) / 2 quantiles of the refitted thresholds and scales. Seeded, so
// the same data give the same interval.
//
// The optimiser is Nelder-Mead (written here, a few dozen lines) on transformed parameters:
// threshold free (log threshold for the Weibull, whose threshold is positive), log scale, and
// the lapse through a logistic squashed into [0, max_lapse], so the simplex never leaves the
// admissible region. It starts from a small grid of thresholds and scales and keeps the best.
#pragma once

#include "engine/experiments/protocol/psychometric.hpp"

#include <cstdint>
#include <string>
#include <vector>

namespace contactlab::experiments {

// Trials at each stimulus level: n presented, k correct.
struct PsyData {
    std::vector<double> x;
    std::vector<int> n, k;
};

struct PsyFitOptions {
    PsyFunction function = PsyFunction::logistic;
    double guess = 0.5;        // fixed: the chance rate (0.5 for two-alternative forced choice)
    double max_lapse = 0.06;   // the lapse is fitted in [0, max_lapse]
    int bootstrap = 1000;      // parametric bootstrap resamples; 0: no intervals
    double confidence = 0.95;
    std::uint64_t seed = 1;
};

struct PsyFit {
    bool ok = false;
    std::string undefined;  // why there is no fit (ok false)
    double threshold = 0.0, scale = 0.0, lapse = 0.0, guess = 0.0;
    double log_likelihood = 0.0;
    double deviance = 0.0;  // against the saturated model, 2 sum k ln(k / n p) + (n - k) ln(...)
    double threshold_ci[2] = {0.0, 0.0}, scale_ci[2] = {0.0, 0.0};
    int bootstrap = 0;      // resamples that converged and went into the intervals
    int trials = 0, levels = 0;
};

// One fit (no intervals): the maximum-likelihood estimate.
PsyFit fit_psychometric_ml(const PsyData& d, const PsyFitOptions& o);
// The fit with its bootstrap intervals (o.bootstrap resamples).
PsyFit fit_psychometric(const PsyData& d, const PsyFitOptions& o);

// "parametric bootstrap, percentile, N resamples, seed S": what the intervals are.
std::string psy_method(const PsyFitOptions& o);

}  // namespace contactlab::experiments
