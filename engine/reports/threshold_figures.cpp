// threshold_figures.cpp — thresholds in the report (threshold_figures.hpp).
#include "engine/reports/threshold_figures.hpp"

#include "engine/experiments/analysis/intervals.hpp"
#include "engine/experiments/protocol/psychometric.hpp"

#include <nlohmann/json.hpp>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <string>
#include <utility>
#include <vector>

namespace contactlab::reports {
namespace {

using nlohmann::json;
using render::Chart;
using render::ChartSeries;

// A file name from a condition's name: letters and digits kept, others '_'.
std::string slug(const std::string& s) {
    std::string out;
    for (char ch : s) out += std::isalnum(static_cast<unsigned char>(ch)) ? ch : '_';
    return out;
}

// The object's keys in natural order (sim2 before sim10): the legend reads as people count.
std::vector<std::string> natural_order(const json& object) {
    std::vector<std::string> keys;
    for (const auto& [k, v] : object.items()) keys.push_back(k);
    auto split = [](const std::string& k) {
        std::size_t i = k.size();
        while (i > 0 && std::isdigit(static_cast<unsigned char>(k[i - 1]))) --i;
        const std::string digits = k.substr(i);
        return std::pair{k.substr(0, i), digits.empty() || digits.size() > 9 ? -1L : std::stol(digits)};
    };
    std::stable_sort(keys.begin(), keys.end(), [&](const std::string& a, const std::string& b) {
        const auto [pa, na] = split(a);
        const auto [pb, nb] = split(b);
        return pa != pb ? pa < pb : na != nb ? na < nb : a < b;
    });
    return keys;
}

}  // namespace

namespace {

// A value, or "not bounded by these data (why)" when the analysis left it null with a reason.
std::string value_or_why(const json& f, const std::string& key, const char* format) {
    const std::string why = key + "_undefined";
    if (f.contains(key) && f[key].is_number()) return report_number(f[key], format);
    if (f.contains(key) && f[key].is_array())
        return report_number(f[key][0], format) + " .. " + report_number(f[key][1], format);
    if (f.contains(why)) {
        std::string w = f[why].get<std::string>();
        const std::string head = "not bounded by these data: ";
        return w.rfind(head, 0) == 0 ? "not bounded by these data (" + w.substr(head.size()) + ")" : w;
    }
    return "-";
}

}  // namespace

void threshold_section(std::ostringstream& md, const json& a) {
    bool any = false;
    for (const auto& [name, c] : a["conditions"].items()) any |= c.contains("adaptive") || c.contains("psychometric");
    if (!any) return;
    md << "\n## Thresholds\n\n"
       << "Adaptive: the procedure's estimate after each participant's last trial (a staircase: the mean stimulus at its last "
          "reversals; QUEST+: the threshold at the posterior's mode), and their median over participants. Fit: maximum likelihood, "
          "the threshold is where F = 0.5.\n\n"
       << "| condition | procedure | target p | median estimate | participants | fit | fitted threshold | 95 % interval | scale | lapse | deviance |\n"
       << "| --- | --- | ---: | ---: | ---: | --- | ---: | --- | ---: | ---: | ---: |\n";
    for (const auto& [name, c] : a["conditions"].items()) {
        md << "| " << name << " | ";
        if (c.contains("adaptive")) {
            const json& ad = c["adaptive"];
            md << ad.value("procedure", std::string("-")) << " | " << report_number(ad.value("target_p", json()), "%.3f") << " | "
               << report_number(ad.value("estimate", json()), "%.4g") << " | " << ad.value("participants", json(1)).dump() << " | ";
        } else {
            md << "- | - | - | - | ";
        }
        if (c.contains("psychometric")) {
            const json& f = c["psychometric"];
            md << f["function"].get<std::string>() << " | ";
            if (!f.contains("undefined"))
                md << value_or_why(f, "threshold", "%.4g") << " | " << value_or_why(f, "threshold_ci", "%.4g") << " | "
                   << value_or_why(f, "scale", "%.3g") << (f.contains("scale_ci_undefined") && f["scale"].is_number() ? " (interval " + value_or_why(f, "scale_ci", "%.3g") + ")" : "")
                   << " | " << report_number(f["lapse"], "%.3f") << (f.value("lapse_at_bound", false) ? " (at its maximum)" : "") << " | "
                   << report_number(f["deviance"], "%.3g") << " |\n";
            else
                md << f.value("undefined", std::string("undefined")) << " | - | - | - | - |\n";
        } else {
            md << "- | - | - | - | - | - |\n";
        }
    }
    for (const auto& [name, c] : a["conditions"].items())
        if (c.contains("psychometric") && c["psychometric"].contains("method")) {
            md << "\nFit method: " << c["psychometric"]["method"].get<std::string>() << ".\n";
            if (c["psychometric"].contains("bounds_rule"))
                md << "\nWhat the data bound: " << c["psychometric"]["bounds_rule"].get<std::string>() << ".\n";
            break;
        }
    // The staircase's estimate and the fit at the same p.
    bool compared = false;
    for (const auto& [name, c] : a["conditions"].items()) compared |= c.contains("thresholds_compared");
    if (compared) {
        md << "\nThe staircase aims at its target p; the fit's threshold sits where F = 0.5, a different p. Read at the same p "
              "(the staircase's target) the two estimate the same point:\n\n"
           << "| condition | staircase target p | adaptive estimate (median) | fit at the target p | fit's threshold | p at the fit's threshold |\n"
           << "| --- | ---: | ---: | ---: | ---: | ---: |\n";
        for (const auto& [name, c] : a["conditions"].items()) {
            if (!c.contains("thresholds_compared")) continue;
            const json& t = c["thresholds_compared"];
            md << "| " << name << " | " << report_number(t["staircase_target_p"], "%.3f") << " | " << report_number(t["adaptive_estimate"], "%.4g")
               << " | " << value_or_why(t, "fit_at_target_p", "%.4g") << " | " << report_number(t.value("fit_threshold", json()), "%.4g")
               << " | " << report_number(t.value("fit_threshold_p", json()), "%.3f") << " |\n";
        }
    }
    // Per participant estimates, with whether each track converged.
    bool parts = false;
    std::string rule;
    for (const auto& [name, c] : a["conditions"].items()) {
        parts |= c.contains("adaptive") && c["adaptive"].contains("estimates");
        if (c.contains("adaptive") && c["adaptive"].contains("convergence_rule")) rule = c["adaptive"]["convergence_rule"].get<std::string>();
    }
    if (parts) {
        md << "\nConvergence: " << rule << ".\n\n"
           << "| condition | participant | estimate | reversals | trials | converged |\n| --- | --- | ---: | ---: | ---: | --- |\n";
        for (const auto& [name, c] : a["conditions"].items()) {
            if (!c.contains("participants")) continue;
            for (const auto& [p, f] : c["participants"].items())
                if (f.contains("adaptive"))
                    md << "| " << name << " | " << p << " | " << report_number(f["adaptive"]["estimate"], "%.4g") << " | "
                       << f["adaptive"]["reversals"] << " | " << f["adaptive"]["trials"] << " | "
                       << f["adaptive"].value("convergence", std::string("-")) << " |\n";
        }
    }
}

std::vector<ReportFigure> threshold_figures(const json& a) {
    std::vector<ReportFigure> out;
    const std::string stimulus = a.contains("stimulus_unit") ? "stimulus (" + a["stimulus_unit"].get<std::string>() + ")" : "stimulus";
    int ci = 0;
    for (const auto& [name, c] : a["conditions"].items()) {
        ++ci;
        if (c.contains("psychometric") && c["psychometric"].contains("bins") && !c["psychometric"]["bins"].empty()) {
            const json& f = c["psychometric"];
            experiments::PsyFunction fn = experiments::PsyFunction::logistic;
            experiments::parse_psy_function(f["function"].get<std::string>(), fn);
            Chart ch = report_chart("Psychometric fit: " + name + " (" + f["function"].get<std::string>() + ")", stimulus,
                                    "proportion correct");
            ch.y.min = 0.0, ch.y.max = 1.0;
            ChartSeries data = marker_series("data (bins)", 0);
            double lo = INFINITY, hi = -INFINITY;
            std::string counts;
            for (const auto& b : f["bins"]) {
                const double x = b["x"].get<double>();
                const long n = b["n"].get<long>(), k = b["k"].get<long>();
                const auto w = experiments::wilson_interval(k, n, 0.95);
                data.x.push_back(x);
                data.y.push_back(static_cast<double>(k) / static_cast<double>(n));
                data.y_low.push_back(w.low);
                data.y_high.push_back(w.high);
                data.labels.push_back("n=" + std::to_string(n));
                counts += (counts.empty() ? "" : ", ") + report_number(b["x"], "%.4g") + ": " + std::to_string(k) + "/" + std::to_string(n);
                lo = std::min(lo, x), hi = std::max(hi, x);
            }
            ch.series.push_back(std::move(data));
            // A little room either side, so the end bins are not cut by the frame.
            ch.x.min = lo - 0.03 * (hi - lo), ch.x.max = hi + 0.03 * (hi - lo);
            // Only what the data bound is drawn (kBoundsRule): a threshold the data do not bound
            // gets no curve and no line, an interval they do not bound no lines; bounded values
            // lie within one stimulus range of the data, so they widen the axis at most that far.
            const bool threshold = f.contains("threshold") && f["threshold"].is_number();
            const std::string interval = f["threshold_ci"].is_array()
                                             ? "vertical lines: its threshold (F = 0.5) and the threshold's 95 % interval " +
                                                   value_or_why(f, "threshold_ci", "%.3g") + " (parametric bootstrap, percentile)"
                                             : "vertical line: its threshold (F = 0.5); its 95 % interval is " +
                                                   value_or_why(f, "threshold_ci", "%.3g") + ", so no line is drawn for it";
            if (threshold) {
                const double t = f["threshold"].get<double>(), s = f["ml"]["scale"].get<double>(), g = f["guess"].get<double>(),
                             l = f["lapse"].get<double>();
                double x0 = std::min(lo, t), x1 = std::max(hi, t);
                if (f["threshold_ci"].is_array())
                    x0 = std::min(x0, f["threshold_ci"][0].get<double>()), x1 = std::max(x1, f["threshold_ci"][1].get<double>());
                const double pad = 0.03 * (x1 - x0);
                ch.x.min = x0 - pad, ch.x.max = x1 + pad;
                ChartSeries curve;
                curve.name = "fit";
                curve.color = render::chart_color(1);
                curve.marker = render::Marker::none;
                for (int i = 0; i <= 200; ++i) {
                    const double x = x0 + (x1 - x0) * i / 200.0;
                    curve.x.push_back(x);
                    curve.y.push_back(experiments::psy_p(fn, x, t, s, g, l));
                }
                ch.series.push_back(std::move(curve));
                ch.references.push_back({"threshold " + report_number(f["threshold"], "%.3g"), true, t});
                if (f["threshold_ci"].is_array()) {
                    ch.references.push_back({"95 % interval", true, f["threshold_ci"][0].get<double>(), {150, 150, 150, 255}});
                    ch.references.push_back({"", true, f["threshold_ci"][1].get<double>(), {150, 150, 150, 255}});
                }
            }
            const std::string fit = threshold ? "the line: the maximum-likelihood " + f["function"].get<std::string>() + " fit; " + interval
                                              : "no fitted curve: the threshold is " + value_or_why(f, "threshold", "%.3g");
            out.push_back({"psychometric_" + slug(name) + ".png", ch,
                           "Each point: the share correct of the n analysed trials at one stimulus value (all participants), "
                           "with its 95 % Wilson interval; " + fit + ". Correct/trials per stimulus: " + counts + "."});
        }
        if (c.contains("participants")) {
            Chart ch = report_chart("Adaptive tracks: " + name, "trial (analysed, in order)", stimulus);
            int pi = 0;
            for (const std::string& p : natural_order(c["participants"])) {
                const nlohmann::json& f = c["participants"][p];
                if (!f.contains("adaptive")) continue;
                // The palette's 8 colours repeat: from the 9th participant on the line is dashed
                // and the reversal marker one shape further, so no two of 32 tracks look alike.
                ChartSeries s;
                s.name = p;
                s.color = render::chart_color(pi % 8);
                s.marker = render::Marker::none;
                s.line_width = 1.5f;
                s.dashed = (pi / 8) % 2 == 1;
                ChartSeries rev = marker_series("", pi % 8);
                rev.marker = marker_series("", pi + pi / 8).marker;
                int k = 0;
                for (const auto& row : f["adaptive"]["track"]) {
                    ++k;
                    s.x.push_back(k);
                    s.y.push_back(row[0].get<double>());
                    if (row[2].is_number() && row[2].get<double>() != 0.0) rev.x.push_back(k), rev.y.push_back(row[0].get<double>());
                }
                ++pi;
                ch.series.push_back(std::move(s));
                if (!rev.x.empty()) ch.series.push_back(std::move(rev));
            }
            if (pi > 0) {
                if (c.contains("adaptive") && c["adaptive"].contains("estimate") && c["adaptive"]["estimate"].is_number())
                    ch.references.push_back({"median estimate " + report_number(c["adaptive"]["estimate"], "%.3g"), false,
                                             c["adaptive"]["estimate"].get<double>()});
                std::string converged;
                if (c.contains("adaptive") && c["adaptive"].contains("judged"))
                    converged = " " + c["adaptive"]["converged"].dump() + " of " + c["adaptive"]["judged"].dump() +
                                " judged tracks converged by the rule under Thresholds.";
                out.push_back({"track_" + slug(name) + ".png", ch,
                               "Each line: one participant's stimulus on each analysed trial of this condition, in order (" +
                                   std::to_string(pi) + " participants); markers: reversals; horizontal line: the median of the "
                                   "participants' final estimates." + converged});
            }
        }
    }
    return out;
}

}  // namespace contactlab::reports
