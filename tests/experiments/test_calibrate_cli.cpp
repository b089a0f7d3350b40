// test_calibrate_cli.cpp — the real `contactlab experiment calibrate`: a small protocol and a
// targets file, the fitted parameter and every target's figure as JSON and as a table, and bad
// options exit 2 naming them.
#include "process.hpp"

#include <doctest/doctest.h>
#include <nlohmann/json.hpp>

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
