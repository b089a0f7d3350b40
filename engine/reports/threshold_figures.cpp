// threshold_figures.cpp — thresholds in the report (threshold_figures.hpp).
#include "engine/reports/threshold_figures.hpp"

#include "engine/experiments/analysis/intervals.hpp"
#include "engine/experiments/protocol/psychometric.hpp"

#include <nlohmann/json.hpp>

#include <algorithm>
#include <cmath>
#include <cstdio>

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
            if (f.contains("threshold"))
                md << report_number(f["threshold"], "%.4g") << " | "
                   << (f.contains("threshold_ci") ? report_number(f["threshold_ci"][0], "%.4g") + " .. " + report_number(f["threshold_ci"][1], "%.4g") : "-")
                   << " | " << report_number(f["scale"], "%.3g") << " | " << report_number(f["lapse"], "%.3f") << " | " << report_number(f["deviance"], "%.3g") << " |\n";
            else
                md << f.value("undefined", std::string("undefined")) << " | - | - | - | - |\n";
        } else {
            md << "- | - | - | - | - | - |\n";
        }
    }
    for (const auto& [name, c] : a["conditions"].items())
        if (c.contains("psychometric") && c["psychometric"].contains("method")) {
            md << "\nFit method: " << c["psychometric"]["method"].get<std::string>() << ".\n";
            break;
        }
    // Per participant estimates.
    bool parts = false;
    for (const auto& [name, c] : a["conditions"].items()) parts |= c.contains("adaptive") && c["adaptive"].contains("estimates");
    if (parts) {
        md << "\n| condition | participant | estimate | reversals | trials |\n| --- | --- | ---: | ---: | ---: |\n";
        for (const auto& [name, c] : a["conditions"].items()) {
            if (!c.contains("participants")) continue;
            for (const auto& [p, f] : c["participants"].items())
                if (f.contains("adaptive"))
                    md << "| " << name << " | " << p << " | " << report_number(f["adaptive"]["estimate"], "%.4g") << " | "
                       << f["adaptive"]["reversals"] << " | " << f["adaptive"]["trials"] << " |\n";
        }
    }
}

std::vector<ReportFigure> threshold_figures(const json& a) {
    std::vector<ReportFigure> out;
    const std::string stimulus = a.contains("stimulus_unit") ? "stimulus (" + a["stimulus_unit"].get<std::string>() + ")" : "stimulus";
    int ci = 0;
    for (const auto& [name, c] : a["conditions"].items()) {
        ++ci;
        if (c.contains("psychometric") && c["psychometric"].contains("threshold")) {
            const json& f = c["psychometric"];
            experiments::PsyFunction fn = experiments::PsyFunction::logistic;
            experiments::parse_psy_function(f["function"].get<std::string>(), fn);
            Chart ch = report_chart("Psychometric fit: " + name + " (" + f["function"].get<std::string>() + ")", stimulus,
                                    "proportion correct");
            ch.y.min = 0.0, ch.y.max = 1.0;
            ChartSeries data = marker_series("data (bins)", 0);
            double lo = INFINITY, hi = -INFINITY;
            for (const auto& b : f["bins"]) {
                const double x = b["x"].get<double>();
                const long n = b["n"].get<long>(), k = b["k"].get<long>();
                const auto w = experiments::wilson_interval(k, n, 0.95);
                data.x.push_back(x);
                data.y.push_back(static_cast<double>(k) / static_cast<double>(n));
                data.y_low.push_back(w.low);
                data.y_high.push_back(w.high);
                data.labels.push_back("n=" + std::to_string(n));
                lo = std::min(lo, x), hi = std::max(hi, x);
            }
            ChartSeries curve;
            curve.name = "fit";
            curve.color = render::chart_color(1);
            curve.marker = render::Marker::none;
            const double t = f["threshold"].get<double>(), s = f["scale"].get<double>(), g = f["guess"].get<double>(),
                         l = f["lapse"].get<double>();
            for (int i = 0; i <= 200; ++i) {
                const double x = lo + (hi - lo) * i / 200.0;
                curve.x.push_back(x);
                curve.y.push_back(experiments::psy_p(fn, x, t, s, g, l));
            }
            ch.series.push_back(std::move(data));
            ch.series.push_back(std::move(curve));
            ch.references.push_back({"threshold " + report_number(f["threshold"], "%.3g"), true, t});
            std::string interval = "no interval";
            if (f.contains("threshold_ci")) {
                ch.references.push_back({"95 % interval", true, f["threshold_ci"][0].get<double>(), {150, 150, 150, 255}});
                ch.references.push_back({"", true, f["threshold_ci"][1].get<double>(), {150, 150, 150, 255}});
                interval = "95 % interval " + report_number(f["threshold_ci"][0], "%.3g") + " .. " + report_number(f["threshold_ci"][1], "%.3g");
            }
            out.push_back({"psychometric_" + slug(name) + ".png", ch,
                           "Each point: the share correct of the n analysed trials at one stimulus value (all participants), "
                           "with its 95 % Wilson interval; the line: the maximum-likelihood " + f["function"].get<std::string>() +
                               " fit; vertical lines: its threshold (F = 0.5) and the threshold's " + interval +
                               " (parametric bootstrap, percentile)."});
        }
        if (c.contains("participants")) {
            Chart ch = report_chart("Adaptive tracks: " + name, "trial (analysed, in order)", stimulus);
            int pi = 0;
            for (const auto& [p, f] : c["participants"].items()) {
                if (!f.contains("adaptive")) continue;
                ChartSeries s;
                s.name = p;
                s.color = render::chart_color(pi % 8);
                s.marker = render::Marker::none;
                s.line_width = 1.5f;
                ChartSeries rev = marker_series("", pi % 8);
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
                out.push_back({"track_" + slug(name) + ".png", ch,
                               "Each line: one participant's stimulus on each analysed trial of this condition, in order (" +
                                   std::to_string(pi) + " participants); markers: reversals; horizontal line: the median of the "
                                   "participants' final estimates."});
            }
        }
    }
    return out;
}

}  // namespace contactlab::reports
