// test_haply_cli.cpp — the real `contactlab` executable against the emulated 2DIY: the child
// inherits the testbed (UMOCKDEV_DIR) and umockdev's preload library, so it finds the board's tty
// in the faked sysfs and opens the same pty a test's HaplyDevice would.
#include "haply_emulator.hpp"
#include "usb_fixture.hpp"

#include "../cli/process.hpp"

#include <doctest/doctest.h>

#include <algorithm>
#include <cstdio>

using namespace contactlab::test;
using namespace cli_test;

TEST_CASE("contactlab devices lists the emulated 2DIY with its tty and permission state") {
    HaplyEmulator emu;
    preload_umockdev_in_children();
    const ProcessResult p = run_contactlab({"devices"});
    CHECK(p.exit_code == 0);
    CHECK(contains(p.out, "Haply 2DIY (Arduino Due native port)"));
    CHECK(contains(p.out, "/dev/ttyACM0"));
    CHECK(contains(p.out, "2341:003e"));
    CHECK(contains(p.out, "--device usb:haply"));
    CHECK(contains(p.out, "available"));
}

TEST_CASE("contactlab devices names the udev rule when the 2DIY's tty cannot be opened") {
    HaplyEmulator emu;
    emu.deny_permission();  // the child inherits the dropped capability
    preload_umockdev_in_children();
    const ProcessResult p = run_contactlab({"devices"});
    CHECK(p.exit_code == 0);
    CHECK(contains(p.out, "/dev/ttyACM0"));
    CHECK(contains(p.out, "permission denied"));
    CHECK(contains(p.out, "assets/udev/70-contactlab.rules"));
}

TEST_CASE("contactlab simulate --device usb:haply exchanges with the emulated board in real time") {
    HaplyEmulator emu;
    preload_umockdev_in_children();
    TempDir dir;
    const std::string csv = dir.file("out.csv");
    const ProcessResult p = run_contactlab(
        {"simulate", scene("block.json"), "--device", "usb:haply", "--duration", "0.5", "-o", csv});
    std::printf("%s", p.err.c_str());  // the run's own figures, for the log
    CHECK(p.exit_code == 0);
    CHECK(contains(p.err, "usb:haply, real time"));
    CHECK(contains(p.err, "2DIY generation 3 on /dev/ttyACM0"));
    CHECK(contains(p.err, "0 rejected"));
    CHECK(contains(p.err, "0 unplugs"));
    CHECK(emu.exchanges() >= 100);
    CHECK(emu.parameters().size() == 26);
    const std::string rows = read_text(csv);
    CHECK(std::count(rows.begin(), rows.end(), '\n') >= 400);  // 500 ticks at 1 kHz, plus header
}

TEST_CASE("contactlab simulate --device usb:haply without a board exits 1 and says what is missing") {
    HaplyEmulator emu(HaplyEmulator::Config{.plugged = false});
    preload_umockdev_in_children();
    TempDir dir;
    const ProcessResult p = run_contactlab(
        {"simulate", scene("block.json"), "--device", "usb:haply", "--duration", "0.1", "-o", dir.file("out.csv")});
    CHECK(p.exit_code == 1);
    CHECK(contains(p.err, "simulate: device usb:haply failed to open: no Haply board found"));
}

TEST_CASE("contactlab simulate --haply-hardware takes 2 or 3 only") {
    const ProcessResult p = run_contactlab({"simulate", scene("block.json"), "--device", "usb:haply", "--haply-hardware",
                                            "4", "--duration", "0.1", "-o", "x.csv"});
    CHECK(p.exit_code == 2);
    CHECK(contains(p.err, "--haply-hardware must be 2 or 3"));
}
