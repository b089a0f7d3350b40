// experiment_cli.cpp — `contactlab experiment run|analyze` (issue 16): the seeds' experiments
// (engine/experiments/). `run PROTOCOL --participant sim|sim:N | --participants sim:A-B --seed S
// --output RESULTS.csv [--jobs J] [--no-traces] [--overwrite] [--profile]` performs the protocol's trials
// with simulated participants through the servo and the simulated rig, durably (started again,
// the same command resumes) with RESULTS.csv.meta.json beside it. `analyze RESULTS.csv...
// [--json OUT.json] [--report DIR] [--confidence C] [--pool-protocols]` prints the figures per
// condition, the tests' rule and any warnings, and writes them as JSON (schema:
// scenes/README.md) with each file's provenance, and as a Markdown page with plots.
#include "engine/app/command_line.hpp"
#include "engine/app/number_options.hpp"
#include "engine/app/participant_options.hpp"
#include "engine/reports/experiment_report.hpp"
#include "engine/experiments/analysis/limits.hpp"
#include "engine/app/progress_bar.hpp"
#include "engine/app/subcommands.hpp"
#include "engine/experiments/analysis/analysis.hpp"
#include "engine/experiments/runs/experiment_run.hpp"
#include "engine/experiments/analysis/pooling.hpp"
#include "engine/experiments/protocol/protocol.hpp"
#include "engine/experiments/analysis/threshold_analysis.hpp"
#include "haptics/atomic_file.hpp"

#include <nlohmann/json.hpp>

#include <chrono>
#include <optional>
#include <cstdio>
#include <fstream>
#include <sstream>
#include <string>
#include <thread>


namespace contactlab::app {
namespace {

struct RunArgs {
    std::string protocol, participant, participants, output;
    std::string hand;  // "" keeps the protocol's hand.model
    unsigned long long seed = 1;
    int jobs = 0;  // 0: every core
    bool no_traces = false, overwrite = false, profile = false;
};

void print_progress(std::size_t done, std::size_t total) {
    show_progress("experiment", static_cast<std::int64_t>(done), static_cast<std::int64_t>(total), "trials");
}

int run_protocol(const RunArgs& a) {
    if (a.participant.empty() == a.participants.empty()) throw BadInput("experiment run: give --participant or --participants");
    experiments::RunOptions o;
    o.participants = sim_participants(a.participant.empty() ? a.participants : a.participant,
                                      a.participant.empty() ? "--participants" : "--participant", &o.observer);
    o.seed = a.seed;
    o.output = a.output;
    o.traces = !a.no_traces;
    o.overwrite = a.overwrite;
    o.profile = a.profile;
    o.protocol_path = a.protocol;
    o.command = command_line();
    o.jobs = a.jobs > 0 ? a.jobs : static_cast<int>(std::max(1u, std::thread::hardware_concurrency()));
    o.progress = print_progress;
    try {
        experiments::Protocol p = experiments::load_protocol(a.protocol);
        if (!a.hand.empty()) experiments::apply_hand_option(p, a.hand);
        const auto t0 = std::chrono::steady_clock::now();
        const experiments::RunSummary s = experiments::run_experiment(p, o);
        const double secs = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
        if (s.already_complete) {
            std::fprintf(stderr, "experiment: %s already holds this run, complete (%zu trials): nothing to do (--overwrite runs it again)\n",
                         a.output.c_str(), s.rows);
            return 0;
        }
        if (s.resumed > 0)
            std::fprintf(stderr, "experiment: resumed: %zu trials were already on disk\n", s.resumed);
        std::fprintf(stderr, "experiment: %s (%s), %zu participant(s), %zu trials (%zu warm-up, %zu invalid) in %.1f s; written to %s with %s%s%s\n",
                     p.name.c_str(), experiments::to_string(p.task), o.participants.size(), s.rows, s.warmup, s.invalid, secs,
                     a.output.c_str(), (a.output + ".meta.json").c_str(), o.traces ? ", traces in " : "",
                     o.traces ? (a.output + ".traces/").c_str() : "");
        if (a.profile) std::printf("%s", experiments::profile_table(s.profile).c_str());
    } catch (const experiments::ExperimentError& e) {
        throw BadInput(e.what());
    }
    return 0;
}

struct AnalyzeArgs {
    std::vector<std::string> results;
    std::string json, report;
    double confidence = 0.95;
    bool pool_protocols = false;
    std::string psychometric;  // "" (no fit), logistic, weibull, cumulative-normal
    double guess = 0.5, max_lapse = 0.06;
    int bootstrap = 1000;
};

std::string figure(const nlohmann::json& c, const char* key, const char* f) {
    if (!c.contains(key) || !c[key].is_number()) return "-";
    char buf[48];
    std::snprintf(buf, sizeof buf, f, c[key].get<double>());
    return buf;
}

std::string figure_at(const nlohmann::json& c, std::size_t index, const char* f) {
    if (!c.is_array() || index >= c.size() || !c[index].is_number()) return "-";
    char buf[48];
    std::snprintf(buf, sizeof buf, f, c[index].get<double>());
    return buf;
}

int run_analyze(const AnalyzeArgs& a) {
    experiments::PooledResults pooled;
    nlohmann::json result;
    try {
        pooled = experiments::pool_results(a.results, a.pool_protocols);
        result = experiments::analyze_results(pooled.table, experiments::AnalyzeOptions{a.confidence});
        experiments::ThresholdOptions to;
        if (!a.psychometric.empty()) {
            experiments::PsyFitOptions fo;
            if (!experiments::parse_psy_function(a.psychometric, fo.function))
                throw BadInput("--psychometric: expected logistic, weibull or cumulative-normal, got \"" + a.psychometric + "\"");
            // Each alone was checked as it was read (number_options.hpp); together:
            if (!(a.guess + a.max_lapse < 1.0))
                throw BadInput("--max-lapse: must be at least 0 with --guess + --max-lapse below 1, got --guess " + number_text(a.guess) +
                               " and --max-lapse " + number_text(a.max_lapse));
            fo.guess = a.guess;
            fo.max_lapse = a.max_lapse;
            fo.bootstrap = a.bootstrap;
            fo.confidence = 0.95;
            fo.seed = 1;
            to.psychometric = fo;
        }
        experiments::add_threshold_analysis(result, pooled.table, to);
    } catch (const experiments::ExperimentError& e) {
        throw BadInput(e.what());
    }
    // The pooling's warnings first: they concern every figure.
    nlohmann::json warnings = pooled.warnings;
    for (const auto& w : result["warnings"]) warnings.push_back(w);
    result["warnings"] = warnings;
    result["provenance"] = pooled.provenance;
    experiments::add_limits(result);
    const experiments::ResultsTable& table = pooled.table;
    std::printf("%s: %zu rows, %zu left out (warm-up or invalid)\n", table.origin.c_str(), result["rows"].get<std::size_t>(),
                result["excluded"].get<std::size_t>());
    for (const auto& w : warnings) std::fprintf(stderr, "experiment analyze: warning: %s\n", w.get<std::string>().c_str());
    for (const auto& [name, c] : result["conditions"].items()) {
        std::printf("  %-24s n %4zu  correct %s  IT %s bits  phi %s", name.c_str(), c["n"].get<std::size_t>(),
                    figure(c, "proportion_correct", "%.3f").c_str(), figure(c, "it_est_bits", "%.3f").c_str(),
                    figure(c, "cramers_phi", "%.3f").c_str());
        if (c.contains("time_s"))
            std::printf("  time %s s  failures %s", figure(c["time_s"], "mean", "%.3f").c_str(),
                        figure(c, "failure_proportion", "%.3f").c_str());
        if (c.contains("contact_fraction") && c.contains("contact_breaks"))
            std::printf("  in contact %s  breaks %s", figure(c["contact_fraction"], "mean", "%.3f").c_str(),
                        figure(c["contact_breaks"], "mean", "%.2f").c_str());
        std::printf("\n");
        if (c.contains("adaptive") && c["adaptive"].contains("estimate"))
            std::printf("  %-24s %s: estimate %s (target p %s)\n", "", c["adaptive"]["procedure"].get<std::string>().c_str(),
                        figure(c["adaptive"], "estimate", "%.4g").c_str(), figure(c["adaptive"], "target_p", "%.3f").c_str());
        if (c.contains("psychometric")) {
            const auto& f = c["psychometric"];
            if (f.contains("threshold") && !f["threshold"].is_number())
                std::printf("  %-24s %s fit: threshold %s\n", "", f["function"].get<std::string>().c_str(),
                            f["threshold_undefined"].get<std::string>().c_str());
            else if (f.contains("threshold"))
                std::printf("  %-24s %s fit: threshold %s, 95 %% interval %s, scale %s, lapse %s, deviance %s\n", "",
                            f["function"].get<std::string>().c_str(), figure(f, "threshold", "%.4g").c_str(),
                            f["threshold_ci"].is_array() ? (figure_at(f["threshold_ci"], 0, "%.4g") + " .. " + figure_at(f["threshold_ci"], 1, "%.4g")).c_str()
                            : f.contains("threshold_ci_undefined") ? "not bounded (below)" : "-",
                            figure(f, "scale", "%.4g").c_str(), figure(f, "lapse", "%.3f").c_str(), figure(f, "deviance", "%.3g").c_str());
            else
                std::printf("  %-24s %s fit: %s\n", "", f["function"].get<std::string>().c_str(), f["undefined"].get<std::string>().c_str());
            for (const char* key : {"threshold_ci_undefined", "scale_ci_undefined"})
                if (f.contains(key)) std::printf("  %-24s %s: %s\n", "", key, f[key].get<std::string>().c_str());
        }
    }
    if (!result["comparisons"].empty()) std::printf("  tests: %s\n", experiments::kPairingRule);
    for (const auto& t : result["comparisons"]) {
        const std::string kind = t["test"]["kind"] == "paired" ? "paired" : "Welch";
        if (!t["valid"].get<bool>()) {
            std::printf("  %s, %s - %s: difference %s, t undefined: %s (%s: %s)\n", t["measure"].get<std::string>().c_str(),
                        t["a"].get<std::string>().c_str(), t["b"].get<std::string>().c_str(), figure(t, "mean_difference", "%.4g").c_str(),
                        t["undefined"].get<std::string>().c_str(), kind.c_str(), t["test"]["because"].get<std::string>().c_str());
            continue;
        }
        std::printf("  %s, %s - %s: difference %s, t(%s) = %s, p = %s, %.0f %% interval %s .. %s (%s: %s)\n",
                    t["measure"].get<std::string>().c_str(), t["a"].get<std::string>().c_str(), t["b"].get<std::string>().c_str(),
                    figure(t, "mean_difference", "%.4g").c_str(), figure(t, "df", "%.3g").c_str(), figure(t, "t", "%.3f").c_str(),
                    figure(t, "p", "%.3g").c_str(), 100.0 * a.confidence, figure(t, "ci_low", "%.4g").c_str(),
                    figure(t, "ci_high", "%.4g").c_str(), kind.c_str(), t["test"]["because"].get<std::string>().c_str());
    }
    if (!a.json.empty()) write_file_atomically(a.json, result.dump(2) + "\n");
    if (!a.report.empty()) {
        try {
            std::printf("report: %s\n", reports::write_experiment_report(table, result, a.report).c_str());
        } catch (const experiments::ExperimentError& e) {
            throw BadInput(e.what());
        }
    }
    return 0;
}

}  // namespace

void register_experiment_command(CLI::App& app, int& rc) {
    CLI::App* exp = app.add_subcommand("experiment", "The seeds' experiments: run a protocol, analyse its results");
    exp->require_subcommand(1);

    auto run = std::make_shared<RunArgs>();
    CLI::App* r = exp->add_subcommand("run", "Run a protocol (scenes/experiments/) with simulated participants into a results CSV");
    r->add_option("protocol", run->protocol, "Protocol file (JSON, scenes/README.md)")->required();
    r->add_option("--participant", run->participant,
                  "sim (a simulated participant), sim:N for participant N, or a model observer "
                  "observer:logistic|weibull|cumulative-normal:threshold=T,scale=S[,guess=G,lapse=L]");
    r->add_option("--participants", run->participants,
                  "sim:A-B: simulated participants A..B, each its own seed; observer:FN:threshold=T,...:A-B: model observers A..B");
    add_whole_option(r, "--seed", run->seed, 0, kMaxSeed, "Seed of the trial orders and the perceptual noise");
    r->add_option("-o,--output", run->output, "Results CSV (one row per trial)")->required();
    add_whole_option(r, "--jobs", run->jobs, 0, kMaxJobs, "Participants run in parallel (0: every core); the results do not depend on it");
    r->add_option("--hand", run->hand,
                  "The simulated person's hand: scripted (a path made from the contour) or feel (closing its loop on what it "
                  "feels); default: the protocol's hand.model, else scripted");
    r->add_flag("--no-traces", run->no_traces, "Skip the per-trial traces (RESULTS.csv.traces/)");
    r->add_flag("--profile", run->profile,
                "Print where the wall time went, by stage (servo tick, simulated rig, hand paths, perception, files), in ms "
                "per s of virtual time; the results do not change");
    r->add_flag("--overwrite", run->overwrite,
                "Replace the results, meta and traces of another run in --output (without it such a run is refused; the same "
                "run resumes)");
    r->callback([run, &rc] {
        run->protocol = installed_data_path(run->protocol);
        rc = run_protocol(*run);
    });

    auto analyze = std::make_shared<AnalyzeArgs>();
    CLI::App* an = exp->add_subcommand("analyze", "Figures per condition from a results CSV: proportion correct, IT, phi, times, t tests");
    an->add_option("results", analyze->results, "Results CSVs (one row per trial; scenes/README.md), pooled")->required();
    an->add_flag("--pool-protocols", analyze->pool_protocols,
                 "Pool results files from different protocols (different protocol_sha256 in their meta files)");
    an->add_option("--json", analyze->json, "Write the figures as JSON");
    an->add_option("--report", analyze->report, "Write report.md and PNG plots into this folder");
    add_real_option(an, "--confidence", analyze->confidence, {0.0, 1.0, true, true, "e.g. 0.99"},
                    "Confidence of the t tests' intervals (seed 000: 0.99)");
    an->add_option("--psychometric", analyze->psychometric,
                   "Fit logistic, weibull or cumulative-normal per condition and participant (maximum likelihood, lapse free, "
                   "parametric-bootstrap 95 % intervals)");
    add_real_option(an, "--guess", analyze->guess, {0.0, 1.0, false, true, "e.g. 0.5 for two-alternative forced choice"},
                    "The fit's chance rate (0.5 for two-alternative forced choice)");
    add_real_option(an, "--max-lapse", analyze->max_lapse, {0.0, 1.0, false, true, "with --guess + --max-lapse below 1"},
                    "The fit's lapse rate is free in [0, this]");
    add_whole_option(an, "--bootstrap", analyze->bootstrap, 0, 100000, "Parametric bootstrap resamples for the fit's intervals (seed 1)");
    an->callback([analyze, &rc] { rc = run_analyze(*analyze); });
}

}  // namespace contactlab::app
