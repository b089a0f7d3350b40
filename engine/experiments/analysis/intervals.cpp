// intervals.cpp — Wilson, t and standard-error intervals (intervals.hpp).
#include "engine/experiments/analysis/intervals.hpp"

#include "engine/experiments/analysis/statistics.hpp"

#include <boost/math/distributions/normal.hpp>
#include <boost/math/distributions/students_t.hpp>

#include <algorithm>
#include <cmath>
#include <limits>

namespace contactlab::experiments {

namespace {
constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();
}

Interval wilson_interval(long successes, long n, double confidence) {
    if (n <= 0 || successes < 0 || successes > n) return {kNaN, kNaN};
    const double z = boost::math::quantile(boost::math::normal(), 0.5 + confidence / 2.0);
    const double nn = static_cast<double>(n), p = static_cast<double>(successes) / nn, z2 = z * z;
    const double denominator = 1.0 + z2 / nn;
    const double centre = (p + z2 / (2.0 * nn)) / denominator;
    const double half = z * std::sqrt(p * (1.0 - p) / nn + z2 / (4.0 * nn * nn)) / denominator;
    // Exactly 0 and 1 at the ends (the formula gives them to rounding).
    return {successes == 0 ? 0.0 : centre - half, successes == n ? 1.0 : centre + half};
}

// The sample's mean and sd come from summarize() (statistics.hpp), the analysis's own.
double standard_error(const Summary& s) {
    return s.n < 2 ? kNaN : s.sd / std::sqrt(static_cast<double>(s.n));
}

double standard_error(const std::vector<double>& x) { return standard_error(summarize(x)); }

Interval mean_interval(const std::vector<double>& x, double confidence) {
    const Summary s = summarize(x);
    const double se = standard_error(s);
    if (!std::isfinite(se)) return {kNaN, kNaN};
    const double t = boost::math::quantile(boost::math::students_t(static_cast<double>(s.n - 1)), 0.5 + confidence / 2.0);
    return {s.mean - t * se, s.mean + t * se};
}

double quantile(std::vector<double> v, double q) {
    std::sort(v.begin(), v.end());
    const double pos = q * static_cast<double>(v.size() - 1);
    const std::size_t i = static_cast<std::size_t>(pos);
    if (i + 1 >= v.size()) return v.back();
    return v[i] + (pos - static_cast<double>(i)) * (v[i + 1] - v[i]);
}

}  // namespace contactlab::experiments
