// intervals.hpp — the intervals a report draws around its points: Wilson's score interval for a
// proportion (it stays inside [0, 1] and is not degenerate at 0 or n successes, unlike the normal
// approximation p +- z sqrt(p (1 - p) / n), which gave a failure interval of (0.55, 1.24)), and
// Student's t interval and the standard error for a mean. Quantiles from Boost.Math.
#pragma once

#include <cstddef>
#include <vector>

namespace contactlab::experiments {

struct Interval {
    double low = 0.0, high = 0.0;
};

// Wilson score interval for `successes` of `n` at the two-sided `confidence` (0.95, 0.99):
//   centre = (p + z^2 / 2n) / (1 + z^2 / n), half = z sqrt(p (1 - p) / n + z^2 / 4n^2) / (1 + z^2 / n).
// NaN bounds when n = 0.
Interval wilson_interval(long successes, long n, double confidence);

// mean +- t_{(1+c)/2, n-1} sd / sqrt(n); NaN bounds for fewer than two values.
Interval mean_interval(const std::vector<double>& x, double confidence);

// The q-quantile of v (0 <= q <= 1), linear between order statistics (type 7, R's default):
// the percentile intervals' ends. v must not be empty.
double quantile(std::vector<double> v, double q);

// sd / sqrt(n) (sample sd, n - 1); NaN for fewer than two values.
double standard_error(const std::vector<double>& x);

}  // namespace contactlab::experiments
