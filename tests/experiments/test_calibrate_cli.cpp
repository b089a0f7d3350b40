// test_calibrate_cli.cpp — the real `contactlab experiment calibrate`: a small protocol and a
// targets file, the fitted parameter and every target's figure as JSON and as a table, and bad
// options exit 2 naming them.
#include "process.hpp"

#include <doctest/doctest.h>
#include <nlohmann/json.hpp>

#include <cmath>
#include <filesystem>
#include <string>
#include <vector>

using namespace cli_test;

namespace {
const char* kProtocol = R"({"format": "contactlab experiment protocol", "version": 1, "name": "small 004", "seed": "004",
  "task": "surface-orientation", "conditions": [{"name": "e0.40", "eccentricity": 0.4, "total_stiffness": 1000},
  {"name": "e1.00", "eccentricity": 1.0, "total_stiffness": 1000}],
  "stimuli": [45, 135], "repetitions": 6, "answers": ["A", "B"], "participant": {"stiffness_noise": 0.1}})";
const char* kTargets = R"({"format": "contactlab calibration targets", "version": 1, "targets": [
  {"name": "phi e0.40", "protocol": "small.json", "figure": "/conditions/e0.40/cramers_phi", "value": 0.5, "scale": 0.15, "source": "made up for the test"},
  {"name": "phi e1.00", "protocol": "small.json", "figure": "/conditions/e1.00/cramers_phi", "value": 0.0, "scale": 0.25, "source": "made up for the test"},
  {"name": "another study", "protocol": "other.json", "figure": "/conditions/x/n", "value": 1.0, "scale": 1.0, "source": "a protocol not given: left out"}]})";
}  // namespace

TEST_CASE("experiment calibrate: a parameter fitted to one target, the other held out, as JSON and a table") {
    TempDir dir;
    write_text(dir.file("small.json"), kProtocol);
    write_text(dir.file("t.json"), kTargets);
    const auto p = run_contactlab({"experiment", "calibrate", dir.file("small.json"), "--target", dir.file("t.json"), "--param",
                                   "stiffness_noise=0.02:3", "--fit", "phi e0.40", "--participants", "2", "--evaluations", "8",
                                   "--jobs", "2", "--json", dir.file("c.json")});
    INFO(p.out << p.err);
    REQUIRE(p.exit_code == 0);
    CHECK(contains(p.out, "held out"));
    CHECK(contains(p.out, "stiffness_noise = "));
    const auto j = nlohmann::json::parse(read_text(dir.file("c.json")));
    CHECK(j["evaluations"].get<int>() <= 8);
    CHECK(j["objective"].get<double>() <= j["start_objective"].get<double>());
    CHECK(j["targets"].size() == 2);  // the target of a protocol not given is left out
    CHECK(j["targets_file"]["sha256"].get<std::string>().size() == 64);
    const double v = j["parameters"]["stiffness_noise"].get<double>();
    CHECK(v > 0.02);
    CHECK(v < 3.0);
}

TEST_CASE("experiment calibrate: a bad parameter, bounds or target name exits 2 saying which") {
    TempDir dir;
    write_text(dir.file("small.json"), kProtocol);
    write_text(dir.file("t.json"), kTargets);
    auto run = [&](const std::string& param, const std::string& fit) {
        return run_contactlab({"experiment", "calibrate", dir.file("small.json"), "--target", dir.file("t.json"), "--param", param,
                               "--fit", fit, "--participants", "2", "--evaluations", "4", "--json", dir.file("c.json")});
    };
    const auto form = run("stiffness_noise=0.1", "phi e0.40");
    CHECK(form.exit_code == 2);
    CHECK(contains(form.err, "expected NAME=LO:HI"));
    const auto name = run("loudness=0:1", "phi e0.40");
    CHECK(name.exit_code == 2);
    CHECK(contains(name.err, "no participant parameter \"loudness\""));
    const auto bounds = run("stiffness_noise=2:1", "phi e0.40");
    CHECK(bounds.exit_code == 2);
    CHECK(contains(bounds.err, "bounds need LO < HI"));
    const auto target = run("stiffness_noise=0.1:1", "phi e9");
    CHECK(target.exit_code == 2);
    CHECK(contains(target.err, "no target called \"phi e9\""));
}

TEST_CASE("experiment calibrate --pool-from: a merged run of the protocol stands for the start, the same fit and figures") {
    TempDir dir;
    write_text(dir.file("small.json"), kProtocol);
    write_text(dir.file("t.json"), kTargets);
    auto ok = [](const std::vector<std::string>& args) {
        const ProcessResult r = run_contactlab(args);
        INFO(r.err);
        REQUIRE(r.exit_code == 0);
    };
    auto calibrate = [&](const std::string& out, const std::string& param, std::vector<std::string> extra) {
        std::vector<std::string> a = {"experiment", "calibrate", dir.file("small.json"), "--target", dir.file("t.json"), "--param", param,
                                      "--fit", "phi e0.40", "--participants", "2", "--evaluations", "6", "--jobs", "2",
                                      "--json", dir.file(out)};
        a.insert(a.end(), extra.begin(), extra.end());
        return run_contactlab(a);
    };
    // The start's run as two array tasks would make it, merged; and one of another seed.
    ok({"experiment", "run", dir.file("small.json"), "--participants", "sim:1-1", "--seed", "1", "--no-traces", "-o", dir.file("a.csv")});
    ok({"experiment", "run", dir.file("small.json"), "--participants", "sim:2-2", "--seed", "1", "--no-traces", "-o", dir.file("b.csv")});
    ok({"experiment", "merge", dir.file("a.csv"), dir.file("b.csv"), "-o", dir.file("start.csv")});
    ok({"experiment", "run", dir.file("small.json"), "--participants", "sim:1-2", "--seed", "2", "--no-traces", "-o", dir.file("s2.csv")});
    REQUIRE(calibrate("own.json", "stiffness_noise=0.02:3", {}).exit_code == 0);
    const ProcessResult pooled = calibrate("pooled.json", "stiffness_noise=0.02:3", {"--pool-from", dir.file("start.csv")});
    INFO(pooled.err);
    REQUIRE(pooled.exit_code == 0);
    const auto own = nlohmann::json::parse(read_text(dir.file("own.json")));
    const auto j = nlohmann::json::parse(read_text(dir.file("pooled.json")));
    for (const char* key : {"parameters", "start", "objective", "start_objective", "evaluations", "targets", "trace"}) {
        CAPTURE(key);
        CHECK(j[key] == own[key]);
    }
    REQUIRE(j["pool_from"].size() == 1);
    CHECK(j["pool_from"][0]["file"] == dir.file("start.csv"));
    CHECK(j["pool_from"][0]["protocol"] == "small.json");
    CHECK(j["pool_from"][0]["sha256"].get<std::string>().size() == 64);
    CHECK(own["pool_from"].empty());

    // A pool that is not the start's run is refused, exit 2, naming the file and why.
    const ProcessResult seed = calibrate("x.json", "stiffness_noise=0.02:3", {"--pool-from", dir.file("s2.csv")});
    CHECK(seed.exit_code == 2);
    CHECK(contains(seed.err, "--pool-from " + dir.file("s2.csv") + ": run with seed 2, the evaluations with 1"));
    // The protocol's own stiffness_noise (0.1) below these bounds: the start is moved, not the file's.
    const ProcessResult moved = calibrate("x.json", "stiffness_noise=0.5:3", {"--pool-from", dir.file("start.csv")});
    CHECK(moved.exit_code == 2);
    CHECK(contains(moved.err, "outside the inner 98 % of the bounds"));
    const ProcessResult few = run_contactlab({"experiment", "calibrate", dir.file("small.json"), "--target", dir.file("t.json"), "--param",
                                              "stiffness_noise=0.02:3", "--fit", "phi e0.40", "--participants", "3", "--json",
                                              dir.file("x.json"), "--pool-from", dir.file("start.csv")});
    CHECK(few.exit_code == 2);
    CHECK(contains(few.err, "holds 2 participants, 3 asked"));
    CHECK_FALSE(std::filesystem::exists(dir.file("x.json")));
}

namespace {
// Seed 002's task in small: force alone, a few trials, the hand that moves by feel fitted.
const char* kSlide = R"({"format": "contactlab experiment protocol", "version": 1, "name": "small 002", "seed": "002",
  "task": "bump-counting", "conditions": [{"name": "F", "contact_location": false}], "stimuli": [0, 1, 2], "trials": 3,
  "answers": ["0", "1", "2"], "hand": {"speed": 0.05, "press": 0.003}, "finger": {"radius": 0.020, "length": 0.020},
  "force": {"stiffness": 1300, "max_force": 1.5}, "bumps": {"small": 0.003, "large": 0.018, "length": 0.184, "base_span": 0.02},
  "participant": {"hand": {"slide_speed_mps": 0.05}}})";
// A time per trial the start (50 mm/s over 16.4 cm, over 3 s with no bump and more with them)
// cannot give: only a faster slide reaches it.
const char* kSlideTargets = R"({"format": "contactlab calibration targets", "version": 1, "targets": [
  {"name": "time F", "protocol": "slide.json", "figure": "/conditions/F/time_s/mean", "value": 1.5, "scale": 0.5, "source": "made up for the test"},
  {"name": "breaks F", "protocol": "slide.json", "figure": "/conditions/F/contact_breaks/mean", "value": 4.9, "scale": 1.2, "source": "held out"}]})";
}  // namespace

TEST_CASE("experiment calibrate --hand feel: the feel hand's free speed fitted to a time per trial, breaks held out") {
    TempDir dir;
    write_text(dir.file("slide.json"), kSlide);
    write_text(dir.file("t.json"), kSlideTargets);
    auto run = [&](std::vector<std::string> extra) {
        std::vector<std::string> args = {"experiment", "calibrate", dir.file("slide.json"), "--target", dir.file("t.json"), "--param",
                                         "hand.slide_speed_mps=0.02:0.2", "--fit", "time F", "--participants", "2", "--evaluations",
                                         "8", "--jobs", "1", "--json", dir.file("c.json")};
        args.insert(args.end(), extra.begin(), extra.end());
        return run_contactlab(args);
    };
    // The protocol's own hand is the scripted one, which the feel hand's population does not move.
    const auto scripted = run({});
    CHECK(scripted.exit_code == 2);
    CHECK(contains(scripted.err, "give --hand feel"));
    const auto p = run({"--hand", "feel"});
    INFO(p.out << p.err);
    REQUIRE(p.exit_code == 0);
    const auto j = nlohmann::json::parse(read_text(dir.file("c.json")));
    CHECK(j["hand"] == "feel");
    CHECK(j["start"]["hand.slide_speed_mps"].get<double>() == doctest::Approx(0.05));  // the protocol's own
    // The time per trial falls as the free speed rises: the fit moves the speed up from its start,
    // and the time toward the target.
    CHECK(j["parameters"]["hand.slide_speed_mps"].get<double>() > 0.05 * 1.2);
    const auto& time = j["targets"][0];
    CHECK(time["fitted"] == true);
    CHECK(std::abs(time["simulated"].get<double>() - 1.5) < std::abs(time["start"].get<double>() - 1.5) - 0.5);
    CHECK(j["targets"][1]["fitted"] == false);
    CHECK(j["targets"][1]["simulated"].is_number());
}

TEST_CASE("experiment calibrate --hand feel on a task without such a hand exits 2 naming the protocol") {
    // Seed 004's person answers from a scripted press: --hand feel would fit nothing the hand does
    // while the runs' meta said feel.
    TempDir dir;
    write_text(dir.file("small.json"), kProtocol);
    write_text(dir.file("t.json"), kTargets);
    const auto p = run_contactlab({"experiment", "calibrate", dir.file("small.json"), "--target", dir.file("t.json"), "--param",
                                   "stiffness_noise=0.02:0.3", "--fit", "phi e0.40", "--participants", "2", "--evaluations", "4", "--hand", "feel",
                                   "--json", dir.file("c.json")});
    CHECK(p.exit_code == 2);
    CHECK(contains(p.err, "calibrate --hand feel: small.json is a surface-orientation protocol, whose simulated person has no hand"));
    CHECK_FALSE(std::filesystem::exists(dir.file("c.json")));
}
