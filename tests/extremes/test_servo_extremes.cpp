// test_servo_extremes.cpp — the servo tick at the extremes: rates 100 Hz to 100 kHz, steady and
// jittered periods, absurd parameters published mid-contact, and broken time stamps. The command
// reaching the device is always finite and within the device's clamp, and where the physics has an
// answer (a finger held 1 mm into a floor: Ke d) the tick gives it at every rate.
#include "extremes_fixture.hpp"

#include "haptics/servo_params_check.hpp"
#include "haptics/servo_tick.hpp"

#include <doctest/doctest.h>

#include <algorithm>
#include <limits>
#include <memory>
#include <random>
#include <stdexcept>
#include <string>
#include <vector>

using namespace contactlab;
using namespace contactlab::extremes;

namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();
constexpr double kInf = std::numeric_limits<double>::infinity();
constexpr double R = kNominalRadius;

bool usable(const ServoCommand& c, const ServoConfig& cfg) {
    return is_finite(c.force) && std::isfinite(c.roller_drive) && std::isfinite(c.roller_target) &&
           glm::length(c.force) <= cfg.device_max_force * (1.0 + 4.0 * kEps);
}

ServoParams params_for(double rate) {
    ServoParams p;
    p.safety.watchdog_timeout = std::max(0.005, 3.0 / rate);  // s
    return p;
}

// A servo on the floor y = 0 at `rate` Hz, connected at t = 0.
struct FloorServo {
    ServoConfig cfg;
    std::unique_ptr<ServoTick> servo;
    double t = 0.0;  // s
    explicit FloorServo(double rate, bool roller = true) {
        cfg.period = 1.0 / rate;
        cfg.has_roller = roller;
        REQUIRE(servo_config_problem(cfg).empty());
        servo = std::make_unique<ServoTick>(cfg, params_for(rate));
        servo->scenes().publish(std::make_unique<ServoScene>(floor_at({0.0, 0.0}, 1.0)));
        servo->connect(0.0);
    }
    const ServoCommand& tick(double dt, double depth, double roller_l = 0.0) {
        ServoInput in;
        in.t = (t += dt);
        in.finger = {0.0, R - depth};
        in.roller_l = roller_l;
        return servo->tick(in);
    }
};

}  // namespace

TEST_CASE("rates 100 Hz to 100 kHz, steady and jittered: a finger held 1 mm into a floor gets Ke d, never more than the clamp") {
    std::mt19937_64 rng(42);
    for (double rate : {100.0, 250.0, 1e3, 4e3, 1e4, 2e4, 1e5}) {
        for (bool jitter : {false, true}) {
            CAPTURE(rate);
            CAPTURE(jitter);
            FloorServo s(rate);
            const double T = 1.0 / rate;  // s
            // Periods from 0.2 T to 1.8 T: inside the watchdog (3 T), a harsh scheduler's spread.
            std::uniform_real_distribution<double> spread(0.2, 1.8);
            auto next_dt = [&] { return jitter ? T * spread(rng) : T; };
            while (s.t < 0.05) REQUIRE(usable(s.tick(next_dt(), -0.002), s.cfg));  // free space: engage
            ServoCommand c;
            while (s.t < 0.6) {  // press; the 0.25 s ramp-in completes
                c = s.tick(next_dt(), 0.001);
                REQUIRE(usable(c, s.cfg));
            }
            CHECK(s.servo->state() == ServoState::engaged);
            CHECK(c.force.y == doctest::Approx(kNominalStiffness * 0.001).epsilon(1e-9));
            CHECK(std::abs(c.force.x) <= 1e-12);
        }
    }
}

TEST_CASE("absurd parameters published mid-contact are refused with the field named, and the force does not change") {
    const ServoParams good = params_for(1e3);
    struct Bad {
        const char* field;
        ServoParams params;
    };
    std::vector<Bad> bad;
    for (double v : {kNaN, kInf, -kInf, -1.0, 0.0, 1e300}) {
        ServoParams p = good;
        p.stiffness = v;
        bad.push_back({"stiffness:", p});
        p = good;
        p.max_force = v;
        bad.push_back({"max_force:", p});
        p = good;
        p.stiffness_slew = v;
        bad.push_back({"stiffness_slew:", p});
        p = good;
        p.roller.kp = v;
        if (v != 0.0) bad.push_back({"roller.kp:", p});  // a zero gain is a choice, not an error
        p = good;
        p.passivity_threshold = v;
        if (v != 1e300) bad.push_back({"passivity_threshold:", p});  // a huge one turns the observer off
    }
    FloorServo s(1e3);
    for (int k = 0; k < 50; ++k) s.tick(1e-3, -0.002);
    ServoCommand c;
    for (int k = 0; k < 400; ++k) c = s.tick(1e-3, 0.001);
    REQUIRE(s.servo->state() == ServoState::engaged);
    REQUIRE(c.force.y == doctest::Approx(1.0).epsilon(1e-12));
    for (const Bad& b : bad) {
        CAPTURE(std::string(b.field));
        const std::string problem = s.servo->publish_params(b.params);
        CAPTURE(problem);
        CHECK(problem.find(b.field) != std::string::npos);
        // Nothing reached the tick: Ke d = 1 N, unchanged, and still engaged.
        for (int k = 0; k < 20; ++k) {
            c = s.tick(1e-3, 0.001);
            REQUIRE(usable(c, s.cfg));
            CHECK(c.force.y == doctest::Approx(1.0).epsilon(1e-12));
        }
        CHECK(s.servo->state() == ServoState::engaged);
    }
    // A good edit still goes through (and slews): 2 mm at Ke 2000 N/m ends at 2 N... clamped 1.5 N.
    ServoParams stiffer = good;
    stiffer.stiffness = 2000.0;
    CHECK(s.servo->publish_params(stiffer).empty());
    for (int k = 0; k < 200; ++k) c = s.tick(1e-3, 0.001);
    CHECK(c.force.y == doctest::Approx(1.5).epsilon(1e-12));
}

TEST_CASE("a servo built with parameters or a device it cannot honour throws, naming the field") {
    ServoConfig fast;
    fast.period = 1e-6;  // 1 MHz
    CHECK_THROWS_WITH_AS(ServoTick(fast, ServoParams{}), doctest::Contains("period:"), std::invalid_argument);
    ServoConfig slow;
    slow.period = 1e-2;  // 100 Hz with the default 5 ms watchdog: every tick would be a stall
    CHECK_THROWS_WITH_AS(ServoTick(slow, ServoParams{}), doctest::Contains("safety.watchdog_timeout:"), std::invalid_argument);
    ServoParams nan_ke;
    nan_ke.stiffness = kNaN;
    CHECK_THROWS_WITH_AS(ServoTick(ServoConfig{}, nan_ke), doctest::Contains("stiffness:"), std::invalid_argument);
    CHECK_NOTHROW(ServoTick(slow, params_for(100.0)));
}

TEST_CASE("time stamps repeating, going backwards, non-finite or jumping: finite commands and the right fault") {
    FloorServo s(1e3);
    for (int k = 0; k < 50; ++k) s.tick(1e-3, -0.002);
    for (int k = 0; k < 400; ++k) s.tick(1e-3, 0.001);
    REQUIRE(s.servo->state() == ServoState::engaged);
    // Repeated and backward stamps: the tick falls back to its nominal period and carries on.
    ServoInput in;
    in.finger = {0.0, R - 0.001};
    in.t = s.t;
    CHECK(usable(s.servo->tick(in), s.cfg));
    in.t = s.t - 0.5;
    CHECK(usable(s.servo->tick(in), s.cfg));
    CHECK(s.servo->state() == ServoState::engaged);
    // A NaN stamp is unusable input: zero force and the fault named.
    in.t = kNaN;
    const ServoCommand nan_cmd = s.servo->tick(in);
    CHECK(usable(nan_cmd, s.cfg));
    CHECK(glm::length(nan_cmd.force) == 0.0);
    CHECK(s.servo->fault() == ServoFault::non_finite_input);
    // A second-long gap is a stall: the watchdog zeroes the force.
    FloorServo w(1e3);
    for (int k = 0; k < 50; ++k) w.tick(1e-3, -0.002);
    for (int k = 0; k < 400; ++k) w.tick(1e-3, 0.001);
    const ServoCommand stalled = w.tick(1.0, 0.001);
    CHECK(usable(stalled, w.cfg));
    CHECK(glm::length(stalled.force) == 0.0);
    CHECK(w.servo->fault() == ServoFault::watchdog);
}

TEST_CASE("device force limits from 1e-6x to 1e3x nominal: the command obeys the device's clamp and per-axis saturation") {
    for (double device_max : {1.5e-6, 1.5, 1.5e3}) {
        for (double axis : {1e-6, 0.7, 1e3}) {
            CAPTURE(device_max);
            CAPTURE(axis);
            ServoConfig cfg;
            cfg.device_max_force = device_max;
            cfg.axis_max = {axis, axis};
            cfg.has_roller = false;
            ServoParams p = params_for(1e3);
            p.max_force = 1e4;  // asks for more than any device gives
            ServoTick servo(cfg, p);
            servo.scenes().publish(std::make_unique<ServoScene>(floor_at({0.0, 0.0}, 1.0)));
            servo.connect(0.0);
            ServoInput in;
            ServoCommand c;
            for (int k = 1; k <= 1300; ++k) {
                in.t = k * 1e-3;
                // 0.3 s 2 mm above the floor (the servo engages and ramps in), then to 1 cm deep
                // (10 N asked for) in 0.1 s, then sideways.
                const double depth = k < 300 ? -0.002 : std::min(0.01, -0.002 + 0.012 * (k - 300) / 100.0);  // m
                in.finger = {0.0005 * std::sin(k * 0.05), R - depth};
                c = servo.tick(in);
                REQUIRE(is_finite(c.force));
                REQUIRE(glm::length(c.force) <= device_max * (1.0 + 4.0 * kEps));
                REQUIRE(std::abs(c.force.x) <= axis * (1.0 + 4.0 * kEps));
                REQUIRE(std::abs(c.force.y) <= axis * (1.0 + 4.0 * kEps));
            }
            CAPTURE(std::string(to_string(servo.fault())));
            CAPTURE(std::string(to_string(servo.state())));
            // Engaged and pressed 1 cm in: Ke d = 10 N unless a limit is smaller, straight up.
            CHECK(c.force.y == doctest::Approx(std::min({kNominalStiffness * 0.01, device_max, axis})).epsilon(1e-9));
        }
    }
}
