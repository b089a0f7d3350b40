// test_switches.cpp — issue 15's switches, made while pressing, through the real editor under
// xvfb-run (--script): a servo rate change, the emergency stop engaged and released, a switch to
// sim-cld, and a scene edit under the finger. In each the surface survives: contact is kept, and
// the force ramps from 0 to Ke d over the safety ramp (0.2 s), never above Ke d. The servo's own
// tick records (`record FILE`) show the ramp tick by tick.
#include "csv.hpp"
#include "xvfb_editor.hpp"

#include <doctest/doctest.h>

#include <algorithm>
#include <cmath>

using namespace cli_test;
using namespace editor_test;

namespace {

constexpr double kKe = 1000.0;    // N/m, the new scene's stiffness
constexpr double kHand = 300.0;   // N/m, sim-cld's hand (drivers' HandParams)
constexpr double kRadius = 26.0;  // mm, the default finger radius
constexpr double kRamp = 0.2;     // s, SafetyParams::ramp_time
// sim-cld's joint friction and encoders (test_devices.cpp): the depth it settles at, +- this.
constexpr double kDepthTol = 0.015 + 0.04;  // mm

// A floor from x = -40 to 40 mm along y = 0, the mouse finger 1 mm into it at x = 0, settled.
const char* kPressed =
    "set snap_mm 1\ntool line\nclick -40 0\nclick 40 0\nrclick 40 0\n"
    "finger 0 40 0\nwait_state engaged 5\n"
    "finger 0 25 0\nwait_contact 3\nwait 0.3\n"
    "expect depth 1 0.000001\nexpect force 1 0.000001\n";

// The recording's columns: t,x,y,phi,roller_l,fx,fy,roller_drive,state,fault.
constexpr int kT = 0, kFx = 5, kFy = 6, kState = 8;

// A ramp in a recording: from the first row with force to the end, |F| rises to `steady` (N)
// within the ramp time, never falls (the finger is held still) and never passes it.
void check_recorded_ramp(const Csv& take, double steady) {
    REQUIRE(take.rows.size() > 50);
    std::size_t first = 0;
    while (first < take.rows.size() && std::hypot(take.rows[first][kFx], take.rows[first][kFy]) == 0.0) ++first;
    REQUIRE(first < take.rows.size());
    double prev = 0.0, highest = 0.0, full_at = -1.0;
    int drops = 0, zeros = 0;
    for (std::size_t i = first; i < take.rows.size(); ++i) {
        const double f = std::hypot(take.rows[i][kFx], take.rows[i][kFy]);
        if (f < prev - 1e-12) ++drops;
        if (f == 0.0) ++zeros;  // contact lost, or force dropped
        if (full_at < 0.0 && f >= steady * (1.0 - 1e-9)) full_at = take.rows[i][kT];
        highest = std::max(highest, f);
        prev = f;
    }
    CHECK(drops == 0);
    CHECK(zeros == 0);
    CHECK(highest <= steady * (1.0 + 1e-9));
    REQUIRE(full_at >= 0.0);
    // The ramp is linear in the servo's time: its end lies within the ramp time of its first row.
    CHECK(full_at - take.rows[first][kT] <= kRamp + 2e-3);
    CHECK(prev == doctest::Approx(steady).epsilon(1e-9));
}

}  // namespace

TEST_CASE("switches while pressing: a servo rate change keeps the surface and ramps back to Ke d") {
    TempDir dir;
    const std::string script = dir.file("rate.txt"), rec = dir.file("rate.csv");
    write_text(script, std::string(kPressed) +
                           "rate 5000\n"
                           "record " + rec + "\n"
                           "wait 0.5\n"
                           "record stop\n"
                           "expect rate 5000\nexpect contact 1\nexpect depth 1 0.000001\nexpect force 1 0.000001\n"
                           "quit\n");
    setenv("TMPDIR", dir.path().c_str(), 1);
    const auto p = run_under_xvfb({"edit", "--script", script, "--software", "--timeout", "100"});
    INFO("stderr: " << p.err);
    CHECK(p.exit_code == 0);
    CHECK_FALSE(contains(p.err, "FAILED"));
    const Csv take = parse_csv(read_text(rec));
    check_recorded_ramp(take, kKe * 0.001);
    // The record began within the ramp (a frame after the switch): it starts below Ke d.
    CHECK(std::hypot(take.rows.front()[kFx], take.rows.front()[kFy]) < kKe * 0.001);
}

TEST_CASE("switches while pressing: the emergency stop released brings the force back to Ke d, no kick") {
    TempDir dir;
    const std::string script = dir.file("estop.txt"), rec = dir.file("estop.csv");
    write_text(script, std::string(kPressed) +
                           "estop on\nwait 0.2\n"
                           "expect force_below 0.000001\nexpect contact 1\nexpect depth 1 0.000001\n"
                           "record " + rec + "\n"
                           "wait 0.1\n"
                           "estop off\n"
                           "wait 0.4\n"
                           "record stop\n"
                           "expect stopped 0\nexpect contact 1\nexpect force 1 0.000001\n"
                           "quit\n");
    setenv("TMPDIR", dir.path().c_str(), 1);
    const auto p = run_under_xvfb({"edit", "--script", script, "--software", "--timeout", "100"});
    INFO("stderr: " << p.err);
    CHECK(p.exit_code == 0);
    CHECK_FALSE(contains(p.err, "FAILED"));
    const Csv take = parse_csv(read_text(rec));
    // Stopped rows first (zero force, state idle), then the whole ramp.
    REQUIRE(take.rows.size() > 50);
    CHECK(take.rows.front()[kState] == 0.0);
    CHECK(take.rows.front()[kFy] == 0.0);
    check_recorded_ramp(take, kKe * 0.001);
}

TEST_CASE("switches while pressing: to sim-cld, the finger settles where the hand and the wall balance") {
    TempDir dir;
    const std::string script = dir.file("device.txt");
    write_text(script, std::string(kPressed) +
                           "device sim-cld\n"
                           "expect device sim-cld\n"
                           "wait 1.0\n"
                           "report settled\n"
                           "quit\n");
    setenv("TMPDIR", dir.path().c_str(), 1);
    const auto p = run_under_xvfb({"edit", "--script", script, "--software", "--timeout", "100"});
    INFO("stderr: " << p.err);
    CHECK(p.exit_code == 0);
    CHECK_FALSE(contains(p.err, "FAILED"));
    const auto s = report(p.err, "settled");
    CHECK(s.at("servo_state") == "engaged");
    REQUIRE(num(s, "contact") == 1);
    // The cursor 1 mm in; the hand's spring and the wall in series: d = K_hand d_c / (K_hand + Ke).
    const double expected = kHand * (kRadius - 25.0) / (kHand + kKe);  // mm: 0.231
    MESSAGE("sim-cld after the switch: depth " << num(s, "depth_mm") << " mm (expected " << expected << ")");
    CHECK(std::abs(num(s, "depth_mm") - expected) < kDepthTol);
    CHECK(std::abs(num(s, "force_n") - kKe * num(s, "depth_mm") * 1e-3) < 1e-6);
}

TEST_CASE("switches while pressing: a scene edit under the finger changes the force by the geometry only") {
    TempDir dir;
    const std::string script = dir.file("edit.txt");
    // The floor's right end raised 0.4 mm: at x = 0 the floor rises 0.2 mm, so the depth goes from
    // 1 mm to 26 - (25 - 0.2) cos(atan(0.005)) = 1.2003 mm.
    write_text(script, std::string(kPressed) +
                           "set snap_mm 0\n"
                           "tool select\n"
                           "drag 40 0 40 0.4\n"
                           "tool finger\n"
                           "finger 0 25 0\n"
                           "wait 0.3\n"
                           "report edited\n"
                           "quit\n");
    setenv("TMPDIR", dir.path().c_str(), 1);
    const auto p = run_under_xvfb({"edit", "--script", script, "--software", "--timeout", "100"});
    INFO("stderr: " << p.err);
    CHECK(p.exit_code == 0);
    CHECK_FALSE(contains(p.err, "FAILED"));
    const auto s = report(p.err, "edited");
    REQUIRE(num(s, "contact") == 1);
    const double depth = kRadius - (25.0 - 0.2) * std::cos(std::atan(0.4 / 80.0));  // mm
    CHECK(num(s, "depth_mm") == doctest::Approx(depth).epsilon(1e-6));
    CHECK(num(s, "force_n") == doctest::Approx(kKe * depth * 1e-3).epsilon(1e-6));
}
