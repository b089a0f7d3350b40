// psychometric_fit.cpp — ML fit and parametric bootstrap (psychometric_fit.hpp).
#include "engine/experiments/analysis/psychometric_fit.hpp"

#include "engine/experiments/analysis/intervals.hpp"
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


// The stimuli in the function's own coordinate (x; ln x for the Weibull) and the limits of
// kBoundsRule (psychometric_fit.hpp) measured against their range.
struct Limits {
    bool log = false;
    double lo = 0.0, hi = 0.0, range = 0.0;  // in the function's coordinate
    double max_lapse = 0.0;
    std::string stimuli;  // "1 .. 5", for the reasons
    bool positive = false;  // every stimulus > 0 (not for the Weibull, whose ln x has no sign to keep)
    static Limits of(const PsyData& d, const PsyFitOptions& o) {
        Limits l;
        l.log = o.function == PsyFunction::weibull;
        l.max_lapse = o.max_lapse;
        double lo = INFINITY, hi = -INFINITY;
        for (double x : d.x)
            if (!l.log || x > 0.0) lo = std::min(lo, x), hi = std::max(hi, x);
        char buf[96];
        std::snprintf(buf, sizeof buf, "%.4g .. %.4g", lo, hi);
        l.stimuli = buf;
        l.lo = l.u(lo), l.hi = l.u(hi), l.range = l.hi - l.lo;
        // Stimuli all above zero are magnitudes (a radius difference, a force): a threshold below
        // zero is not one of them, however near the stimuli (1 participant's edge-sharpness
        // force+cld interval ran to -1.13 mm).
        l.positive = !l.log && lo > 0.0;
        return l;
    }
    double u(double x) const { return log ? std::log(x) : x; }
    double width(double scale) const { return log ? 1.0 / scale : scale; }
    // Each test: the reason when the value runs past its limit, else "".
    std::string threshold(double t) const {
        const double v = u(t);
        // Half the range: beyond it the threshold is where the assumed shape of the function,
        // extrapolated over more than half the tested span, puts it, not where the data do.
        if (std::isfinite(v) && v >= lo - 0.5 * range && v <= hi + 0.5 * range && range > 0.0) {
            if (positive && v < 0.0) return "it lies below zero, and every stimulus (" + stimuli + ") is a magnitude above it";
            return "";
        }
        return "it lies outside the stimuli (" + stimuli + ") by more than half their range";
    }
    std::string width_of(double s) const {
        const double w = width(s);
        if (!(w <= range)) return "the fitted function would rise less than a quarter of its span over all the stimuli (" + stimuli +
                                  "): the data cannot tell it from a flat line";
        if (!(w >= range / 1000.0)) return "the fitted function would be a step between two levels: the data cannot bound its slope";
        return "";
    }
    bool lapse_at_bound(double lapse) const { return lapse >= 0.999 * max_lapse && max_lapse > 0.0; }
    // The lapse is not among them: its bound is there by design (Wichmann & Hill 2001a), and
    // on constant-stimuli data with a true lapse of 0.02 (test_psychometric_fit.cpp) 20-45 % of
    // the resamples put it at 0.06 while their thresholds stay well inside the stimuli; the
    // bound is what keeps threshold and slope estimable there. A fit whose own lapse is at the
    // bound says so (lapse_at_bound) and the report names it as a limit.
    bool ran_to_limit(const PsyFit& g) const { return !threshold(g.threshold).empty() || !width_of(g.scale).empty(); }
};

constexpr double kMaxAtLimitShare = 0.20;   // of converged resamples (kBoundsRule)
constexpr double kMinConvergedShare = 0.90; // of resamples drawn

const std::string kNotBounded = "not bounded by these data: ";

// Every trial right, every trial wrong: the likelihood has no interior maximum (it keeps rising
// as the function moves past the stimuli), so no estimate is supported; nor with fewer levels
// than parameters.
std::string not_identifiable(const PsyData& d, const PsyFitOptions& o) {
    long n = 0, k = 0;
    for (std::size_t i = 0; i < d.x.size(); ++i) n += d.n[i], k += d.k[i];
    if (n > 0 && k == n) return "not identifiable: every trial was answered correctly, so the likelihood has no maximum (it rises as the function moves below the stimuli)";
    if (n > 0 && k == 0) return "not identifiable: every trial was answered wrongly, so the likelihood has no maximum (it rises as the function moves above the stimuli)";
    // Fewer levels than free parameters: curves through the levels' proportions form a family,
    // all with the same likelihood (two levels gave a threshold of 1.5 or of 166, the lapse
    // deciding which).
    const std::size_t free = o.max_lapse > 0.0 ? 3 : 2;
    if (d.x.size() < free)
        return "not identifiable: " + std::to_string(d.x.size()) + " stimulus levels for " + std::to_string(free) +
               " free parameters (threshold, scale" + (free == 3 ? ", lapse" : "") + "): curves through every level fit equally well";
    return "";
}

// The ML fit and kBoundsRule's verdicts on its estimates.
PsyFit fit_checked(const PsyData& d, const PsyFitOptions& o, Limits& lim) {
    PsyFit f = fit_from(d, o, nullptr);
    if (!f.ok) return f;
    if (const std::string why = not_identifiable(d, o); !why.empty()) {
        f.ok = false;
        f.undefined = why;
        return f;
    }
    lim = Limits::of(d, o);
    if (const std::string why = lim.threshold(f.threshold); !why.empty()) {
        char buf[64];
        std::snprintf(buf, sizeof buf, "the likelihood's maximum at %.4g ", f.threshold);
        f.threshold_unbounded = kNotBounded + buf + why;
        f.scale_unbounded = kNotBounded + "the threshold is not bounded, so neither is the slope";
    } else if (const std::string w = lim.width_of(f.scale); !w.empty()) {
        f.scale_unbounded = kNotBounded + w;
        // A function flat over the stimuli crosses F = 0.5 wherever the noise puts it.
        if (lim.width(f.scale) > lim.range)
            f.threshold_unbounded = kNotBounded + "the fitted function is flat over the stimuli, so where it crosses F = 0.5 is not located";
    }
    f.lapse_at_bound = lim.lapse_at_bound(f.lapse);
    return f;
}

}  // namespace

const char* const kBoundsRule =
    "a value is not bounded by the data when the likelihood has no single maximum (every trial right or every trial "
    "wrong, fewer stimulus levels than free parameters), when a threshold lies outside the stimuli by more than half "
    "their range (or below zero when every stimulus is above it: a magnitude), or a fitted function's width (scale; 1 / beta in ln x for the Weibull) exceeds that range (flat over the "
    "stimuli: then its threshold is not located either) or is below 1/1000 of it (a step); an interval is not bounded "
    "when an end runs past those limits, when more than 20 % of the bootstrap fits ran past them, when fewer than 90 % "
    "of the resamples converged, or when it misses the estimate or has no width; a lapse at its maximum is reported, not "
    "counted (its bound is by design)";

PsyFit fit_psychometric_ml(const PsyData& d, const PsyFitOptions& o) {
    Limits lim;
    return fit_checked(d, o, lim);
}

PsyFit fit_psychometric(const PsyData& d, const PsyFitOptions& o) {
    Limits lim;
    PsyFit f = fit_checked(d, o, lim);
    if (!f.ok || o.bootstrap <= 0) return f;
    if (!f.threshold_unbounded.empty()) {
        f.threshold_ci_unbounded = f.scale_ci_unbounded = kNotBounded + "the threshold itself is not";
        return f;
    }
    std::uint64_t rng = mix64(o.seed ^ 0xB0075Dull);
    std::vector<double> ts, ss;
    int at_limit = 0;
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
        // A resample's own flat likelihood is not refused here: its fit runs to a limit and is
        // counted as one, which is what it says about the data.
        const PsyFit g = fit_from(r, o, &hint);
        if (!g.ok) continue;
        ts.push_back(g.threshold), ss.push_back(g.scale);
        at_limit += lim.ran_to_limit(g);
    }
    f.bootstrap = static_cast<int>(ts.size());
    f.at_limit_share = ts.empty() ? 0.0 : static_cast<double>(at_limit) / static_cast<double>(ts.size());
    char share[160];
    std::snprintf(share, sizeof share, "%d of %d bootstrap fits ran to a limit (more than %.0f %% do)", at_limit, f.bootstrap,
                  100.0 * kMaxAtLimitShare);
    std::string whole;  // a reason that holds for both intervals
    if (f.bootstrap < 2 || f.bootstrap < kMinConvergedShare * o.bootstrap)
        whole = kNotBounded + std::to_string(f.bootstrap) + " of " + std::to_string(o.bootstrap) + " resamples converged";
    else if (f.at_limit_share > kMaxAtLimitShare)
        whole = kNotBounded + share;
    if (!whole.empty()) {
        f.threshold_ci_unbounded = f.scale_ci_unbounded = whole;
        return f;
    }
    const double a = (1.0 - o.confidence) / 2.0;
    f.threshold_ci[0] = quantile(ts, a), f.threshold_ci[1] = quantile(ts, 1.0 - a);
    f.scale_ci[0] = quantile(ss, a), f.scale_ci[1] = quantile(ss, 1.0 - a);
    // An interval's ends against the limits, then against its own estimate.
    auto judge = [&](const double ci[2], double estimate, bool is_threshold) -> std::string {
        for (int e = 0; e < 2; ++e) {
            const std::string why = is_threshold ? lim.threshold(ci[e]) : lim.width_of(ci[e]);
            if (!why.empty()) {
                char buf[80];
                std::snprintf(buf, sizeof buf, "its %s end (%.4g): ", e == 0 ? "lower" : "upper", ci[e]);
                return kNotBounded + buf + why;
            }
        }
        if (!(ci[0] < ci[1])) return kNotBounded + "the bootstrap fits do not vary (an interval of no width)";
        if (!(ci[0] <= estimate && estimate <= ci[1])) return kNotBounded + "the bootstrap interval does not contain the estimate";
        return "";
    };
    f.threshold_ci_unbounded = judge(f.threshold_ci, f.threshold, true);
    f.scale_ci_unbounded = f.scale_unbounded.empty() ? judge(f.scale_ci, f.scale, false) : kNotBounded + "the scale itself is not";
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
