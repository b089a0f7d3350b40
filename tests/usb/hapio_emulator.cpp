// hapio_emulator.cpp — firmware behaviour behind umockdev's usbfs ioctl emulation (see .hpp).
#include "hapio_emulator.hpp"

#include "deny_node_access.hpp"

// <linux/ioctl.h> first: <linux/usbdevice_fs.h> needs its macros.
#include <linux/ioctl.h>
#include <linux/usbdevice_fs.h>
#include <sys/stat.h>
#include <sys/syscall.h>
#include <unistd.h>

#include <umockdev.h>

#include <cerrno>
#include <chrono>
#include <cstddef>
#include <algorithm>
#include <cstring>
#include <stdexcept>
#include <vector>

namespace contactlab::test {

using namespace drivers::hapio;

namespace {

// Full-speed device 1209:c1d0 with one configuration: interface 0 (class ff/48/01) with
// interrupt IN 0x81 and interrupt OUT 0x01, 64 bytes, 1 ms (HAPIO.md §2).
constexpr const char* kDescriptors =
    "12011001000000400912d0c1000101020301"
    "090220000101008032"
    "0904000002ff480100"
    "07058103400001"
    "07050103400001";

double seconds() {
    using namespace std::chrono;
    return duration<double>(steady_clock::now().time_since_epoch()).count();
}

}  // namespace

namespace {
gboolean on_ioctl_cb(UMockdevIoctlBase*, UMockdevIoctlClient* client, gpointer self);
}  // namespace

struct HapioEmulator::Impl {
    Config cfg;
    UMockdevTestbed* testbed = nullptr;
    // One ioctl handler per plug-in: a handler shared by the old node (closed by libusb after the
    // unplug) and the new one was seen to drop the new node's connection.
    std::vector<UMockdevIoctlBase*> handlers;
    mutable std::mutex mu;

    int address = 1;  // devnum; a replug gets the next one, as on a real bus
    bool plugged = false;
    std::string syspath;

    // Firmware state.
    bool streaming = false;
    bool kernel_driver = false;
    bool motors_on = false;
    bool halted = false;
    bool stall_next = false;
    bool silent = false;
    Corruption corrupt = Corruption::none;
    int corrupt_left = 0;
    std::uint16_t seq = 0, ack = 0, faults = 0, rejected = 0;
    std::array<std::int32_t, 4> encoders{};
    std::array<std::uint16_t, 4> adc{};
    Command last;
    std::uint64_t applied = 0, rejected_total = 0, frames = 0, clear_halts = 0, discards = 0;
    double next_frame = 0.0;
    double t0 = seconds();

    // URBs: kept referenced from submit until reaped (libusb owns their memory meanwhile).
    // Each URB belongs to one open descriptor (client): a URB submitted before an unplug must
    // never be handed to the descriptor of the replugged device.
    struct Urb {
        UMockdevIoctlData* data;
        usbdevfs_urb* urb;
        UMockdevIoctlClient* client;
    };
    std::deque<Urb> pending_in;  // IN transfers waiting for a frame
    std::deque<Urb> ready;       // completed, waiting to be reaped (status/length already set)

    void fill_state(Urb u) {
        State s;
        s.sequence = ++seq;
        s.encoders = cfg.info.encoders;  // the channels the board said it has (GET_INFO)
        s.analog = cfg.info.analog;
        s.motors = cfg.info.motors;
        s.adc = adc;
        s.time_us = static_cast<std::uint32_t>((seconds() - t0) * 1e6);
        s.encoder = encoders;
        s.status = static_cast<std::uint16_t>((streaming ? kStatusStreaming : 0) | (motors_on ? kStatusMotorsOn : 0));
        s.faults = faults;
        s.ack_sequence = ack;
        s.rejected_commands = rejected;
        std::uint8_t buf[kStateSize];
        pack(s, buf);
        int len = kStateSize;
        if (corrupt_left > 0) {
            switch (corrupt) {
                case Corruption::none: break;
                case Corruption::short_frame: len = 20; break;
                case Corruption::bad_magic: buf[0] = 'X'; break;
                case Corruption::bad_crc: buf[13] ^= 0x40; break;  // a flipped bit in encoder 0
                case Corruption::bad_version:
                    buf[2] = kVersion + 1;
                    break;
                case Corruption::bad_counts: {
                    buf[3] = 9;  // nine encoders: impossible in a 64-byte frame
                    const std::uint32_t c = crc32(buf, 60);
                    for (int i = 0; i < 4; ++i) buf[60 + i] = (c >> (8 * i)) & 0xFF;
                    break;
                }
            }
            if (--corrupt_left == 0) corrupt = Corruption::none;
        }
        std::memcpy(u.urb->buffer, buf, static_cast<std::size_t>(std::min(len, u.urb->buffer_length)));
        u.urb->actual_length = std::min(len, u.urb->buffer_length);
        u.urb->status = 0;
        ++frames;
    }

    void apply_command(const std::uint8_t* d, int n) {
        Command c;
        if (unpack(d, static_cast<std::size_t>(n), c) != FrameError::none) {
            ++rejected;
            ++rejected_total;
            faults |= kFaultBadCommand;
            motors_on = false;  // a garbled command never reaches the amplifiers
            return;
        }
        if (c.flags & kCommandClearFault) faults &= static_cast<std::uint16_t>(~(kFaultHostWatchdog | kFaultBadCommand));
        last = c;
        ack = c.sequence;
        ++applied;
        motors_on = (c.flags & kCommandEnable) && faults == 0;
    }

    // A control transfer: the 8 setup bytes, then data. Completes at once.
    void control(Urb u) {
        auto* b = static_cast<std::uint8_t*>(u.urb->buffer);
        const std::uint8_t type = b[0], req = b[1];
        const std::uint16_t value = static_cast<std::uint16_t>(b[2] | (b[3] << 8));
        const std::uint16_t length = static_cast<std::uint16_t>(b[6] | (b[7] << 8));
        u.urb->status = 0;
        u.urb->actual_length = 0;  // excludes the setup bytes, as the kernel reports it
        if ((type & 0x60) != 0x40) {
            u.urb->status = -EPIPE;  // only vendor requests are implemented
        } else if (req == static_cast<std::uint8_t>(Request::get_info) && (type & 0x80)) {
            std::uint8_t info[kInfoSize];
            pack(cfg.info, info);
            const int n = std::min<int>(length, kInfoSize);
            std::memcpy(b + 8, info, static_cast<std::size_t>(n));
            u.urb->actual_length = n;
        } else if (req == static_cast<std::uint8_t>(Request::set_streaming)) {
            streaming = value != 0;
            if (!streaming) motors_on = false;
        } else if (req == static_cast<std::uint8_t>(Request::clear_fault)) {
            faults = 0;
        } else {
            u.urb->status = -EPIPE;
        }
        ready.push_back(u);
    }

    gboolean handle(UMockdevIoctlClient* client) {
        const gulong request = umockdev_ioctl_client_get_request(client);
        UMockdevIoctlData* arg = umockdev_ioctl_client_get_arg(client);
        std::lock_guard<std::mutex> lock(mu);
        if (!plugged && request != USBDEVFS_GET_CAPABILITIES) {
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
            case USBDEVFS_RESET:
            case USBDEVFS_RESETEP:
                umockdev_ioctl_client_complete(client, 0, 0);
                return TRUE;
            case USBDEVFS_CLEAR_HALT:
                halted = false;
                ++clear_halts;
                umockdev_ioctl_client_complete(client, 0, 0);
                return TRUE;
            case USBDEVFS_GETDRIVER: {
                UMockdevIoctlData* d = umockdev_ioctl_data_resolve(arg, 0, sizeof(usbdevfs_getdriver), nullptr);
                auto* g = reinterpret_cast<usbdevfs_getdriver*>(d->data);
                if (!kernel_driver) {
                    umockdev_ioctl_client_complete(client, -1, ENODATA);
                } else {
                    std::snprintf(g->driver, sizeof g->driver, "usbhid");
                    umockdev_ioctl_client_complete(client, 0, 0);
                }
                umockdev_ioctl_data_unref(d);
                return TRUE;
            }
            case USBDEVFS_DISCONNECT_CLAIM:
                kernel_driver = false;  // detached, and the interface claimed by usbfs
                umockdev_ioctl_client_complete(client, 0, 0);
                return TRUE;
            case USBDEVFS_IOCTL: {
                UMockdevIoctlData* d = umockdev_ioctl_data_resolve(arg, 0, sizeof(usbdevfs_ioctl), nullptr);
                const auto* io = reinterpret_cast<usbdevfs_ioctl*>(d->data);
                if (io->ioctl_code == static_cast<int>(USBDEVFS_DISCONNECT)) {
                    const bool had = kernel_driver;
                    kernel_driver = false;
                    umockdev_ioctl_client_complete(client, had ? 0 : -1, had ? 0 : ENODATA);
                } else if (io->ioctl_code == static_cast<int>(USBDEVFS_CONNECT)) {
                    kernel_driver = true;
                    umockdev_ioctl_client_complete(client, 1, 0);  // the kernel returns 1 here
                } else {
                    umockdev_ioctl_client_complete(client, -1, ENOTTY);
                }
                umockdev_ioctl_data_unref(d);
                return TRUE;
            }
            case USBDEVFS_SUBMITURB: {
                UMockdevIoctlData* data = umockdev_ioctl_data_resolve(arg, 0, sizeof(usbdevfs_urb), nullptr);
                auto* urb = reinterpret_cast<usbdevfs_urb*>(data->data);
                // The parent keeps the resolved buffer alive and writes it back when the URB is reaped.
                umockdev_ioctl_data_unref(umockdev_ioctl_data_resolve(data, offsetof(usbdevfs_urb, buffer),
                                                                      static_cast<gsize>(urb->buffer_length), nullptr));
                Urb u{data, urb, client};  // our reference until reaped
                if (urb->type == USBDEVFS_URB_TYPE_CONTROL) {
                    control(u);
                } else if (urb->endpoint == kEndpointIn) {
                    pending_in.push_back(u);
                } else if (urb->endpoint == kEndpointOut) {
                    apply_command(static_cast<const std::uint8_t*>(urb->buffer), urb->buffer_length);
                    urb->actual_length = urb->buffer_length;
                    urb->status = 0;
                    ready.push_back(u);
                } else {
                    umockdev_ioctl_data_unref(data);
                    umockdev_ioctl_client_complete(client, -1, ENOENT);
                    return TRUE;
                }
                umockdev_ioctl_client_complete(client, 0, 0);
                return TRUE;
            }
            case USBDEVFS_DISCARDURB: {
                void* addr = *reinterpret_cast<void**>(arg->data);
                for (auto it = pending_in.begin(); it != pending_in.end(); ++it) {
                    if (reinterpret_cast<void*>(it->data->client_addr) == addr) {
                        it->urb->status = -ENOENT;
                        it->urb->actual_length = 0;
                        ready.push_back(*it);
                        pending_in.erase(it);
                        ++discards;
                        umockdev_ioctl_client_complete(client, 0, 0);
                        return TRUE;
                    }
                }
                umockdev_ioctl_client_complete(client, -1, EINVAL);
                return TRUE;
            }
            case USBDEVFS_REAPURB:
            case USBDEVFS_REAPURBNDELAY: {
                auto mine = [client](const Urb& u) { return u.client == client; };
                auto in = std::find_if(pending_in.begin(), pending_in.end(), mine);
                if (in != pending_in.end() && streaming && !silent) {
                    const double now = seconds();
                    if (halted || stall_next) {
                        Urb u = *in;
                        pending_in.erase(in);
                        u.urb->status = -EPIPE;
                        u.urb->actual_length = 0;
                        stall_next = false;
                        halted = true;  // until the host clears the halt
                        ready.push_back(u);
                    } else if (cfg.frame_period <= 0.0 || now >= next_frame) {
                        next_frame = std::max(now, next_frame + cfg.frame_period);
                        Urb u = *in;
                        pending_in.erase(in);
                        fill_state(u);
                        ready.push_back(u);
                    }
                }
                auto done = std::find_if(ready.begin(), ready.end(), mine);
                if (done == ready.end()) {
                    umockdev_ioctl_client_complete(client, -1, EAGAIN);
                    return TRUE;
                }
                Urb u = *done;
                ready.erase(done);
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
        std::snprintf(buf, sizeof buf, "/dev/bus/usb/001/%03d", address);
        return buf;
    }

    void add_device() {
        const std::string n = node();
        GError* err = nullptr;
        UMockdevIoctlBase* handler = umockdev_ioctl_base_new();
        g_signal_connect(handler, "handle-ioctl", G_CALLBACK(on_ioctl_cb), this);
        handlers.push_back(handler);
        if (!umockdev_testbed_attach_ioctl(testbed, n.c_str(), handler, &err)) {
            const std::string msg = err ? err->message : "?";
            if (err) g_error_free(err);
            throw std::runtime_error("umockdev_testbed_attach_ioctl: " + msg);
        }
        char dev[16];
        std::snprintf(dev, sizeof dev, "%03d", address);
        const std::string devpath = "/devices/pci0000:00/usb1/1-" + std::to_string(address);
        const std::string rec = "P: " + devpath + "\n" +
                                "N: bus/usb/001/" + dev + "=00\n"
                                "E: SUBSYSTEM=usb\n"
                                "E: DEVTYPE=usb_device\n"
                                "E: DRIVER=usb\n"
                                "E: BUSNUM=001\n"
                                "E: DEVNUM=" + dev + "\n"
                                "E: DEVNAME=" + n + "\n"
                                "A: busnum=1\\n\n"
                                "A: devnum=" + std::to_string(address) + "\\n\n"
                                "A: speed=12\\n\n"
                                "A: bConfigurationValue=1\\n\n"
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
    return static_cast<HapioEmulator::Impl*>(self)->handle(client);
}
}  // namespace

HapioEmulator::HapioEmulator(const Config& c) : impl_(std::make_unique<Impl>()) {
    impl_->cfg = c;
    impl_->kernel_driver = c.kernel_driver_bound;
    impl_->testbed = umockdev_testbed_new();
    if (c.plugged) plug();
}

HapioEmulator::~HapioEmulator() {
    {
        std::lock_guard<std::mutex> lock(impl_->mu);
        for (auto& u : impl_->pending_in) umockdev_ioctl_data_unref(u.data);
        for (auto& u : impl_->ready) umockdev_ioctl_data_unref(u.data);
        impl_->pending_in.clear();
        impl_->ready.clear();
    }
    g_clear_object(&impl_->testbed);
    for (UMockdevIoctlBase* h : impl_->handlers) g_object_unref(h);
}

void HapioEmulator::plug() {
    {
        std::lock_guard<std::mutex> lock(impl_->mu);
        if (impl_->plugged) return;
        ++impl_->address;
        impl_->plugged = true;
        // Power-on state of the firmware.
        impl_->streaming = false;
        impl_->motors_on = false;
        impl_->halted = false;
        impl_->seq = impl_->ack = 0;
        impl_->kernel_driver = impl_->cfg.kernel_driver_bound;
    }
    impl_->add_device();
}

void HapioEmulator::unplug() {
    std::string path;
    {
        std::lock_guard<std::mutex> lock(impl_->mu);
        if (!impl_->plugged) return;
        impl_->plugged = false;
        impl_->streaming = false;
        impl_->motors_on = false;
        path = impl_->syspath;
    }
    // Only the udev "remove" event, not umockdev_testbed_remove_device(): removing the record
    // also closes the ioctl socket under descriptors libusb still holds open (it closes them
    // only after it has seen ENODEV), and umockdev's preload aborts the process on that EOF.
    // The device already answers ENODEV to everything, as an unplugged one does.
    umockdev_testbed_uevent(impl_->testbed, path.c_str(), "remove");
}

void HapioEmulator::deny_permission() { usb_test::deny_node_access(impl_->testbed, impl_->node()); }

void HapioEmulator::set_encoders(const std::array<std::int32_t, 4>& c) {
    std::lock_guard<std::mutex> lock(impl_->mu);
    impl_->encoders = c;
}
void HapioEmulator::set_adc(const std::array<std::uint16_t, 4>& counts) {
    std::lock_guard<std::mutex> lock(impl_->mu);
    impl_->adc = counts;
}
void HapioEmulator::set_faults(std::uint16_t f) {
    std::lock_guard<std::mutex> lock(impl_->mu);
    impl_->faults = f;
}
void HapioEmulator::stall_next_in() {
    std::lock_guard<std::mutex> lock(impl_->mu);
    impl_->stall_next = true;
}
void HapioEmulator::set_silent(bool s) {
    std::lock_guard<std::mutex> lock(impl_->mu);
    impl_->silent = s;
}
void HapioEmulator::corrupt_next(Corruption c, int n) {
    std::lock_guard<std::mutex> lock(impl_->mu);
    impl_->corrupt = c;
    impl_->corrupt_left = n;
}
Command HapioEmulator::last_command() const {
    std::lock_guard<std::mutex> lock(impl_->mu);
    return impl_->last;
}
std::uint64_t HapioEmulator::commands_applied() const {
    std::lock_guard<std::mutex> lock(impl_->mu);
    return impl_->applied;
}
std::uint64_t HapioEmulator::commands_rejected() const {
    std::lock_guard<std::mutex> lock(impl_->mu);
    return impl_->rejected_total;
}
std::uint64_t HapioEmulator::frames_sent() const {
    std::lock_guard<std::mutex> lock(impl_->mu);
    return impl_->frames;
}
std::uint64_t HapioEmulator::clear_halts() const {
    std::lock_guard<std::mutex> lock(impl_->mu);
    return impl_->clear_halts;
}
std::uint64_t HapioEmulator::discarded_urbs() const {
    std::lock_guard<std::mutex> lock(impl_->mu);
    return impl_->discards;
}
bool HapioEmulator::streaming() const {
    std::lock_guard<std::mutex> lock(impl_->mu);
    return impl_->streaming;
}
bool HapioEmulator::kernel_driver_bound() const {
    std::lock_guard<std::mutex> lock(impl_->mu);
    return impl_->kernel_driver;
}
bool HapioEmulator::motors_enabled() const {
    std::lock_guard<std::mutex> lock(impl_->mu);
    return impl_->motors_on;
}
int HapioEmulator::address() const {
    std::lock_guard<std::mutex> lock(impl_->mu);
    return impl_->address;
}

}  // namespace contactlab::test
