// test_simulate.cpp — `contactlab simulate`: the roller travel option (seed 002's 18 mm software
// range) and the roller bandwidth task, run through the real executable.
#include "trace_fixture.hpp"

#include <doctest/doctest.h>

#include <algorithm>
#include <cmath>

using namespace cli_test;

namespace {

struct SimRun {
    ProcessResult proc;
    Csv csv;
    bool output_exists = false;
    std::size_t col(const std::string& name) const {
        const std::vector<std::string> names = split_commas(csv.header);
        const auto it = std::find(names.begin(), names.end(), name);
        REQUIRE(it != names.end());
        return static_cast<std::size_t>(it - names.begin());
    }
};

// Runs `contactlab simulate SCENE --hand DIR/hand.csv --output DIR/out.csv EXTRA...`.
SimRun run_simulate(const TempDir& dir, const std::string& scene_path, const std::string& hand_text,
                    const std::vector<std::string>& extra) {
    const std::string hand = dir.file("hand.csv"), out = dir.file("out.csv");
    write_text(hand, hand_text);
    std::vector<std::string> args = {"simulate", scene_path, "--hand", hand, "--output", out};
    args.insert(args.end(), extra.begin(), extra.end());
    SimRun r;
    r.proc = run_contactlab(args);
    r.output_exists = fs::exists(out);
    if (r.proc.exit_code == 0 && r.output_exists) r.csv = parse_csv(read_text(out));
    return r;
}

// The hand comes down on scenes/flat.json, presses 2 mm in and tilts the finger to phi (rad):
// on a flat floor the contact sits at l = -R phi (DESIGN.md), here past -9 mm. The tilt takes 1 s,
// so l_d moves at R * 0.365 rad / 1 s = 9.5 mm/s, slow motion in seed 001's terms.
constexpr double kTilt = 0.365;  // rad: l_d = -0.026 m * 0.365 = -9.49 mm
std::string tilt_hand() {
    const double R = kFlatR;
    return samples_csv({{0.0, 0.0, R + 0.010, 0.0},
                        {0.3, 0.0, R - 0.002, 0.0},
                        {0.5, 0.0, R - 0.002, 0.0},
                        {1.5, 0.0, R - 0.002, kTilt},
                        {2.0, 0.0, R - 0.002, kTilt}});
}

}  // namespace

TEST_CASE("simulate --roller-travel 0.018 limits the roller to seed 002's 18 mm") {
    TempDir dir;
    const SimRun full = run_simulate(dir, scene("flat.json"), tilt_hand(), {});
    INFO("stderr: " << full.proc.err);
    REQUIRE(full.proc.exit_code == 0);
    const SimRun lim = run_simulate(dir, scene("flat.json"), tilt_hand(), {"--roller-travel", "0.018"});
    INFO("stderr: " << lim.proc.err);
    REQUIRE(lim.proc.exit_code == 0);
    CHECK(contains(lim.proc.err, "18.0 mm"));

    auto min_of = [](const SimRun& r, const std::string& name) {
        double m = 1e9;
        for (const auto& row : r.csv.rows) m = std::min(m, row[r.col(name)]);
        return m;
    };
    // Full travel: the target follows l_d = -R phi past the 18 mm range, to within one count of
    // the angle encoder (R * 2 pi / 4096 = 0.04 mm).
    const double l_full = -kFlatR * kTilt;  // m
    CHECK(std::abs(min_of(full, "roller_target") - l_full) < 0.04e-3);
    CHECK(min_of(full, "roller_target") < -0.009 - 0.4e-3);
    // 18 mm: the target stops exactly at -9 mm, the roller never runs past it by more than the
    // tracking error (seed 001: 0.05 mm, fast motion) and comes to rest there within seed 001's
    // slow-motion error (0.01 mm).
    CHECK(std::abs(min_of(lim, "roller_target") + 0.009) < 1e-12);
    CHECK(min_of(lim, "roller_l") > -0.009 - 0.05e-3);
    CHECK(std::abs(lim.csv.rows.back()[lim.col("roller_l")] + 0.009) < 0.01e-3);
}

TEST_CASE("simulate --roller-travel rejects lengths the device cannot give (exit 2, no output)") {
    for (const char* v : {"0", "-0.018", "0.0201", "0.5", "nan", "inf", "abc"}) {
        CAPTURE(v);
        TempDir dir;
        const SimRun r = run_simulate(dir, scene("flat.json"), tilt_hand(), {"--roller-travel", v});
        INFO("stderr: " << r.proc.err);
        CHECK(r.proc.exit_code == 2);
        CHECK(contains(r.proc.err, "--roller-travel"));
        CHECK_FALSE(r.output_exists);
    }
}

TEST_CASE("simulate --task roller-bandwidth prints the -3 dB frequency and writes the sweep") {
    TempDir dir;
    const std::string out = dir.file("bw.csv");
    const auto p = run_contactlab({"simulate", scene("block.json"), "--task", "roller-bandwidth", "--output", out});
    INFO("stderr: " << p.err);
    REQUIRE(p.exit_code == 0);
    const std::string key = "bandwidth (-3 dB) ";
    const std::size_t at = p.err.find(key);
    REQUIRE(at != std::string::npos);
    const double bw = std::strtod(p.err.c_str() + at + key.size(), nullptr);  // Hz
    const Csv csv = parse_csv(read_text(out));
    CHECK(csv.header == "freq,gain,phase_deg,element_gain,max_error");
    // The printed figure is the sweep's first crossing of 1/sqrt(2): every frequency below it is
    // above -3 dB and the next one measured above it is below (bisection to 0.01 Hz, printed to 0.01).
    const double half_power = 1.0 / std::sqrt(2.0);
    bool below_seen = false;
    for (const auto& row : csv.rows) {
        if (row[0] < bw - 0.01) CHECK(row[1] >= half_power);
        if (row[0] > bw + 0.01 && row[1] < half_power) below_seen = true;
    }
    CHECK(below_seen);
    // The seed band (tests/drivers/test_roller_tracking.cpp derives it): 7.5 .. 8.5 sqrt(2) Hz.
    CHECK(bw >= 7.5);
    CHECK(bw <= 8.5 * std::sqrt(2.0));
}

TEST_CASE("simulate --task roller-bandwidth refuses real time, a hand path and a travel too short for the sine") {
    TempDir dir;
    const std::string out = dir.file("bw.csv");
    for (const std::vector<std::string>& extra : std::vector<std::vector<std::string>>{
             {"--realtime"}, {"--hand", dir.file("none.csv")}, {"--roller-travel", "0.008"}, {"--device", "replay:x"}}) {
        std::vector<std::string> args = {"simulate", scene("block.json"), "--task", "roller-bandwidth", "--output", out};
        args.insert(args.end(), extra.begin(), extra.end());
        const auto p = run_contactlab(args);
        INFO("stderr: " << p.err << " extra: " << extra[0]);
        CHECK(p.exit_code == 2);
        CHECK(contains(p.err, "roller"));
        CHECK_FALSE(fs::exists(out));
    }
}

TEST_CASE("simulate runs the block task at the ends of the rate range without a fault") {
    // At 100 Hz a tick comes every 10 ms: the stall watchdogs (5 ms at 1 kHz and above) must
    // stretch to a few periods, or every tick would be a stall. The stiffness stays below the
    // passivity bound 2 b / T = 2 x 1.7 N s/m / 10 ms = 343 N/m there (the block's 1000 N/m is
    // above it and is rightly reported unstable).
    for (const char* rate : {"100", "20000"}) {
        CAPTURE(rate);
        TempDir dir;
        const std::string out = dir.file("out.csv");
        const auto p = run_contactlab({"simulate", scene("block.json"), "--task", "contour-block", "--rate", rate,
                                       "--stiffness", "250", "--output", out});
        INFO("stderr: " << p.err);
        CHECK(p.exit_code == 0);
        CHECK(contains(p.err, "state engaged, 0 fault(s)"));
    }
}

TEST_CASE("simulate: a hand path starting with the pad inside the floor is said, with its time and depth") {
    TempDir dir;
    const double R = kFlatR;
    const std::string inside = samples_csv({{0.0, 0.0, R - 0.002, 0.0}, {0.2, 0.0, R + 0.01, 0.0}});
    const SimRun r = run_simulate(dir, scene("flat.json"), inside, {});
    REQUIRE(r.proc.exit_code == 0);
    CHECK(r.proc.err.find("simulate: warning: the first hand sample (t = 0 s") != std::string::npos);
    CHECK(r.proc.err.find("2.000 mm inside a solid") != std::string::npos);
    const SimRun clear = run_simulate(dir, scene("flat.json"), tilt_hand(), {});
    REQUIRE(clear.proc.exit_code == 0);
    CHECK(clear.proc.err.find("warning") == std::string::npos);
}

TEST_CASE("simulate --task contour-block refuses a scene that is not seed 000's block, naming the probe it failed") {
    TempDir dir;
    for (const char* other : {"flat.json", "bowl.json", "steps.json"}) {
        CAPTURE(other);
        const std::string out = dir.file("out.csv");
        const auto p = run_contactlab({"simulate", scene(other), "--task", "contour-block", "-o", out});
        CHECK(p.exit_code == 2);
        CHECK(p.err.find("--task contour-block: the scene is not seed 000's block") != std::string::npos);
        CHECK(p.err.find(" m is ") != std::string::npos);  // the probe point that failed
        CHECK_FALSE(fs::exists(out));
    }
    const auto ok = run_contactlab({"simulate", scene("block.json"), "--task", "contour-block", "-o", dir.file("b.csv")});
    CHECK(ok.exit_code == 0);
}
