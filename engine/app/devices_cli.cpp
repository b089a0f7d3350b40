// devices_cli.cpp — `contactlab devices`: the haptic USB devices that are plugged in, their bus
// and address, whether this user may open them, or why none were found. Always exits 0: finding
// no device is an answer, not an error.
#include "engine/app/subcommands.hpp"

#include "drivers/usb/usb_devices.hpp"

#include <cstdio>

namespace contactlab::app {

void register_devices_command(CLI::App& app, int& rc) {
    CLI::App* cmd = app.add_subcommand("devices", "List haptic USB devices (hapio boards, Novint Falcon, Haply 2DIY) and their state");
    cmd->callback([&rc] {
        drivers::usb::UsbContext ctx;
        const drivers::usb::UsbScan scan = drivers::usb::scan_usb_devices(ctx);
        std::fputs(drivers::usb::format_scan(scan).c_str(), stdout);
        rc = 0;
    });
}

}  // namespace contactlab::app
