// power_analysis.cpp — resampled power of the paired comparison (power_analysis.hpp).
#include "engine/experiments/analysis/power_analysis.hpp"

#include "engine/experiments/base/results_table.hpp"
#include "engine/experiments/analysis/statistics.hpp"
#include "engine/experiments/base/random_stream.hpp"

#include <nlohmann/json.hpp>

#include <algorithm>
#include <cmath>

namespace contactlab::experiments {
namespace {

using json = nlohmann::json;

json num(double v) { return std::isfinite(v) ? json(v) : json(nullptr); }

// A participant's value of the measure in one condition's analysis: a number, or an object's
// "mean" (time_s); NaN when absent or null.
double value_of(const json& figures, const std::string& measure) {
    if (!figures.contains(measure)) return NAN;
    const json& v = figures[measure];
    if (v.is_number()) return v.get<double>();
    if (v.is_object() && v.contains("mean") && v["mean"].is_number()) return v["mean"].get<double>();
    return NAN;
}

// An index in [0, n) from the draw state (n is small: the modulo's bias, n / 2^64, is nil).
std::size_t draw(std::uint64_t& state, std::size_t n) {
    state = mix64(state);
    return static_cast<std::size_t>(state % n);
}

}  // namespace

std::vector<PowerPoint> resampled_power(const std::vector<double>& a, const std::vector<double>& b, const PowerOptions& o) {
    if (a.size() != b.size() || a.size() < 2) throw ExperimentError("power: need at least 2 participants with a value in both conditions");
    if (!(o.alpha > 0.0 && o.alpha < 1.0)) throw ExperimentError("power: alpha must lie in (0, 1)");
    if (o.resamples < 1) throw ExperimentError("power: resamples must be at least 1");
    std::vector<PowerPoint> out;
    std::vector<double> ga, gb;
    for (int n : o.sizes) {
        if (n < 2) throw ExperimentError("power: a paired t test needs groups of at least 2 participants, got " + std::to_string(n));
        PowerPoint pt;
        pt.participants = n;
        pt.resamples = o.resamples;
        // Each size its own stream, so adding a size leaves the others' figures as they were.
        std::uint64_t state = mix64(o.seed ^ mix64(0x706f776572ULL + static_cast<std::uint64_t>(n)));
        std::vector<double> ps;
        for (int r = 0; r < o.resamples; ++r) {
            ga.clear(), gb.clear();
            for (int i = 0; i < n; ++i) {
                const std::size_t k = draw(state, a.size());
                ga.push_back(a[k]);
                gb.push_back(b[k]);
            }
            const TTest t = paired_t_test(ga, gb);
            if (!t.valid) {
                ++pt.undefined;
                continue;
            }
            ps.push_back(t.p);
            if (t.p < o.alpha) ++pt.significant;
        }
        pt.power = static_cast<double>(pt.significant) / pt.resamples;
        pt.power_ci = wilson_interval(pt.significant, pt.resamples, 0.95);
        if (!ps.empty()) {
            std::sort(ps.begin(), ps.end());
            const std::size_t m = ps.size();
            pt.median_p = m % 2 ? ps[m / 2] : 0.5 * (ps[m / 2 - 1] + ps[m / 2]);
        } else {
            pt.median_p = NAN;
        }
        out.push_back(pt);
    }
    return out;
}

json power_analysis(const json& analysis, const PowerOptions& o) {
    const json& conditions = analysis.at("conditions");
    std::string a = o.condition_a, b = o.condition_b;
    if (a.empty() != b.empty()) throw ExperimentError("power: name both conditions or neither");
    if (a.empty()) {
        if (conditions.size() != 2) {
            std::string names;
            for (const auto& [k, v] : conditions.items()) names += (names.empty() ? "" : ", ") + k;
            throw ExperimentError("power: the results have " + std::to_string(conditions.size()) + " conditions (" + names +
                                  "); name the two to compare (--conditions A,B)");
        }
        a = conditions.begin().key();
        b = std::next(conditions.begin()).key();
    }
    for (const std::string& c : {a, b})
        if (!conditions.contains(c)) throw ExperimentError("power: no condition \"" + c + "\" in the results");
    if (!conditions[a].contains("participants") || !conditions[b].contains("participants"))
        throw ExperimentError("power: the results have no participant column");
    std::vector<double> va, vb;
    json left_out = json::array();
    std::size_t pool = 0;
    bool measure_seen = false;
    for (const auto& [p, fa] : conditions[a]["participants"].items()) {
        ++pool;
        const double x = value_of(fa, o.measure);
        const double y = conditions[b]["participants"].contains(p) ? value_of(conditions[b]["participants"][p], o.measure) : NAN;
        measure_seen = measure_seen || fa.contains(o.measure);
        if (std::isfinite(x) && std::isfinite(y)) {
            va.push_back(x);
            vb.push_back(y);
        } else {
            left_out.push_back({{"participant", p}, {"reason", "no value of " + o.measure + " in " + (std::isfinite(x) ? b : a)}});
        }
    }
    if (!measure_seen)
        throw ExperimentError("power: the results have no per-participant " + o.measure +
                              " (measures: it_est_bits, proportion_correct, cramers_phi, time_s, failure_proportion, as the task has them)");
    if (va.size() < 2) throw ExperimentError("power: fewer than 2 participants have " + o.measure + " in both conditions");
    std::vector<double> d(va.size());
    for (std::size_t i = 0; i < va.size(); ++i) d[i] = va[i] - vb[i];
    const Summary s = summarize(d);
    json points = json::array();
    for (const PowerPoint& pt : resampled_power(va, vb, o))
        points.push_back({{"participants", pt.participants},
                          {"power", pt.power},
                          {"power_ci", {pt.power_ci.low, pt.power_ci.high}},
                          {"significant", pt.significant},
                          {"undefined", pt.undefined},
                          {"median_p", num(pt.median_p)}});
    return {{"measure", o.measure},
            {"alpha", o.alpha},
            {"pool", va.size()},
            {"resamples", o.resamples},
            {"seed", o.seed},
            {"conditions", {a, b}},
            {"test", "paired t test, two-sided, on each participant's " + o.measure + " in " + a + " and " + b},
            {"sampling", "groups of n drawn with replacement from the pool's participants, " + std::to_string(o.resamples) +
                             " per n; power = share with p < alpha (undefined tests count as not significant); power_ci: "
                             "Wilson 95 % over the resamples (Monte Carlo error only)"},
            {"pool_effect", {{"mean_difference", num(s.mean)}, {"sd_difference", num(s.sd)}, {"dz", num(s.sd > 0.0 ? s.mean / s.sd : NAN)}}},
            {"pool_participants", pool},
            {"left_out", left_out},
            {"points", points}};
}

}  // namespace contactlab::experiments
