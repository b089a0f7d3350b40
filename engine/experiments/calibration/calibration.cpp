// calibration.cpp — the participant's parameters fitted to published figures (calibration.hpp).
#include "engine/experiments/calibration/calibration.hpp"

#include "engine/experiments/analysis/analysis.hpp"
#include "engine/experiments/runs/experiment_run.hpp"
#include "engine/experiments/runs/finished_run.hpp"
#include "engine/experiments/runs/run_meta.hpp"
#include "engine/experiments/analysis/nelder_mead.hpp"
#include "engine/experiments/base/results_table.hpp"
#include "engine/experiments/base/sha256.hpp"

#include <algorithm>
#include <cerrno>
#include <cmath>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <map>
#include <set>
#include <sstream>

namespace contactlab::experiments {
namespace {

using json = nlohmann::json;

json num(double v) { return std::isfinite(v) ? json(v) : json(nullptr); }

[[noreturn]] void fail(const std::string& origin, const std::string& where, const std::string& why) {
    throw ExperimentError(origin + ": " + where + ": " + why);
}

std::string text_of(const std::string& origin, const json& j, const std::string& where, const char* key, bool required) {
    if (!j.contains(key)) {
        if (required) fail(origin, where, std::string("missing \"") + key + "\"");
        return {};
    }
    if (!j[key].is_string() || j[key].get<std::string>().empty()) fail(origin, where + "." + key, "expected a non-empty string");
    return j[key].get<std::string>();
}

bool valid_pointer(const std::string& p) {
    try {
        (void)json::json_pointer(p);
        return !p.empty();
    } catch (const json::exception&) {
        return false;
    }
}

// The ParticipantModel fields, by name.
const std::vector<std::pair<const char*, double ParticipantModel::*>>& fields() {
    static const std::vector<std::pair<const char*, double ParticipantModel::*>> f = {
        {"force_angle_threshold_deg", &ParticipantModel::force_angle_threshold_deg},
        {"force_angle_noise_deg", &ParticipantModel::force_angle_noise_deg},
        {"location_threshold_mm", &ParticipantModel::location_threshold_mm},
        {"location_noise_mm", &ParticipantModel::location_noise_mm},
        {"stiffness_noise", &ParticipantModel::stiffness_noise},
        {"reaction_time_s", &ParticipantModel::reaction_time_s},
        {"reaction_time_sd_s", &ParticipantModel::reaction_time_sd_s},
        {"stop_time_s", &ParticipantModel::stop_time_s},
        {"lapse_rate_hz", &ParticipantModel::lapse_rate_hz},
        {"lapse_duration_s", &ParticipantModel::lapse_duration_s},
        {"tilt_range_noise", &ParticipantModel::tilt_range_noise},
        {"edge_rate_noise", &ParticipantModel::edge_rate_noise},
        {"path_threshold_mm", &ParticipantModel::path_threshold_mm},
        {"path_noise_mm", &ParticipantModel::path_noise_mm},
    };
    return f;
}

double logistic(double u) { return 1.0 / (1.0 + std::exp(-u)); }

}  // namespace

TargetsFile parse_targets(const std::string& json_text, const std::string& origin) {
    json root;
    try {
        root = json::parse(json_text);
    } catch (const json::exception& e) {
        fail(origin, "(file)", std::string("invalid JSON: ") + e.what());
    }
    if (!root.is_object()) fail(origin, "(file)", "expected an object");
    for (const auto& [k, v] : root.items())
        if (k != "format" && k != "version" && k != "targets") fail(origin, k, "unknown key");
    if (!root.contains("format") || root["format"] != "contactlab calibration targets")
        fail(origin, "format", "expected \"contactlab calibration targets\"");
    if (!root.contains("version") || root["version"] != 1) fail(origin, "version", "expected 1");
    if (!root.contains("targets") || !root["targets"].is_array() || root["targets"].empty())
        fail(origin, "targets", "expected a non-empty array");
    TargetsFile f;
    f.origin = origin;
    f.sha256 = sha256_hex(json_text);
    std::set<std::string> names;
    for (std::size_t i = 0; i < root["targets"].size(); ++i) {
        const json& j = root["targets"][i];
        const std::string where = "targets[" + std::to_string(i) + "]";
        if (!j.is_object()) fail(origin, where, "expected an object");
        for (const auto& [k, v] : j.items())
            if (k != "name" && k != "protocol" && k != "figure" && k != "over" && k != "value" && k != "scale" && k != "source")
                fail(origin, where + "." + k, "unknown key");
        CalibrationTarget t;
        t.name = text_of(origin, j, where, "name", true);
        t.protocol = text_of(origin, j, where, "protocol", true);
        t.figure = text_of(origin, j, where, "figure", true);
        t.over = text_of(origin, j, where, "over", false);
        t.source = text_of(origin, j, where, "source", true);
        if (!names.insert(t.name).second) fail(origin, where + ".name", "\"" + t.name + "\" appears twice");
        if (t.name.find(',') != std::string::npos) fail(origin, where + ".name", "no commas: --fit lists names separated by commas");
        if (!valid_pointer(t.figure)) fail(origin, where + ".figure", "expected a JSON pointer such as \"/conditions/F/it_est_bits\"");
        if (!t.over.empty() && !valid_pointer(t.over)) fail(origin, where + ".over", "expected a JSON pointer");
        if (!j.contains("value") || !j["value"].is_number() || !std::isfinite(j["value"].get<double>()))
            fail(origin, where + ".value", "expected a finite number");
        if (!j.contains("scale") || !j["scale"].is_number() || !(j["scale"].get<double>() > 0.0) || !std::isfinite(j["scale"].get<double>()))
            fail(origin, where + ".scale", "expected a positive number (the size of a misfit that matters)");
        t.value = j["value"].get<double>();
        t.scale = j["scale"].get<double>();
        f.targets.push_back(t);
    }
    return f;
}

TargetsFile load_targets(const std::string& path) {
    std::ifstream in(path, std::ios::binary);
    if (!in) throw ExperimentError(path + ": cannot open (" + std::strerror(errno) + ")");
    std::ostringstream s;
    s << in.rdbuf();
    return parse_targets(s.str(), path);
}

double figure_of(const json& analysis, const CalibrationTarget& t) {
    auto at = [&](const std::string& p) {
        const json::json_pointer ptr(p);
        if (!analysis.contains(ptr)) return static_cast<double>(NAN);
        const json& v = analysis.at(ptr);
        return v.is_number() ? v.get<double>() : static_cast<double>(NAN);
    };
    const double a = at(t.figure);
    if (t.over.empty()) return a;
    const double b = at(t.over);
    return b != 0.0 ? a / b : static_cast<double>(NAN);
}

// The feel hand's population (protocol.hpp's HandPopulation) is fitted by "hand.NAME".
constexpr const char* kHandPrefix = "hand.";

double* participant_parameter(ParticipantModel& m, const std::string& name) {
    for (const auto& [n, field] : fields())
        if (name == n) return &(m.*field);
    if (name.rfind(kHandPrefix, 0) == 0)
        for (const HandField& f : hand_population_fields())
            if (name.substr(std::strlen(kHandPrefix)) == f.name) return &(m.hand.*f.member);
    return nullptr;
}

std::string participant_parameter_names() {
    std::string s;
    for (const auto& [n, field] : fields()) s += (s.empty() ? "" : ", ") + std::string(n);
    for (const HandField& f : hand_population_fields()) s += ", " + std::string(kHandPrefix) + f.name;
    return s;
}

json calibrate(const CalibrationOptions& o) {
    namespace fs = std::filesystem;
    if (o.parameters.empty()) throw ExperimentError("calibrate: no parameter to fit");
    if (o.participants.empty()) throw ExperimentError("calibrate: no participants");
    std::map<std::string, const Protocol*> by_file;
    for (const Protocol& p : o.protocols) by_file[fs::path(p.origin).filename().string()] = &p;
    std::set<std::string> used;  // protocols some target needs
    for (const CalibrationTarget& t : o.targets) {
        if (!by_file.count(t.protocol))
            throw ExperimentError("calibrate: target \"" + t.name + "\" needs protocol " + t.protocol + ", which was not given");
        used.insert(t.protocol);
    }
    std::set<std::string> fit(o.fit_to.begin(), o.fit_to.end());
    for (const std::string& f : fit) {
        bool known = false;
        for (const CalibrationTarget& t : o.targets) known = known || t.name == f;
        if (!known) throw ExperimentError("calibrate: no target called \"" + f + "\" to fit to");
    }
    if (fit.empty()) throw ExperimentError("calibrate: no target to fit to");
    ParticipantModel probe;
    for (const CalibrationParameter& p : o.parameters) {
        if (!participant_parameter(probe, p.name))
            throw ExperimentError("calibrate: no participant parameter \"" + p.name + "\" (" + participant_parameter_names() + ")");
        if (!(std::isfinite(p.lo) && std::isfinite(p.hi) && p.lo < p.hi))
            throw ExperimentError("calibrate: " + p.name + ": bounds need LO < HI, both finite");
    }
    // --hand feel asks every protocol's person to move by feel: one whose task has no such hand
    // would run its scripted strategy while the runs' meta said feel.
    if (o.hand && *o.hand == HandModel::feel)
        for (const std::string& file : used)
            if (!task_has_feel_hand(by_file[file]->task))
                throw ExperimentError("calibrate --hand feel: " + file + " is " + no_feel_hand_reason(by_file[file]->task));
    // The feel hand's population moves nothing on a protocol run with the scripted hand: a fit of it
    // there would wander on a flat objective.
    for (const CalibrationParameter& p : o.parameters)
        if (p.name.rfind(kHandPrefix, 0) == 0)
            for (const std::string& file : used)
                if ((o.hand ? *o.hand : by_file[file]->hand_model) != HandModel::feel)
                    throw ExperimentError("calibrate: " + p.name + " is the feel hand's, and " + file +
                                          " runs with the scripted hand (give --hand feel)");
    // The start point: each parameter at the protocols' own value (the first protocol's), moved
    // inside its bounds' inner 98 % (the logistic below never reaches a bound).
    std::vector<double> v_start;
    std::vector<bool> moved;
    for (const CalibrationParameter& p : o.parameters) {
        ParticipantModel m = o.protocols.empty() ? ParticipantModel{} : by_file[*used.begin()]->participant;
        const double own = *participant_parameter(m, p.name);
        v_start.push_back(std::clamp(own, p.lo + 0.01 * (p.hi - p.lo), p.hi - 0.01 * (p.hi - p.lo)));
        moved.push_back(v_start.back() != own);
    }
    // --pool-from: a finished run of a protocol as given stands for that protocol's runs at the start.
    std::map<std::string, ResultsTable> start_tables;  // protocol file name -> its rows
    json pool_from = json::array();
    for (const std::string& path : o.pool_from) {
        const auto meta = read_meta(path);
        const json sha = meta ? meta->value("protocol_sha256", json()) : json();
        std::string file;
        for (const std::string& f : used)
            if (by_file[f]->sha256 == sha) file = f;
        if (file.empty())
            throw ExperimentError("--pool-from " + path + ": not a run of any protocol a target needs (by its meta's protocol_sha256)");
        if (start_tables.count(file)) throw ExperimentError("--pool-from " + path + ": a second pool for " + file);
        const FinishedRun run = read_pool_run(path, *by_file[file], o.participants.size(), "--pool-from");
        const char* hand = to_string(o.hand ? *o.hand : by_file[file]->hand_model);
        if (run.meta.value("hand", std::string("scripted")) != hand)
            throw ExperimentError("--pool-from " + path + ": run with the " + run.meta.value("hand", std::string("scripted")) +
                                  " hand, the evaluations with the " + hand + " one");
        if (run.meta.value("seed", json()) != json(o.seed))
            throw ExperimentError("--pool-from " + path + ": run with seed " + run.meta.value("seed", json()).dump() +
                                  ", the evaluations with " + std::to_string(o.seed));
        for (std::size_t i = 0; i < o.participants.size(); ++i)
            if (run.participants[i] != "sim" + std::to_string(o.participants[i]))
                throw ExperimentError("--pool-from " + path + ": its participant " + std::to_string(i + 1) + " is " + run.participants[i] +
                                      ", the evaluations' is sim" + std::to_string(o.participants[i]));
        ParticipantModel own = by_file[file]->participant;
        for (std::size_t i = 0; i < o.parameters.size(); ++i)
            if (*participant_parameter(own, o.parameters[i].name) != v_start[i])
                throw ExperimentError("--pool-from " + path + ": " + file + "'s own " + o.parameters[i].name + " is not the start (" +
                                      (moved[i] ? "it lies outside the inner 98 % of the bounds" : "the first protocol's differs") +
                                      "), so the run in the file is not the start's");
        start_tables[file] = first_participants(run, o.participants.size());
        pool_from.push_back({{"file", path}, {"sha256", sha256_hex(run.bytes)}, {"protocol", file}});
    }
    fs::create_directories(o.work_dir);

    // One evaluation: the parameters on every protocol, every protocol a target needs run and
    // analysed (at the start, a pool file's rows where one was given), each target's figure.
    auto figures_at = [&](const std::vector<double>& values, bool start) {
        std::map<std::string, double> out;
        for (const std::string& file : used) {
            if (start && start_tables.count(file)) {
                const json analysis = analyze_results(start_tables.at(file));
                for (const CalibrationTarget& t : o.targets)
                    if (t.protocol == file) out[t.name] = figure_of(analysis, t);
                continue;
            }
            Protocol p = *by_file[file];
            if (o.hand) p.hand_model = *o.hand;
            for (std::size_t i = 0; i < o.parameters.size(); ++i) *participant_parameter(p.participant, o.parameters[i].name) = values[i];
            RunOptions r;
            r.participants = o.participants;
            r.seed = o.seed;
            r.output = (fs::path(o.work_dir) / file).replace_extension(".csv").string();
            r.protocol_path = p.origin;
            r.traces = false;
            r.overwrite = true;
            r.jobs = o.jobs;
            run_experiment(p, r);
            const json analysis = analyze_results(read_results_csv(r.output));
            for (const CalibrationTarget& t : o.targets)
                if (t.protocol == file) out[t.name] = figure_of(analysis, t);
        }
        return out;
    };
    auto objective_of = [&](const std::map<std::string, double>& figures) {
        double sum = 0.0;
        for (const CalibrationTarget& t : o.targets) {
            if (!fit.count(t.name)) continue;
            const double f = figures.at(t.name);
            // A figure the run could not give (no trial left, a division by zero) is as bad as a
            // misfit of 10 scales: the optimiser moves away from it instead of stopping there.
            const double e = std::isfinite(f) ? (f - t.value) / t.scale : 10.0;
            sum += e * e;
        }
        return sum;
    };
    // Bounded parameters through a logistic: u in R -> lo + (hi - lo) / (1 + exp(-u)).
    auto values_of = [&](const std::vector<double>& u) {
        std::vector<double> v(u.size());
        for (std::size_t i = 0; i < u.size(); ++i) v[i] = o.parameters[i].lo + (o.parameters[i].hi - o.parameters[i].lo) * logistic(u[i]);
        return v;
    };
    std::vector<double> u0, step(o.parameters.size(), 1.0);
    for (std::size_t i = 0; i < o.parameters.size(); ++i) {
        const double q = (v_start[i] - o.parameters[i].lo) / (o.parameters[i].hi - o.parameters[i].lo);
        u0.push_back(std::log(q / (1.0 - q)));
    }
    json trace = json::array();
    int evaluations = 0;
    std::map<std::string, double> start_figures;
    double start_objective = NAN;
    auto f = [&](const std::vector<double>& u) {
        // The start exactly (the logistic's round trip may move it by a last bit).
        const std::vector<double> v = u == u0 ? v_start : values_of(u);
        const std::map<std::string, double> figures = figures_at(v, u == u0);
        const double obj = objective_of(figures);
        json params = json::object();
        for (std::size_t i = 0; i < v.size(); ++i) params[o.parameters[i].name] = v[i];
        trace.push_back({{"parameters", params}, {"objective", obj}});
        if (evaluations == 0) start_figures = figures, start_objective = obj;
        ++evaluations;
        if (o.progress) o.progress(evaluations, obj);
        return obj;
    };
    // The objective is flat between the parameter values where an answer changes, and the simplex
    // stops on a plateau. So first a coarse look along each parameter's range (5, 18, 50, 82 and
    // 95 % of it, the others at the start), then the simplex from the best point found, its steps
    // the coarse spacing.
    std::vector<double> best_u = u0;
    double best = f(u0);
    for (std::size_t i = 0; i < u0.size() && evaluations + 5 <= o.max_evaluations; ++i)
        for (const double at : {-3.0, -1.5, 0.0, 1.5, 3.0}) {
            std::vector<double> u = u0;
            u[i] = at;
            if (const double v = f(u); v < best) best = v, best_u = u;
        }
    std::fill(step.begin(), step.end(), 1.5);
    const int left = std::max(o.max_evaluations - evaluations, static_cast<int>(o.parameters.size()) + 2);
    double simplex_best = 0.0;
    std::vector<double> u = nelder_mead(f, best_u, step, left, simplex_best);
    if (!(simplex_best <= best)) u = best_u;
    const std::vector<double> v = u == u0 ? v_start : values_of(u);
    // The best parameters' figures (run again: the simplex keeps values, not figures).
    const std::map<std::string, double> final_figures = figures_at(v, u == u0);
    json params = json::object(), bounds = json::object(), start_params = json::object();
    const std::vector<double>& v0 = v_start;
    for (std::size_t i = 0; i < v.size(); ++i) {
        params[o.parameters[i].name] = v[i];
        start_params[o.parameters[i].name] = v0[i];
        bounds[o.parameters[i].name] = {o.parameters[i].lo, o.parameters[i].hi};
    }
    json targets = json::array();
    for (const CalibrationTarget& t : o.targets) {
        const double sim = final_figures.at(t.name);
        targets.push_back({{"name", t.name},
                           {"protocol", t.protocol},
                           {"figure", t.figure},
                           {"over", t.over},
                           {"value", t.value},
                           {"scale", t.scale},
                           {"source", t.source},
                           {"fitted", fit.count(t.name) > 0},
                           {"start", num(start_figures.at(t.name))},
                           {"simulated", num(sim)},
                           {"error", num(sim - t.value)},
                           {"within_scale", std::isfinite(sim) && std::abs(sim - t.value) <= t.scale}});
    }
    json participants = json::array();
    for (std::uint64_t n : o.participants) participants.push_back("sim" + std::to_string(n));
    return {{"parameters", params},       {"start", start_params}, {"bounds", bounds},
            {"objective", objective_of(final_figures)}, {"start_objective", start_objective}, {"evaluations", evaluations},
            {"fit_to", o.fit_to},         {"participants", participants}, {"seed", o.seed},
            {"targets", targets},         {"trace", trace}, {"pool_from", pool_from},
            {"hand", o.hand ? json(to_string(*o.hand)) : json(nullptr)}};
}

}  // namespace contactlab::experiments
