// test_transport.cpp — enumeration, open + handshake, kernel driver, permissions, no USB at all:
// the real libusb against an emulated hapio board.
#include "hapio_emulator.hpp"
#include "usb_fixture.hpp"

#include "drivers/usb/hapio_device.hpp"
#include "drivers/usb/usb_devices.hpp"

#include <doctest/doctest.h>

#include <memory>

using namespace contactlab;
using namespace contactlab::drivers;
using namespace contactlab::test;

TEST_CASE("no USB at all: nothing found, and the reason is said") {
    // No testbed: libusb meets this machine as it is (no /sys/bus/usb). Debian's libusb then
    // initialises with an empty list; one built without udev fails libusb_init. Both are "none".
    auto ctx = std::make_shared<usb::UsbContext>();
    const usb::UsbScan scan = usb::scan_usb_devices(*ctx);
    CHECK(scan.devices.empty());
    CHECK_FALSE(scan.why_none.empty());
    const std::string text = usb::format_scan(scan);
    CHECK(text.find("No haptic USB devices found") == 0);
    if (ctx->ok()) CHECK(text.find("libusb sees no USB devices at all") != std::string::npos);
    else CHECK(text.find("libusb_init failed") != std::string::npos);

    hapio::HapioDevice dev({}, ctx);
    CHECK_FALSE(dev.open());
    CHECK(dev.state() == DeviceState::fault);
    CHECK(dev.fault().code == DeviceFaultCode::not_found);
    CHECK(std::string(dev.fault().detail).find("1209:c1d0") != std::string::npos);
}

TEST_CASE("enumerate: the emulated board is listed with its bus, address and state") {
    HapioEmulator emu;
    auto ctx = std::make_shared<usb::UsbContext>();
    REQUIRE(ctx->ok());
    const usb::UsbScan scan = usb::scan_usb_devices(*ctx);
    REQUIRE(scan.devices.size() == 1);
    const usb::UsbDeviceEntry& e = scan.devices[0];
    CHECK(e.model == "hapio board (CLD rig)");
    CHECK(e.device == "usb:hapio");
    CHECK(e.bus == 1);
    CHECK(e.address == emu.address());
    CHECK(e.vendor_id == 0x1209);
    CHECK(e.product_id == 0xc1d0);
    CHECK(e.state == "available");
    CHECK(e.problem.empty());
    CHECK(usb::format_scan(scan).find("bus 001 address 002") != std::string::npos);
}

TEST_CASE("open and handshake: Ready, board info read, streaming started") {
    HapioEmulator emu;
    hapio::HapioDevice dev;
    CHECK(dev.serial().empty());  // nothing said yet
    REQUIRE(dev.open());
    CHECK(dev.state() == DeviceState::ready);
    CHECK(dev.fault().code == DeviceFaultCode::none);
    CHECK(dev.serial() == "4242");  // the board's own, from its handshake (for results' provenance)
    const hapio::Info info = dev.info();
    CHECK(info.model == 1);
    CHECK(info.encoders == 4);
    CHECK(info.motors == 3);
    CHECK(info.serial == 4242);
    CHECK(emu.streaming());
    CHECK(wait_until([&] { return dev.stats().frames >= 10; }));
    dev.close();
    CHECK(dev.state() == DeviceState::disconnected);
    CHECK_FALSE(emu.streaming());  // close stops the stream
}

TEST_CASE("handshake refuses a board with too few channels") {
    HapioEmulator::Config c;
    c.info.encoders = 2;
    HapioEmulator emu(c);
    hapio::HapioDevice dev;
    CHECK_FALSE(dev.open());
    CHECK(dev.state() == DeviceState::fault);
    CHECK(dev.fault().code == DeviceFaultCode::open_failed);
    CHECK(std::string(dev.fault().detail).find("too few channels") != std::string::npos);
}

TEST_CASE("kernel driver bound: detached on open, re-attached on close") {
    HapioEmulator::Config c;
    c.kernel_driver_bound = true;
    HapioEmulator emu(c);
    {
        auto ctx = std::make_shared<usb::UsbContext>();
        const usb::UsbScan scan = usb::scan_usb_devices(*ctx);
        REQUIRE(scan.devices.size() == 1);
        CHECK(scan.devices[0].state.find("kernel driver is bound") != std::string::npos);
        CHECK(emu.kernel_driver_bound());  // listing never detaches
    }
    hapio::HapioDevice dev;
    REQUIRE(dev.open());
    CHECK_FALSE(emu.kernel_driver_bound());
    CHECK(wait_until([&] { return dev.stats().frames >= 5; }));
    dev.close();
    CHECK(emu.kernel_driver_bound());
}

TEST_CASE("permission denied: open fails and names the udev rule, and listing says so too") {
    HapioEmulator emu;
    emu.deny_permission();
    auto ctx = std::make_shared<usb::UsbContext>();
    const usb::UsbScan scan = usb::scan_usb_devices(*ctx);
    REQUIRE(scan.devices.size() == 1);
    CHECK(scan.devices[0].state == "permission denied");
    CHECK(scan.devices[0].problem.find("70-contactlab.rules") != std::string::npos);

    hapio::HapioDevice dev({}, ctx);
    CHECK_FALSE(dev.open());
    CHECK(dev.state() == DeviceState::fault);
    CHECK(dev.fault().code == DeviceFaultCode::permission_denied);
    CHECK(std::string(dev.fault().detail).find("udev") != std::string::npos);
}
