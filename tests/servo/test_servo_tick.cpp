// The servo tick on plain structs: NaN guard, engage gate and ramp, scene swap continuity,
// slew-limited parameters, lock-free snapshots, the roller PID's saturation and anti-windup.
#include "sim_fixture.hpp"

#include <doctest/doctest.h>

#include <atomic>
#include <cmath>
#include <limits>
#include <random>
#include <thread>

using namespace contactlab;
using namespace contactlab::test;

namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();
constexpr double R = 0.026;  // m, the default finger radius

ServoConfig cfg_no_roller() {
    ServoConfig c;
    c.has_roller = false;
    return c;
}

// Ticks at 1 kHz from time t0 (s) pressing `depth` (m) into the floor y = 0.
ServoCommand press(ServoTick& s, double& t, double depth, int ticks) {
    ServoCommand c;
    ServoInput in;
    in.finger = {0.0, R - depth};
    for (int k = 0; k < ticks; ++k) {
        in.t = (t += 1e-3);
        c = s.tick(in);
    }
    return c;
}

}  // namespace

TEST_CASE("a NaN reading gives zero force and a fault, never a NaN command") {
    ServoTick s(ServoConfig{}, ServoParams{});
    s.scenes().publish(std::make_unique<ServoScene>(floor_scene()));
    s.connect(0.0);
    double t = 0.0;
    press(s, t, -0.005, 5);        // free space: engage
    ServoCommand c = press(s, t, 0.001, 400);
    REQUIRE(s.state() == ServoState::engaged);
    CHECK(c.force.y == doctest::Approx(1.0).epsilon(1e-6));  // Ke 1000 N/m x 1 mm

    std::mt19937 rng(7);
    const double bad[] = {kNaN, std::numeric_limits<double>::infinity(), -std::numeric_limits<double>::infinity()};
    for (int k = 0; k < 300; ++k) {
        ServoInput in;
        in.t = (t += 1e-3);
        in.finger = {0.0, R - 0.001};
        in.roller_l = 0.0;
        switch (rng() % 4) {
            case 0: in.finger.x = bad[rng() % 3]; break;
            case 1: in.finger.y = bad[rng() % 3]; break;
            case 2: in.phi = bad[rng() % 3]; break;
            default: in.roller_l = bad[rng() % 3]; break;
        }
        c = s.tick(in);
        CHECK(c.force == Vec2{0.0});
        CHECK(std::isfinite(c.roller_drive));
        CHECK(std::isfinite(c.roller_target));
        CHECK(s.state() == ServoState::fault);
    }
    CHECK(s.snapshot().fault == ServoFault::non_finite_input);
}

TEST_CASE("no kick: starting inside an object gives no force, and after a fault the force ramps back to Ke d within ramp_time") {
    ServoTick s(cfg_no_roller(), ServoParams{});
    s.scenes().publish(std::make_unique<ServoScene>(floor_scene()));
    s.connect(0.0);
    double t = 0.0;
    // Starting 3 mm deep the proxy has no history and starts at the finger: nothing pushes.
    CHECK(press(s, t, 0.003, 200).force == Vec2{0.0});
    press(s, t, -0.002, 400);  // out into free space: engaged by now
    REQUIRE(s.state() == ServoState::engaged);
    REQUIRE(press(s, t, 0.001, 50).force.y == doctest::Approx(1.0).epsilon(1e-6));

    // A fault while pressing 1 mm (a NaN reading), then valid readings, still 1 mm deep. The fault
    // holds zero for fault_hold; then the force ramps in at once, without waiting for the finger
    // to back off (the old engage rule left it at zero for as long as the finger stayed).
    ServoInput bad;
    bad.t = (t += 1e-3);
    bad.finger = {kNaN, 0.0};
    s.tick(bad);
    REQUIRE(s.state() == ServoState::fault);
    const double fault_t = t;
    const SafetyParams sp;  // the defaults: fault_hold, ramp_time 0.2 s
    CHECK(sp.ramp_time == 0.2);
    const double steady = 1000.0 * 0.001;  // N: Ke d
    double prev = 0.0, max_step = 0.0, ramp_start = -1.0, full_at = -1.0;
    bool contact_lost = false;
    for (int k = 0; k < 1200; ++k) {
        const ServoCommand c = press(s, t, 0.001, 1);
        contact_lost = contact_lost || !s.snapshot().contact;
        CHECK(c.force.y <= steady * (1.0 + 1e-9));  // never above the steady value: no kick
        CHECK(std::abs(c.force.x) < 1e-9);
        if (ramp_start < 0.0 && c.force.y > 0.0) ramp_start = t;
        if (full_at < 0.0 && c.force.y >= steady * (1.0 - 1e-9)) full_at = t;
        max_step = std::max(max_step, std::abs(c.force.y - prev));
        prev = c.force.y;
    }
    CHECK_FALSE(contact_lost);  // the proxy kept its history through the fault
    CHECK(s.state() == ServoState::engaged);
    // Zero through the hold, then from 0 to Ke d in ramp_time (to a tick).
    CHECK(ramp_start - fault_t >= sp.fault_hold - 1e-9);
    CHECK(ramp_start - fault_t <= sp.fault_hold + 2e-3 + 1e-9);
    CHECK(full_at - ramp_start <= sp.ramp_time + 1e-3 + 1e-9);
    CHECK(full_at - ramp_start >= sp.ramp_time - 2e-3 - 1e-9);
    // Per tick the ramp adds Ke d T / ramp_time = 5 mN.
    CHECK(max_step <= steady * 1e-3 / sp.ramp_time + 1e-9);
}

TEST_CASE("a scene swap in contact changes the force only by what the geometry changed") {
    ServoTick s(cfg_no_roller(), ServoParams{});
    s.scenes().publish(std::make_unique<ServoScene>(floor_scene()));
    s.connect(0.0);
    double t = 0.0;
    press(s, t, -0.005, 5);
    const ServoCommand before = press(s, t, 0.001, 400);
    REQUIRE(before.force.y == doctest::Approx(1.0).epsilon(1e-6));

    // Same geometry again: no step at all.
    s.scenes().publish(std::make_unique<ServoScene>(floor_scene()));
    const ServoCommand same = press(s, t, 0.001, 1);
    CHECK(s.snapshot().scene_swaps == 2);
    CHECK(glm::length(same.force - before.force) < 1e-9);

    // The floor raised by 0.2 mm: the force grows by Ke x 0.2 mm = 0.2 N, and no more.
    Scene raised = floor_scene();
    raised.contours[0].segments[0] = LineSegment{{-1.0, 0.0002}, {1.0, 0.0002}};
    s.scenes().publish(std::make_unique<ServoScene>(raised));
    const ServoCommand after = press(s, t, 0.001, 1);
    CHECK(after.force.y == doctest::Approx(1.2).epsilon(1e-6));
    CHECK(std::abs(after.force.x) < 1e-9);
    s.scenes().reclaim();  // the publisher frees the retired scene, off the servo thread
}

TEST_CASE("parameters apply at a tick boundary, stiffness slew-limited") {
    ServoParams p;
    p.stiffness_slew = 10000.0;  // N/m per s: 10 N/m per tick
    ServoTick s(cfg_no_roller(), p);
    s.scenes().publish(std::make_unique<ServoScene>(floor_scene()));
    s.connect(0.0);
    double t = 0.0;
    press(s, t, -0.005, 5);
    press(s, t, 0.001, 400);
    p.stiffness = 500.0;
    s.publish_params(p);
    const ServoCommand c1 = press(s, t, 0.001, 1);
    CHECK(s.snapshot().stiffness == doctest::Approx(990.0));
    CHECK(c1.force.y == doctest::Approx(0.99));
    press(s, t, 0.001, 100);
    CHECK(s.snapshot().stiffness == doctest::Approx(500.0));
}

TEST_CASE("snapshots read concurrently are never torn") {
    ServoTick s(cfg_no_roller(), ServoParams{});
    s.scenes().publish(std::make_unique<ServoScene>(floor_scene()));
    s.connect(0.0);
    std::atomic<bool> done{false};
    std::atomic<long> torn{0}, reads{0};
    std::thread reader([&] {
        while (!done.load()) {
            const ServoSnapshot snap = s.snapshot();
            // Each tick writes finger.x = t and phi = -t: a torn copy breaks the relation.
            if (snap.ticks > 0 && snap.finger.x != snap.t) torn.fetch_add(1);
            reads.fetch_add(1);
        }
    });
    ServoInput in;
    for (int k = 1; k <= 200000; ++k) {
        in.t = k * 1e-3;
        in.finger = {in.t, 1.0};
        s.tick(in);
    }
    done = true;
    reader.join();
    CHECK(torn.load() == 0);
    CHECK(reads.load() > 0);
}

TEST_CASE("roller PID: saturates, does not wind up, travel-limited, bumpless gain change") {
    RollerGains g;
    RollerController pid(g, {-0.01, 0.01});
    pid.reset(0.0);
    // A 5 mm step with the roller held (stuck): the drive saturates at max_drive and the
    // integral stays bounded by it, so releasing does not leave seconds of wound-up drive.
    for (int k = 0; k < 2000; ++k) CHECK(std::abs(pid.step(0.005, 0.0, 1e-3)) <= g.max_drive);
    CHECK(pid.saturated());
    // At the target now: proportional 0, derivative 0 after the filter settles: the output is
    // the integral alone and must be within one rail.
    double u = 0.0;
    for (int k = 0; k < 200; ++k) u = pid.step(0.005, 0.005, 1e-3);
    CHECK(std::abs(u) <= g.max_drive);
    // Target beyond travel is clamped.
    pid.step(0.05, 0.005, 1e-3);
    CHECK(pid.target() == doctest::Approx(0.01));
    // Changing Ki keeps the output continuous (integral stored in volts).
    pid.reset(0.0);
    for (int k = 0; k < 50; ++k) pid.step(0.0001, 0.0, 1e-3);
    const double before = pid.step(0.0001, 0.0, 1e-3);
    g.ki *= 3.0;
    pid.set_gains(g);
    const double after = pid.step(0.0001, 0.0, 1e-3);
    CHECK(std::abs(after - before) < 0.5);  // V: one tick of integration, no jump
    // Non-finite input: zero drive.
    CHECK(pid.step(kNaN, 0.0, 1e-3) == 0.0);
}

TEST_CASE("force clamp keeps direction, then per-axis saturation") {
    const Vec2 f = clamp_then_saturate({3.0, 4.0}, 1.5, {10.0, 10.0});
    CHECK(glm::length(f) == doctest::Approx(1.5));
    CHECK(f.y / f.x == doctest::Approx(4.0 / 3.0));
    const Vec2 g = clamp_then_saturate({3.0, 4.0}, 1.5, {0.5, 10.0});
    CHECK(g.x == doctest::Approx(0.5));
    CHECK(g.y == doctest::Approx(1.2));
    CHECK(clamp_then_saturate({kNaN, 1.0}, 1.5, {1.0, 1.0}) == Vec2{0.0});
}

TEST_CASE("roller travel: l_d is held within the usable travel, centred in the device's, changed live") {
    // Pressed 1 mm into the floor with the finger tilted by phi: the pad touches at l = -R phi
    // (seed 000), 6.5 mm at phi = -0.25 rad, inside the device's +-10 mm.
    ServoTick s(ServoConfig{}, ServoParams{});
    s.scenes().publish(std::make_unique<ServoScene>(floor_scene()));
    s.connect(0.0);
    double t = 0.0;
    ServoInput in;
    in.phi = -0.25;  // rad
    auto run = [&](double depth, int ticks) {
        ServoCommand c;
        in.finger = {0.0, R - depth};
        for (int k = 0; k < ticks; ++k) {
            in.t = (t += 1e-3);
            c = s.tick(in);
        }
        return c;
    };
    run(-0.005, 5);
    ServoCommand c = run(0.001, 400);
    REQUIRE(s.state() == ServoState::engaged);
    CHECK(c.roller_target == doctest::Approx(0.25 * R).epsilon(1e-9));
    ServoParams p;
    p.roller_travel = 0.006;  // m: +-3 mm usable
    REQUIRE(s.publish_params(p).empty());
    c = run(0.001, 2);
    CHECK(c.roller_target == doctest::Approx(0.003).epsilon(1e-12));
    // Longer than the device's travel: the device's own limits hold (+-10 mm), l_d unclamped.
    p.roller_travel = 0.5;
    REQUIRE(s.publish_params(p).empty());
    c = run(0.001, 2);
    CHECK(c.roller_target == doctest::Approx(0.25 * R).epsilon(1e-9));
    p.roller_travel = -0.001;
    CHECK(s.publish_params(p).find("roller_travel:") != std::string::npos);
}
