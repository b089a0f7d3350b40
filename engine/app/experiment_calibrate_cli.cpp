// experiment_calibrate_cli.cpp — `contactlab experiment calibrate PROTOCOL... --target TARGETS.json
// --param NAME=LO:HI [--param ...] --fit NAME[,NAME...]|all [--participants N] [--seed S]
// [--jobs J] [--evaluations E] [--pool-from RESULTS.csv...] [--hand scripted|feel] --json OUT`: the
// simulated participant's parameters fitted to published figures
// (engine/experiments/calibration/calibration.hpp). --hand runs every evaluation with that hand, as
// `experiment run --hand` does; with feel, the hand's population ("hand.NAME") can be fitted to
// the movement figures.
// --pool-from gives the start's runs (the protocols' own parameters) from results files made
// elsewhere, e.g. on a cluster (docs/cluster.md). The same parameters go to every
// protocol; targets not in --fit are held out and reported as they come out. Each evaluation's
// results files are kept in OUT's stem + ".runs/" (rewritten by the next).
#include "engine/app/command_line.hpp"
#include "engine/app/number_options.hpp"
#include "engine/app/progress_bar.hpp"
#include "engine/app/subcommands.hpp"
#include "engine/experiments/calibration/calibration.hpp"
#include "engine/experiments/base/results_table.hpp"
#include "engine/experiments/protocol/protocol.hpp"
#include "haptics/atomic_file.hpp"

#include <nlohmann/json.hpp>

#include <algorithm>
#include <cstdio>
#include <filesystem>
#include <sstream>
#include <thread>

namespace contactlab::app {
namespace {

namespace fs = std::filesystem;

struct CalibrateArgs {
    std::vector<std::string> protocols, params, pool_from;
    std::string target, fit, json, hand;
    int participants = 10, jobs = 0, evaluations = 40;
    unsigned long long seed = 1;
};

// "NAME=LO:HI" -> a bounded parameter; LO and HI read by real_number (finite, no blanks).
experiments::CalibrationParameter parameter_of(const std::string& spec) {
    const auto eq = spec.find('='), colon = spec.find(':', eq == std::string::npos ? 0 : eq);
    if (eq == std::string::npos || colon == std::string::npos)
        throw BadInput("--param: expected NAME=LO:HI (e.g. force_angle_noise_deg=0.5:20), got " + given(spec));
    experiments::CalibrationParameter p;
    p.name = spec.substr(0, eq);
    const std::string what = "--param " + p.name;
    p.lo = real_number(spec.substr(eq + 1, colon - eq - 1), what + ": LO", {});
    p.hi = real_number(spec.substr(colon + 1), what + ": HI", {});
    return p;
}

std::vector<std::string> split_commas(const std::string& s) {
    std::vector<std::string> out;
    std::stringstream in(s);
    for (std::string item; std::getline(in, item, ',');)
        if (!item.empty()) out.push_back(item);
    return out;
}

int run_calibrate(const CalibrateArgs& a) {
    experiments::CalibrationOptions o;
    nlohmann::json result;
    try {
        const experiments::TargetsFile targets = experiments::load_targets(a.target);
        for (const std::string& p : a.protocols) o.protocols.push_back(experiments::load_protocol(installed_data_path(p)));
        // Targets of protocols not given are left out (the shipped file covers all four seeds);
        // one named by --fit is an error in calibrate().
        std::vector<std::string> given;
        for (const auto& p : o.protocols) given.push_back(fs::path(p.origin).filename().string());
        const std::vector<std::string> fit = a.fit == "all" ? std::vector<std::string>{} : split_commas(a.fit);
        for (const auto& t : targets.targets) {
            const bool have = std::find(given.begin(), given.end(), t.protocol) != given.end();
            const bool named = std::find(fit.begin(), fit.end(), t.name) != fit.end();
            if (have || named) o.targets.push_back(t);
            if (have && a.fit == "all") o.fit_to.push_back(t.name);
        }
        if (a.fit != "all") o.fit_to = fit;
        for (const std::string& p : a.params) o.parameters.push_back(parameter_of(p));
        o.participants.clear();
        for (int i = 1; i <= a.participants; ++i) o.participants.push_back(static_cast<std::uint64_t>(i));
        o.seed = a.seed;
        o.jobs = a.jobs > 0 ? a.jobs : static_cast<int>(std::max(1u, std::thread::hardware_concurrency()));
        o.max_evaluations = a.evaluations;
        o.pool_from = a.pool_from;
        if (!a.hand.empty()) {
            experiments::HandModel h = experiments::HandModel::scripted;
            if (!experiments::parse_hand_model(a.hand, h)) throw BadInput("--hand: expected scripted or feel, got \"" + a.hand + "\"");
            o.hand = h;
        }
        const fs::path out(a.json);
        o.work_dir = (out.parent_path() / (out.stem().string() + ".runs")).string();
        o.progress = [&](int k, double objective) {
            std::fprintf(stderr, "calibrate: evaluation %d of at most %d: objective %.4g\n", k, a.evaluations, objective);
        };
        result = experiments::calibrate(o);
        result["targets_file"] = {{"path", a.target}, {"sha256", targets.sha256}};
        result["command"] = command_line();
    } catch (const experiments::ExperimentError& e) {
        throw BadInput(e.what());
    }
    std::printf("calibrated (%d evaluations, objective %.4g from %.4g):", result["evaluations"].get<int>(), result["objective"].get<double>(),
                result["start_objective"].get<double>());
    for (const auto& [k, v] : result["parameters"].items()) std::printf(" %s = %.4g", k.c_str(), v.get<double>());
    std::printf("\n  %-40s %-9s %10s %10s %10s\n", "target", "", "published", "start", "now");
    for (const auto& t : result["targets"]) {
        auto f = [](const nlohmann::json& v) {
            char b[32];
            if (v.is_number()) std::snprintf(b, sizeof b, "%.4g", v.get<double>());
            else std::snprintf(b, sizeof b, "-");
            return std::string(b);
        };
        std::printf("  %-40s %-9s %10s %10s %10s%s\n", t["name"].get<std::string>().c_str(), t["fitted"].get<bool>() ? "fitted" : "held out",
                    f(t["value"]).c_str(), f(t["start"]).c_str(), f(t["simulated"]).c_str(), t["within_scale"].get<bool>() ? "" : "  (off by more than its scale)");
    }
    write_file_atomically(a.json, result.dump(2) + "\n");
    return 0;
}

}  // namespace

void register_experiment_calibrate_command(CLI::App& app, int& rc) {
    CLI::App* exp = app.get_subcommand("experiment");
    auto args = std::make_shared<CalibrateArgs>();
    CLI::App* c = exp->add_subcommand("calibrate", "Fit the simulated participant's parameters to published figures (a targets file)");
    c->add_option("protocols", args->protocols, "Protocol files the targets name (by file name)")->required();
    c->add_option("--target", args->target, "Targets file (scenes/experiments/seed-targets.json: the seeds' figures)")->required();
    c->add_option("--param", args->params, "A parameter to fit and its bounds, NAME=LO:HI (repeat for more)")->required();
    c->add_option("--fit", args->fit, "Targets in the objective, by name, comma-separated, or all; the rest are held out")->required();
    add_whole_option(c, "--participants", args->participants, 2, 1000, "Simulated participants sim:1..N in every evaluation");
    add_whole_option(c, "--seed", args->seed, 0, kMaxSeed, "Seed of every evaluation's runs (the same for all: a deterministic objective)");
    add_whole_option(c, "--jobs", args->jobs, 0, kMaxJobs, "Participants run in parallel (0: every core)");
    add_whole_option(c, "--evaluations", args->evaluations, 2, 10000, "At most this many evaluations (each runs every protocol)");
    c->add_option("--pool-from", args->pool_from,
                  "A finished results file of one of the protocols, as given, with this seed and these participants (e.g. merged "
                  "from a cluster's tasks): the start's runs of that protocol, not run again (repeat for more)");
    c->add_option("--hand", args->hand,
                  "The simulated person's hand in every evaluation, scripted or feel (default: each protocol's hand.model); "
                  "with feel, hand.NAME parameters (the feel hand's population) can be fitted");
    c->add_option("--json", args->json, "Write the fitted parameters, every target's figure and the trace as JSON")->required();
    c->callback([args, &rc] {
        args->target = installed_data_path(args->target);
        rc = run_calibrate(*args);
    });
}

}  // namespace contactlab::app
