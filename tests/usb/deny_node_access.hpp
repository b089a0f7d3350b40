// deny_node_access.hpp — an emulated device node this process (and what it starts) cannot open,
// as an ordinary user meets a board the udev rule has not reached yet: the emulators'
// deny_permission().
#pragma once

#include <umockdev.h>

#include <string>

namespace usb_test {

// chmod 0 on the testbed's copy of `node` (e.g. "/dev/bus/usb/001/002"); as root, also drops
// CAP_DAC_OVERRIDE and CAP_DAC_READ_SEARCH, which ignore file modes.
void deny_node_access(UMockdevTestbed* testbed, const std::string& node);

}  // namespace usb_test
