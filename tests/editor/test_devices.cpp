// test_devices.cpp — the editor's live devices, run for real under xvfb-run with lavapipe: the
// simulated CLD whose hand follows a scripted cursor into contact (force = Ke * depth, depth from
// the hand and the wall in series), a recording made in the editor replayed by `contactlab
// simulate --device replay:FILE` and by the editor's own replay device, and servo rate changes.
#include "csv.hpp"
#include "haptics/scene_io.hpp"
#include "xvfb_editor.hpp"

#include <doctest/doctest.h>

#include <cmath>

using namespace cli_test;
using namespace editor_test;

namespace {

// Physics of the cursor-held sim-cld (engine/editor/cursor_cld_device.hpp) and the scene below.
constexpr double kHand = 300.0;     // N/m, the hand's stiffness (drivers' HandParams)
constexpr double kKe = 1000.0;      // N/m, the scene's stiffness (the default)
constexpr double kRadius = 26.0;    // mm, the default finger radius: the c-space floor is y = 26 mm
// What the arm's Coulomb joint friction (2 mN m on each joint, a 0.2 m forearm) can hold against
// the hand: ~0.02 N, i.e. 0.07 mm of hand-spring stretch in free space and 0.015 mm of depth in
// contact; the encoders quantise the finger to 2 pi / 65536 rad * 0.4 m = 0.04 mm.
constexpr double kFreeTol = 0.07 + 0.04;     // mm
constexpr double kDepthTol = 0.015 + 0.04;   // mm

// A floor from x = -40 to 40 mm along y = 0 (solid below), drawn with the line tool.
const char* kFloor = "set snap_mm 1\ntool line\nclick -40 0\nclick 40 0\nrclick 40 0\n";

}  // namespace

TEST_CASE("sim-cld in the editor: the finger follows the cursor into contact, force = Ke * depth") {
    TempDir dir;
    const std::string script = dir.file("simcld.txt");
    write_text(script, std::string(kFloor) +
                           "finger 0 40 0\n"
                           "device sim-cld\n"
                           "expect device sim-cld\n"
                           "wait_state engaged 5\n"
                           "finger 10 40 0\n"
                           "wait 1.0\n"
                           "report free\n"
                           "# The cursor 5 mm into the floor: the finger stops near the surface.\n"
                           "finger 10 21 0\n"
                           "wait_contact 3\n"
                           "wait 1.0\n"
                           "report contact\n"
                           "key space\nwait 0.05\nexpect force_below 0.000001\n"
                           "# A switch keeps the emergency stop engaged; released with the mouse finger 5 mm\n"
                           "# inside the floor, the new servo has the old proxy (on the surface): the force\n"
                           "# ramps in to Ke d = 5 N, clamped at the scene's 1.5 N, without a kick.\n"
                           "device mouse\nexpect stopped 1\nexpect state idle\n"
                           "key space\nwait 0.3\nexpect stopped 0\nexpect contact 1\nexpect force 1.5 0.000001\n"
                           "quit\n");
    const auto p = run_validated_script(script, dir.path());
    INFO("stderr: " << p.err);
    CHECK(p.exit_code == 0);
    CHECK_FALSE(contains(p.err, "FAILED"));
    CHECK(contains(p.err, "validation layers on, 0 messages"));

    const auto free = report(p.err, "free");
    CHECK(free.at("device") == "sim-cld");
    CHECK(free.at("device_state") == "engaged");
    CHECK(num(free, "contact") == 0);
    // Free space, at rest: the finger is where the hand (the cursor) holds it.
    CHECK(std::abs(num(free, "finger_x_mm") - 10.0) < kFreeTol);
    CHECK(std::abs(num(free, "finger_y_mm") - 40.0) < kFreeTol);
    CHECK(num(free, "force_n") == 0.0);

    const auto c = report(p.err, "contact");
    REQUIRE(num(c, "contact") == 1);
    // Hand spring and wall in series: depth = K_hand d_c / (K_hand + Ke), d_c = 5 mm.
    const double d_c = kRadius - 21.0;                        // mm
    const double depth_expected = kHand * d_c / (kHand + kKe);  // mm: 1.154
    const double depth = num(c, "depth_mm");
    MESSAGE("sim-cld depth " << depth << " mm (expected " << depth_expected << "), |F| " << num(c, "force_n") << " N");
    CHECK(std::abs(depth - depth_expected) < kDepthTol);
    // The rendered spring: |F| = Ke * depth (the finger at rest: no damping force, below 1.5 N).
    CHECK(std::abs(num(c, "force_n") - kKe * depth * 1e-3) < 1e-6);
    // The finger is the simulation's: it stopped at the surface while the cursor went 5 mm in.
    CHECK(std::abs(num(c, "finger_y_mm") - (kRadius - depth)) < 1e-9 + 1e-6);
    CHECK(num(c, "cursor_y_mm") == doctest::Approx(21.0));
}

TEST_CASE("a recording made in the editor replays the same finger trajectory") {
    TempDir dir;
    const std::string script = dir.file("rec.txt"), rec = dir.file("take.csv"), scene_file = dir.file("floor.json");
    write_text(script, std::string(kFloor) + "save " + scene_file +
                           "\nfinger 0 40 0\n"
                           "device sim-cld\n"
                           "wait_state engaged 5\n"
                           "record " + rec + "\n"
                           "expect recording 1\n"
                           "finger 5 30 0\nwait 0.3\nfinger 10 22 0\nwait 0.4\nfinger 15 35 0\nwait 0.3\n"
                           "record stop\n"
                           "expect recording 0\n"
                           "# Played back in the editor: the replay holds its last sample at the end.\n"
                           "device replay " + rec + "\n"
                           "expect device replay:" + rec + "\n"
                           "wait 2.5\n"
                           "report replayed\n"
                           "# Recording over the file being replayed would destroy it: refused.\n"
                           "record " + rec + "\nexpect error 1\nexpect recording 0\n"
                           "device replay " + dir.file("missing.csv") + "\n"
                           "quit\n");
    const auto p = run_validated_script(script, dir.path());
    INFO("stderr: " << p.err);
    // The two expected failures: recording over the take being replayed, and a recording that
    // does not exist, named in the message.
    CHECK(p.exit_code == 1);
    CHECK(contains(p.err, "script " + script + ":29: FAILED: device replay: " + dir.file("missing.csv") + ": cannot open"));
    CHECK(contains(p.err, "script " + script + ":26: FAILED: refused: " + rec + " is the file being replayed"));
    CHECK(contains(p.err, "check(s) failed"));
    CHECK(contains(p.err, ": 2 check(s) failed"));

    const Csv take = parse_csv(read_text(rec));
    CHECK(take.header == "t,x,y,phi,roller_l,fx,fy,roller_drive,state,fault");
    // About a second of ticks at 1 kHz (the UI forwards every tick it drains).
    REQUIRE(take.rows.size() > 500);
    double max_force = 0.0;
    for (const auto& r : take.rows) max_force = std::max(max_force, std::hypot(r[5], r[6]));
    CHECK(max_force > 0.5);  // the take went into contact (cursor 4 mm into the floor)

    // The editor's replay ended on the recording's last finger position, exactly.
    const auto end = report(p.err, "replayed");
    CHECK(end.at("device") == "replay:" + rec);
    CHECK(num(end, "finger_x_mm") == doctest::Approx(take.rows.back()[1] * 1e3).epsilon(1e-12));
    CHECK(num(end, "finger_y_mm") == doctest::Approx(take.rows.back()[2] * 1e3).epsilon(1e-12));

    // `contactlab simulate --device replay:FILE`: the same trajectory, row for row, to the bit.
    const std::string out = dir.file("replayed.csv");
    const auto sim = run_contactlab({"simulate", scene_file, "--device", "replay:" + rec, "--output", out});
    INFO("simulate stderr: " << sim.err);
    REQUIRE(sim.exit_code == 0);
    const Csv replayed = parse_csv(read_text(out));
    REQUIRE(replayed.rows.size() == take.rows.size());
    std::size_t differing = 0;
    for (std::size_t i = 0; i < take.rows.size(); ++i)
        for (int col : {0, 1, 2, 3})  // t, x, y, phi
            if (replayed.rows[i][col] != take.rows[i][col]) ++differing;
    CHECK(differing == 0);
}

TEST_CASE("servo rate: changing it restarts the servo safely and the period statistics follow") {
    TempDir dir;
    const std::string script = dir.file("rate.txt");
    write_text(script, std::string(kFloor) +
                           "finger 0 40 0\n"
                           "device sim-cld\n"
                           "wait_state engaged 5\n"
                           "rate 5000\n"
                           "expect rate 5000\n"
                           "expect device sim-cld\n"
                           "wait_state engaged 5\n"
                           "finger 0 21 0\n"
                           "wait_contact 3\n"
                           "wait 1.5\n"
                           "report fast\n"
                           "finger 0 40 0\nwait 0.5\n"
                           "rate 200\n"
                           "wait_state engaged 5\n"
                           "wait 1.5\n"
                           "report slow\n"
                           "rate 50\n"
                           "expect rate 200\n"
                           "quit\n");
    const auto p = run_validated_script(script, dir.path());
    INFO("stderr: " << p.err);
    // The one expected failure: 50 Hz is refused, naming the range, and the servo carries on.
    CHECK(p.exit_code == 1);
    CHECK(contains(p.err, "FAILED: servo rate 50 Hz: must be between 100 and 20000 Hz"));
    CHECK(contains(p.err, ": 1 check(s) failed"));

    const auto fast = report(p.err, "fast");
    CHECK(num(fast, "rate_hz") == 5000.0);
    // The median tick-to-tick period is the nominal one (the 100 ns histogram bins of the drain's
    // statistics, and the clock's wake-up latency of a few us, bound the difference).
    CHECK(std::abs(num(fast, "p50_us") - 200.0) < 20.0);
    // Same equilibrium at 5 kHz: the rate changes the sampling, not the springs.
    const double depth_expected = kHand * (kRadius - 21.0) / (kHand + kKe);  // mm
    CHECK(num(fast, "contact") == 1);
    CHECK(std::abs(num(fast, "depth_mm") - depth_expected) < kDepthTol);
    CHECK(std::abs(num(fast, "force_n") - kKe * num(fast, "depth_mm") * 1e-3) < 1e-6);

    const auto slow = report(p.err, "slow");
    CHECK(num(slow, "rate_hz") == 200.0);
    CHECK(std::abs(num(slow, "p50_us") - 5000.0) < 50.0);
    CHECK(slow.at("servo_state") == "engaged");
}

TEST_CASE("the device menu lists the USB models, and one that cannot open leaves the mouse running") {
    TempDir dir;
    const std::string script = dir.file("usb.txt");
    write_text(script, "devices\ndevice sim-cld\nwait_state engaged 5\ndevice usb:hapio\nexpect device mouse\n"
                       "wait_state engaged 5\nexpect device_state engaged\nquit\n");
    const auto p = run_validated_script(script, dir.path());
    INFO("stderr: " << p.err);
    for (const char* spec : {"mouse", "sim-cld", "replay:"}) CHECK(contains(p.err, std::string("script device option ") + spec + ": available"));
    for (const char* spec : {"usb:hapio", "usb:falcon"}) {
        const auto at = p.err.find(std::string("script device option ") + spec + ": ");
        REQUIRE(at != std::string::npos);
        const std::string line = p.err.substr(at, p.err.find('\n', at) - at);
        // Either usable, or disabled with a reason (this machine's USB bus decides which).
        CHECK((contains(line, ": available") || line.size() > line.find("unavailable: ") + 20));
    }
    const bool hapio_present = contains(p.err, "script device option usb:hapio: available");
    if (!hapio_present) {
        // No board: the switch fails with the reason, the mouse runs, armed again.
        CHECK(p.exit_code == 1);
        CHECK(contains(p.err, "FAILED: device usb:hapio did not open (not found"));
        CHECK(contains(p.err, "the mouse drives the finger"));
        CHECK(contains(p.err, "ok: device = mouse"));
        CHECK(contains(p.err, "ok: device_state = engaged"));
    }
}

TEST_CASE("edit --device: the servo starts on the device asked for, or says why and keeps the mouse") {
    TempDir dir;
    const std::string script = dir.file("device.txt");
    write_text(script, "expect device sim-cld\nwait_state engaged 5\nquit\n");
    const auto p = run_under_xvfb({"edit", "--device", "sim-cld", "--script", script, "--software", "--validation",
                                   "--timeout", "60"});
    INFO("stderr: " << p.err);
    CHECK(p.exit_code == 0);
    CHECK_FALSE(contains(p.err, "FAILED"));
    // No hapio board on this bus (the emulated ones live in the usb tests): named, and the mouse runs.
    const std::string fallback = dir.file("fallback.txt");
    write_text(fallback, "expect device mouse\nexpect error 1\nquit\n");
    const auto q = run_under_xvfb({"edit", "--device", "usb:hapio", "--script", fallback, "--software", "--timeout", "60"});
    INFO("stderr: " << q.err);
    CHECK(q.exit_code == 0);
    CHECK(contains(q.err, "--device usb:hapio"));
    CHECK(contains(q.err, "the mouse drives the finger"));
    // A replay file that does not exist: named, and the mouse runs.
    const auto r = run_under_xvfb({"edit", "--device", "replay:" + dir.file("missing.csv"), "--script", fallback,
                                   "--software", "--timeout", "60"});
    INFO("stderr: " << r.err);
    CHECK(r.exit_code == 0);
    CHECK(contains(r.err, "missing.csv"));
}

TEST_CASE("sim-wearable in the editor: the cursor is the finger and the platform tilts to the floor under it") {
    TempDir dir;
    const std::string script = dir.file("wearable.txt"), shot = dir.file("wearable.png");
    // The finger 1.5 mm into the floor and tilted by 11.46 deg (0.2 rad): the platform shows the
    // floor sloping away from the fingertip (roll -0.2 rad) and presses 1.5 N / 2 N/mm = 0.75 mm.
    write_text(script, std::string(kFloor) +
                           "finger 0 40 0\n"
                           "device sim-wearable\n"
                           "expect device sim-wearable\n"
                           "wait_state engaged 5\n"
                           "finger 0 24.5 11.459155902616465\n"
                           "wait_contact 3\n"
                           "wait 1.5\n"
                           "report wearable\n"
                           "screenshot " + shot + "\n"
                           "quit\n");
    const auto p = run_validated_script(script, dir.path());
    INFO("stderr: " << p.err);
    CHECK(p.exit_code == 0);
    CHECK_FALSE(contains(p.err, "FAILED"));
    CHECK(contains(p.err, "validation layers on, 0 messages"));
    const auto w = report(p.err, "wearable");
    CHECK(w.at("device") == "sim-wearable");
    CHECK(num(w, "contact") == 1);
    // The cursor is the finger (no kinesthetic feedback moves it).
    CHECK(num(w, "finger_y_mm") == doctest::Approx(24.5).epsilon(1e-9));
    MESSAGE("platform roll " << num(w, "platform_roll_rad") << " rad, press " << num(w, "platform_press_mm") << " mm");
    // Within the position loop's and the FSR noise's ~0.02 rad (tests/drivers, curvature task).
    CHECK(std::abs(num(w, "platform_roll_rad") + 0.2) < 0.03);
    CHECK(num(w, "platform_press_mm") == doctest::Approx(0.75).epsilon(0.2));
    CHECK(num(w, "platform_tension_n") > 0.0);
    CHECK(fs::exists(shot));
}

TEST_CASE("a scene asking for the passivity controller on the mouse, which has no effective mass, is told so") {
    TempDir dir;
    std::string text = read_text((source_dir() / "scenes/block.json").string());
    const std::string key = "\"force\": {";
    REQUIRE(text.find(key) != std::string::npos);
    text.insert(text.find(key) + key.size(), " \"passivity\": \"control\",");
    const std::string scene_path = dir.file("control.json");
    write_text(scene_path, text);
    // The status line carries the warning as an error; the same scene without "control" none.
    const std::string script = dir.file("s.txt");
    write_text(script, "wait_state engaged 5\nframes 3\nexpect error 1\nquit\n");
    const auto p = run_under_xvfb({"edit", scene_path, "--script", script, "--software", "--timeout", "60"});
    INFO("stderr: " << p.err);
    CHECK(p.exit_code == 0);
    CHECK_FALSE(contains(p.err, "FAILED"));
    const std::string plain = dir.file("p.txt");
    write_text(plain, "wait_state engaged 5\nframes 3\nexpect error 0\nquit\n");
    const auto q = run_under_xvfb({"edit", (source_dir() / "scenes/block.json").string(), "--script", plain, "--software",
                                   "--timeout", "60"});
    INFO("stderr: " << q.err);
    CHECK(q.exit_code == 0);
    CHECK_FALSE(contains(q.err, "FAILED"));
}
