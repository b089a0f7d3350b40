// usb_devices.hpp — which known haptic devices are on the USB bus, and in what state
// (`contactlab devices`). Opening is attempted only to learn about permission problems; nothing
// is claimed or detached, so listing never disturbs a device another program is using.
#pragma once

#include "drivers/usb/usb_context.hpp"

#include <cstdint>
#include <string>
#include <vector>

namespace contactlab::drivers::usb {

struct KnownModel {
    std::uint16_t vendor_id, product_id;
    const char* model;    // what a user calls it
    const char* device;   // the --device value that drives it
};
// hapio boards and the Novint Falcon (libusb), and the Haply 2DIY (its tty). Haply boards are USB serial ports: they are found
// through their ttys (serial_port.hpp) and listed with their node.
const std::vector<KnownModel>& known_models();

struct UsbDeviceEntry {
    std::string model, device;
    std::string node;     // the tty of a USB serial board (Haply 2DIY), "" for libusb devices
    int bus = 0, address = 0;
    std::uint16_t vendor_id = 0, product_id = 0;
    std::string state;    // "available", "permission denied", "busy", ...
    std::string problem;  // what to do about it (empty when available)
};

struct UsbScan {
    bool usb_available = false;  // libusb initialised
    std::string why_none;        // set when devices is empty: why nothing was found
    std::vector<UsbDeviceEntry> devices;
    int other_devices = 0;       // USB devices that are not known haptic devices
};

UsbScan scan_usb_devices(UsbContext& ctx);
// The report `contactlab devices` prints.
std::string format_scan(const UsbScan& scan);

}  // namespace contactlab::drivers::usb
