// The servo loop against the simulated rig: virtual-time determinism, the watchdog on a stalled
// tick, record -> replay, and no NaN reaching the device.
#include "sim_fixture.hpp"

#include "drivers/record_writer.hpp"
#include "drivers/replay_device.hpp"

#include <doctest/doctest.h>

#include <cmath>
#include <cstdio>
#include <cstring>
#include <fstream>
#include <sstream>
#include <unistd.h>

using namespace contactlab;
using namespace contactlab::test;

namespace {

std::string slurp(const std::string& p) {
    std::ifstream in(p);
    std::stringstream ss;
    ss << in.rdbuf();
    return ss.str();
}

std::string temp_path(const char* name) {
    return "/tmp/contactlab_drivers_test_" + std::to_string(::getpid()) + "_" + name;
}

// Runs the block task in virtual time through the writer thread; returns the output file text.
std::string run_block(const std::string& out, const std::string& rec, double rate = 1000.0) {
    SpscRing<drivers::TickRecord> ring(256);  // small: the virtual loop must wait, not drop
    Scene scene = load_shipped_scene("block.json");
    drivers::sim::SimCldDevice dev({}, drivers::contour_block_task({}));
    ServoTick servo(drivers::servo_config_for(dev, rate), ServoParams{});
    servo.scenes().publish(std::make_unique<ServoScene>(scene));
    drivers::RecordWriter writer(ring, out, rec);
    drivers::ServoLoop loop(dev, servo, 1.0 / rate, &ring);
    REQUIRE(loop.start());
    loop.run_virtual(static_cast<std::uint64_t>(std::lround(dev.hand().path().end() * rate)));
    const drivers::RecordSummary sum = writer.finish();
    CHECK(loop.dropped_records() == 0);
    CHECK(sum.rows == loop.ticks());
    return slurp(out);
}

}  // namespace

TEST_CASE("virtual-time runs are bit-identical") {
    const std::string a = temp_path("a.csv"), b = temp_path("b.csv");
    const std::string ta = run_block(a, ""), tb = run_block(b, "");
    CHECK(ta.size() > 100000);
    CHECK(ta == tb);
    std::remove(a.c_str());
    std::remove(b.c_str());
}

TEST_CASE("a recording replays the finger trajectory exactly") {
    const std::string out = temp_path("out.csv"), rec = temp_path("rec.csv"), out2 = temp_path("out2.csv");
    run_block(out, rec);
    const auto samples = drivers::read_recording_file(rec);
    REQUIRE(samples.size() > 1000);
    drivers::ReplayDevice dev(samples);
    Scene scene = load_shipped_scene("block.json");
    ServoTick servo(drivers::servo_config_for(dev, 1000.0), ServoParams{});
    servo.scenes().publish(std::make_unique<ServoScene>(scene));
    drivers::ServoLoop loop(dev, servo, 1e-3);
    REQUIRE(loop.start());
    std::size_t mismatches = 0;
    for (std::size_t k = 0; k < samples.size(); ++k) {
        loop.step(1e-3, true);
        const ServoSnapshot s = servo.snapshot();
        const auto& r = samples[k];
        mismatches += (s.t != r.t || s.finger != r.finger || s.phi != r.phi || s.roller_l != r.roller_l) ? 1 : 0;
    }
    CHECK(mismatches == 0);
    std::remove(out.c_str());
    std::remove(rec.c_str());
}

TEST_CASE("the watchdog zeroes the force when the servo stalls, then force ramps back in") {
    const double R = 0.026;
    drivers::HandPath path({{0.0, {0.0, R + 0.005}, 0.0}, {0.3, {0.0, R - 0.002}, 0.0}, {3.0, {0.0, R - 0.002}, 0.0}});
    SimRig rig(floor_scene(1000.0), std::move(path));
    REQUIRE(rig.opened);
    rig.loop.run_virtual(1000);  // 1 s: pressing, engaged
    REQUIRE(rig.servo.snapshot().state == ServoState::engaged);
    const double pressing = glm::length(rig.device.applied_force());
    REQUIRE(pressing > 0.3);  // N: k_hand 300 N/m x 2 mm against Ke 1000 N/m -> ~0.46 N

    // Stall: 50 ms with no tick while the device keeps running (its physics, its clock).
    rig.loop.stall(0.05);
    CHECK(rig.device.watchdog_tripped());
    CHECK(glm::length(rig.device.applied_force()) == 0.0);

    // The next tick sees the device fault and holds zero; the servo then re-arms and ramps.
    rig.loop.step(1e-3, true);
    CHECK(rig.servo.snapshot().state == ServoState::fault);
    CHECK(glm::length(rig.servo.snapshot().force) == 0.0);
    double max_step = 0.0, prev = 0.0;
    for (int k = 0; k < 1500; ++k) {
        rig.loop.step(1e-3, true);
        const double f = glm::length(rig.servo.snapshot().force);
        max_step = std::max(max_step, std::abs(f - prev));
        prev = f;
    }
    // Re-engaging while pressed: the gate waits for a small force, so the hand (which keeps
    // pressing) sees no kick; whatever force returns comes through the ramp.
    CHECK(max_step < 0.05);  // N per tick
}

TEST_CASE("the servo's own stall detector faults on a gap in device time") {
    ServoConfig cfg;
    cfg.has_roller = false;
    ServoTick servo(cfg, ServoParams{});
    servo.scenes().publish(std::make_unique<ServoScene>(floor_scene()));
    servo.connect(0.0);
    ServoInput in;
    in.finger = {0.0, 0.03};
    for (int k = 0; k < 10; ++k) {
        in.t = k * 1e-3;
        servo.tick(in);
    }
    in.t = 0.1;  // 90 ms later
    const ServoCommand c = servo.tick(in);
    CHECK(servo.fault() == ServoFault::watchdog);
    CHECK(c.force == Vec2{0.0});
}

TEST_CASE("a hand path's interval answers as the path does inside it and holds nothing else") {
    const drivers::HandPath path({{0.0, {0.0, 0.010}, 0.1}, {0.001, {0.001, 0.011}, 0.2}, {0.002, {0.003, 0.0105}, 0.25}});
    const drivers::HandPath::Interval first = path.interval_at(0.0005);
    CHECK_FALSE(first.holds(0.0));  // the path holds its first sample there, at rest
    CHECK_FALSE(first.holds(0.001));
    CHECK_FALSE(first.holds(std::nan("")));
    for (const double t : {1e-9, 0.0003, 0.0009999}) {
        REQUIRE(first.holds(t));
        const drivers::PathPoint a = first.at(t), b = path.at(t);  // m, m/s, rad
        CHECK(a.x.x == doctest::Approx(b.x.x).epsilon(1e-15));
        CHECK(a.x.y == doctest::Approx(b.x.y).epsilon(1e-15));
        CHECK(a.v.x == doctest::Approx(b.v.x).epsilon(1e-15));  // 1 m/s along x
        CHECK(a.v.y == doctest::Approx(b.v.y).epsilon(1e-15));
        CHECK(first.phi_at(t) == doctest::Approx(path.phi_at(t)).epsilon(1e-15));
    }
    const drivers::HandPath::Interval second = path.interval_at(0.001);
    CHECK(second.holds(0.001));
    CHECK(second.at(0.0015).x.x == doctest::Approx(0.002).epsilon(1e-12));  // m, halfway
    CHECK(second.at(0.0015).v.x == doctest::Approx(2.0).epsilon(1e-12));    // m/s
    CHECK_FALSE(second.holds(0.002));
    CHECK_FALSE(path.interval_at(0.002).holds(0.002));  // the last sample: held by the path
    CHECK_FALSE(path.interval_at(-1.0).holds(-1.0));
}
