// psychometric.cpp — the psychometric functions (psychometric.hpp).
#include "engine/experiments/protocol/psychometric.hpp"

#include <cmath>

namespace contactlab::experiments {

const char* to_string(PsyFunction f) {
    switch (f) {
        case PsyFunction::logistic: return "logistic";
        case PsyFunction::weibull: return "weibull";
        case PsyFunction::cumulative_normal: return "cumulative-normal";
    }
    return "?";
}

bool parse_psy_function(const std::string& name, PsyFunction& out) {
    if (name == "logistic") out = PsyFunction::logistic;
    else if (name == "weibull") out = PsyFunction::weibull;
    else if (name == "cumulative-normal") out = PsyFunction::cumulative_normal;
    else return false;
    return true;
}

double psy_F(PsyFunction f, double x, double threshold, double scale) {
    switch (f) {
        case PsyFunction::logistic: return 1.0 / (1.0 + std::exp(-(x - threshold) / scale));
        case PsyFunction::cumulative_normal: return 0.5 * std::erfc(-(x - threshold) / (scale * std::sqrt(2.0)));
        case PsyFunction::weibull:
            if (x <= 0.0 || threshold <= 0.0) return 0.0;
            return 1.0 - std::exp(-std::log(2.0) * std::pow(x / threshold, scale));
    }
    return 0.0;
}

double psy_inverse(PsyFunction f, double p, double threshold, double scale, double guess, double lapse) {
    const double F = (p - guess) / (1.0 - guess - lapse);
    if (!(F > 0.0 && F < 1.0)) return NAN;
    switch (f) {
        case PsyFunction::logistic: return threshold + scale * std::log(F / (1.0 - F));
        case PsyFunction::cumulative_normal: {
            // Phi^-1 by bisection: no inverse erf in the standard library, and this is not hot.
            double lo = -40.0, hi = 40.0;
            for (int i = 0; i < 200; ++i) {
                const double mid = 0.5 * (lo + hi);
                (0.5 * std::erfc(-mid / std::sqrt(2.0)) < F ? lo : hi) = mid;
            }
            return threshold + scale * 0.5 * (lo + hi);
        }
        case PsyFunction::weibull: return threshold * std::pow(-std::log(1.0 - F) / std::log(2.0), 1.0 / scale);
    }
    return NAN;
}

}  // namespace contactlab::experiments
