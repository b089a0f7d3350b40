// test_psychometric_fit.cpp — the maximum-likelihood fit recovers a known psychometric function
// and its bootstrap intervals cover the truth about as often as they claim.
#include "engine/experiments/protocol/psychometric.hpp"
#include "engine/experiments/analysis/psychometric_fit.hpp"
#include "engine/experiments/protocol/trial_plan.hpp"
#include "engine/experiments/base/random_stream.hpp"

#include <doctest/doctest.h>

#include <algorithm>
#include <cmath>
#include <vector>

using namespace contactlab::experiments;

namespace {

PsyData draw(PsyFunction f, const std::vector<double>& levels, int n, double t, double s, double guess, double lapse,
             std::uint64_t& rng) {
    PsyData d;
    for (double x : levels) {
        const double p = psy_p(f, x, t, s, guess, lapse);
        int k = 0;
        for (int j = 0; j < n; ++j) k += uniform01(rng) < p;
        d.x.push_back(x), d.n.push_back(n), d.k.push_back(k);
    }
    return d;
}

}  // namespace

TEST_CASE("psychometric functions: F is one half at the threshold and the inverse undoes p") {
    for (PsyFunction f : {PsyFunction::logistic, PsyFunction::weibull, PsyFunction::cumulative_normal}) {
        CHECK(psy_F(f, 2.0, 2.0, 0.4) == doctest::Approx(0.5).epsilon(1e-12));
        const double x = psy_inverse(f, 0.8, 2.0, f == PsyFunction::weibull ? 3.0 : 0.4, 0.5, 0.02);
        CHECK(psy_p(f, x, 2.0, f == PsyFunction::weibull ? 3.0 : 0.4, 0.5, 0.02) == doctest::Approx(0.8).epsilon(1e-9));
    }
    // The 70.7 % point of the brief's observer (2AFC, lapse 0.02): 2 + 0.4 ln(F / (1 - F)),
    // F = (0.7071 - 0.5) / 0.48.
    CHECK(psy_inverse(PsyFunction::logistic, std::sqrt(0.5), 2.0, 0.4, 0.5, 0.02) == doctest::Approx(1.8898).epsilon(1e-4));
}

TEST_CASE("psychometric fit: 40 logistic 2AFC data sets, the 95 % bootstrap interval covers the true threshold in at least 32") {
    // 7 levels x 40 trials around the threshold, as a method-of-constant-stimuli study would
    // place them. Coverage of a nominal 95 % interval over 40 data sets is Binomial(40, 0.95):
    // P(<= 31) < 0.001, so 32 is a bound an honest interval passes and a bad one (e.g. 80 %
    // real coverage: P(>= 32) = 0.59 at best) fails often.
    const double t = 2.0, s = 0.4, guess = 0.5, lapse = 0.02;
    const std::vector<double> levels = {1.0, 1.4, 1.8, 2.2, 2.6, 3.0, 3.4};
    std::uint64_t rng = 2026;
    int covered = 0;
    std::vector<double> errors, signed_errors, scale_errors;
    for (int i = 0; i < 40; ++i) {
        const PsyData d = draw(PsyFunction::logistic, levels, 40, t, s, guess, lapse, rng);
        PsyFitOptions o;
        o.bootstrap = 200;
        o.seed = static_cast<std::uint64_t>(i + 1);
        const PsyFit f = fit_psychometric(d, o);
        REQUIRE(f.ok);
        CHECK(f.threshold_ci_unbounded.empty());  // the bounds rule leaves constant-stimuli intervals alone
        CHECK(f.lapse >= 0.0);
        CHECK(f.lapse <= 0.06);
        CHECK(f.threshold_ci[0] <= f.threshold);
        CHECK(f.threshold <= f.threshold_ci[1]);
        covered += f.threshold_ci[0] <= t && t <= f.threshold_ci[1];
        errors.push_back(std::abs(f.threshold - t));
        signed_errors.push_back(f.threshold - t);
        scale_errors.push_back(std::abs(f.scale - s));
    }
    std::sort(errors.begin(), errors.end());
    std::sort(scale_errors.begin(), scale_errors.end());
    std::sort(signed_errors.begin(), signed_errors.end());
    const double bias = 0.5 * (signed_errors[19] + signed_errors[20]);
    const double median = 0.5 * (errors[19] + errors[20]);
    MESSAGE("coverage ", covered, "/40, median |threshold error| ", median, ", median signed error ", bias, ", median |scale error| ",
            0.5 * (scale_errors[19] + scale_errors[20]));
    CHECK(covered >= 32);
    // The threshold's standard error here is at least 0.128: the Fisher information about the
    // threshold alone, summed over the 7 levels x 40 trials, is 61 (1 / sqrt(61)); with the
    // scale and lapse free too it is larger. The median absolute error of an unbiased normal
    // estimate is 0.674 SE, 0.09 at 0.128: 0.16 allows the nuisance parameters' share and still
    // fails a fit off by a scale's worth. The median signed error is 0 for an unbiased fit, with
    // a standard error of about 1.25 SE / sqrt(40) = 0.03: 0.08 is over 2.5 of those.
    CHECK(median < 0.16);
    CHECK(std::abs(bias) < 0.08);
}

TEST_CASE("psychometric fit: Weibull and cumulative normal recover their thresholds from large samples") {
    std::uint64_t rng = 7;
    {
        const PsyData d = draw(PsyFunction::weibull, {0.5, 1.0, 1.5, 2.0, 2.5, 3.0, 4.0}, 400, 2.0, 3.0, 0.5, 0.0, rng);
        PsyFitOptions o;
        o.function = PsyFunction::weibull;
        o.bootstrap = 0;
        const PsyFit f = fit_psychometric_ml(d, o);
        REQUIRE(f.ok);
        CHECK(f.threshold == doctest::Approx(2.0).epsilon(0.05));
        CHECK(f.scale == doctest::Approx(3.0).epsilon(0.25));
    }
    {
        const PsyData d = draw(PsyFunction::cumulative_normal, {-2, -1, -0.5, 0, 0.5, 1, 2}, 400, 0.3, 0.6, 0.0, 0.0, rng);
        PsyFitOptions o;
        o.function = PsyFunction::cumulative_normal;
        o.guess = 0.0;
        o.bootstrap = 0;
        const PsyFit f = fit_psychometric_ml(d, o);
        REQUIRE(f.ok);
        CHECK(f.threshold == doctest::Approx(0.3).epsilon(0.1));  // within 0.03: sd/sqrt(n) over the levels is 0.02
        CHECK(f.scale == doctest::Approx(0.6).epsilon(0.15));
        // The deviance of a true model is about chi-square with levels - parameters = 4 df.
        CHECK(f.deviance < 20.0);
    }
}

TEST_CASE("psychometric fit: one stimulus level is undefined, with the reason") {
    PsyData d{{1.0}, {20}, {15}};
    const PsyFit f = fit_psychometric(d, {});
    CHECK_FALSE(f.ok);
    CHECK(f.undefined.find("two stimulus levels") != std::string::npos);
}
