// test_simulate_wearable.cpp — `contactlab simulate --device sim-wearable --task ...`: seed 003's
// step, bandwidth and curvature experiments through the real executable, their JSON against the
// seed's figures (issue 17: within 20 %) and their refusals of bad options.
#include "trace_fixture.hpp"

#include <doctest/doctest.h>

#include <cmath>
#include <cstdlib>

using namespace cli_test;

namespace {
// The number after "key": in a flat JSON text (NaN when absent).
double json_number(const std::string& text, const std::string& key) {
    const std::string k = "\"" + key + "\": ";
    const std::size_t at = text.find(k);
    if (at == std::string::npos) return std::nan("");
    return std::strtod(text.c_str() + at + k.size(), nullptr);
}
}  // namespace

TEST_CASE("simulate wearable-step: rise about 0.1 s and steady error under 2 % in the JSON") {
    TempDir dir;
    const std::string out = dir.file("step.csv"), json = dir.file("step.json");
    const auto p = run_contactlab({"simulate", scene("flat.json"), "--device", "sim-wearable", "--task", "wearable-step",
                                   "--output", out, "--json", json});
    INFO("stderr: " << p.err);
    REQUIRE(p.exit_code == 0);
    const std::string j = read_text(json);
    CHECK(json_number(j, "rise_time_s") == doctest::Approx(0.1).epsilon(0.2));
    CHECK(json_number(j, "steady_error_pct") < 2.0);
    const Csv csv = parse_csv(read_text(out));
    CHECK(csv.header == "t,Q_r,Qhat_1,Qhat_2,Qhat_3,Q_1,Q_2,Q_3,fault");
    REQUIRE(csv.rows.size() == 800);
    CHECK(csv.rows.back()[1] == doctest::Approx(0.3));
    for (const auto& row : csv.rows) CHECK(row[8] == 0.0);  // no fault
}

TEST_CASE("simulate wearable-bandwidth: about 3.5 Hz, and the seed's 0.5 Hz sine written") {
    TempDir dir;
    const std::string out = dir.file("sine.csv"), json = dir.file("bw.json");
    const auto p = run_contactlab({"simulate", scene("flat.json"), "--device", "sim-wearable", "--task",
                                   "wearable-bandwidth", "--output", out, "--json", json});
    INFO("stderr: " << p.err);
    REQUIRE(p.exit_code == 0);
    CHECK(json_number(read_text(json), "bandwidth_hz") == doctest::Approx(3.5).epsilon(0.2));
    const Csv csv = parse_csv(read_text(out));
    REQUIRE_FALSE(csv.rows.empty());
    // Q_r = 0.15 sin(pi t) + 0.15 N: between 0 and 0.3 N.
    double lo = 1.0, hi = -1.0;
    for (const auto& row : csv.rows) {
        lo = std::min(lo, row[1]);
        hi = std::max(hi, row[1]);
    }
    CHECK(lo >= -1e-9);
    CHECK(hi <= 0.3 + 1e-9);
    CHECK(hi - lo > 0.29);
}

TEST_CASE("simulate curvature-arc: the generated arc's slope is followed by the platform's tilt") {
    TempDir dir;
    const std::string arc = dir.file("arc.json"), out = dir.file("arc.csv"), json = dir.file("arc.json.out");
    REQUIRE(run_contactlab({"generate", "arc", "--chord", "0.30", "--height", "0.02", "--output", arc}).exit_code == 0);
    const auto p = run_contactlab({"simulate", arc, "--device", "sim-wearable", "--task", "curvature-arc", "--output", out,
                                   "--json", json});
    INFO("stderr: " << p.err);
    REQUIRE(p.exit_code == 0);
    const std::string j = read_text(json);
    CHECK(json_number(j, "height_m") == doctest::Approx(0.02).epsilon(1e-9));
    CHECK(json_number(j, "radius_m") == doctest::Approx((0.0225 + 0.0004) / 0.04).epsilon(1e-6));
    CHECK(json_number(j, "tilt_rms_rad") < 0.1 * json_number(j, "max_surface_angle_rad"));
    const Csv csv = parse_csv(read_text(out));
    CHECK(csv.header == "t,contact_x,surface_angle,platform_tilt,platform_force,Q_1,Q_2,Q_3,contact,fault");
    int in_contact = 0;
    for (const auto& row : csv.rows)
        if (row[8] == 1.0) {
            ++in_contact;
            CHECK(std::abs(row[2]) <= json_number(j, "max_surface_angle_rad") + 1e-9);
        }
    CHECK(in_contact > 500);  // 0.30 m at 0.05 m/s, a row per 10 ms
}

TEST_CASE("simulate sim-wearable refuses a scene without an arc, real time, absurd FSR noise, and neither hand nor task") {
    TempDir dir;
    const std::string out = dir.file("x.csv");
    auto run = [&](std::vector<std::string> extra) {
        std::vector<std::string> args = {"simulate", scene("flat.json"), "--device", "sim-wearable", "--output", out};
        args.insert(args.end(), extra.begin(), extra.end());
        return run_contactlab(args);
    };
    const auto no_arc = run({"--task", "curvature-arc"});
    CHECK(no_arc.exit_code == 2);
    CHECK(contains(no_arc.err, "generate arc"));
    const auto rt = run({"--task", "wearable-step", "--realtime"});
    CHECK(rt.exit_code == 2);
    const auto noise = run({"--task", "wearable-step", "--fsr-noise", "5"});
    CHECK(noise.exit_code == 2);
    const auto none = run({});
    CHECK(none.exit_code == 2);
    CHECK(contains(none.err, "wearable-step"));
    CHECK_FALSE(fs::exists(out));
}

TEST_CASE("simulate sim-wearable with a hand path: the servo's contact tilts and presses the platform") {
    TempDir dir;
    const std::string hand = dir.file("hand.csv"), out = dir.file("out.csv");
    // Down 1.5 mm into scenes/flat.json's floor, then the finger tilts by 0.2 rad.
    write_text(hand, "t,x,y,phi\n0,0,0.036,0\n0.3,0,0.0245,0\n0.8,0,0.0245,0\n1.3,0,0.0245,0.2\n2.0,0,0.0245,0.2\n");
    const auto p = run_contactlab({"simulate", scene("flat.json"), "--device", "sim-wearable", "--hand", hand, "--output", out});
    INFO("stderr: " << p.err);
    REQUIRE(p.exit_code == 0);
    const std::string key = "roll ";
    const std::size_t at = p.err.find(key);
    REQUIRE(at != std::string::npos);
    const double roll = std::strtod(p.err.c_str() + at + key.size(), nullptr);  // rad
    CHECK(roll == doctest::Approx(-0.2).epsilon(0.15));
    CHECK(contains(p.err, "0 fault(s)"));
}
