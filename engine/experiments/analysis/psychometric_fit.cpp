// psychometric_fit.cpp — ML fit and parametric bootstrap (psychometric_fit.hpp).
#include "engine/experiments/analysis/psychometric_fit.hpp"

#include "engine/experiments/analysis/nelder_mead.hpp"
#include "engine/experiments/base/random_stream.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <limits>

namespace contactlab::experiments {
namespace {

using P3 = std::array<double, 3>;

// Nelder-Mead (nelder_mead.hpp) over the three transformed parameters.
template <class F>
P3 nelder_mead(F f, P3 start, P3 step, int max_evals, double& best) {
    const std::vector<double> u = experiments::nelder_mead([&](const std::vector<double>& x) { return f(P3{x[0], x[1], x[2]}); },
                                                           {start.begin(), start.end()}, {step.begin(), step.end()}, max_evals, best);
    return {u[0], u[1], u[2]};
}

struct Model {
    const PsyData& d;
    const PsyFitOptions& o;
    bool log_threshold() const { return o.function == PsyFunction::weibull; }
    void params(const P3& u, double& t, double& s, double& lapse) const {
        t = log_threshold() ? std::exp(u[0]) : u[0];
        s = std::exp(u[1]);
        lapse = o.max_lapse / (1.0 + std::exp(-u[2]));
    }
    double nll(const P3& u) const {
        double t, s, lapse;
        params(u, t, s, lapse);
        double sum = 0.0;
        for (std::size_t i = 0; i < d.x.size(); ++i) {
            const double p = std::clamp(psy_p(o.function, d.x[i], t, s, o.guess, lapse), 1e-12, 1.0 - 1e-12);
            sum -= d.k[i] * std::log(p) + (d.n[i] - d.k[i]) * std::log(1.0 - p);
        }
        return std::isfinite(sum) ? sum : std::numeric_limits<double>::max();
    }
};

double deviance(const PsyData& d, const PsyFitOptions& o, double t, double s, double lapse) {
    double dev = 0.0;
    for (std::size_t i = 0; i < d.x.size(); ++i) {
        const double p = std::clamp(psy_p(o.function, d.x[i], t, s, o.guess, lapse), 1e-12, 1.0 - 1e-12);
        const double n = d.n[i], k = d.k[i];
        if (k > 0) dev += 2.0 * k * std::log(k / (n * p));
        if (n - k > 0) dev += 2.0 * (n - k) * std::log((n - k) / (n * (1.0 - p)));
    }
    return dev;
}

PsyFit fit_from(const PsyData& d, const PsyFitOptions& o, const P3* hint) {
    PsyFit f;
    f.guess = o.guess;
    for (std::size_t i = 0; i < d.x.size(); ++i) f.trials += d.n[i];
    f.levels = static_cast<int>(d.x.size());
    if (d.x.size() < 2 || f.trials < 4) {
        f.undefined = "undefined, because a psychometric function needs at least two stimulus levels and four trials";
        return f;
    }
    const double lo = *std::min_element(d.x.begin(), d.x.end()), hi = *std::max_element(d.x.begin(), d.x.end());
    if (o.function == PsyFunction::weibull && lo <= 0.0 && hi <= 0.0) {
        f.undefined = "undefined, because the Weibull function needs positive stimuli";
        return f;
    }
    const double span = hi - lo;
    const Model m{d, o};
    auto tr = [&](double t) { return m.log_threshold() ? std::log(std::max(t, 1e-9)) : t; };
    double best = std::numeric_limits<double>::max();
    P3 u_best{};
    auto try_start = [&](const P3& u0) {
        double v = 0.0;
        const P3 step{m.log_threshold() ? 0.3 : 0.25 * span, 0.5, 1.0};
        const P3 u = nelder_mead([&](const P3& u) { return m.nll(u); }, u0, step, 600, v);
        if (v < best) best = v, u_best = u;
    };
    if (hint) {
        try_start(*hint);
    } else {
        // Starts over the data's range: the likelihood can have a poor local optimum when a
        // start puts the whole function beyond the data.
        const double lo_pos = o.function == PsyFunction::weibull ? std::max(lo, 1e-3 * hi) : lo;
        for (double a : {0.25, 0.5, 0.75})
            for (double sc : o.function == PsyFunction::weibull ? std::array<double, 2>{1.5, 4.0}
                                                               : std::array<double, 2>{span / 10.0, span / 3.0})
                try_start({tr(lo_pos + a * (hi - lo_pos)), std::log(std::max(sc, 1e-9)), -2.0});
    }
    // Polish: restart from the best (Nelder-Mead can stall on a ridge).
    try_start(u_best);
    double t, s, lapse;
    m.params(u_best, t, s, lapse);
    f.ok = std::isfinite(t) && std::isfinite(s);
    if (!f.ok) f.undefined = "undefined, because the likelihood has no finite maximum for these data";
    f.threshold = t, f.scale = s, f.lapse = lapse;
    f.log_likelihood = -best;
    f.deviance = deviance(d, o, t, s, lapse);
    return f;
}

double quantile(std::vector<double> v, double q) {
    std::sort(v.begin(), v.end());
    const double pos = q * static_cast<double>(v.size() - 1);
    const std::size_t i = static_cast<std::size_t>(pos);
    if (i + 1 >= v.size()) return v.back();
    return v[i] + (pos - static_cast<double>(i)) * (v[i + 1] - v[i]);
}

}  // namespace

PsyFit fit_psychometric_ml(const PsyData& d, const PsyFitOptions& o) { return fit_from(d, o, nullptr); }

PsyFit fit_psychometric(const PsyData& d, const PsyFitOptions& o) {
    PsyFit f = fit_from(d, o, nullptr);
    if (!f.ok || o.bootstrap <= 0) return f;
    std::uint64_t rng = mix64(o.seed ^ 0xB0075Dull);
    std::vector<double> ts, ss;
    const bool log_t = o.function == PsyFunction::weibull;
    const P3 hint{log_t ? std::log(f.threshold) : f.threshold, std::log(f.scale),
                  std::log(std::max(f.lapse, 1e-6) / std::max(o.max_lapse - f.lapse, 1e-6))};
    for (int b = 0; b < o.bootstrap; ++b) {
        PsyData r = d;
        for (std::size_t i = 0; i < d.x.size(); ++i) {
            const double p = psy_p(o.function, d.x[i], f.threshold, f.scale, o.guess, f.lapse);
            int k = 0;
            for (int j = 0; j < d.n[i]; ++j) k += uniform01(rng) < p;
            r.k[i] = k;
        }
        const PsyFit g = fit_from(r, o, &hint);
        if (g.ok) ts.push_back(g.threshold), ss.push_back(g.scale);
    }
    f.bootstrap = static_cast<int>(ts.size());
    if (ts.size() >= 2) {
        const double a = (1.0 - o.confidence) / 2.0;
        f.threshold_ci[0] = quantile(ts, a), f.threshold_ci[1] = quantile(ts, 1.0 - a);
        f.scale_ci[0] = quantile(ss, a), f.scale_ci[1] = quantile(ss, 1.0 - a);
    }
    return f;
}

std::string psy_method(const PsyFitOptions& o) {
    char buf[200];
    std::snprintf(buf, sizeof buf,
                  "maximum likelihood, lapse free in [0, %g], guess fixed at %g; %g %% intervals by parametric bootstrap, "
                  "percentile, %d resamples, seed %llu",
                  o.max_lapse, o.guess, o.confidence * 100.0, o.bootstrap, static_cast<unsigned long long>(o.seed));
    return buf;
}

}  // namespace contactlab::experiments
