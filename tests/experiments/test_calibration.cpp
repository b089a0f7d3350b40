// test_calibration.cpp — `experiment calibrate`'s parts (engine/experiments/calibration/calibration.hpp): the
// shipped targets file (the seeds' figures), strict parsing, reading a figure from an analysis,
// and a calibration end to end through the servo that recovers a figure made with a known
// parameter, with a held-out target reported beside it.
#include "engine/experiments/analysis/analysis.hpp"
#include "engine/experiments/calibration/calibration.hpp"
#include "engine/experiments/runs/experiment_run.hpp"
#include "engine/experiments/base/results_table.hpp"
#include "process.hpp"

#include <doctest/doctest.h>
#include <nlohmann/json.hpp>

#include <cmath>

using namespace contactlab::experiments;
using cli_test::TempDir;

TEST_CASE("calibration targets: the shipped file holds the seeds' figures, each with its protocol and source") {
    const TargetsFile f = load_targets((cli_test::source_dir() / "scenes/experiments/seed-targets.json").string());
    CHECK(f.targets.size() == 13);
    CHECK(f.sha256.size() == 64);
    for (const CalibrationTarget& t : f.targets) {
        CAPTURE(t.name);
        CHECK(std::filesystem::exists(cli_test::source_dir() / "scenes/experiments" / t.protocol));
        CHECK_FALSE(t.source.empty());
        CHECK(t.scale > 0.0);
    }
    CHECK(f.targets[0].value == doctest::Approx(0.406));  // seed 000's failures with force alone
}

TEST_CASE("calibration targets: a bad file names the file, the target and why") {
    auto bad = [](const std::string& target) {
        return R"({"format": "contactlab calibration targets", "version": 1, "targets": [)" + target + "]}";
    };
    const std::string good = R"({"name": "a", "protocol": "p.json", "figure": "/conditions/F/n", "value": 1, "scale": 0.5, "source": "s"})";
    CHECK_NOTHROW(parse_targets(bad(good), "t.json"));
    CHECK_THROWS_WITH_AS(parse_targets(bad(R"({"name": "a", "protocol": "p.json", "figure": "/x", "value": 1, "scale": 0, "source": "s"})"), "t.json"),
                         doctest::Contains("t.json: targets[0].scale: expected a positive number"), ExperimentError);
    CHECK_THROWS_WITH_AS(parse_targets(bad(R"({"name": "a", "protocol": "p.json", "figure": "conditions", "value": 1, "scale": 1, "source": "s"})"), "t.json"),
                         doctest::Contains("t.json: targets[0].figure: expected a JSON pointer"), ExperimentError);
    CHECK_THROWS_WITH_AS(parse_targets(bad(good + ", " + good), "t.json"), doctest::Contains("targets[1].name: \"a\" appears twice"),
                         ExperimentError);
    CHECK_THROWS_WITH_AS(parse_targets(bad(R"({"name": "a, b", "protocol": "p.json", "figure": "/x", "value": 1, "scale": 1, "source": "s"})"), "t.json"),
                         doctest::Contains("t.json: targets[0].name: no commas"), ExperimentError);
    CHECK_THROWS_WITH_AS(parse_targets(bad(R"({"name": "a", "protocol": "p.json", "figure": "/x", "value": 1, "scale": 1, "source": "s", "weight": 2})"), "t.json"),
                         doctest::Contains("t.json: targets[0].weight: unknown key"), ExperimentError);
}

TEST_CASE("calibration: a figure from an analysis, a ratio of two, and NaN where there is none") {
    const nlohmann::json a = {{"conditions", {{"F", {{"time_s", {{"mean", 8.0}}}}}, {"F+CLD", {{"time_s", {{"mean", 4.4}}}}}}}};
    CalibrationTarget t;
    t.figure = "/conditions/F+CLD/time_s/mean";
    CHECK(figure_of(a, t) == 4.4);
    t.over = "/conditions/F/time_s/mean";
    CHECK(figure_of(a, t) == doctest::Approx(0.55));
    t.figure = "/conditions/G/time_s/mean";
    CHECK(std::isnan(figure_of(a, t)));
    ParticipantModel m;
    REQUIRE(participant_parameter(m, "stiffness_noise"));
    *participant_parameter(m, "stiffness_noise") = 0.7;
    CHECK(m.stiffness_noise == 0.7);
    CHECK(participant_parameter(m, "loudness") == nullptr);
}

TEST_CASE("calibration: through the servo, the fitted parameter brings the figure to the target, held-out targets reported") {
    TempDir dir;
    // Seed 004's task at one field (e 0.40), 8 presentations of each template, a participant whose
    // felt stiffness is noisy by `stiffness_noise`: phi falls as the noise grows.
    const std::string text = R"({"format": "contactlab experiment protocol", "version": 1, "name": "small 004", "seed": "004",
      "task": "surface-orientation", "conditions": [{"name": "e0.40", "eccentricity": 0.4, "total_stiffness": 1000},
      {"name": "e1.00", "eccentricity": 1.0, "total_stiffness": 1000}],
      "stimuli": [45, 135], "repetitions": 8, "answers": ["A", "B"], "participant": {"stiffness_noise": 0.1}})";
    const std::string path = dir.file("small-004.json");
    cli_test::write_text(path, text);
    Protocol p = load_protocol(path);
    // The target: phi made with a noise of 0.8 by the same participants and seed.
    p.participant.stiffness_noise = 0.8;
    RunOptions r;
    r.participants = {1, 2, 3};
    r.traces = false;
    r.output = dir.file("truth.csv");
    run_experiment(p, r);
    const nlohmann::json truth = analyze_results(read_results_csv(r.output));
    const double phi = truth["conditions"]["e0.40"]["cramers_phi"].get<double>();
    CAPTURE(phi);
    REQUIRE(phi > 0.05);
    REQUIRE(phi < 0.95);

    CalibrationOptions o;
    o.protocols = {load_protocol(path)};  // starts from the file's 0.1
    CalibrationTarget fit, held;
    fit.name = "phi e0.40";
    fit.protocol = held.protocol = "small-004.json";
    fit.figure = "/conditions/e0.40/cramers_phi";
    fit.value = phi;
    fit.scale = 0.1;
    held.name = "phi e1.00";
    held.figure = "/conditions/e1.00/cramers_phi";
    held.value = 0.0;
    held.scale = 0.25;
    o.targets = {fit, held};
    o.fit_to = {"phi e0.40"};
    o.parameters = {{"stiffness_noise", 0.02, 3.0}};
    o.participants = {1, 2, 3};
    o.max_evaluations = 14;
    o.work_dir = dir.file("runs");
    const nlohmann::json c = calibrate(o);
    const double noise = c["parameters"]["stiffness_noise"].get<double>();
    CAPTURE(c.dump());
    CHECK(noise > 0.02);
    CHECK(noise < 3.0);
    CHECK(c["objective"].get<double>() <= c["start_objective"].get<double>());
    REQUIRE(c["targets"].size() == 2);
    CHECK(c["targets"][0]["fitted"] == true);
    CHECK(c["targets"][0]["within_scale"] == true);
    CHECK(std::abs(c["targets"][0]["simulated"].get<double>() - phi) <= 0.1);
    CHECK(c["targets"][1]["fitted"] == false);
    CHECK(c["targets"][1]["simulated"].is_number());
    CHECK(c["trace"].size() == c["evaluations"].get<std::size_t>());
    CHECK(c["evaluations"].get<int>() <= 14);
    // Unknown parameters and targets are refused, naming them.
    o.parameters = {{"loudness", 0.0, 1.0}};
    CHECK_THROWS_WITH_AS(calibrate(o), doctest::Contains("no participant parameter \"loudness\""), ExperimentError);
    o.parameters = {{"stiffness_noise", 0.02, 3.0}};
    o.fit_to = {"phi e9"};
    CHECK_THROWS_WITH_AS(calibrate(o), doctest::Contains("no target called \"phi e9\""), ExperimentError);
}
