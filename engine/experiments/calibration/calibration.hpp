// calibration.hpp — `contactlab experiment calibrate`: fit the simulated participant's free
// parameters (ParticipantModel, protocol.hpp) to published figures.
//
// A targets file (scenes/experiments/seed-targets.json: the seeds' own figures) names, for each
// figure, the protocol that measures it, where it sits in `experiment analyze`'s JSON (a JSON
// pointer, optionally divided by another: a ratio), the published value, the scale of a misfit
// that matters (the objective adds ((simulated - value) / scale)^2) and its source. Calibration
// runs the protocols with the same participant parameters for every protocol (one model of a
// person, not a knob per protocol), simulated through the servo, and moves the parameters within
// their bounds by Nelder-Mead (nelder_mead.hpp) to minimise the objective over the targets it is
// told to fit; the other targets are reported as they come out (held out), so the fit is shown
// honestly. Every evaluation runs the same participants with the same seed: the objective is a
// deterministic function of the parameters (piecewise constant: answers change in steps).
//
// Room engine/experiments/calibration/: the top floor: the simulated person fitted to the seeds' figures by running
// (runs/) and analysing (analysis/) studies. Includes every room below.
// The rooms and their arrows: docs/ARCHITECTURE.md, "The experiments' rooms".
#pragma once

#include "engine/experiments/protocol/protocol.hpp"

#include <nlohmann/json.hpp>

#include <cstdint>
#include <functional>
#include <optional>
#include <string>
#include <vector>

namespace contactlab::experiments {

struct CalibrationTarget {
    std::string name;      // unique, e.g. "002 IT_est, F"
    std::string protocol;  // the protocol's file name, e.g. "002-bump-counting.json"
    std::string figure;    // JSON pointer into the analysis, e.g. "/conditions/F/participant_means/it_est_bits"
    std::string over;      // optional JSON pointer: the figure is figure / over (a ratio)
    double value = 0.0;    // the published figure
    double scale = 1.0;    // a misfit of this size adds 1 to the objective (> 0)
    std::string source;    // where the value comes from
};

struct TargetsFile {
    std::string origin, sha256;
    std::vector<CalibrationTarget> targets;
};

// Read strictly: an unknown key, a wrong type or a bad value is an ExperimentError naming the
// file, the target and why.
TargetsFile parse_targets(const std::string& json_text, const std::string& origin);
TargetsFile load_targets(const std::string& path);

// The figure a target reads from an analysis (analyze_results' JSON); NaN when the analysis has
// no number there (or the ratio's denominator is 0).
double figure_of(const nlohmann::json& analysis, const CalibrationTarget& t);

// The participant parameter called `name` (ParticipantModel's field names), or nullptr.
double* participant_parameter(ParticipantModel& m, const std::string& name);
// Every name participant_parameter knows, for messages.
std::string participant_parameter_names();

struct CalibrationParameter {
    std::string name;
    double lo = 0.0, hi = 1.0;  // bounds (the parameter's units), lo < hi
};

struct CalibrationOptions {
    std::vector<Protocol> protocols;        // every protocol a target names (by file name)
    std::vector<CalibrationTarget> targets;
    std::vector<std::string> fit_to;        // target names in the objective; the rest are held out
    std::vector<CalibrationParameter> parameters;
    // The hand every evaluation's runs use (`experiment run --hand`); unset: each protocol's own.
    // A pool file must have been run with the same hand.
    std::optional<HandModel> hand;
    std::vector<std::uint64_t> participants = {1, 2, 3, 4, 5, 6, 7, 8, 9, 10};
    std::uint64_t seed = 1;
    int jobs = 1;
    int max_evaluations = 40;
    std::string work_dir;  // the evaluations' results files (rewritten by each evaluation)
    // Finished results files of some of the protocols, each run with the protocol as given, this
    // seed and these participants (first in the file): each stands for its protocol's runs at the
    // start point (the protocols' own parameter values), which are then not run again here.
    std::vector<std::string> pool_from;
    std::function<void(int evaluation, double objective)> progress;
};

// Returns {"parameters": {name: value}, "start": {name: value}, "bounds", "objective",
// "start_objective", "evaluations", "fit_to", "participants", "seed", "targets": [{"name",
// "protocol", "figure", "over", "value", "scale", "source", "fitted", "start", "simulated",
// "error", "within_scale"}], "trace": [{"parameters", "objective"}], "pool_from": [{"file",
// "sha256", "protocol"}], "hand": "scripted", "feel" or null (each protocol's own)}. Throws ExperimentError for a target naming a protocol not given, an
// unknown parameter, bad bounds, a fit target unknown, or a pool file that is not a finished run
// of a given protocol with this seed and these participants, or whose protocol's own parameter
// values are not the start (outside the bounds' inner 98 %).
nlohmann::json calibrate(const CalibrationOptions& o);

}  // namespace contactlab::experiments
