// nelder_mead.hpp — the downhill simplex (Nelder & Mead 1965, the standard coefficients 1, 2,
// 0.5, 0.5) minimising f over N parameters: the psychometric fits (psychometric_fit.cpp) and the
// simulated participant's calibration (calibration.hpp). No derivatives, so it works on
// objectives that are simulations. Unbounded: callers transform bounded parameters.
#pragma once

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <numeric>
#include <vector>

namespace contactlab::experiments {

// Starts from `start` with the simplex's other vertices `step` away along each axis; stops when
// the simplex's values agree to 1e-9 relative, or after `max_evals` evaluations of f. Returns the
// best vertex and its value in `best`.
template <class F>
std::vector<double> nelder_mead(F f, const std::vector<double>& start, const std::vector<double>& step, int max_evals, double& best) {
    const std::size_t n = start.size();
    std::vector<std::vector<double>> s(n + 1, start);
    std::vector<double> v(n + 1);
    for (std::size_t i = 0; i <= n; ++i) {
        if (i > 0) s[i][i - 1] += step[i - 1];
        v[i] = f(s[i]);
    }
    int evals = static_cast<int>(n + 1);
    std::vector<std::size_t> idx(n + 1);
    std::vector<double> c(n);
    auto along = [&](std::size_t hi, double t) {
        std::vector<double> p(n);
        for (std::size_t j = 0; j < n; ++j) p[j] = c[j] + t * (s[hi][j] - c[j]);
        return p;
    };
    while (evals < max_evals) {
        std::iota(idx.begin(), idx.end(), std::size_t{0});
        std::sort(idx.begin(), idx.end(), [&](std::size_t a, std::size_t b) { return v[a] < v[b]; });
        const std::size_t lo = idx[0], hi = idx[n], second = idx[n - 1];
        if (std::abs(v[hi] - v[lo]) < 1e-9 * (1.0 + std::abs(v[lo]))) break;
        std::fill(c.begin(), c.end(), 0.0);
        for (std::size_t k = 0; k < n; ++k)
            for (std::size_t j = 0; j < n; ++j) c[j] += s[idx[k]][j] / static_cast<double>(n);
        const std::vector<double> r = along(hi, -1.0);
        const double fr = f(r);
        ++evals;
        if (fr < v[lo]) {
            const std::vector<double> e = along(hi, -2.0);
            const double fe = f(e);
            ++evals;
            if (fe < fr) s[hi] = e, v[hi] = fe;
            else s[hi] = r, v[hi] = fr;
        } else if (fr < v[second]) {
            s[hi] = r, v[hi] = fr;
        } else {
            const std::vector<double> k = fr < v[hi] ? along(hi, -0.5) : along(hi, 0.5);
            const double fk = f(k);
            ++evals;
            if (fk < std::min(fr, v[hi])) {
                s[hi] = k, v[hi] = fk;
            } else {  // shrink toward the best
                for (std::size_t i = 0; i <= n; ++i)
                    if (i != lo) {
                        for (std::size_t j = 0; j < n; ++j) s[i][j] = s[lo][j] + 0.5 * (s[i][j] - s[lo][j]);
                        v[i] = f(s[i]);
                        ++evals;
                    }
            }
        }
    }
    const std::size_t b = static_cast<std::size_t>(std::min_element(v.begin(), v.end()) - v.begin());
    best = v[b];
    return s[b];
}

}  // namespace contactlab::experiments
