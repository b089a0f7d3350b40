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
        j["undefined"] = f.undefined;
        return j;
    }
    j["threshold"] = f.threshold;
    j["scale"] = f.scale;
    j["lapse"] = f.lapse;
    j["deviance"] = f.deviance;
    j["log_likelihood"] = f.log_likelihood;
    j["bootstrap_converged"] = f.bootstrap;
    if (f.bootstrap >= 2) {
        j["threshold_ci"] = {f.threshold_ci[0], f.threshold_ci[1]};
        j["scale_ci"] = {f.scale_ci[0], f.scale_ci[1]};
    }
    j["convention"] = o.function == PsyFunction::weibull
                          ? "threshold: F = 0.5; F = 1 - exp(-ln2 (x / threshold)^scale), scale the shape beta"
                          : "threshold: F = 0.5; scale in stimulus units";
    return j;
}

}  // namespace

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
            }
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
    }
}

}  // namespace contactlab::experiments
