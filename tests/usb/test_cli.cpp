// test_cli.cpp — the real `contactlab` executable against the emulated board: the child process
// inherits the testbed (UMOCKDEV_DIR) and loads umockdev's preload library, so its libusb talks
// to this process's emulator exactly as it would to a plugged-in board.
#include "hapio_emulator.hpp"
#include "usb_fixture.hpp"

#include "../cli/process.hpp"

#include <doctest/doctest.h>

#include <cstdio>
#include <cstdlib>

using namespace contactlab::test;
using namespace cli_test;

TEST_CASE("contactlab devices lists the emulated board and exits 0") {
    HapioEmulator emu;
    preload_umockdev_in_children();
    const ProcessResult p = run_contactlab({"devices"});
    CHECK(p.exit_code == 0);
    CHECK(contains(p.out, "hapio board (CLD rig)"));
    CHECK(contains(p.out, "bus 001 address 002"));
    CHECK(contains(p.out, "1209:c1d0"));
    CHECK(contains(p.out, "--device usb:hapio"));
    CHECK(contains(p.out, "available"));
}

TEST_CASE("contactlab devices names the udev rule when the board cannot be opened") {
    HapioEmulator emu;
    emu.deny_permission();  // the child inherits the dropped capability
    preload_umockdev_in_children();
    const ProcessResult p = run_contactlab({"devices"});
    CHECK(p.exit_code == 0);
    CHECK(contains(p.out, "permission denied"));
    CHECK(contains(p.out, "assets/udev/70-contactlab.rules"));
}

TEST_CASE("contactlab simulate --device usb:hapio streams the emulated board in real time") {
    HapioEmulator emu;
    preload_umockdev_in_children();
    TempDir dir;
    const std::string csv = dir.file("out.csv");
    const ProcessResult p = run_contactlab(
        {"simulate", scene("block.json"), "--device", "usb:hapio", "--duration", "0.5", "-o", csv});
    std::printf("%s", p.err.c_str());  // the run's own figures, for the log
    CHECK(p.exit_code == 0);
    CHECK(contains(p.err, "usb:hapio, real time"));
    CHECK(contains(p.err, "0 rejected"));
    CHECK(contains(p.err, "0 unplugs"));
    CHECK(emu.frames_sent() >= 100);
    CHECK(emu.commands_applied() >= 100);
    CHECK_FALSE(emu.streaming());  // the run closed the device and stopped the stream
    const std::string rows = read_text(csv);
    CHECK(std::count(rows.begin(), rows.end(), '\n') >= 400);  // 500 ticks at 1 kHz, plus header
}

// Below, a testbed with no device on it: the child's libusb initialises and finds an empty bus,
// which is what a machine without USB looks like to Debian's libusb, the same on every machine.

TEST_CASE("contactlab devices with no USB device says none were found and why, and exits 0") {
    HapioEmulator emu(HapioEmulator::Config{.plugged = false});
    preload_umockdev_in_children();
    const ProcessResult p = run_contactlab({"devices"});
    CHECK(p.exit_code == 0);
    CHECK(p.out ==
          "No haptic USB devices found: libusb sees no USB devices at all (no USB bus on this machine, or no "
          "access to it).\nSimulated devices are always available: --device sim-cld or replay:FILE.\n");
}

TEST_CASE("contactlab simulate --device usb:hapio without a board exits 1 and says what is missing") {
    HapioEmulator emu(HapioEmulator::Config{.plugged = false});
    preload_umockdev_in_children();
    TempDir dir;
    const ProcessResult p = run_contactlab(
        {"simulate", scene("block.json"), "--device", "usb:hapio", "--duration", "0.1", "-o", dir.file("out.csv")});
    CHECK(p.exit_code == 1);
    CHECK(contains(p.err, "simulate: device usb:hapio failed to open: no hapio board (USB 1209:c1d0) is plugged in"));
}

TEST_CASE("contactlab simulate --device usb:hapio needs --duration and takes no hand path") {
    const ProcessResult a = run_contactlab({"simulate", scene("block.json"), "--device", "usb:hapio", "-o", "x.csv"});
    CHECK(a.exit_code == 2);
    CHECK(contains(a.err, "--device usb:hapio needs --duration (s)"));
    const ProcessResult b = run_contactlab(
        {"simulate", scene("block.json"), "--device", "usb:hapio", "--task", "contour-block", "-o", "x.csv"});
    CHECK(b.exit_code == 2);
    CHECK(contains(b.err, "--device usb:hapio takes no --hand or --task"));
}
