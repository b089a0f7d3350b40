// usb_status.hpp — every libusb status mapped to a DeviceFault with a message a user can act on.
//
// Details are static strings: the transport sets them from libusb callbacks and the servo thread
// reads them, so nothing here may allocate.
#pragma once

#include "drivers/device.hpp"

namespace contactlab::drivers::usb {

// The rule that grants the logged-in user access (assets/udev/70-contactlab.rules; the Debian
// package installs it in /usr/lib/udev/rules.d/, where udev reads it once reloaded).
inline constexpr const char* kUdevHint =
    "permission denied opening the USB device: install the udev rule (sudo cp assets/udev/70-contactlab.rules "
    "/etc/udev/rules.d/ && sudo udevadm control --reload && sudo udevadm trigger; the Debian package has put it in "
    "/usr/lib/udev/rules.d/: only reload and trigger), then unplug and replug it";

// A libusb_error (negative int; LIBUSB_SUCCESS, 0, is no fault) as a fault.
DeviceFault fault_of_error(int libusb_error) noexcept;
// A libusb_transfer_status (completed is no fault).
DeviceFault fault_of_transfer(int libusb_transfer_status) noexcept;
// libusb_error_name without needing libusb.h in the caller.
const char* error_name(int libusb_error) noexcept;

}  // namespace contactlab::drivers::usb
