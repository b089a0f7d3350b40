// falcon_emulator.cpp — the FTDI bridge and the Falcon's microcontroller behind umockdev's usbfs
// ioctl emulation (see falcon_emulator.hpp and hapio_emulator.cpp for the URB handling rules).
#include "falcon_emulator.hpp"

#include <linux/ioctl.h>
#include <linux/usbdevice_fs.h>

#include <umockdev.h>

#include <algorithm>
#include <cerrno>
#include <cstddef>
#include <cstdio>
#include <cstring>
#include <deque>
#include <mutex>
#include <stdexcept>
#include <string>

namespace contactlab::test {

using namespace drivers::falcon;

namespace {

// FT232 as the Falcon has it: 0403:cb48, one vendor interface, bulk 0x81 IN and 0x02 OUT.
constexpr const char* kDescriptors =
    "1201100100000008" "0304" "48cb" "0006" "01020301"
    "090220000101008032"
    "0904000002ffffff02"
    "07058102400000"
    "07050202400000";

gboolean on_ioctl_cb(UMockdevIoctlBase*, UMockdevIoctlClient* client, gpointer self);

}  // namespace

struct FalconEmulator::Impl {
    Config cfg;
    UMockdevTestbed* testbed = nullptr;
    std::vector<UMockdevIoctlBase*> handlers;
    mutable std::mutex mu;
    int address = 1;
    bool plugged = false;
    std::string syspath;

    // FTDI and microcontroller state.
    std::uint16_t baud = 0;
    bool dtr = false, kernel_driver = false;
    enum class Mode { off, bootloader, uploading, running } mode = Mode::off;
    bool upload_armed = false;  // 'A' seen at the upload speed
    std::vector<std::uint8_t> uploaded;
    std::deque<std::uint8_t> rx;  // serial bytes waiting for the host (IN)
    std::vector<std::uint8_t> cmd_buf;
    std::array<std::int16_t, 3> encoders{};
    std::uint8_t homed = 0;
    Command last;
    std::uint64_t commands = 0;
    int handshakes = 0;

    struct Urb {
        UMockdevIoctlData* data;
        usbdevfs_urb* urb;
        UMockdevIoctlClient* client;
    };
    std::deque<Urb> ready;

    void serial_in(const std::uint8_t* d, int n) {  // bytes the host wrote to the serial port
        for (int i = 0; i < n; ++i) {
            const std::uint8_t b = d[i];
            if (mode == Mode::bootloader && baud == 0x4138) {
                cmd_buf.push_back(b);
                if (cmd_buf.size() >= kBootProbe.size() &&
                    std::equal(kBootProbe.begin(), kBootProbe.end(), cmd_buf.end() - kBootProbe.size())) {
                    cmd_buf.clear();
                    if (cfg.bootloader_answers) {
                        ++handshakes;
                        rx.insert(rx.end(), kBootReply.begin(), kBootReply.end());
                    }
                }
            } else if (mode == Mode::bootloader && baud == 0x0015 && !upload_armed) {
                if (b == kUploadProbe) {
                    upload_armed = true;
                    mode = Mode::uploading;
                    uploaded.clear();
                    rx.push_back(b);
                }
            } else if (mode == Mode::uploading && baud == 0x0015) {
                uploaded.push_back(b);
                rx.push_back(b);  // the bootloader echoes every byte
            } else if (mode == Mode::running) {
                cmd_buf.push_back(b);
                if (cmd_buf.size() == kPacketSize) {
                    State dummy;
                    // Commands use the same armour as replies: decode with the reply decoder.
                    if (unpack(cmd_buf.data(), kPacketSize, dummy)) {
                        last.motor = dummy.encoder;
                        last.flags = dummy.buttons;
                        ++commands;
                        std::uint8_t out[kPacketSize];
                        Command reply;
                        reply.motor = encoders;
                        pack(reply, out);
                        out[13] = static_cast<std::uint8_t>(0x41 + (homed << 4));
                        rx.insert(rx.end(), out, out + kPacketSize);
                    }
                    cmd_buf.clear();
                } else if (cmd_buf.size() == 1 && cmd_buf[0] != '<') {
                    cmd_buf.clear();
                }
            }
        }
    }

    void control(std::uint8_t req, std::uint16_t value) {
        switch (req) {
            case kFtdiBaudRate:
                baud = value;
                // Switching to the normal speed after a complete upload starts the firmware.
                if (value == 0x0002 && mode == Mode::uploading && uploaded == cfg.firmware) mode = Mode::running;
                break;
            case kFtdiModemCtrl:
                if ((value & 0x0100) != 0) {
                    const bool high = (value & 0x0001) != 0;
                    if (dtr && !high) { /* falling edge: nothing */ }
                    if (!dtr && high) {  // a DTR pulse resets the microcontroller into its bootloader
                        mode = Mode::bootloader;
                        upload_armed = false;
                        cmd_buf.clear();
                        rx.clear();
                    }
                    dtr = high;
                }
                break;
            case kFtdiReset:
                if (value == 1) rx.clear();
                if (value == 2) cmd_buf.clear();
                break;
            default: break;
        }
    }

    gboolean handle(UMockdevIoctlClient* client) {
        const gulong request = umockdev_ioctl_client_get_request(client);
        UMockdevIoctlData* arg = umockdev_ioctl_client_get_arg(client);
        std::lock_guard<std::mutex> lock(mu);
        if (!plugged) {
            umockdev_ioctl_client_complete(client, -1, ENODEV);
            return TRUE;
        }
        switch (request) {
            case USBDEVFS_GET_CAPABILITIES: {
                UMockdevIoctlData* d = umockdev_ioctl_data_resolve(arg, 0, sizeof(guint32), nullptr);
                *reinterpret_cast<guint32*>(d->data) = USBDEVFS_CAP_BULK_CONTINUATION | USBDEVFS_CAP_NO_PACKET_SIZE_LIM |
                                                       USBDEVFS_CAP_REAP_AFTER_DISCONNECT | USBDEVFS_CAP_ZERO_PACKET;
                umockdev_ioctl_client_complete(client, 0, 0);
                umockdev_ioctl_data_unref(d);
                return TRUE;
            }
            case USBDEVFS_CLAIMINTERFACE:
            case USBDEVFS_RELEASEINTERFACE:
            case USBDEVFS_CLEAR_HALT:
            case USBDEVFS_RESET:
            case USBDEVFS_RESETEP:
                umockdev_ioctl_client_complete(client, 0, 0);
                return TRUE;
            case USBDEVFS_GETDRIVER: {
                UMockdevIoctlData* d = umockdev_ioctl_data_resolve(arg, 0, sizeof(usbdevfs_getdriver), nullptr);
                auto* g = reinterpret_cast<usbdevfs_getdriver*>(d->data);
                if (kernel_driver) {
                    std::snprintf(g->driver, sizeof g->driver, "ftdi_sio");
                    umockdev_ioctl_client_complete(client, 0, 0);
                } else {
                    umockdev_ioctl_client_complete(client, -1, ENODATA);
                }
                umockdev_ioctl_data_unref(d);
                return TRUE;
            }
            case USBDEVFS_DISCONNECT_CLAIM:
                kernel_driver = false;
                umockdev_ioctl_client_complete(client, 0, 0);
                return TRUE;
            case USBDEVFS_IOCTL: {
                UMockdevIoctlData* d = umockdev_ioctl_data_resolve(arg, 0, sizeof(usbdevfs_ioctl), nullptr);
                const auto* io = reinterpret_cast<usbdevfs_ioctl*>(d->data);
                if (io->ioctl_code == static_cast<int>(USBDEVFS_CONNECT)) {
                    kernel_driver = true;
                    umockdev_ioctl_client_complete(client, 1, 0);
                } else if (io->ioctl_code == static_cast<int>(USBDEVFS_DISCONNECT)) {
                    kernel_driver = false;
                    umockdev_ioctl_client_complete(client, 0, 0);
                } else {
                    umockdev_ioctl_client_complete(client, -1, ENOTTY);
                }
                umockdev_ioctl_data_unref(d);
                return TRUE;
            }
            case USBDEVFS_SUBMITURB: {
                UMockdevIoctlData* data = umockdev_ioctl_data_resolve(arg, 0, sizeof(usbdevfs_urb), nullptr);
                auto* urb = reinterpret_cast<usbdevfs_urb*>(data->data);
                umockdev_ioctl_data_unref(umockdev_ioctl_data_resolve(data, offsetof(usbdevfs_urb, buffer),
                                                                      static_cast<gsize>(urb->buffer_length), nullptr));
                Urb u{data, urb, client};
                auto* b = static_cast<std::uint8_t*>(urb->buffer);
                urb->status = 0;
                urb->actual_length = 0;
                if (urb->type == USBDEVFS_URB_TYPE_CONTROL && b[0] == 0x80 && b[1] == 6 && b[3] == 3) {
                    // GET_DESCRIPTOR (string): index 0 lists the languages (US English), index 3
                    // is the FTDI chip's serial number, UTF-16LE. actual_length excludes the setup.
                    std::vector<std::uint8_t> d{0, 3};
                    if (b[2] == 0) {
                        d.insert(d.end(), {0x09, 0x04});
                    } else if (b[2] == 3) {
                        for (char ch : cfg.serial) d.insert(d.end(), {static_cast<std::uint8_t>(ch), 0});
                    } else {
                        urb->status = -EPIPE;  // no such string: the device stalls the request
                    }
                    d[0] = static_cast<std::uint8_t>(d.size());
                    const int want = b[6] | (b[7] << 8);
                    const int n = urb->status == 0 ? std::min<int>(want, static_cast<int>(d.size())) : 0;
                    std::memcpy(b + 8, d.data(), static_cast<std::size_t>(n));
                    urb->actual_length = n;
                } else if (urb->type == USBDEVFS_URB_TYPE_CONTROL) {
                    control(b[1], static_cast<std::uint16_t>(b[2] | (b[3] << 8)));
                } else if (urb->endpoint == kEndpointOut) {
                    serial_in(b, urb->buffer_length);
                    urb->actual_length = urb->buffer_length;
                } else if (urb->endpoint == kEndpointIn) {
                    // Two modem-status bytes, then whatever serial data is waiting (up to 62 per
                    // 64-byte packet; one packet per URB keeps this simple and legal).
                    b[0] = 0x31;
                    b[1] = 0x60;
                    int n = 2;
                    while (n < std::min<int>(urb->buffer_length, static_cast<int>(kFtdiPacket)) && !rx.empty()) {
                        b[n++] = rx.front();
                        rx.pop_front();
                    }
                    urb->actual_length = n;
                }
                ready.push_back(u);
                umockdev_ioctl_client_complete(client, 0, 0);
                return TRUE;
            }
            case USBDEVFS_DISCARDURB: {
                umockdev_ioctl_client_complete(client, -1, EINVAL);  // every URB completes at once
                return TRUE;
            }
            case USBDEVFS_REAPURB:
            case USBDEVFS_REAPURBNDELAY: {
                auto it = std::find_if(ready.begin(), ready.end(), [client](const Urb& u) { return u.client == client; });
                if (it == ready.end()) {
                    umockdev_ioctl_client_complete(client, -1, EAGAIN);
                    return TRUE;
                }
                Urb u = *it;
                ready.erase(it);
                UMockdevIoctlData* ptr = umockdev_ioctl_data_resolve(arg, 0, sizeof(gpointer), nullptr);
                umockdev_ioctl_data_set_ptr(ptr, 0, u.data);
                umockdev_ioctl_client_complete(client, 0, 0);
                umockdev_ioctl_data_unref(ptr);
                umockdev_ioctl_data_unref(u.data);
                return TRUE;
            }
            default:
                umockdev_ioctl_client_complete(client, -1, ENOTTY);
                return TRUE;
        }
    }

    std::string node() const {
        char buf[64];
        std::snprintf(buf, sizeof buf, "/dev/bus/usb/002/%03d", address);
        return buf;
    }

    void add_device() {
        const std::string n = node();
        UMockdevIoctlBase* handler = umockdev_ioctl_base_new();
        g_signal_connect(handler, "handle-ioctl", G_CALLBACK(on_ioctl_cb), this);
        handlers.push_back(handler);
        GError* err = nullptr;
        if (!umockdev_testbed_attach_ioctl(testbed, n.c_str(), handler, &err)) {
            const std::string msg = err ? err->message : "?";
            if (err) g_error_free(err);
            throw std::runtime_error("umockdev_testbed_attach_ioctl: " + msg);
        }
        char dev[16];
        std::snprintf(dev, sizeof dev, "%03d", address);
        const std::string devpath = "/devices/pci0000:00/usb2/2-" + std::to_string(address);
        const std::string rec = "P: " + devpath + "\n" + "N: bus/usb/002/" + dev +
                                "=00\nE: SUBSYSTEM=usb\nE: DEVTYPE=usb_device\nE: DRIVER=usb\nE: BUSNUM=002\n"
                                "E: DEVNUM=" + dev + "\nE: DEVNAME=" + n + "\nA: busnum=2\\n\nA: devnum=" +
                                std::to_string(address) + "\\n\nA: speed=12\\n\nA: bConfigurationValue=1\\n\n" +
                                "H: descriptors=" + kDescriptors + "\n";
        if (!umockdev_testbed_add_from_string(testbed, rec.c_str(), &err)) {
            const std::string msg = err ? err->message : "?";
            if (err) g_error_free(err);
            throw std::runtime_error("umockdev_testbed_add_from_string: " + msg);
        }
        syspath = "/sys" + devpath;
    }
};

namespace {
gboolean on_ioctl_cb(UMockdevIoctlBase*, UMockdevIoctlClient* client, gpointer self) {
    return static_cast<FalconEmulator::Impl*>(self)->handle(client);
}
}  // namespace

FalconEmulator::FalconEmulator(const Config& c) : impl_(std::make_unique<Impl>()) {
    impl_->cfg = c;
    impl_->testbed = umockdev_testbed_new();
    plug();
}

FalconEmulator::~FalconEmulator() {
    {
        std::lock_guard<std::mutex> lock(impl_->mu);
        for (auto& u : impl_->ready) umockdev_ioctl_data_unref(u.data);
        impl_->ready.clear();
    }
    g_clear_object(&impl_->testbed);
    for (UMockdevIoctlBase* h : impl_->handlers) g_object_unref(h);
}

void FalconEmulator::plug() {
    {
        std::lock_guard<std::mutex> lock(impl_->mu);
        if (impl_->plugged) return;
        ++impl_->address;
        impl_->plugged = true;
        // Power-on: the microcontroller runs its firmware only if it kept it (Config).
        impl_->mode = impl_->cfg.firmware_running ? Impl::Mode::running : Impl::Mode::off;
        impl_->dtr = false;
        impl_->rx.clear();
        impl_->cmd_buf.clear();
        impl_->kernel_driver = impl_->cfg.kernel_driver_bound;
    }
    impl_->add_device();
}

void FalconEmulator::unplug() {
    std::string path;
    {
        std::lock_guard<std::mutex> lock(impl_->mu);
        if (!impl_->plugged) return;
        impl_->plugged = false;
        impl_->cfg.firmware_running = false;  // power is gone: the firmware must be uploaded again
        path = impl_->syspath;
    }
    umockdev_testbed_uevent(impl_->testbed, path.c_str(), "remove");  // see HapioEmulator::unplug
}

void FalconEmulator::set_encoders(const std::array<std::int16_t, 3>& c) {
    std::lock_guard<std::mutex> lock(impl_->mu);
    impl_->encoders = c;
}
void FalconEmulator::set_homed(std::uint8_t bits) {
    std::lock_guard<std::mutex> lock(impl_->mu);
    impl_->homed = bits;
}
Command FalconEmulator::last_command() const {
    std::lock_guard<std::mutex> lock(impl_->mu);
    return impl_->last;
}
std::uint64_t FalconEmulator::commands() const {
    std::lock_guard<std::mutex> lock(impl_->mu);
    return impl_->commands;
}
std::uint64_t FalconEmulator::uploaded_bytes() const {
    std::lock_guard<std::mutex> lock(impl_->mu);
    return impl_->uploaded.size();
}
int FalconEmulator::handshakes() const {
    std::lock_guard<std::mutex> lock(impl_->mu);
    return impl_->handshakes;
}
bool FalconEmulator::firmware_running() const {
    std::lock_guard<std::mutex> lock(impl_->mu);
    return impl_->mode == Impl::Mode::running;
}
bool FalconEmulator::kernel_driver_bound() const {
    std::lock_guard<std::mutex> lock(impl_->mu);
    return impl_->kernel_driver;
}

}  // namespace contactlab::test
