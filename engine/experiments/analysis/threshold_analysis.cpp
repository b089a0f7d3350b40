// threshold_analysis.cpp — adaptive estimates and psychometric fits (threshold_analysis.hpp).
#include "engine/experiments/analysis/threshold_analysis.hpp"

#include <nlohmann/json.hpp>

#include <algorithm>
#include <cmath>
#include <map>

namespace contactlab::experiments {
namespace {

using nlohmann::json;

json num(double v) { return std::isfinite(v) ? json(v) : json(nullptr); }

double median(std::vector<double> v) {
    if (v.empty()) return NAN;
    std::sort(v.begin(), v.end());
    const std::size_t n = v.size();
    return n % 2 ? v[n / 2] : 0.5 * (v[n / 2 - 1] + v[n / 2]);
}

json fit_json(const PsyData& d, const PsyFitOptions& o) {
    const PsyFit f = fit_psychometric(d, o);
    json bins = json::array();
    for (std::size_t i = 0; i < d.x.size(); ++i) bins.push_back({{"x", d.x[i]}, {"n", d.n[i]}, {"k", d.k[i]}});
    json j = {{"function", to_string(o.function)}, {"guess", o.guess}, {"method", psy_method(o)}, {"bins", bins},
              {"trials", f.trials}, {"levels", f.levels}};
    if (!f.ok) {
        // No estimate: each value null with the one reason (kBoundsRule's "not identifiable").
        j["undefined"] = f.undefined;
        for (const char* key : {"threshold", "scale", "threshold_ci", "scale_ci"})
            j[key] = nullptr, j[std::string(key) + "_undefined"] = f.undefined;
        j["bounds_rule"] = kBoundsRule;
        return j;
    }
    // A value the data do not bound goes out as null beside its reason (kBoundsRule).
    auto value = [&](const char* key, double v, const std::string& why) {
        j[key] = why.empty() ? json(v) : json(nullptr);
        if (!why.empty()) j[std::string(key) + "_undefined"] = why;
    };
    auto interval = [&](const char* key, const double ci[2], const std::string& why) {
        if (o.bootstrap <= 0) return;
        j[key] = why.empty() ? json::array({ci[0], ci[1]}) : json(nullptr);
        if (!why.empty()) j[std::string(key) + "_undefined"] = why;
    };
    value("threshold", f.threshold, f.threshold_unbounded);
    value("scale", f.scale, f.scale_unbounded);
    j["lapse"] = f.lapse;
    j["lapse_at_bound"] = f.lapse_at_bound;
    j["deviance"] = f.deviance;
    j["log_likelihood"] = f.log_likelihood;
    j["bootstrap_converged"] = f.bootstrap;
    j["bootstrap_at_limit_share"] = f.at_limit_share;
    interval("threshold_ci", f.threshold_ci, f.threshold_ci_unbounded);
    interval("scale_ci", f.scale_ci, f.scale_ci_unbounded);
    j["bounds_rule"] = kBoundsRule;
    // The maximum of the likelihood, for the figure's curve and for readers who want it; a
    // number here is not an estimate unless "threshold" above is one too.
    j["ml"] = {{"threshold", num(f.threshold)}, {"scale", num(f.scale)}, {"lapse", num(f.lapse)}};
    j["convention"] = o.function == PsyFunction::weibull
                          ? "threshold: F = 0.5; F = 1 - exp(-ln2 (x / threshold)^scale), scale the shape beta"
                          : "threshold: F = 0.5; scale in stimulus units";
    return j;
}

// kConvergenceRule on one staircase track ({stimulus, correct, reversal} per analysed trial):
// {"converged": true|false|null, "convergence": why}.
json convergence(const json& track, const std::string& procedure) {
    if (procedure.rfind("staircase", 0) != 0)
        return {{"converged", nullptr}, {"convergence", "not judged: " + procedure + " has no reversals to judge by (its posterior's width would say)"}};
    std::vector<double> at_reversals;
    double step = NAN;
    for (std::size_t i = 0; i < track.size(); ++i) {
        const double x = track[i][0].get<double>();
        if (track[i][2].is_number() && track[i][2].get<double>() != 0.0) at_reversals.push_back(x);
        if (i > 0) {
            const double d = std::abs(x - track[i - 1][0].get<double>());
            if (d > 0.0) step = d;
        }
    }
    char buf[200];
    if (at_reversals.size() < static_cast<std::size_t>(kConvergenceReversals)) {
        std::snprintf(buf, sizeof buf, "not converged: %zu reversals, %d needed to judge", at_reversals.size(), kConvergenceReversals);
        return {{"converged", false}, {"convergence", buf}};
    }
    const auto last = at_reversals.end() - kConvergenceReversals;
    const auto [lo, hi] = std::minmax_element(last, at_reversals.end());
    const double spread = *hi - *lo;
    const bool ok = std::isfinite(step) && spread <= kConvergenceSteps * step;
    std::snprintf(buf, sizeof buf, "%s: the last %d reversals span %.4g, %s %g final steps of %.4g", ok ? "converged" : "not converged",
                  kConvergenceReversals, spread, ok ? "within" : "more than", kConvergenceSteps, step);
    return {{"converged", ok}, {"convergence", buf}, {"reversal_spread", spread}, {"final_step", num(step)}};
}

}  // namespace

const char* const kConvergenceRule =
    "a staircase track converged when it has at least 6 reversals and the stimuli at its last 6 reversals span at most 4 of "
    "its final steps: a converged 1-up-N-down track turns between levels a few steps apart, one still drifting spreads its "
    "reversals further; QUEST+ is not judged by reversals";

void add_threshold_analysis(json& result, const ResultsTable& t, const ThresholdOptions& o) {
    const auto cond = t.column("condition"), part = t.column("participant"), stim = t.column("stimulus"),
               correct = t.column("correct"), valid = t.column("valid"), warmup = t.column("warmup"),
               proc = t.column("procedure"), target = t.column("target_p"), reversal = t.column("reversal"),
               estimate = t.column("estimate");
    auto cond_of = [&](std::size_t i) { return cond ? t.rows[i][*cond] : std::string("all"); };
    auto part_of = [&](std::size_t i) { return part ? t.rows[i][*part] : std::string(); };
    auto kept = [&](std::size_t i) {
        return !(valid && t.number(i, *valid) == 0.0) && !(warmup && t.number(i, *warmup) != 0.0);
    };
    json& conditions = result["conditions"];
    // The stimulus's unit, for the figures' axes, when every row gives the same one.
    if (const auto unit = t.column("stimulus_unit"); unit && !t.rows.empty()) {
        const std::string& u = t.rows.front()[*unit];
        if (std::all_of(t.rows.begin(), t.rows.end(), [&](const auto& r) { return r[*unit] == u; }) && !u.empty())
            result["stimulus_unit"] = u;
    }

    if (proc && estimate && reversal) {
        // condition -> participant -> rows in file order
        std::map<std::string, std::map<std::string, std::vector<std::size_t>>> rows;
        for (std::size_t i = 0; i < t.rows.size(); ++i) rows[cond_of(i)][part_of(i)].push_back(i);
        for (const auto& [c, parts] : rows) {
            std::vector<double> estimates;
            json each = json::object();
            std::string procedure;
            double target_p = NAN;
            int converged = 0, judged = 0;
            for (const auto& [p, prow] : parts) {
                json a;
                int reversals = 0, trials = 0;
                json track = json::array();
                for (std::size_t i : prow) {
                    procedure = t.rows[i][*proc];
                    if (target && !t.rows[i][*target].empty()) target_p = t.number(i, *target);
                    if (!kept(i)) continue;
                    ++trials;
                    reversals += t.number(i, *reversal) != 0.0;
                    track.push_back({t.number(i, *stim), correct ? t.number(i, *correct) : NAN, t.number(i, *reversal)});
                }
                const std::size_t last = prow.back();
                const double e = t.rows[last][*estimate].empty() ? NAN : t.number(last, *estimate);
                a = {{"procedure", procedure}, {"target_p", num(target_p)}, {"estimate", num(e)}, {"reversals", reversals},
                     {"trials", trials}, {"track", track}};
                a.update(convergence(track, procedure));
                converged += a["converged"].is_boolean() && a["converged"].get<bool>();
                judged += a["converged"].is_boolean();
                if (std::isfinite(e)) estimates.push_back(e);
                if (part) conditions[c]["participants"][p]["adaptive"] = a;
                else conditions[c]["adaptive"] = a;
                each[p.empty() ? "all" : p] = num(e);
            }
            if (part) {
                json& a = conditions[c]["adaptive"];
                a["procedure"] = procedure;
                a["target_p"] = num(target_p);
                a["estimate"] = num(median(estimates));
                a["estimate_is"] = "the median of the participants' estimates";
                a["estimates"] = each;
                a["participants"] = estimates.size();
                a["converged"] = converged;
                a["judged"] = judged;
            }
            conditions[c]["adaptive"]["convergence_rule"] = kConvergenceRule;
        }
    }

    if (o.psychometric && stim && correct) {
        PsyFitOptions fo = *o.psychometric;
        // condition -> participant ("" pooled) -> stimulus value -> (n, k)
        std::map<std::string, std::map<std::string, std::map<double, std::pair<int, int>>>> bins;
        for (std::size_t i = 0; i < t.rows.size(); ++i) {
            if (!kept(i) || t.rows[i][*correct].empty()) continue;
            const double x = t.number(i, *stim);
            const int k = t.number(i, *correct) != 0.0;
            for (const std::string& p : {std::string(), part_of(i)}) {
                auto& b = bins[cond_of(i)][p][x];
                b.first += 1, b.second += k;
                if (!part) break;
            }
        }
        for (const auto& [c, parts] : bins)
            for (const auto& [p, levels] : parts) {
                PsyData d;
                for (const auto& [x, nk] : levels) d.x.push_back(x), d.n.push_back(nk.first), d.k.push_back(nk.second);
                const json f = fit_json(d, fo);
                if (p.empty()) conditions[c]["psychometric"] = f;
                else conditions[c]["participants"][p]["psychometric"] = f;
            }
        // Both thresholds at the same p: the staircase aims at its target p, the fit's threshold
        // is where F = 0.5 (p = guess + (1 - guess - lapse) / 2); read off the fitted function at
        // the target p, the two estimate the same point.
        for (auto& [c, cj] : conditions.items()) {
            if (!cj.contains("adaptive") || !cj.contains("psychometric")) continue;
            const json& f = cj["psychometric"];
            const json& ad = cj["adaptive"];
            json cmp = {{"staircase_target_p", ad["target_p"]}, {"adaptive_estimate", ad["estimate"]}};
            if (f.contains("threshold") && f["threshold"].is_number() && f["scale"].is_number()) {
                const double g = f["guess"].get<double>(), l = f["lapse"].get<double>();
                cmp["fit_threshold"] = f["threshold"];
                cmp["fit_threshold_p"] = g + (1.0 - g - l) / 2.0;
                const double tp = ad["target_p"].is_number() ? ad["target_p"].get<double>() : NAN;
                cmp["fit_at_target_p"] = num(psy_inverse(fo.function, tp, f["threshold"].get<double>(), f["scale"].get<double>(), g, l));
                if (!cmp["fit_at_target_p"].is_number())
                    cmp["fit_at_target_p_undefined"] = "the target p is outside the fitted function's range (guess .. 1 - lapse)";
            } else {
                cmp["fit_at_target_p"] = nullptr;
                cmp["fit_at_target_p_undefined"] = "the fit's threshold or scale is not bounded by these data";
            }
            cmp["why_they_differ"] =
                "the staircase estimate is the median over participants of each track's mean at its last reversals, aimed at its "
                "target p; the fit's threshold is where F = 0.5 of one function fitted to all trials pooled; compare the estimate "
                "with the fit read at the target p";
            cj["thresholds_compared"] = cmp;
        }
    }
}

}  // namespace contactlab::experiments
