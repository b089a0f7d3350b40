// experiment_report.cpp — the analysis as Markdown with plots (experiment_report.hpp).
#include "engine/reports/experiment_report.hpp"

#include "engine/reports/experiment_figures.hpp"
#include "engine/reports/threshold_figures.hpp"
#include "engine/experiments/analysis/analysis.hpp"
#include "engine/experiments/analysis/binary_tests.hpp"
#include "engine/experiments/analysis/intervals.hpp"
#include "engine/experiments/analysis/statistics.hpp"
#include "engine/render/chart_image.hpp"
#include "engine/render/matrix_chart.hpp"
#include "haptics/atomic_file.hpp"

#include <nlohmann/json.hpp>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <map>
#include <sstream>

namespace contactlab::reports {
namespace {

using nlohmann::json;
using render::Chart;
using render::ChartSeries;

// Where the results came from, per file: what its meta says (run_meta.hpp), or that it has none.
void provenance_section(std::ostringstream& md, const json& a) {
    if (!a.contains("provenance")) return;
    md << "\n## Provenance\n\n| file | protocol | sha256 | seed | participants | device | rate (Hz) | program | started | finished |\n"
          "| --- | --- | --- | ---: | --- | --- | ---: | --- | --- | --- |\n";
    for (const auto& [file, m] : a["provenance"].items()) {
        if (m.is_null()) {
            md << "| " << file << " | (no meta file) | | | | | | | | |\n";
            continue;
        }
        auto text = [&](const char* key) {
            const json v = m.value(key, json());
            return v.is_string() ? v.get<std::string>() : v.is_null() ? std::string("-") : v.dump();
        };
        std::string participants;
        const json who = m.value("participants", json::array());
        for (const auto& p : who) participants += (participants.empty() ? "" : " ") + p.get<std::string>();
        md << "| " << file << " | " << text("protocol_path") << " | `" << text("protocol_sha256").substr(0, 12) << "` | " << text("seed")
           << " | " << participants << " | " << text("device") << " | " << text("servo_rate_hz") << " | " << text("contactlab_version")
           << (m.contains("commit") ? " " + text("commit").substr(0, 12) : std::string()) << " | " << text("started_utc") << " | "
           << text("finished_utc") << " |\n";
    }
}

// What the analysis left out or could not estimate, first (limits.hpp gathers it).
void limits_section(std::ostringstream& md, const json& a) {
    md << "## Limits\n\n";
    const json limits = a.value("limits", json::array());
    if (limits.empty()) md << "None found: every row was analysed and every figure below was estimable from these data.\n\n";
    for (const auto& l : limits) md << "- " << l.get<std::string>() << "\n";
    if (!limits.empty()) md << "\n";
}

// A comparison's binary-outcome tests (binary_tests.hpp): "p = ..; interval .. (rule below)".
std::string binary_cell(const json& t) {
    if (!t.contains("binary")) return "-";
    const json& b = t["binary"];
    if (b.contains("undefined")) return b["undefined"].get<std::string>();
    std::string cell = "d = " + report_number(b["mean_difference"]) + ", permutation p = " + report_number(b["permutation"]["p"]) +
                       (b["permutation"]["exact"].get<bool>() ? " (exact, " : " (Monte Carlo, ") + b["permutation"]["assignments"].dump() +
                       "), ";
    if (b["interval"].is_array())
        cell += report_number(b["confidence"].get<double>() * 100.0, "%.0f") + " % bootstrap interval " + report_number(b["interval"][0]) +
                " .. " + report_number(b["interval"][1]);
    else cell += "interval " + b.value("interval_undefined", std::string("-"));
    return cell;
}

// Seed 002: eq. 7's average error and the accuracy per number of small bumps, and Fig. 6's
// small-only and large-only accuracy, per condition.
void bump_section(std::ostringstream& md, const json& a) {
    bool any = false;
    for (const auto& [name, c] : a["conditions"].items()) any |= c.contains("by_small_bumps");
    if (!any) return;
    md << "\n## By number of small bumps (seed 002 eq. 7)\n\n| condition | small bumps | n | proportion correct | average error |\n"
          "| --- | ---: | ---: | ---: | ---: |\n";
    for (const auto& [name, c] : a["conditions"].items()) {
        if (!c.contains("by_small_bumps")) continue;
        for (const auto& [k, f] : c["by_small_bumps"].items())
            md << "| " << name << " | " << k << " | " << f["n"] << " | " << report_number(f["proportion_correct"]) << " | "
               << report_number(f["average_error"]) << " |\n";
    }
    md << "\n## Small bumps only, large bumps only (seed 002 Fig. 6)\n\n| condition | small only: n | correct | large only: n | correct |\n"
          "| --- | ---: | ---: | ---: | ---: |\n";
    for (const auto& [name, c] : a["conditions"].items())
        if (c.contains("small_only"))
            md << "| " << name << " | " << c["small_only"]["n"] << " | " << report_number(c["small_only"]["proportion_correct"]) << " | "
               << c["large_only"]["n"] << " | " << report_number(c["large_only"]["proportion_correct"]) << " |\n";
}

// Any other protocol: proportion correct per stimulus, one marker series per condition on a
// categorical axis (the stimuli as the analysis labels them), 95 % Wilson intervals, n per point.
Chart per_stimulus_chart(const json& analysis) {
    Chart c = report_chart("Proportion correct per stimulus", "stimulus", "proportion correct");
    c.y.min = 0.0;
    c.y.max = 1.0;
    std::vector<std::string> stimuli;
    for (const auto& [name, cond] : analysis["conditions"].items())
        if (cond.contains("per_stimulus"))
            for (const auto& [stim, f] : cond["per_stimulus"].items())
                if (std::find(stimuli.begin(), stimuli.end(), stim) == stimuli.end()) stimuli.push_back(stim);
    c.x.categories = stimuli;
    int colour = 0;
    const int count = static_cast<int>(analysis["conditions"].size());
    for (const auto& [name, cond] : analysis["conditions"].items()) {
        ChartSeries s = marker_series(name, colour);
        const double offset = dodge(colour, count);
        ++colour;
        if (!cond.contains("per_stimulus")) continue;
        for (const auto& [stim, f] : cond["per_stimulus"].items()) {
            if (!f.contains("proportion_correct") || !f["proportion_correct"].is_number() || !f.contains("n")) continue;
            const long n = f["n"].get<long>();
            const double p = f["proportion_correct"].get<double>();
            const auto w = experiments::wilson_interval(std::lround(p * static_cast<double>(n)), n, 0.95);
            const auto at = std::find(stimuli.begin(), stimuli.end(), stim) - stimuli.begin();
            s.x.push_back(static_cast<double>(at) + offset);
            s.y.push_back(p);
            s.y_low.push_back(w.low);
            s.y_high.push_back(w.high);
            s.labels.push_back("n=" + std::to_string(n));
        }
        if (!s.x.empty()) c.series.push_back(std::move(s));
    }
    return c;
}

}  // namespace

std::string write_experiment_report(const experiments::ResultsTable& table, const json& a, const std::string& dir) {
    namespace fs = std::filesystem;
    fs::create_directories(dir);
    std::ostringstream md;
    md << "# Experiment results\n\nSource: `" << a["source"].get<std::string>() << "`, " << a["rows"] << " rows, "
       << a["excluded"] << " left out (warm-up or invalid).\n\n";
    limits_section(md, a);
    md << "| condition | n | proportion correct | IT_est (bits) | Cramer's phi | time (s, mean +- sd) | failures |\n";
    md << "| --- | ---: | ---: | ---: | ---: | ---: | ---: |\n";
    for (const auto& [name, c] : a["conditions"].items()) {
        md << "| " << name << " | " << c["n"] << " | " << report_number(c.value("proportion_correct", json())) << " | "
           << report_number(c.value("it_est_bits", json())) << " | " << report_number(c.value("cramers_phi", json())) << " | ";
        if (c.contains("time_s")) md << report_number(c["time_s"]["mean"]) << " +- " << report_number(c["time_s"]["sd"]);
        else md << "-";
        md << " | " << report_number(c.value("failure_proportion", json())) << " |\n";
    }
    for (const auto& [name, c] : a["conditions"].items()) {
        if (!c.contains("confusion")) continue;
        md << "\n## Confusion matrix: " << name << "\n\nRows: stimulus; columns: response.\n\n| |";
        for (const auto& r : c["labels"]["responses"]) md << " " << r.get<std::string>() << " |";
        md << "\n| --- |";
        for (std::size_t j = 0; j < c["labels"]["responses"].size(); ++j) md << " ---: |";
        md << "\n";
        for (std::size_t i = 0; i < c["labels"]["stimuli"].size(); ++i) {
            md << "| " << c["labels"]["stimuli"][i].get<std::string>() << " |";
            for (const auto& v : c["confusion"][i]) md << " " << v << " |";
            md << "\n";
        }
    }
    bump_section(md, a);
    threshold_section(md, a);
    if (!a["comparisons"].empty()) {
        md << "\n## Comparisons (t tests, and tests for binary outcomes)\n\nRule: " << experiments::kPairingRule << ".\n\n"
           << "Binary outcomes: " << experiments::kBinaryRule << ". The t test is the seeds' own analysis and is kept; on proportions its "
              "interval can leave [-1, 1], these cannot.\n\n"
           << "| measure | a - b | test | t | df | p | interval | binary outcome |\n| --- | --- | --- | ---: | ---: | ---: | --- | --- |\n";
        for (const auto& t : a["comparisons"]) {
            char ci[96];
            std::snprintf(ci, sizeof ci, "%.0f %%: %s .. %s", 100.0 * t["confidence"].get<double>(), report_number(t["ci_low"]).c_str(),
                          report_number(t["ci_high"]).c_str());
            md << "| " << t["measure"].get<std::string>() << " | " << t["a"].get<std::string>() << " - " << t["b"].get<std::string>()
               << " = " << report_number(t["mean_difference"]) << " | " << (t["test"]["kind"] == "paired" ? "paired" : "Welch") << " ("
               << t["test"]["because"].get<std::string>() << ") | ";
            if (t["valid"].get<bool>()) md << report_number(t["t"]) << " | " << report_number(t["df"]) << " | " << report_number(t["p"]) << " | " << ci;
            else md << "undefined: " << t["undefined"].get<std::string>() << " | - | - | -";
            md << " | " << binary_cell(t) << " |\n";
        }
    }
    if (a.contains("warnings") && !a["warnings"].empty()) {
        md << "\n## Warnings\n\n";
        for (const auto& w : a["warnings"]) md << "- " << w.get<std::string>() << "\n";
    }
    provenance_section(md, a);

    // Plots: the seed's own figures when the results are one of the seeds' experiments
    // (experiment_figures.hpp), else proportion correct per stimulus; only those with data.
    std::vector<ReportFigure> charts = seed_figures(table);
    // Thresholds (adaptive tracks, fitted curves) replace the per-stimulus chart: an adaptive
    // run's stimuli are wherever the procedure went, not a designed set of levels.
    for (ReportFigure& f : threshold_figures(a)) charts.push_back(std::move(f));
    if (charts.empty()) {
        Chart pc = per_stimulus_chart(a);
        if (!pc.series.empty())
            charts.push_back({"proportion_correct.png", pc,
                              "Each point: the share of the n valid trials answered correctly, with its 95 % Wilson interval."});
    }
    // Confusion matrices as pictures too, one per condition.
    std::vector<std::pair<std::string, render::MatrixChart>> matrices;
    int index = 0;
    for (const auto& [name, c] : a["conditions"].items()) {
        ++index;
        if (!c.contains("confusion")) continue;
        render::MatrixChart m;
        m.title = "Confusion: " + name;
        m.rows = c["labels"]["stimuli"].get<std::vector<std::string>>();
        m.columns = c["labels"]["responses"].get<std::vector<std::string>>();
        m.counts = c["confusion"].get<std::vector<std::vector<long>>>();
        matrices.emplace_back("confusion_" + std::to_string(index) + ".png", std::move(m));
    }
    if (!charts.empty() || !matrices.empty()) {
        md << "\n## Plots\n\n";
        try {
            const render::VulkanContext ctx(render::ContextOptions{});
            auto draw = [&](const std::string& file, const std::string& title, auto&& write) {
                try {
                    write((fs::path(dir) / file).string());
                    md << "![" << title << "](" << file << ")\n\n";
                } catch (const std::exception& e) {
                    md << "(" << title << ": not drawn: " << e.what() << ")\n\n";
                }
            };
            for (const auto& f : charts) {
                draw(f.file, f.chart.title, [&](const std::string& path) { render::write_chart_png(ctx, f.chart, path); });
                md << f.caption << "\n\n";
            }
            for (const auto& [file, m] : matrices)
                draw(file, m.title, [&](const std::string& path) { render::write_matrix_chart_png(ctx, m, path); });
        } catch (const std::exception& e) {
            md << "(no plots: no Vulkan device: " << e.what() << ")\n";
        }
    }
    const std::string page = (fs::path(dir) / "report.md").string();
    write_file_atomically(page, md.str());
    return page;
}

}  // namespace contactlab::reports
