// psychometric.hpp — psychometric functions shared by the model observer (model_observer.hpp),
// QUEST+ (quest_plus.hpp) and the maximum-likelihood fit (psychometric_fit.hpp), so that the
// observer answers from exactly the function the fit and QUEST+ assume.
//
// p(correct | x) = guess + (1 - guess - lapse) F(x; threshold, scale)   (Wichmann & Hill 2001)
//
// Convention: `threshold` is the stimulus at which F = 0.5 for every function (for 2AFC with
// guess 0.5 and lapse 0 that is the 75 % correct point).
//   logistic           F = 1 / (1 + exp(-(x - threshold) / scale))          scale in stimulus units
//   cumulative-normal  F = Phi((x - threshold) / scale)                      scale = the sd
//   weibull            F = 1 - exp(-ln 2 (x / threshold)^scale), x > 0; 0 at x <= 0
//                      (threshold > 0; `scale` is the dimensionless shape beta: the usual
//                      1 - exp(-(x / alpha)^beta) with alpha = threshold / (ln 2)^(1/beta))
#pragma once

#include <string>

namespace contactlab::experiments {

enum class PsyFunction { logistic, weibull, cumulative_normal };

const char* to_string(PsyFunction f);
// "logistic", "weibull", "cumulative-normal"; false for anything else.
bool parse_psy_function(const std::string& name, PsyFunction& out);

double psy_F(PsyFunction f, double x, double threshold, double scale);
inline double psy_p(PsyFunction f, double x, double threshold, double scale, double guess, double lapse) {
    return guess + (1.0 - guess - lapse) * psy_F(f, x, threshold, scale);
}
// The stimulus at which p(correct) = p (guess < p < 1 - lapse); NaN outside.
double psy_inverse(PsyFunction f, double p, double threshold, double scale, double guess, double lapse);

}  // namespace contactlab::experiments
