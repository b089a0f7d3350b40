// test_trial_profile.cpp — `experiment run --profile` (trial_profile.hpp): profiling changes no
// result, the virtual time it divides by is the trials' own (from their hand paths), and the
// stages add up to no more than the wall time they were taken from.
#include "engine/experiments/runs/experiment_run.hpp"
#include "engine/experiments/protocol/protocol.hpp"
#include "engine/experiments/base/trial_profile.hpp"
#include "process.hpp"

#include <doctest/doctest.h>

#include <filesystem>
#include <string>

using namespace contactlab::experiments;
using cli_test::TempDir;

namespace {

std::string protocol_path(const char* name) { return (cli_test::source_dir() / "scenes" / "experiments" / name).string(); }

RunSummary run(const Protocol& p, const std::string& out, bool profile) {
    RunOptions o;
    o.participants = {1};
    o.output = out;
    o.profile = profile;
    return run_experiment(p, o);
}

// Every stage is a time, and together they are the wall time they were split from: nothing is
// counted twice (the sum stays within the wall time, which also holds the loops around them).
void check_stages(const TrialProfile& t) {
    for (const double s : {t.stimulus, t.servo_scene, t.device, t.tick, t.records, t.platform, t.perception, t.files}) CHECK(s >= 0.0);
    const double staged = t.staged();
    CHECK(staged <= t.wall * (1.0 + 1e-9));
    CHECK(staged >= 0.5 * t.wall);  // the stages are the trials: the loops around them are small
}

}  // namespace

TEST_CASE("experiment run --profile: the rows and traces are the same bytes, and seed 002's virtual time is its hand paths'") {
    Protocol p = load_protocol(protocol_path("002-bump-counting.json"));
    p.hand_model = HandModel::scripted;  // its hand path's length is known in advance (below)
    p.trials = 3;
    p.warmup = 0;
    TempDir dir;
    const RunSummary plain = run(p, dir.file("plain.csv"), false);
    const RunSummary timed = run(p, dir.file("timed.csv"), true);
    REQUIRE(plain.rows == 6);  // 3 trials in each of 2 conditions
    CHECK(cli_test::read_text(dir.file("plain.csv")) == cli_test::read_text(dir.file("timed.csv")));
    namespace fs = std::filesystem;
    int traces = 0;
    for (const auto& e : fs::directory_iterator(dir.file("plain.csv.traces"))) {
        const std::string name = e.path().filename().string();
        CHECK(cli_test::read_text(e.path().string()) == cli_test::read_text(dir.file("timed.csv.traces/" + name)));
        ++traces;
    }
    CHECK(traces == 6);
    // Off, nothing is timed.
    CHECK(plain.profile.wall == 0.0);
    CHECK(plain.profile.trials == 0);
    CHECK(plain.profile.tick == 0.0);
    // On: each trial's hand path is 0.3 s down, 0.3 s settling, the slide over 0.164 m at 5 cm/s
    // (3.28 s) and a 0.2 s hold: 4.08 s of servo ticks at 1 kHz, to a tick or two of rounding.
    const TrialProfile& t = timed.profile;
    CHECK(t.trials == 6);
    CHECK(t.virtual_s == doctest::Approx(6 * 4.08).epsilon(0.003 / 4.08));
    CHECK(t.tick > 0.0);
    CHECK(t.device > 0.0);
    CHECK(t.stimulus > 0.0);
    CHECK(t.platform == 0.0);  // no wearable platform in seed 002
    check_stages(t);
    CHECK(profile_table(t).find("| servo tick |") != std::string::npos);
}

TEST_CASE("experiment run --profile: seed 003 on the wearable platform is timed as the platform, over its passes' time") {
    Protocol p = load_protocol(protocol_path("003-curvature.json"));
    p.repetitions = 1;
    TempDir dir;
    const RunSummary s = run(p, dir.file("r.csv"), true);
    const TrialProfile& t = s.profile;
    REQUIRE(s.rows == 6);  // 3 heights in each of tasks A and B
    CHECK(t.trials == 6);
    // Each pass moves the arc 0.30 m + 2 x 2 cm at 10 cm/s: 3.4 s, sampled every 10 ms (341
    // samples, each advancing the platform by one period).
    CHECK(t.virtual_s == doctest::Approx(6 * 3.41).epsilon(1e-9));
    CHECK(t.platform > 0.0);
    CHECK(t.tick == 0.0);  // the CLD rig's servo is not used
    CHECK(t.device == 0.0);
    check_stages(t);
}
