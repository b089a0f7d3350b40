// limits.cpp — the analysis's own limits, gathered (limits.hpp).
#include "engine/experiments/analysis/limits.hpp"

#include <nlohmann/json.hpp>

#include <algorithm>
#include <cstdio>
#include <string>

namespace contactlab::experiments {
namespace {

using nlohmann::json;

// The fit's null values and their reasons, for one condition or participant ("who").
void fit_limits(json& out, const std::string& who, const json& f) {
    if (f.contains("undefined")) {
        out.push_back(who + ": no psychometric fit: " + f["undefined"].get<std::string>());
        return;
    }
    for (const char* key : {"threshold", "scale", "threshold_ci", "scale_ci"}) {
        const std::string why = std::string(key) + "_undefined";
        if (f.contains(why)) out.push_back(who + ": " + key + " " + f[why].get<std::string>());
    }
    if (f.value("lapse_at_bound", false))
        out.push_back(who + ": the fitted lapse rate is at its maximum (--max-lapse): the data do not bound it, and the threshold and "
                            "scale are conditional on it");
}

}  // namespace

void add_limits(json& result) {
    json out = json::array();
    if (result.value("excluded", 0) > 0)
        out.push_back(std::to_string(result["excluded"].get<long>()) + " rows left out of every figure (warm-up or invalid trials)");
    for (const auto& [name, c] : result["conditions"].items()) {
        if (c.contains("psychometric")) fit_limits(out, "condition " + name + " (pooled)", c["psychometric"]);
        if (c.contains("participants")) {
            int unbounded = 0, fits = 0;
            for (const auto& [p, f] : c["participants"].items()) {
                if (!f.contains("psychometric")) continue;
                ++fits;
                json mine = json::array();
                fit_limits(mine, p, f["psychometric"]);
                unbounded += !mine.empty();
            }
            if (unbounded > 0)
                out.push_back("condition " + name + ": the per-participant fits of " + std::to_string(unbounded) + " of " +
                              std::to_string(fits) + " participants have values the data do not bound (null in the JSON, with the reason)");
        }
        if (c.contains("adaptive") && c["adaptive"].contains("judged")) {
            const json& ad = c["adaptive"];
            const int judged = ad["judged"].get<int>(), converged = ad["converged"].get<int>();
            const int all = ad["participants"].get<int>();
            if (judged < all)
                out.push_back("condition " + name + ": " + std::to_string(all - judged) + " tracks not judged for convergence (" +
                              ad.value("procedure", std::string()) + ")");
            if (converged < judged)
                out.push_back("condition " + name + ": " + std::to_string(judged - converged) + " of " + std::to_string(judged) +
                              " staircase tracks did not converge (rule: " + ad["convergence_rule"].get<std::string>() +
                              "); their estimates are where the track stopped, not where it settled");
        }
        if (c.contains("thresholds_compared") && c["thresholds_compared"].contains("fit_at_target_p_undefined"))
            out.push_back("condition " + name + ": the fit cannot be read at the staircase's target p: " +
                          c["thresholds_compared"]["fit_at_target_p_undefined"].get<std::string>());
    }
    for (const auto& n : result.value("not_compared", json::array()))
        out.push_back(n["measure"].get<std::string>() + ": not compared: " + n["reason"].get<std::string>());
    for (const auto& t : result.value("comparisons", json::array())) {
        const std::string what = t["measure"].get<std::string>() + " (" + t["a"].get<std::string>() + " - " + t["b"].get<std::string>() + ")";
        if (!t["valid"].get<bool>()) out.push_back(what + ": t test " + t["undefined"].get<std::string>());
        if (t["test"]["kind"] != "paired")
            out.push_back(what + ": Welch's t test over trials taken as independent, because " + t["test"]["because"].get<std::string>());
        for (const auto& l : t["test"]["left_out"]) {
            const json line = "participant " + l["participant"].get<std::string>() + " left out of the paired comparisons: " +
                              l["reason"].get<std::string>();
            if (std::find(out.begin(), out.end(), line) == out.end()) out.push_back(line);
        }
        if (!t.contains("binary")) continue;
        const json& b = t["binary"];
        if (b.contains("undefined")) {
            out.push_back(what + ": binary-outcome tests " + b["undefined"].get<std::string>());
            continue;
        }
        char buf[200];
        std::snprintf(buf, sizeof buf, ": with %d participants the permutation test cannot give p below %.3g",
                      b["participants"].get<int>(), b["permutation"]["smallest_possible_p"].get<double>());
        if (b["permutation"]["exact"].get<bool>()) out.push_back(what + buf);
        if (b.contains("interval_undefined"))
            out.push_back(what + ": participant bootstrap interval " + b["interval_undefined"].get<std::string>());
    }
    result["limits"] = out;
}

}  // namespace contactlab::experiments
