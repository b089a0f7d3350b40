// test_falcon.cpp — FalconDevice through the real libusb against an emulated Falcon: firmware
// upload from the user's file, streaming through the delta kinematics, forces reaching the motors,
// the failures a user meets at bring-up, unplug and replug.
#include "falcon_emulator.hpp"
#include "usb_fixture.hpp"

#include "../cli/process.hpp"
#include "drivers/usb/falcon_device.hpp"

#include <doctest/doctest.h>

#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <fstream>

using namespace contactlab;
using namespace contactlab::drivers;
using namespace contactlab::drivers::falcon;
using namespace contactlab::test;

namespace {

// Stand-in firmware: arbitrary bytes (Novint's is never shipped); the emulator runs only these.
std::vector<std::uint8_t> fake_firmware(std::size_t n, std::uint8_t seed) {
    std::vector<std::uint8_t> fw(n);
    std::uint32_t x = 2463534242u + seed;
    for (auto& b : fw) {
        x ^= x << 13;
        x ^= x >> 17;
        x ^= x << 5;
        b = static_cast<std::uint8_t>(x);
    }
    return fw;
}

std::string write_file(const cli_test::TempDir& dir, const std::vector<std::uint8_t>& bytes) {
    const std::string path = dir.file("falcon_firmware.bin");
    std::ofstream(path, std::ios::binary).write(reinterpret_cast<const char*>(bytes.data()),
                                                static_cast<std::streamsize>(bytes.size()));
    return path;
}

FalconOptions tolerant(const std::string& firmware = {}) {
    FalconOptions o;
    o.firmware = firmware;
    o.stale_after = 0.5;  // loaded CI machines (see test_stream.cpp)
    return o;
}

std::array<std::int16_t, 3> counts_at(const FalconKinematics& k, const Vec3& p) {
    std::array<double, 3> th{};
    REQUIRE(k.inverse(p, th));
    return {k.counts_of(0, th[0]), k.counts_of(1, th[1]), k.counts_of(2, th[2])};
}

}  // namespace

TEST_CASE("falcon: firmware uploaded from the user's file, then positions stream through the kinematics") {
    const auto fw = fake_firmware(3000, 1);
    FalconEmulator emu({fw});
    cli_test::TempDir dir;
    FalconDevice dev(tolerant(write_file(dir, fw)));
    const FalconKinematics kin;
    const Vec3 p{0.01, 0.02, 0.11};
    emu.set_encoders(counts_at(kin, p));
    REQUIRE(dev.open());
    CHECK(dev.state() == DeviceState::ready);
    CHECK(emu.firmware_running());
    CHECK(emu.uploaded_bytes() == 3000);
    CHECK(emu.handshakes() >= 1);
    CHECK_FALSE(emu.kernel_driver_bound());  // ftdi_sio detached
    CHECK(dev.stats().firmware_uploads == 1);
    CHECK(dev.serial() == "FTB3X9QZ");  // the FTDI chip's serial, for the results' meta

    DeviceReading r;
    CHECK(wait_until([&] { return dev.stats().packets >= 50; }));
    CHECK_FALSE(dev.read(r));  // not homed yet: no reading the servo could trust
    emu.set_homed(0x7);
    REQUIRE(wait_until([&] { return dev.read(r); }));
    // Encoder quantisation (0.64 mrad per count, 360/9880.7 deg, on 60 mm thighs): within 0.2 mm.
    CHECK(std::abs(r.finger.x - 0.01) < 2e-4);
    CHECK(std::abs(r.finger.y - 0.02) < 2e-4);
    CHECK(std::abs(r.z) < 2e-4);
    CHECK(dev.stats().malformed == 0);
    dev.close();
    CHECK(emu.kernel_driver_bound());  // re-attached
}

TEST_CASE("falcon: an engaged force reaches the motors as J^T F, clamped and saturated") {
    FalconEmulator::Config c;
    c.firmware_running = true;
    FalconEmulator emu(c);
    FalconDevice dev(tolerant());
    const FalconKinematics kin;
    const Vec3 p{0.0, 0.0, 0.11};
    emu.set_encoders(counts_at(kin, p));
    emu.set_homed(0x7);
    REQUIRE(dev.open());
    CHECK(dev.stats().firmware_uploads == 0);  // already running: used as is
    DeviceReading r;
    REQUIRE(wait_until([&] { return dev.read(r); }));
    dev.set_engaged(true);
    DeviceCommand cmd;
    cmd.force = Vec2{1.0, 0.5};  // N
    dev.write(cmd);
    REQUIRE(wait_until([&] { return emu.last_command().motor[0] != 0; }));
    Command last = emu.last_command();
    CHECK((last.flags & kLedGreen) != 0);
    std::array<double, 3> tau{};
    for (int i = 0; i < 3; ++i) tau[i] = last.motor[i] / FalconPlanarParams{}.motor_counts_per_nm;
    Vec3 f;
    REQUIRE(kin.force(dev.grip(), tau, f));
    CHECK(f.x == doctest::Approx(1.0).epsilon(0.02));
    CHECK(f.y == doctest::Approx(0.5).epsilon(0.02));
    CHECK(std::abs(f.z) < 0.1);  // only the restoring spring's pull for the sub-mm depth error

    cmd.force = Vec2{0.0, 100.0};  // far past the clamp
    dev.write(cmd);
    REQUIRE(wait_until([&] { return emu.last_command().motor != last.motor; }));
    last = emu.last_command();
    for (int i = 0; i < 3; ++i) CHECK(std::abs(last.motor[i]) <= FalconPlanarParams{}.motor_max);
}

TEST_CASE("falcon: bootloader and no firmware file gives a message saying which file to supply") {
    FalconEmulator emu({fake_firmware(100, 2)});
    FalconDevice dev(tolerant());
    CHECK_FALSE(dev.open());
    CHECK(dev.state() == DeviceState::fault);
    CHECK(dev.fault().code == DeviceFaultCode::open_failed);
    CHECK(std::string(dev.fault().detail).find("no firmware running") != std::string::npos);
    CHECK(std::string(dev.fault().detail).find("does not ship it") != std::string::npos);
}

TEST_CASE("falcon: a silent bootloader fails after bounded retries and says to check the power supply") {
    FalconEmulator::Config c;
    c.firmware = fake_firmware(100, 3);
    c.bootloader_answers = false;  // what a Falcon powered only by USB does
    FalconEmulator emu(c);
    cli_test::TempDir dir;
    FalconOptions o = tolerant(write_file(dir, c.firmware));
    o.handshake_attempts = 5;
    o.open_attempts = 2;
    FalconDevice dev(o);
    const auto t0 = std::chrono::steady_clock::now();
    CHECK_FALSE(dev.open());
    const double secs = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    CHECK(secs < 5.0);  // bounded: 2 bring-ups x 5 probes x 20 ms, plus USB time
    CHECK(dev.fault().code == DeviceFaultCode::timeout);
    CHECK(std::string(dev.fault().detail).find("power supply") != std::string::npos);
    CHECK(emu.uploaded_bytes() == 0);
}

TEST_CASE("falcon: a file that is not the Falcon's firmware is uploaded but reported as not answering") {
    FalconEmulator emu({fake_firmware(500, 4)});
    cli_test::TempDir dir;
    FalconDevice dev(tolerant(write_file(dir, fake_firmware(500, 5))));
    CHECK_FALSE(dev.open());
    CHECK(emu.uploaded_bytes() == 500);
    CHECK(std::string(dev.fault().detail).find("is the file the Falcon's firmware?") != std::string::npos);
}

TEST_CASE("falcon: unplug is Fault(disconnected), and replugging uploads the firmware again and streams") {
    const auto fw = fake_firmware(800, 6);
    FalconEmulator emu({fw});
    cli_test::TempDir dir;
    FalconDevice dev(tolerant(write_file(dir, fw)));
    emu.set_homed(0x7);
    emu.set_encoders(counts_at(FalconKinematics{}, {0.0, 0.0, 0.11}));
    REQUIRE(dev.open());
    DeviceReading r;
    REQUIRE(wait_until([&] { return dev.read(r); }));
    emu.unplug();
    REQUIRE(wait_until([&] { return dev.fault().code == DeviceFaultCode::disconnected; }));
    CHECK_FALSE(dev.read(r));
    emu.plug();
    emu.set_homed(0x7);
    REQUIRE(wait_until([&] { return dev.stats().reconnects == 1; }, 10.0));
    CHECK(dev.stats().firmware_uploads == 2);
    CHECK(wait_until([&] { return dev.read(r); }));
    CHECK(dev.state() == DeviceState::ready);
}

TEST_CASE("falcon: contactlab simulate --device usb:falcon uploads the firmware and streams in real time") {
    const auto fw = fake_firmware(1000, 7);
    FalconEmulator emu({fw});
    emu.set_homed(0x7);
    emu.set_encoders(counts_at(FalconKinematics{}, {0.0, 0.0, 0.11}));
    preload_umockdev_in_children();
    cli_test::TempDir dir;
    const auto p = cli_test::run_contactlab({"simulate", cli_test::scene("block.json"), "--device", "usb:falcon",
                                             "--firmware", write_file(dir, fw), "--duration", "0.3", "-o",
                                             dir.file("out.csv")});
    std::printf("%s", p.err.c_str());
    CHECK(p.exit_code == 0);
    CHECK(cli_test::contains(p.err, "usb:falcon, real time"));
    CHECK(cli_test::contains(p.err, "0 malformed"));
    CHECK(cli_test::contains(p.err, "1 firmware uploads"));
    CHECK(emu.uploaded_bytes() == 1000);
    CHECK(emu.commands() >= 100);
}
