// usb_devices.cpp — listing known devices (see usb_devices.hpp).
#include "drivers/usb/usb_devices.hpp"
#include "drivers/usb/hapio_protocol.hpp"
#include "drivers/usb/haply_device.hpp"
#include "drivers/usb/serial_port.hpp"
#include "drivers/usb/usb_status.hpp"

#include <libusb.h>

#include <cstdio>

namespace contactlab::drivers::usb {

const std::vector<KnownModel>& known_models() {
    static const std::vector<KnownModel> models{
        {hapio::kVendorId, hapio::kProductId, "hapio board (CLD rig)", "usb:hapio"},
        {0x0403, 0xcb48, "Novint Falcon", "usb:falcon"},
        // Listed through its tty (add_haply_boards), not libusb: the id is the Due's native port.
        {0x2341, 0x003e, "Haply 2DIY", "usb:haply"},
    };
    return models;
}

namespace {

// Haply boards: ttys whose USB device has one of the 2DIY board ids. Only access() is asked:
// opening a tty may reset an Arduino-class board, and listing must never disturb a device.
void add_haply_boards(UsbScan& scan) {
    for (const serial::UsbTty& t : serial::usb_ttys()) {
        const haply::BoardId* id = nullptr;
        for (const haply::BoardId& b : haply::kBoardIds)
            if (b.vendor_id == t.vendor_id && b.product_id == t.product_id) id = &b;
        if (id == nullptr) continue;
        UsbDeviceEntry e;
        e.model = std::string("Haply 2DIY (") + id->what + ")";
        e.device = "usb:haply";
        e.node = t.node;
        e.vendor_id = t.vendor_id;
        e.product_id = t.product_id;
        if (t.accessible) {
            e.state = "available";
        } else {
            e.state = "permission denied";
            e.problem = "permission denied opening " + t.node +
                        ": install the udev rule (sudo cp assets/udev/70-contactlab.rules /etc/udev/rules.d/ && sudo "
                        "udevadm control --reload && sudo udevadm trigger), or add yourself to the dialout group; then "
                        "unplug and replug the board";
        }
        scan.devices.push_back(e);
    }
}

}  // namespace

UsbScan scan_usb_devices(UsbContext& ctx) {
    UsbScan scan;
    add_haply_boards(scan);
    if (!ctx.ok()) {
        if (scan.devices.empty()) scan.why_none = ctx.why();
        return scan;
    }
    scan.usb_available = true;
    libusb_device** list = nullptr;
    const ssize_t n = libusb_get_device_list(ctx.raw(), &list);
    if (n < 0) {
        scan.why_none = std::string("listing USB devices failed: ") + libusb_error_name(static_cast<int>(n));
        return scan;
    }
    for (ssize_t i = 0; i < n; ++i) {
        libusb_device_descriptor d{};
        if (libusb_get_device_descriptor(list[i], &d) != LIBUSB_SUCCESS) continue;
        if (haply::is_board_id(d.idVendor, d.idProduct)) continue;  // a serial board: its tty is listed
        const KnownModel* m = nullptr;
        for (const KnownModel& k : known_models())
            if (k.vendor_id == d.idVendor && k.product_id == d.idProduct) m = &k;
        if (m == nullptr) {
            ++scan.other_devices;
            continue;
        }
        UsbDeviceEntry e;
        e.model = m->model;
        e.device = m->device;
        e.bus = libusb_get_bus_number(list[i]);
        e.address = libusb_get_device_address(list[i]);
        e.vendor_id = d.idVendor;
        e.product_id = d.idProduct;
        libusb_device_handle* h = nullptr;
        const int rc = libusb_open(list[i], &h);
        if (rc == LIBUSB_SUCCESS) {
            const int active = libusb_kernel_driver_active(h, 0);
            e.state = active == 1 ? "available (a kernel driver is bound; it is detached on open)" : "available";
            libusb_close(h);
        } else if (rc == LIBUSB_ERROR_ACCESS) {
            e.state = "permission denied";
            e.problem = kUdevHint;
        } else {
            const DeviceFault f = fault_of_error(rc);
            e.state = std::string("cannot open (") + libusb_error_name(rc) + ")";
            e.problem = f.detail;
        }
        scan.devices.push_back(e);
    }
    libusb_free_device_list(list, 1);
    if (scan.devices.empty()) {
        scan.why_none = n == 0 ? "libusb sees no USB devices at all (no USB bus on this machine, or no access to it)"
                               : "none of the " + std::to_string(n) +
                                     " USB devices is a known haptic device (hapio 1209:c1d0, Falcon 0403:cb48, Haply "
                                     "2DIY on an Arduino Due 2341:003e/003d or Zero 2341:804d serial port)";
    }
    return scan;
}

std::string format_scan(const UsbScan& scan) {
    std::string out;
    char line[256];
    if (scan.devices.empty()) {
        out += "No haptic USB devices found: " + scan.why_none + ".\n";
        out += "Simulated devices are always available: --device sim-cld or replay:FILE.\n";
        return out;
    }
    for (const UsbDeviceEntry& e : scan.devices) {
        if (!e.node.empty()) {
            std::snprintf(line, sizeof line, "%-24s %-21s  %04x:%04x  --device %-10s  %s\n", e.model.c_str(), e.node.c_str(),
                          e.vendor_id, e.product_id, e.device.c_str(), e.state.c_str());
            out += line;
            if (!e.problem.empty()) out += "    " + e.problem + "\n";
            continue;
        }
        std::snprintf(line, sizeof line, "%-24s bus %03d address %03d  %04x:%04x  --device %-10s  %s\n", e.model.c_str(),
                      e.bus, e.address, e.vendor_id, e.product_id, e.device.c_str(), e.state.c_str());
        out += line;
        if (!e.problem.empty()) out += "    " + e.problem + "\n";
    }
    return out;
}

}  // namespace contactlab::drivers::usb
