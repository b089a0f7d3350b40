// experiment_cli.cpp — `contactlab experiment run|analyze` (issue 16): the seeds' experiments
// (engine/experiments/). `analyze RESULTS.csv [--json OUT.json] [--report DIR] [--confidence C]`
// prints the figures per condition and writes them as JSON (schema: scenes/README.md) and as a
// Markdown page with plots.
#include "engine/app/experiment_report.hpp"
#include "engine/app/subcommands.hpp"
#include "engine/experiments/analysis.hpp"
#include "haptics/atomic_file.hpp"

#include <nlohmann/json.hpp>

#include <cstdio>
#include <string>

namespace contactlab::app {
namespace {

struct AnalyzeArgs {
    std::string results, json, report;
    double confidence = 0.95;
};

std::string figure(const nlohmann::json& c, const char* key, const char* f) {
    if (!c.contains(key) || !c[key].is_number()) return "-";
    char buf[48];
    std::snprintf(buf, sizeof buf, f, c[key].get<double>());
    return buf;
}

int run_analyze(const AnalyzeArgs& a) {
    if (!(a.confidence > 0.0 && a.confidence < 1.0)) throw BadInput("--confidence: must lie in (0, 1), e.g. 0.99");
    experiments::ResultsTable table;
    nlohmann::json result;
    try {
        table = experiments::read_results_csv(a.results);
        result = experiments::analyze_results(table, experiments::AnalyzeOptions{a.confidence});
    } catch (const experiments::ExperimentError& e) {
        throw BadInput(e.what());
    }
    std::printf("%s: %zu rows, %zu left out (warm-up or invalid)\n", a.results.c_str(), result["rows"].get<std::size_t>(),
                result["excluded"].get<std::size_t>());
    for (const auto& [name, c] : result["conditions"].items()) {
        std::printf("  %-24s n %4zu  correct %s  IT %s bits  phi %s", name.c_str(), c["n"].get<std::size_t>(),
                    figure(c, "proportion_correct", "%.3f").c_str(), figure(c, "it_est_bits", "%.3f").c_str(),
                    figure(c, "cramers_phi", "%.3f").c_str());
        if (c.contains("time_s"))
            std::printf("  time %s s  failures %s", figure(c["time_s"], "mean", "%.3f").c_str(),
                        figure(c, "failure_proportion", "%.3f").c_str());
        std::printf("\n");
    }
    for (const auto& t : result["comparisons"])
        std::printf("  %s, %s - %s: difference %s, t(%s) = %s, p = %s, %.0f %% interval %s .. %s (%s)\n",
                    t["measure"].get<std::string>().c_str(), t["a"].get<std::string>().c_str(), t["b"].get<std::string>().c_str(),
                    figure(t, "mean_difference", "%.4g").c_str(), figure(t, "df", "%.3g").c_str(), figure(t, "t", "%.3f").c_str(),
                    figure(t, "p", "%.3g").c_str(), 100.0 * a.confidence, figure(t, "ci_low", "%.4g").c_str(),
                    figure(t, "ci_high", "%.4g").c_str(), t["paired"].get<bool>() ? "paired" : "Welch");
    if (!a.json.empty()) write_file_atomically(a.json, result.dump(2) + "\n");
    if (!a.report.empty()) std::printf("report: %s\n", write_experiment_report(table, result, a.report).c_str());
    return 0;
}

}  // namespace

void register_experiment_command(CLI::App& app, int& rc) {
    CLI::App* exp = app.add_subcommand("experiment", "The seeds' experiments: run a protocol, analyse its results");
    exp->require_subcommand(1);

    auto analyze = std::make_shared<AnalyzeArgs>();
    CLI::App* an = exp->add_subcommand("analyze", "Figures per condition from a results CSV: proportion correct, IT, phi, times, t tests");
    an->add_option("results", analyze->results, "Results CSV (one row per trial; scenes/README.md)")->required();
    an->add_option("--json", analyze->json, "Write the figures as JSON");
    an->add_option("--report", analyze->report, "Write report.md and PNG plots into this folder");
    an->add_option("--confidence", analyze->confidence, "Confidence of the t tests' intervals (seed 000: 0.99)")
        ->default_val(0.95);
    an->callback([analyze, &rc] { rc = run_analyze(*analyze); });
}

}  // namespace contactlab::app
