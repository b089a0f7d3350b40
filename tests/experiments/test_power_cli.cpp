// test_power_cli.cpp — the real `contactlab experiment power`: a pool simulated through the servo
// (seed 003's protocol on the CLD rig, 3 participants), resampled; its JSON, provenance, report, reuse of the
// pool, and errors.
#include "process.hpp"

#include <doctest/doctest.h>
#include <nlohmann/json.hpp>

#include <filesystem>

using namespace cli_test;

TEST_CASE("experiment power: a pool through the servo, power per group size with provenance and a plot") {
    TempDir dir;
    const std::string proto = (source_dir() / "scenes/experiments/003-curvature-cld.json").string();
    const std::vector<std::string> args = {"experiment", "power", proto, "--measure", "proportion_correct", "--participants", "2-5",
                                           "--pool", "3", "--resamples", "300", "--seed", "4", "--jobs", "2",
                                           "--json", dir.file("p.json"), "--report", dir.file("rep")};
    const auto p = run_contactlab(args);
    INFO("stderr: " << p.err);
    REQUIRE(p.exit_code == 0);
    const auto j = nlohmann::json::parse(read_text(dir.file("p.json")));
    CHECK(j["measure"] == "proportion_correct");
    CHECK(j["pool"] == 3);
    CHECK(j["resamples"] == 300);
    CHECK(j["conditions"] == nlohmann::json::array({"A", "B"}));
    REQUIRE(j["points"].size() == 4);
    for (std::size_t i = 0; i < 4; ++i) {
        const auto& pt = j["points"][i];
        CHECK(pt["participants"] == static_cast<int>(i) + 2);
        const double power = pt["power"].get<double>();
        CHECK(power >= 0.0);
        CHECK(power <= 1.0);
        CHECK(pt["power_ci"][0].get<double>() <= power);
        CHECK(pt["power_ci"][1].get<double>() >= power);
        // The share is a count over the resamples.
        CHECK(pt["significant"].get<double>() == doctest::Approx(power * 300));
    }
    // The pool is an `experiment run` results file: its meta names the protocol and the device.
    CHECK(std::filesystem::exists(dir.file("p.pool.csv")));
    CHECK(j["pool_results"]["sha256"].get<std::string>().size() == 64);
    CHECK(j["pool_results"]["meta"]["device"] == "sim-cld");
    CHECK(j["pool_results"]["meta"]["protocol_sha256"].get<std::string>().size() == 64);
    CHECK(std::filesystem::exists(dir.file("rep/power.png")));
    CHECK(contains(read_text(dir.file("rep/report.md")), "| participants | power |"));
    // The same command again reuses the pool and gives the same figures.
    const auto again = run_contactlab(args);
    REQUIRE(again.exit_code == 0);
    CHECK(contains(again.err, "already complete"));
    CHECK(nlohmann::json::parse(read_text(dir.file("p.json")))["points"] == j["points"]);
}

TEST_CASE("experiment power: bad sizes, an unknown measure and a pool of another run exit 2 and say why") {
    TempDir dir;
    const std::string proto = (source_dir() / "scenes/experiments/003-curvature-cld.json").string();
    auto power = [&](std::vector<std::string> extra) {
        std::vector<std::string> a = {"experiment", "power", proto, "--pool", "2", "--resamples", "50", "--json", dir.file("p.json")};
        a.insert(a.end(), extra.begin(), extra.end());
        return run_contactlab(a);
    };
    const auto one = power({"--participants", "1-4"});
    CHECK(one.exit_code == 2);
    CHECK(contains(one.err, "a paired t test needs 2"));
    const auto measure = power({"--participants", "2-3", "--measure", "loudness"});
    CHECK(measure.exit_code == 2);
    CHECK(contains(measure.err, "no per-participant loudness"));
    // The pool file now holds that run (seed 1); another seed must not silently reuse or clobber it.
    const auto other = power({"--participants", "2-3", "--seed", "9"});
    CHECK(other.exit_code == 2);
    CHECK(contains(other.err, "--overwrite"));
}
