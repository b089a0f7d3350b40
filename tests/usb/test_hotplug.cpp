// test_hotplug.cpp — the servo loop driving the emulated board through the real libusb: unplug
// in contact zeroes the force and says Fault(disconnected); replugging (udev add -> libusb
// hot-plug ARRIVED) brings the device back, and the servo re-engages only through its gate and
// ramp, never with a kick.
#include "hapio_emulator.hpp"
#include "sim_fixture.hpp"
#include "usb_fixture.hpp"

#include "drivers/servo_loop.hpp"
#include "drivers/usb/hapio_device.hpp"

#include <doctest/doctest.h>

#include <chrono>
#include <thread>
#include <vector>

using namespace contactlab;
using namespace contactlab::drivers;
using namespace contactlab::test;

namespace {

struct UsbRig {
    UsbRig() : dev(options()), servo(servo_config_for(dev, 1000.0), params()), loop(dev, servo, 1e-3) {
        servo.scenes().publish(std::make_unique<ServoScene>(floor_scene(1000.0)));
    }
    static hapio::HapioOptions options() {
        hapio::HapioOptions o;
        o.stale_after = 0.2;  // shared, loaded CI machines (see test_stream.cpp)
        return o;
    }
    static ServoParams params() {
        ServoParams p;
        p.stiffness = 1000.0;
        p.max_force = 1.5;
        p.safety.watchdog_timeout = 0.2;  // same reason: scheduling hiccups are not what is tested
        p.safety.fault_hold = 0.1;
        p.safety.ramp_time = 0.25;
        return p;
    }
    // Steps the servo about once a millisecond (real time: the device clock is the host's) until
    // `done` or `timeout` s; `each` sees every tick's snapshot.
    template <class Done, class Each>
    bool run_until(Done done, double timeout, Each each) {
        const auto end = std::chrono::steady_clock::now() + std::chrono::duration<double>(timeout);
        while (std::chrono::steady_clock::now() < end) {
            loop.step(1e-3, false);
            each(servo.snapshot());
            if (done()) return true;
            std::this_thread::sleep_for(std::chrono::microseconds(900));
        }
        return false;
    }
    template <class Done>
    bool run_until(Done done, double timeout = 5.0) {
        return run_until(done, timeout, [](const ServoSnapshot&) {});
    }

    hapio::HapioDevice dev;
    ServoTick servo;
    ServoLoop loop;
    const hapio::CldCalibration cal = options().calibration;
    const double R = Scene{}.finger.radius;
    const Vec2 free_x{0.0, 0.05};                 // m: 24 mm above the floor
    Vec2 contact_x() const { return Vec2{0.0, R - 0.001}; }  // m: 1 mm into it -> 1 N at 1000 N/m
};

}  // namespace

TEST_CASE("unplug in contact: servo sees Fault(disconnected) and outputs zero force") {
    HapioEmulator emu;
    UsbRig rig;
    emu.set_encoders(counts_at(rig.cal, rig.free_x));
    REQUIRE(rig.loop.start());
    REQUIRE(rig.run_until([&] { return rig.servo.state() == ServoState::engaged; }));
    emu.set_encoders(counts_at(rig.cal, rig.contact_x()));
    REQUIRE(rig.run_until([&] { return std::abs(rig.servo.snapshot().force.y - 1.0) < 0.05; }));
    // What reached the board: the torques for ~1 N straight up.
    REQUIRE(wait_until([&] {
        double q1 = 0.0, q2 = 0.0;
        arm_ik(rig.cal, rig.contact_x(), q1, q2);
        return std::abs(hapio::CldModel(rig.cal).force_of(emu.last_command(), q1, q2).y - 1.0) < 0.05;
    }));

    emu.unplug();
    REQUIRE(rig.run_until([&] { return rig.servo.state() == ServoState::fault; }));
    CHECK(rig.dev.state() == DeviceState::fault);
    CHECK(rig.dev.fault().code == DeviceFaultCode::disconnected);
    CHECK(std::string(rig.dev.fault().detail).find("unplugged") != std::string::npos);
    CHECK(rig.servo.fault() == ServoFault::device);
    double max_force = 0.0;
    rig.run_until([] { return false; }, 0.2,
                  [&](const ServoSnapshot& s) { max_force = std::max(max_force, glm::length(s.force)); });
    CHECK(max_force == 0.0);
    CHECK(rig.dev.stats().disconnects == 1);
    DeviceReading r;
    CHECK_FALSE(rig.dev.read(r));
}

TEST_CASE("replug: hot-plug brings the board back and, still pressing, the force ramps back to Ke d") {
    HapioEmulator emu;
    UsbRig rig;
    emu.set_encoders(counts_at(rig.cal, rig.free_x));
    REQUIRE(rig.loop.start());
    REQUIRE(rig.run_until([&] { return rig.servo.state() == ServoState::engaged; }));
    emu.set_encoders(counts_at(rig.cal, rig.contact_x()));
    REQUIRE(rig.run_until([&] { return rig.servo.snapshot().force.y > 0.9; }));
    const int first_address = emu.address();

    emu.unplug();
    REQUIRE(rig.run_until([&] { return rig.dev.fault().code == DeviceFaultCode::disconnected; }));
    emu.plug();  // still pressing into the floor
    REQUIRE(rig.run_until([&] { return rig.dev.stats().reconnects == 1; }));
    CHECK(emu.address() != first_address);
    CHECK(emu.streaming());

    // Back, still pressing 1 mm into the floor: the proxy kept its place on the surface, and the
    // force ramps from zero to Ke d = 1 N over ramp_time, rising every tick and never above it
    // (no kick; it used to stay at zero until the user backed out).
    std::vector<double> ramp;
    bool contact = true;
    REQUIRE(rig.run_until([&] { return rig.servo.state() == ServoState::engaged; }, 5.0,
                          [&](const ServoSnapshot& s) {
                              ramp.push_back(s.force.y);
                              contact = contact && s.contact;
                          }));
    CHECK(contact);
    REQUIRE(ramp.size() > 20);
    CHECK(ramp.front() < 0.2);  // starts near zero
    int drops = 0;
    double highest = 0.0;
    for (std::size_t i = 1; i < ramp.size(); ++i) {
        if (ramp[i] < ramp[i - 1] - 1e-9) ++drops;
        highest = std::max(highest, ramp[i]);
    }
    CHECK(drops == 0);  // never steps down while ramping in
    // Never above the steady Ke d (the encoders' counts make d 1 mm to within a few um).
    rig.run_until([] { return false; }, 0.1);
    const double steady = rig.servo.snapshot().force.y;
    CHECK(steady == doctest::Approx(1.0).epsilon(0.01));
    CHECK(highest <= steady * (1.0 + 1e-6));
    REQUIRE(rig.run_until([&] { return std::abs(rig.servo.snapshot().force.y - 1.0) < 0.05; }));
    CHECK(wait_until([&] { return (emu.last_command().flags & hapio::kCommandEnable) != 0; }));
    CHECK(rig.dev.state() == DeviceState::engaged);
}
