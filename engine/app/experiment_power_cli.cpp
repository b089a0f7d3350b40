// experiment_power_cli.cpp — `contactlab experiment power PROTOCOL --measure NAME --participants
// A-B --pool N --resamples M [--alpha 0.05] [--seed S] [--jobs J] --json OUT [--report DIR]
// [--conditions A,B] [--overwrite] [--pool-from FILE] [--hand scripted|feel]`: how many participants a protocol needs
// (engine/experiments/analysis/power_analysis.hpp). The pool of N simulated participants runs once through
// the servo into OUT's stem + ".pool.csv" (an `experiment run` results file with its meta: kept,
// resumable, and reused when the same command runs again), then groups of A..B participants are
// resampled from it. With --pool-from FILE the pool is a finished results file of the same
// protocol instead (a cluster's merged run, docs/cluster.md): its participants, or its first N
// with --pool; --seed then seeds the draws only. The JSON carries the pool file's provenance (version, protocol and its hash,
// seed, device, rate) and its own hash; --report draws power against group size
// (engine/reports/power_report.hpp). --hand runs the pool with that simulated hand, as `experiment
// run --hand` does, and asks a --pool-from file to have been run with it.
#include "engine/app/command_line.hpp"
#include "engine/app/number_options.hpp"
#include "engine/app/progress_bar.hpp"
#include "engine/app/subcommands.hpp"
#include "engine/reports/power_report.hpp"
#include "engine/experiments/analysis/analysis.hpp"
#include "engine/experiments/runs/experiment_run.hpp"
#include "engine/experiments/runs/finished_run.hpp"
#include "engine/experiments/analysis/power_analysis.hpp"
#include "engine/experiments/protocol/protocol.hpp"
#include "engine/experiments/base/sha256.hpp"
#include "haptics/atomic_file.hpp"

#include <nlohmann/json.hpp>

#include <chrono>
#include <cstdio>
#include <filesystem>
#include <thread>
#include <tuple>
#include <utility>

namespace contactlab::app {
namespace {

namespace fs = std::filesystem;
using nlohmann::json;

struct PowerArgs {
    std::string protocol, measure = "it_est_bits", participants, json, report, conditions;
    int pool = 20, resamples = 1000, jobs = 0;
    double alpha = 0.05;
    unsigned long long seed = 1;
    bool overwrite = false;
    bool conditions_given = false;  // "--conditions ''" is refused, not taken for the default
    std::string pool_from;          // a finished results file taken as the pool instead of running one
    std::string hand;               // "" keeps the protocol's hand.model
    bool pool_given = false;        // --pool given: with --pool-from, the file's first N participants
};

// "4-16" -> 4..16; "10" -> {10}. Each size read by whole_number (never wrapped or saturated).
std::vector<int> group_sizes(const std::string& spec) {
    constexpr std::uint64_t kMost = 10000;
    const std::string rule = "--participants: group sizes A-B need whole numbers 2 <= A <= B <= " + std::to_string(kMost) +
                             " (a paired t test needs 2), e.g. 4-16 or one size N, got " + given(spec);
    const std::size_t dash = spec.find('-');
    std::uint64_t a = 0, b = 0;
    try {
        a = whole_number(spec.substr(0, dash), "--participants", 0, kMost);
        b = dash == std::string::npos ? a : whole_number(spec.substr(dash + 1), "--participants", 0, kMost);
    } catch (const BadInput&) {
        throw BadInput(rule);
    }
    if (a < 2 || b < a) throw BadInput(rule);
    std::vector<int> out;
    for (std::uint64_t i = a; i <= b; ++i) out.push_back(static_cast<int>(i));
    return out;
}

// "A,B": two different conditions of the protocol, by name (which exist is checked against the
// pool's analysis). "A,B,x" is not condition "B,x": condition names hold no comma (protocol.cpp).
std::pair<std::string, std::string> two_conditions(const std::string& spec) {
    const auto comma = spec.find(',');
    const std::string a = spec.substr(0, comma), b = comma == std::string::npos ? std::string() : spec.substr(comma + 1);
    if (comma == std::string::npos || a.empty() || b.empty() || b.find(',') != std::string::npos)
        throw BadInput("--conditions: expected two conditions A,B (names without commas), got " + given(spec));
    if (a == b) throw BadInput("--conditions: \"" + a + "\" compared with itself: name two different conditions A,B, got " + given(spec));
    return {a, b};
}

int run_power(const PowerArgs& a) {
    if (a.json.empty()) throw BadInput("experiment power: --json OUT is required");
    experiments::PowerOptions o;
    o.measure = a.measure == "IT_est" ? "it_est_bits" : a.measure;
    o.sizes = group_sizes(a.participants);
    o.resamples = a.resamples;
    o.alpha = a.alpha;
    o.seed = a.seed;
    if (a.conditions_given) std::tie(o.condition_a, o.condition_b) = two_conditions(a.conditions);
    const fs::path out(a.json);
    // The pool: a results file given (--pool-from: e.g. merged from a cluster's array tasks), or
    // run here into OUT's stem + ".pool.csv".
    const std::string pool_path =
        a.pool_from.empty() ? (out.parent_path() / (out.stem().string() + ".pool.csv")).string() : a.pool_from;
    json result;
    try {
        experiments::Protocol p = experiments::load_protocol(a.protocol);
        if (!a.hand.empty()) experiments::apply_hand_option(p, a.hand);
        if (a.pool_from.empty()) {
            experiments::RunOptions ro;
            for (int i = 1; i <= a.pool; ++i) ro.participants.push_back(static_cast<std::uint64_t>(i));
            ro.seed = a.seed;
            ro.output = pool_path;
            ro.protocol_path = a.protocol;
            ro.command = command_line();
            ro.traces = false;
            ro.overwrite = a.overwrite;
            ro.jobs = a.jobs > 0 ? a.jobs : static_cast<int>(std::max(1u, std::thread::hardware_concurrency()));
            ro.progress = [](std::size_t done, std::size_t total) {
                show_progress("power pool", static_cast<std::int64_t>(done), static_cast<std::int64_t>(total), "trials");
            };
            const auto t0 = std::chrono::steady_clock::now();
            const experiments::RunSummary s = experiments::run_experiment(p, ro);
            const double secs = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
            std::fprintf(stderr, "experiment power: pool of %d participants in %s (%s, %.1f s)\n", a.pool, pool_path.c_str(),
                         s.already_complete ? "already complete" : "simulated", secs);
        }
        // Read back and checked either way: finished, its rows as its meta says, this protocol.
        const bool own = a.pool_from.empty();
        const experiments::FinishedRun run = experiments::read_pool_run(
            pool_path, p, own || a.pool_given ? static_cast<std::size_t>(a.pool) : 2, own ? "the pool" : "--pool-from");
        // A pool run with another hand is another population: refused when --hand names one.
        const std::string pool_hand = run.meta.value("hand", std::string("scripted"));
        if (!a.hand.empty() && pool_hand != experiments::to_string(p.hand_model))
            throw BadInput("--pool-from " + pool_path + ": its participants moved with the " + pool_hand + " hand, --hand asks " +
                           experiments::to_string(p.hand_model));
        const std::size_t take = own || a.pool_given ? static_cast<std::size_t>(a.pool) : run.rows_of.size();
        if (!own)
            std::fprintf(stderr, "experiment power: pool of %zu of its %zu participants from %s\n", take, run.rows_of.size(),
                         pool_path.c_str());
        const json analysis = experiments::analyze_results(experiments::first_participants(run, take));
        result = experiments::power_analysis(analysis, o);
        result["pool_results"] = {{"file", pool_path}, {"sha256", experiments::sha256_hex(run.bytes)}, {"meta", run.meta}};
        result["command"] = command_line();
    } catch (const experiments::ExperimentError& e) {
        throw BadInput(e.what());
    }
    std::printf("power of the %s (alpha %g, pool %d, %d groups per size):\n", result["test"].get<std::string>().c_str(), a.alpha,
                result["pool"].get<int>(), a.resamples);
    std::printf("  participants  power  95 %% interval\n");
    for (const auto& pt : result["points"])
        std::printf("  %12d  %.3f  %.3f .. %.3f\n", pt["participants"].get<int>(), pt["power"].get<double>(),
                    pt["power_ci"][0].get<double>(), pt["power_ci"][1].get<double>());
    for (const auto& l : result["left_out"])
        std::fprintf(stderr, "experiment power: participant %s left out: %s\n", l["participant"].get<std::string>().c_str(),
                     l["reason"].get<std::string>().c_str());
    write_file_atomically(a.json, result.dump(2) + "\n");
    if (!a.report.empty()) {
        reports::write_power_report(result, a.report);
        std::printf("report: %s\n", (fs::path(a.report) / "report.md").string().c_str());
    }
    return 0;
}

}  // namespace

void register_experiment_power_command(CLI::App& app, int& rc) {
    CLI::App* exp = app.get_subcommand("experiment");
    auto args = std::make_shared<PowerArgs>();
    CLI::App* c = exp->add_subcommand("power", "How many participants a protocol needs: resampled power of its paired comparison");
    c->add_option("protocol", args->protocol, "Protocol file (JSON, scenes/README.md)")->required();
    c->add_option("--measure", args->measure,
                  "Per-participant measure compared: it_est_bits (or IT_est), proportion_correct, cramers_phi, time_s, "
                  "failure_proportion")
        ->default_val("it_est_bits");
    c->add_option("--participants", args->participants, "Group sizes A-B (e.g. 4-16), or one size N")->required();
    CLI::Option* pool = add_whole_option(c, "--pool", args->pool, 2, 10000,
                                         "Simulated participants run once through the servo, the population resampled (with "
                                         "--pool-from: the file's first N, default all)");
    c->add_option("--pool-from", args->pool_from,
                  "Take the pool from this finished results file of the protocol (e.g. merged from a cluster's tasks) instead of "
                  "running it");
    add_whole_option(c, "--resamples", args->resamples, 1, 1000000, "Groups drawn per size");
    add_real_option(c, "--alpha", args->alpha, {0.0, 1.0, true, true, "e.g. 0.05"}, "Two-sided significance level");
    add_whole_option(c, "--seed", args->seed, 0, kMaxSeed, "Seed of the pool's run and of the draws");
    add_whole_option(c, "--jobs", args->jobs, 0, kMaxJobs, "Pool participants run in parallel (0: every core)");
    CLI::Option* conditions = c->add_option("--conditions", args->conditions, "The two conditions compared, A,B (default: the protocol's two)");
    c->add_option("--json", args->json, "Write the power per group size as JSON (the pool goes to OUT's stem + .pool.csv)")->required();
    c->add_option("--report", args->report, "Write report.md and power.png into this folder");
    c->add_flag("--overwrite", args->overwrite, "Replace a pool file made by another run (without it such a file is refused)");
    c->add_option("--hand", args->hand,
                  "The pool's simulated hand, scripted or feel, as experiment run --hand (default: the protocol's hand.model); "
                  "a --pool-from file must have been run with it");
    c->callback([args, conditions, pool, &rc] {
        args->conditions_given = conditions->count() > 0;
        args->pool_given = pool->count() > 0;
        args->protocol = installed_data_path(args->protocol);
        rc = run_power(*args);
    });
}

}  // namespace contactlab::app
