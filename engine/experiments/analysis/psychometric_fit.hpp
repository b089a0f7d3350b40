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
//
// What the data can bound (kBoundsRule, written into the JSON and the report). The fit works
// in the function's own coordinate u (x; ln x for the Weibull) and measures the stimuli by their
// range R = u(max) - u(min), and a fitted function by its width w (the scale; 1 / beta for the
// Weibull, whose ln-x form is a Gumbel of scale 1 / beta). A fit "ran to a limit" when
//   - its threshold lies outside the stimuli by more than R / 2 (the function's assumed shape,
//     extrapolated over more than half the tested span, puts it there, not the data: a
//     staircase's 1.03 mm threshold with a lower end at -7,194 mm), or
//   - its width exceeds R (over the whole stimulus range the function then rises less than a
//     quarter of its span for the logistic, 0.38 for the normal: the data cannot tell it from a
//     flat line, so the slope is not bounded), or is below R / 1000 (a step between two
//     levels: complete separation, the likelihood keeps rising as the width shrinks).
//   A lapse within 0.1 % of --max-lapse is reported (lapse_at_bound) but not counted: the
//   bound is there by design, and on constant-stimuli data a third of the resamples reach it
//   while their thresholds stay well inside the stimuli.
// Then:
//   - the estimate itself is not identifiable when every trial is correct, every one wrong (the
//     likelihood has no interior maximum), or there are fewer levels than free parameters (3
//     with the lapse free: a family of curves fits equally well); the threshold is not bounded
//     when the ML threshold lies outside the stimuli by more than R / 2;
//   - an interval is not bounded when an end runs past those limits, when more than 20 % of the
//     converged resamples ran to a limit (a percentile interval over fits a bound stopped is the
//     bound's interval, not the data's: 20 % is eight times the 2.5 % tail a 95 % interval
//     cuts, so a few stray resamples in a well-bounded fit never trigger it), when fewer than
//     90 % of the resamples converged, or when it does not contain the estimate or has no width.
// Each such value is reported as null with the reason; bounded fits are unchanged.
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
    // Empty when bounded by the data; else "not bounded by these data: why" (kBoundsRule).
    std::string threshold_unbounded, scale_unbounded, threshold_ci_unbounded, scale_ci_unbounded;
    double at_limit_share = 0.0;  // share of converged resamples that ran to a limit
    bool lapse_at_bound = false;  // the ML lapse is at --max-lapse
};

extern const char* const kBoundsRule;

// One fit (no intervals): the maximum-likelihood estimate.
PsyFit fit_psychometric_ml(const PsyData& d, const PsyFitOptions& o);
// The fit with its bootstrap intervals (o.bootstrap resamples).
PsyFit fit_psychometric(const PsyData& d, const PsyFitOptions& o);

// "parametric bootstrap, percentile, N resamples, seed S": what the intervals are.
std::string psy_method(const PsyFitOptions& o);

}  // namespace contactlab::experiments
