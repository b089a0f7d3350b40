// test_haply.cpp — the Haply 2DIY driver through a real tty: umockdev's /dev/ttyACM0 (a pty, with
// the board's USB device in a faked sysfs) and hAPI's firmware on the pty's other end. The driver
// finds the board by its USB id, configures the tty, sends reset and the parameter message, and
// exchanges torques for angles; the board misbehaves as real ones do (another device id, short
// frames, NaN angles, silence, an unplug in the middle of an exchange).
#include "haply_emulator.hpp"
#include "sim_fixture.hpp"
#include "usb_fixture.hpp"

#include "drivers/servo_loop.hpp"
#include "drivers/usb/haply_device.hpp"
#include "drivers/usb/haply_protocol.hpp"
#include "drivers/usb/serial_port.hpp"

#include <doctest/doctest.h>

#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <string>
#include <thread>

using namespace contactlab;
using namespace contactlab::drivers;
using namespace contactlab::test;
using haply::HaplyDevice;
using haply::HaplyOptions;

namespace {

HaplyOptions options() {
    HaplyOptions o;
    o.stale_after = 0.2;        // shared, loaded CI machines: scheduling is not what is tested
    o.handshake_timeout = 0.5;  // s: the emulator answers at once, or never
    return o;
}

// A float angle near 90 deg carries 4e-6 deg (7e-8 rad) of rounding; |J| < 0.2 m/rad here, so
// the handle the driver computes is within ~1.5e-8 m of the emulator's: 1e-7 m covers it.
constexpr double kPositionTol = 1e-7;  // m

bool contains(const std::string& s, const std::string& what) { return s.find(what) != std::string::npos; }

}  // namespace

TEST_CASE("haply: the board's tty is found by its USB id, with its serial number and permission") {
    HaplyEmulator emu;
    const auto ttys = serial::usb_ttys();
    REQUIRE(ttys.size() == 1);
    CHECK(ttys[0].node == "/dev/ttyACM0");
    CHECK(ttys[0].vendor_id == 0x2341);
    CHECK(ttys[0].product_id == 0x003e);
    CHECK(ttys[0].serial == "HAPLY-0042");
    CHECK(ttys[0].accessible);
    CHECK(haply::is_board_id(ttys[0].vendor_id, ttys[0].product_id));
}

TEST_CASE("haply: open sends hAPI's reset and the parameter message, then reads the handle where the board is") {
    HaplyEmulator emu;
    const haply::Vec p{0.03, 0.09};  // m, device frame
    emu.set_position(p);
    HaplyDevice dev(options());
    REQUIRE(dev.open());
    CHECK(dev.state() == DeviceState::ready);
    CHECK(dev.port() == "/dev/ttyACM0");
    CHECK(dev.serial() == "HAPLY-0042");
    CHECK(emu.resets() >= 1);
    std::uint8_t expect[haply::kParametersSize];
    haply::pack_parameters(haply::hardware(3), 5, expect);
    const auto got = emu.parameters();
    REQUIRE(got.size() == haply::kParametersSize);
    CHECK(std::memcmp(got.data(), expect, sizeof expect) == 0);
    CHECK(emu.device_id() == 5);
    DeviceReading r;
    REQUIRE(wait_until([&] { return dev.read(r); }));
    const Vec2 w = dev.to_world(p);
    CHECK(std::abs(r.finger.x - w.x) < kPositionTol);
    CHECK(std::abs(r.finger.y - w.y) < kPositionTol);
    // The workspace's centre is the world origin; the plane is turned by 180 degrees.
    const Aabb box = haply::workspace(haply::hardware(3).geometry);
    CHECK(w.x == doctest::Approx(0.5 * (box.lo.x + box.hi.x) - p.x).epsilon(1e-12));
    CHECK(w.y == doctest::Approx(0.5 * (box.lo.y + box.hi.y) - p.y).epsilon(1e-12));
    REQUIRE(wait_until([&] { return emu.exchanges() > 50; }));
    dev.close();
    CHECK(dev.state() == DeviceState::disconnected);
}

TEST_CASE("haply: engaged, a world force reaches the board as the motor torques J^T F") {
    HaplyEmulator emu;
    const haply::Vec p{0.0, 0.08};
    emu.set_position(p);
    HaplyDevice dev(options());
    REQUIRE(dev.open());
    DeviceCommand c;
    c.force = {0.6, -0.8};  // N, world
    dev.write(c);
    // Not engaged: zero torque whatever the servo asks.
    REQUIRE(wait_until([&] { return emu.exchanges() > 20; }));
    CHECK(emu.last_torques()[0] == 0.0f);
    CHECK(emu.last_torques()[1] == 0.0f);
    dev.set_engaged(true);
    std::array<double, 2> t{};
    REQUIRE(haply::inverse_kinematics(haply::hardware(3).geometry, p, t) == haply::KinStatus::ok);
    std::array<double, 2> tau{};
    REQUIRE(haply::joint_torques(haply::hardware(3).geometry, t, haply::Vec{-0.6, 0.8}, tau) == haply::KinStatus::ok);
    // Sent as float32: 6e-8 relative, on torques of ~0.1 N m.
    REQUIRE(wait_until([&] {
        const auto s = emu.last_torques();
        return std::abs(s[0] - tau[0]) < 1e-6 && std::abs(s[1] - tau[1]) < 1e-6;
    }));
    MESSAGE("torques for (0.6, -0.8) N at (0, 0.08) m: " << tau[0] << ", " << tau[1] << " N m");
    // The servo's NaN never reaches the board.
    c.force = {std::nan(""), 0.0};
    dev.write(c);
    REQUIRE(wait_until([&] { return emu.last_torques()[0] == 0.0f && emu.last_torques()[1] == 0.0f; }));
}

TEST_CASE("haply: a board answering as another device id is refused at open, saying which id it used") {
    HaplyEmulator emu;
    emu.misbehave(HaplyMisbehaviour::wrong_device);
    HaplyDevice dev(options());
    CHECK_FALSE(dev.open());
    CHECK(dev.state() == DeviceState::fault);
    CHECK(dev.fault().code == DeviceFaultCode::open_failed);
    CHECK(contains(dev.fault().detail, "answers as hAPI device 6, not 5"));
}

TEST_CASE("haply: a silent board is refused at open with what to check") {
    HaplyEmulator emu;
    emu.misbehave(HaplyMisbehaviour::silent);
    HaplyDevice dev(options());
    CHECK_FALSE(dev.open());
    CHECK(contains(dev.fault().detail, "does not answer hAPI's exchange"));
}

TEST_CASE("haply: no board plugged in, or a port that does not exist, says so") {
    HaplyEmulator emu(HaplyEmulator::Config{.plugged = false});
    HaplyDevice dev(options());
    CHECK_FALSE(dev.open());
    CHECK(dev.fault().code == DeviceFaultCode::not_found);
    CHECK(contains(dev.fault().detail, "no Haply board found"));
    HaplyOptions o = options();
    o.port = "/dev/ttyACM7";
    HaplyDevice named(o);
    CHECK_FALSE(named.open());
    CHECK(named.fault().code == DeviceFaultCode::not_found);
    CHECK(contains(named.fault().detail, "/dev/ttyACM7 does not exist"));
}

TEST_CASE("haply: short frames and NaN angles while streaming are dropped and counted, and the reading never goes bad") {
    HaplyEmulator emu;
    HaplyOptions o = options();
    o.stale_after = 0.05;
    HaplyDevice dev(o);
    REQUIRE(dev.open());
    DeviceReading r;
    REQUIRE(wait_until([&] { return dev.read(r); }));
    const Vec2 before = r.finger;
    for (const HaplyMisbehaviour m : {HaplyMisbehaviour::short_frames, HaplyMisbehaviour::nan_angles}) {
        emu.misbehave(m);
        // No valid reply: the reading goes stale (the servo zeroes the force) and the device faults.
        REQUIRE(wait_until([&] { return !dev.read(r) && dev.state() == DeviceState::fault; }));
        CHECK(dev.fault().code == DeviceFaultCode::io_error);
        CHECK(contains(dev.fault().detail, m == HaplyMisbehaviour::short_frames ? "short frames" : "not finite"));
        emu.misbehave(HaplyMisbehaviour::none);
        REQUIRE(wait_until([&] { return dev.read(r) && dev.state() == DeviceState::ready; }));
        CHECK(std::isfinite(r.finger.x));
        CHECK(std::abs(r.finger.x - before.x) < kPositionTol);
    }
    const haply::HaplyStats s = dev.stats();
    CHECK(s.short_frames > 0);
    CHECK(s.not_finite > 0);
    CHECK(s.wrong_device == 0);
    CHECK(s.disconnects == 0);
}

TEST_CASE("haply: unplugged mid-exchange, zero torque and the servo keeps running, and replugged it comes back") {
    HaplyEmulator emu;
    emu.set_position(haply::Vec{0.019, 0.075});
    HaplyDevice dev(options());
    ServoParams params;
    params.stiffness = 1000.0;
    params.max_force = 1.5;
    params.safety.watchdog_timeout = 0.2;
    params.safety.fault_hold = 0.1;
    params.safety.ramp_time = 0.05;
    ServoTick servo(servo_config_for(dev, 1000.0), params);
    servo.scenes().publish(std::make_unique<ServoScene>(floor_scene(1000.0)));
    ServoLoop loop(dev, servo, 1e-3);
    REQUIRE(loop.start());
    auto run_until = [&](auto done, double timeout) {
        const auto end = std::chrono::steady_clock::now() + std::chrono::duration<double>(timeout);
        while (std::chrono::steady_clock::now() < end) {
            loop.step(1e-3, false);
            if (done()) return true;
            std::this_thread::sleep_for(std::chrono::microseconds(900));
        }
        return false;
    };
    REQUIRE(run_until([&] { return servo.state() == ServoState::engaged; }, 5.0));
    emu.misbehave(HaplyMisbehaviour::unplug_mid_exchange);
    REQUIRE(run_until([&] { return dev.fault().code == DeviceFaultCode::disconnected; }, 5.0));
    CHECK(contains(dev.fault().detail, "disconnected"));
    emu.unplug();
    // The servo keeps ticking with no reading: it reports the device fault and outputs zero force.
    const std::uint64_t ticks_before = servo.snapshot().ticks;
    REQUIRE(run_until([&] { return servo.state() == ServoState::fault; }, 5.0));
    run_until([] { return false; }, 0.1);
    CHECK(servo.snapshot().ticks > ticks_before);
    CHECK(glm::length(servo.snapshot().force) == 0.0);
    DeviceReading r;
    CHECK_FALSE(dev.read(r));
    CHECK(dev.stats().disconnects == 1);

    emu.misbehave(HaplyMisbehaviour::none);
    emu.plug();
    REQUIRE(run_until([&] { return dev.stats().reconnects == 1; }, 5.0));
    REQUIRE(run_until([&] { return dev.read(r); }, 5.0));
    CHECK(emu.parameters().size() == haply::kParametersSize);  // set up again after the replug
    REQUIRE(run_until([&] { return servo.state() == ServoState::engaged; }, 5.0));
}

TEST_CASE("haply: the udev rule tags the tty of every board id the driver looks for") {
    const std::string rules = [] {
        std::FILE* f = std::fopen(CONTACTLAB_SOURCE_DIR "/assets/udev/70-contactlab.rules", "r");
        REQUIRE(f != nullptr);
        std::string s;
        char buf[4096];
        for (std::size_t n; (n = std::fread(buf, 1, sizeof buf, f)) > 0;) s.append(buf, n);
        std::fclose(f);
        return s;
    }();
    for (const haply::BoardId& b : haply::kBoardIds) {
        char line[160];
        std::snprintf(line, sizeof line, "SUBSYSTEM==\"tty\", ATTRS{idVendor}==\"%04x\", ATTRS{idProduct}==\"%04x\", TAG+=\"uaccess\"",
                      b.vendor_id, b.product_id);
        INFO(line);
        CHECK(contains(rules, line));
    }
}
