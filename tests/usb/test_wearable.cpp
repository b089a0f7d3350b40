// test_wearable.cpp — a hapio model 2 board (seed 003's wearable platform, HAPIO.md) through the
// real libusb against the emulated board: the FSR counts become readings, the cable force
// commands become motor drives, and bad input (a saturated FSR, a force above the motors' stall
// limit, too few channels) is a fault with zero drive.
#include "hapio_emulator.hpp"
#include "usb_fixture.hpp"

#include "drivers/finger_sweep.hpp"
#include "drivers/usb/hapio_device.hpp"
#include "engine/editor/platform_finger_device.hpp"

#include <doctest/doctest.h>

#include <memory>
#include <string>

using namespace contactlab;
using namespace contactlab::drivers;
using namespace contactlab::test;

namespace {
HapioEmulator::Config wearable_board(std::uint8_t analog = 3) {
    HapioEmulator::Config c;
    c.info = hapio::Info{hapio::kVersion, 2, 0, analog, 3, 1000, 0x0100, 4243};
    c.frame_period = 1e-3;  // s: paced like the real board
    return c;
}
hapio::HapioOptions tolerant() {
    hapio::HapioOptions o;
    o.stale_after = 0.5;  // s: shared, loaded CI machines
    return o;
}
bool zero_drive(const hapio::Command& c) { return c.motor[0] == 0 && c.motor[1] == 0 && c.motor[2] == 0; }
}  // namespace

TEST_CASE("hapio model 2: FSR counts are read in newtons and a cable force command pulls the cables") {
    HapioEmulator emu(wearable_board());
    emu.set_adc({10, 20, 30, 0});
    hapio::HapioDevice dev(tolerant());
    REQUIRE(dev.open());
    CHECK(dev.is_wearable());
    CHECK(dev.capabilities().platform);
    CHECK(dev.capabilities().force_sensors == 3);
    CHECK_FALSE(dev.capabilities().roller);
    REQUIRE(wait_until([&] { return dev.stats().frames >= 20; }));
    DeviceReading r;
    REQUIRE(dev.read(r));
    const double per_count = hapio::WearableCalibration{}.fsr_newton_per_count;
    CHECK(r.sensors[0] == doctest::Approx(10 * per_count));
    CHECK(r.sensors[2] == doctest::Approx(30 * per_count));
    // Not engaged: zero drive, motors not enabled.
    CHECK(zero_drive(emu.last_command()));
    // 0.5 N asked, 0.1-0.4 N estimated: every motor pulls (positive drive), enabled.
    dev.set_engaged(true);
    DeviceCommand cmd;
    cmd.platform_mode = DeviceCommand::PlatformMode::wrench;
    cmd.platform = {0.5, 0.5, 0.5};
    dev.write(cmd);
    const std::uint64_t c0 = emu.commands_applied();
    REQUIRE(wait_until([&] { return emu.commands_applied() >= c0 + 50; }));
    const hapio::Command last = emu.last_command();
    CHECK(last.motors == 3);
    CHECK((last.flags & hapio::kCommandEnable) != 0);
    for (int i = 0; i < 3; ++i) CHECK(last.motor[i] > 0);
    CHECK(dev.state() == DeviceState::engaged);
}

TEST_CASE("hapio model 2: a saturated FSR and a force above stall are faults with zero drive") {
    HapioEmulator emu(wearable_board());
    emu.set_adc({10, 10, 10, 0});
    hapio::HapioDevice dev(tolerant());
    REQUIRE(dev.open());
    REQUIRE(wait_until([&] { return dev.stats().frames >= 20; }));
    dev.set_engaged(true);
    DeviceCommand cmd;
    cmd.platform_mode = DeviceCommand::PlatformMode::wrench;
    cmd.platform = {0.3, 0.3, 0.3};
    dev.write(cmd);
    REQUIRE(wait_until([&] { return !zero_drive(emu.last_command()); }));
    // Each fault lasts until the next clean frame (about a millisecond: the device is then ready,
    // not engaged, so it does not fault again), shorter than a loaded machine may take to poll
    // state(); the device counts faults and keeps the last one (HapioStats::faults, last_fault).
    const std::uint64_t before_saturation = dev.stats().faults;
    emu.set_adc({10, 1023, 10, 0});  // channel 2 at the ADC's full scale
    REQUIRE(wait_until([&] { return dev.stats().faults > before_saturation; }));
    CHECK(dev.last_fault().code == DeviceFaultCode::io_error);
    CHECK(std::string(dev.last_fault().detail).find("saturated") != std::string::npos);
    REQUIRE(wait_until([&] { return zero_drive(emu.last_command()); }));
    // The reading comes back in range: the fault clears (ready, to be re-engaged by the servo).
    emu.set_adc({10, 10, 10, 0});
    REQUIRE(wait_until([&] { return dev.state() == DeviceState::ready; }));
    const std::uint64_t before_stall = dev.stats().faults;
    cmd.platform = {0.3, 2.0, 0.3};  // above the 1.54 N stall force
    dev.write(cmd);
    dev.set_engaged(true);
    // Another fault may come first and disengage it (a clean-clone CI run once read an io_error
    // here, after the state had read ready): as the servo would, engage it again until the stall's
    // own fault comes.
    REQUIRE(wait_until([&] {
        if (dev.stats().faults > before_stall && dev.last_fault().code == DeviceFaultCode::over_limit) return true;
        if (dev.state() == DeviceState::ready) dev.set_engaged(true);
        return false;
    }));
    CHECK(std::string(dev.last_fault().detail).find("stall") != std::string::npos);
    REQUIRE(wait_until([&] { return zero_drive(emu.last_command()); }));
    // The fault disengaged it (the servo decides): within a frame of the last engage above.
    CHECK(wait_until([&] { return dev.state() != DeviceState::engaged; }));
}

TEST_CASE("hapio model 2: a board with too few analog channels is refused at open") {
    HapioEmulator emu(wearable_board(2));
    hapio::HapioDevice dev(tolerant());
    CHECK_FALSE(dev.open());
    CHECK(dev.state() == DeviceState::fault);
    CHECK(std::string(dev.fault().detail).find("wearable platform") != std::string::npos);
}

TEST_CASE("hapio model 2: in the editor the board's finger is seed 003's live sweep, and a model 1 board keeps its own") {
    // The platform tracks no finger: behind PlatformFingerDevice (as `edit --device usb:hapio`
    // opens it) each reading's finger is the sweep's, timed from the first reading after it
    // started, on the board's clock. A CLD rig (model 1) measures the finger and refuses it.
    drivers::FingerSweep s;
    s.x0 = -0.17;
    s.x1 = 0.17;
    s.speed = 0.1;
    s.finger_radius = 0.010;
    s.chord = 0.30;
    s.height = 0.01;
    {
        HapioEmulator emu(wearable_board());
        editor::PlatformFingerDevice dev(std::make_unique<hapio::HapioDevice>(tolerant()), editor::MousePose{{0.0, 0.03}, 0.0});
        REQUIRE(dev.open());
        REQUIRE(dev.capabilities().platform);
        REQUIRE(dev.start_sweep(s));
        DeviceReading r;
        REQUIRE(wait_until([&] { return dev.read(r); }));
        const double t0 = r.t;
        CHECK(r.finger.x == s.x0);
        for (int i = 0; i < 20; ++i) {
            REQUIRE(wait_until([&] { return dev.read(r) && r.t > t0 + 0.05 * i; }));
            const Vec2 want = drivers::finger_sweep_at(s, r.t - t0);
            CHECK(r.finger.x == want.x);
            CHECK(r.finger.y == want.y);
        }
        dev.close();
    }
    {
        HapioEmulator::Config rig;  // the emulator's default board: model 1, the CLD rig
        rig.frame_period = 1e-3;
        HapioEmulator emu(rig);
        editor::PlatformFingerDevice dev(std::make_unique<hapio::HapioDevice>(tolerant()), editor::MousePose{});
        REQUIRE(dev.open());
        CHECK_FALSE(dev.capabilities().platform);
        CHECK_FALSE(dev.start_sweep(s));
        dev.close();
    }
}
