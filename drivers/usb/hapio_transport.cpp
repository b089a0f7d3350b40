// hapio_transport.cpp — the event-thread half of HapioDevice: bring-up (open, auto-detach, claim,
// handshake, start streaming), the streaming transfers, stalls, timeouts, unplug and hot-plug.
// Everything here runs on the UsbContext's event thread; callbacks only touch atomics, seqlocks
// and event-thread fields, and defer anything libusb forbids in a callback through post().
#include "drivers/usb/hapio_counters.hpp"
#include "drivers/usb/hapio_device.hpp"
#include "drivers/usb/usb_status.hpp"

#include <libusb.h>

#include <chrono>
#include <thread>

namespace contactlab::drivers::hapio {

namespace {

constexpr std::uint8_t kVendorIn = unsigned{LIBUSB_ENDPOINT_IN} | unsigned{LIBUSB_REQUEST_TYPE_VENDOR} | unsigned{LIBUSB_RECIPIENT_INTERFACE};
constexpr std::uint8_t kVendorOut = unsigned{LIBUSB_ENDPOINT_OUT} | unsigned{LIBUSB_REQUEST_TYPE_VENDOR} | unsigned{LIBUSB_RECIPIENT_INTERFACE};

// Faults a retry cannot fix: tell the user at once instead of retrying.
bool permanent(DeviceFaultCode c) {
    return c == DeviceFaultCode::permission_denied || c == DeviceFaultCode::not_found ||
           c == DeviceFaultCode::disconnected;
}

// The hapio interface (HAPIO.md §2) on configuration 1, or -1.
int find_interface(libusb_device* dev) {
    libusb_config_descriptor* cfg = nullptr;
    if (libusb_get_active_config_descriptor(dev, &cfg) != LIBUSB_SUCCESS &&
        libusb_get_config_descriptor(dev, 0, &cfg) != LIBUSB_SUCCESS)
        return -1;
    int found = -1;
    for (int i = 0; i < cfg->bNumInterfaces && found < 0; ++i) {
        for (int a = 0; a < cfg->interface[i].num_altsetting; ++a) {
            const libusb_interface_descriptor& d = cfg->interface[i].altsetting[a];
            if (d.bInterfaceClass == kInterfaceClass && d.bInterfaceSubClass == kInterfaceSubclass &&
                d.bInterfaceProtocol == kInterfaceProtocol) {
                found = d.bInterfaceNumber;
                break;
            }
        }
    }
    libusb_free_config_descriptor(cfg);
    return found;
}

}  // namespace

bool HapioDevice::bring_up_with_retries() {
    DeviceFault f;
    for (int attempt = 0; attempt < std::max(1, opt_.open_attempts); ++attempt) {
        if (attempt > 0) std::this_thread::sleep_for(std::chrono::duration<double>(opt_.retry_delay));
        f = bring_up();
        if (f.code == DeviceFaultCode::none) return true;
        teardown(false);
        if (permanent(f.code)) break;
    }
    set_fault(f);
    return false;
}

DeviceFault HapioDevice::bring_up() {
    if (handle_ != nullptr) return {};
    status_.state.store(DeviceState::opening);
    libusb_context* ctx = ctx_->raw();

    libusb_device** list = nullptr;
    const ssize_t n = libusb_get_device_list(ctx, &list);
    if (n < 0) return usb::fault_of_error(static_cast<int>(n));
    for (ssize_t i = 0; i < n && dev_ == nullptr; ++i) {
        libusb_device_descriptor d{};
        if (libusb_get_device_descriptor(list[i], &d) != LIBUSB_SUCCESS) continue;
        if (d.idVendor != opt_.vendor_id || d.idProduct != opt_.product_id) continue;
        if (opt_.bus >= 0 && libusb_get_bus_number(list[i]) != opt_.bus) continue;
        if (opt_.address >= 0 && libusb_get_device_address(list[i]) != opt_.address) continue;
        dev_ = libusb_ref_device(list[i]);
    }
    libusb_free_device_list(list, 1);
    if (dev_ == nullptr) return {DeviceFaultCode::not_found, "no hapio board (USB 1209:c1d0) is plugged in"};

    const int iface = find_interface(dev_);
    iface_ = iface < 0 ? 0 : iface;
    if (iface < 0) return {DeviceFaultCode::open_failed, "USB 1209:c1d0 has no hapio interface (class ff/48/01)"};
    if (const int rc = libusb_open(dev_, &handle_); rc != LIBUSB_SUCCESS) {
        handle_ = nullptr;
        return usb::fault_of_error(rc);
    }
    // A kernel driver bound to the interface (e.g. a generic HID or CDC driver picked by class)
    // is detached on claim and re-attached on release.
    const int ad = libusb_set_auto_detach_kernel_driver(handle_, 1);
    if (ad != LIBUSB_SUCCESS && ad != LIBUSB_ERROR_NOT_SUPPORTED) return usb::fault_of_error(ad);
    if (const int rc = libusb_claim_interface(handle_, iface); rc != LIBUSB_SUCCESS) return usb::fault_of_error(rc);

    // Handshake: the board says what it is; refuse anything the CLD model cannot drive.
    std::uint8_t buf[kInfoSize]{};
    const int got = libusb_control_transfer(handle_, kVendorIn, static_cast<std::uint8_t>(Request::get_info), 0,
                                            static_cast<std::uint16_t>(iface), buf, sizeof buf, opt_.control_timeout_ms);
    if (got < 0) return usb::fault_of_error(got);
    Info info;
    const FrameError fe = unpack(buf, static_cast<std::size_t>(got), info);
    if (fe == FrameError::bad_version)
        return {DeviceFaultCode::open_failed, "hapio handshake: the board speaks another protocol version (update its firmware or ContactLab)"};
    if (fe != FrameError::none)
        return {DeviceFaultCode::open_failed, "hapio handshake: malformed GET_INFO reply (wrong firmware?)"};
    if (info.model == 2) {
        if (info.analog < kWearableAnalog || info.motors < kWearableMotors)
            return {DeviceFaultCode::open_failed, "hapio handshake: the board has too few channels for the wearable platform (needs 3 analog, 3 motors)"};
    } else if (info.encoders < kCldEncoders || info.motors < kCldMotors) {
        return {DeviceFaultCode::open_failed, "hapio handshake: the board has too few channels for the CLD rig (needs 4 encoders, 3 motors)"};
    }
    board_model_.store(info.model == 2 ? 2 : 1, std::memory_order_release);
    wearable_.reset();
    have_board_us_ = false;
    info_.store(info);
    for (std::uint8_t req : {static_cast<std::uint8_t>(Request::clear_fault), static_cast<std::uint8_t>(Request::set_streaming)}) {
        const std::uint16_t value = req == static_cast<std::uint8_t>(Request::set_streaming) ? 1 : 0;
        const int rc = libusb_control_transfer(handle_, kVendorOut, req, value, static_cast<std::uint16_t>(iface),
                                               nullptr, 0, opt_.control_timeout_ms);
        if (rc < 0) return usb::fault_of_error(rc);
    }

    for (auto& t : in_) t = libusb_alloc_transfer(0);
    out_ = libusb_alloc_transfer(0);
    stopping_ = false;
    gone_ = false;
    have_in_seq_ = false;
    sent_open_ = {};
    latest_.store(Sample{});
    for (int i = 0; i < kInFlight; ++i) {
        libusb_fill_interrupt_transfer(in_[i], handle_, kEndpointIn, in_buf_[i].data(), kStateSize,
                                       &HapioDevice::in_callback, this, opt_.transfer_timeout_ms);
        submit_in(i);
        if (!in_active_[i]) return {DeviceFaultCode::io_error, "could not start streaming (IN transfer refused)"};
    }
    clear_fault_to_ready();
    return {};
}

void HapioDevice::submit_in(int i) noexcept {
    const int rc = libusb_submit_transfer(in_[i]);
    in_active_[i] = rc == LIBUSB_SUCCESS;
    if (rc == LIBUSB_ERROR_NO_DEVICE) on_gone();
    else if (rc != LIBUSB_SUCCESS) set_fault(usb::fault_of_error(rc));
}

void HapioDevice::teardown(bool device_gone) {
    stopping_ = true;
    if (handle_ != nullptr) {
        for (int i = 0; i < kInFlight; ++i)
            if (in_active_[i]) libusb_cancel_transfer(in_[i]);
        if (out_active_) libusb_cancel_transfer(out_);
        // Cancelled transfers complete through their callbacks; we are outside any callback here,
        // so handling events on this thread is allowed. Bounded: a dead device completes at once.
        for (int round = 0; round < 500; ++round) {
            bool active = out_active_;
            for (bool a : in_active_) active = active || a;
            if (!active) break;
            timeval tv{0, 2000};
            libusb_handle_events_timeout_completed(ctx_->raw(), &tv, nullptr);
        }
        if (!device_gone && !gone_) {
            libusb_control_transfer(handle_, kVendorOut, static_cast<std::uint8_t>(Request::set_streaming), 0,
                                    static_cast<std::uint16_t>(iface_),
                                    nullptr, 0, opt_.control_timeout_ms);
            libusb_release_interface(handle_, iface_);  // re-attaches a kernel driver we detached
        }
        libusb_close(handle_);
        handle_ = nullptr;
    }
    // A transfer still in flight after the bounded wait is left allocated (a leak) rather than
    // freed under libusb: never seen, but a use-after-free would be far worse.
    for (int i = 0; i < kInFlight; ++i) {
        if (in_[i] != nullptr && !in_active_[i]) libusb_free_transfer(in_[i]);
        in_[i] = nullptr;
    }
    in_active_ = {};
    if (out_ != nullptr && !out_active_) libusb_free_transfer(out_);
    out_ = nullptr;
    out_active_ = false;
    if (dev_ != nullptr) libusb_unref_device(dev_);
    dev_ = nullptr;
}

void HapioDevice::on_gone() noexcept {
    if (gone_) return;
    gone_ = true;
    counters_->disconnects.fetch_add(1);
    set_fault(DeviceFaultCode::disconnected, "USB device unplugged (force zeroed; plug it back in to resume)");
    // Closing inside a transfer or hot-plug callback is forbidden: do it between rounds.
    ctx_->post([this] { teardown(true); });
}

void HapioDevice::in_callback(libusb_transfer* t) { static_cast<HapioDevice*>(t->user_data)->on_in(t); }
void HapioDevice::out_callback(libusb_transfer* t) { static_cast<HapioDevice*>(t->user_data)->on_out(t); }

void HapioDevice::on_in(libusb_transfer* t) noexcept {
    int i = 0;
    while (i < kInFlight && in_[i] != t) ++i;
    if (i == kInFlight) return;
    in_active_[i] = false;
    if (stopping_ || gone_) return;
    switch (t->status) {
        case LIBUSB_TRANSFER_COMPLETED:
            process_frame(t->buffer, t->actual_length);
            break;
        case LIBUSB_TRANSFER_TIMED_OUT:
            counters_->timeouts.fetch_add(1);
            set_fault(usb::fault_of_transfer(t->status));
            break;  // keep listening: a board that resumes clears the fault
        case LIBUSB_TRANSFER_STALL:
            counters_->stalls.fetch_add(1);
            set_fault(usb::fault_of_transfer(t->status));
            // libusb_clear_halt is synchronous: not allowed here. Resubmit after clearing.
            ctx_->post([this, i] {
                if (handle_ == nullptr || stopping_ || gone_) return;
                const int rc = libusb_clear_halt(handle_, kEndpointIn);
                if (rc == LIBUSB_ERROR_NO_DEVICE) return on_gone();
                if (!in_active_[i]) submit_in(i);
            });
            return;
        case LIBUSB_TRANSFER_NO_DEVICE:
            on_gone();
            return;
        case LIBUSB_TRANSFER_CANCELLED:
            return;
        case LIBUSB_TRANSFER_OVERFLOW:
            counters_->bad_counts.fetch_add(1);  // longer than a frame: malformed
            break;
        default:
            counters_->transfer_errors.fetch_add(1);
            set_fault(usb::fault_of_transfer(t->status));
            break;
    }
    submit_in(i);
}

void HapioDevice::process_frame(const std::uint8_t* data, int length) noexcept {
    State s;
    const FrameError e = unpack(data, length > 0 ? static_cast<std::size_t>(length) : 0, s);
    Counters& c = *counters_;
    switch (e) {
        case FrameError::none: break;
        case FrameError::short_frame: c.short_frames.fetch_add(1); return;
        case FrameError::bad_magic: c.bad_magic.fetch_add(1); return;
        case FrameError::bad_version: c.bad_version.fetch_add(1); return;
        case FrameError::bad_crc: c.bad_crc.fetch_add(1); return;
        case FrameError::bad_counts:
        case FrameError::bad_value: c.bad_counts.fetch_add(1); return;
    }
    const bool wearable = is_wearable();
    if (wearable ? (s.analog < kWearableAnalog || s.motors < kWearableMotors)
                 : (s.encoders < kCldEncoders || s.motors < kCldMotors)) {
        c.bad_counts.fetch_add(1);
        return;
    }
    const double t = now();
    if (have_in_seq_) {
        const std::uint16_t gap = static_cast<std::uint16_t>(s.sequence - last_in_seq_ - 1);
        if (gap != 0 && gap < 0x8000) c.sequence_gaps.fetch_add(gap);
    }
    have_in_seq_ = true;
    last_in_seq_ = s.sequence;
    c.board_rejected.store(s.rejected_commands);

    // Round trip: from sending command k to the first frame that says it was applied.
    const int slot = s.ack_sequence % 64;
    if (sent_open_[slot] && sent_seq_[slot] == s.ack_sequence) {
        sent_open_[slot] = false;
        const double rtt = t - sent_at_[slot];
        const std::uint64_t n = c.rtt_count.fetch_add(1);
        if (n == 0 || rtt < c.rtt_min.load()) c.rtt_min.store(rtt);
        if (rtt > c.rtt_max.load()) c.rtt_max.store(rtt);
        c.rtt_sum.store(c.rtt_sum.load() + rtt);
    }

    Sample prev = latest_.load();
    latest_.store(Sample{s, t, prev.count + 1});
    c.frames.fetch_add(1);

    // Board faults switch its motors off; the servo must see them. Transport faults (timeout,
    // stall, I/O) clear on the next clean frame; the board's own latched faults clear when it
    // reports none.
    constexpr std::uint16_t kHardware = kFaultOvercurrent | kFaultEncoder | kFaultEstop | kFaultSupply;
    if (s.faults & kFaultEstop) set_fault(DeviceFaultCode::io_error, "hapio board: emergency stop pressed");
    else if (s.faults & kFaultOvercurrent) set_fault(DeviceFaultCode::over_limit, "hapio board: motor overcurrent");
    else if (s.faults & kFaultEncoder) set_fault(DeviceFaultCode::io_error, "hapio board: encoder error");
    else if (s.faults & kFaultSupply) set_fault(DeviceFaultCode::io_error, "hapio board: motor supply under voltage");
    else if (!(s.faults & kHardware) && state() == DeviceState::fault) {
        const DeviceFaultCode code = status_.code.load();
        if (code != DeviceFaultCode::disconnected && code != DeviceFaultCode::permission_denied) clear_fault_to_ready();
    }
    send_command(s);
}

void HapioDevice::send_command(const State& s) noexcept {
    if (out_active_ || out_ == nullptr) return;  // one command in flight; the next frame sends the newest
    Command cmd;
    DeviceState st = state();
    if (is_wearable()) {
        // The platform's loop runs here, once per frame (HAPIO.md, model 2): dt from the board's clock.
        const Info info = info_.load();
        double dt = info.frame_rate > 0 ? 1.0 / info.frame_rate : 1e-3;  // s
        if (have_board_us_) {
            const std::uint32_t us = s.time_us - last_board_us_;  // wraps
            if (us > 0 && us < 100000) dt = 1e-6 * us;
        }
        last_board_us_ = s.time_us;
        have_board_us_ = true;
        if (st == DeviceState::engaged) {
            const WearableLinkStatus ws = wearable_.to_command(command_.load(), s, dt, cmd);
            if (ws == WearableLinkStatus::fsr_saturated) {
                set_fault(DeviceFaultCode::io_error, "hapio wearable: an FSR channel is saturated (force unknown)");
                st = DeviceState::fault;
            } else if (ws == WearableLinkStatus::fault) {
                set_fault(DeviceFaultCode::over_limit, to_string(wearable_.control_status()));
                st = DeviceState::fault;
            }
        } else {
            wearable_.reset();
            cmd.motors = kWearableMotors;  // all zero: not engaged, or faulted
        }
    } else {
        double q1 = 0.0, q2 = 0.0;
        model_.joints(s, q1, q2);
        if (st == DeviceState::engaged) model_.to_command(command_.load(), q1, q2, cmd);
        else cmd.motors = kCldMotors;  // all zero: not engaged, or faulted
    }
    cmd.sequence = ++out_seq_;
    cmd.watchdog_ms = opt_.watchdog_ms;
    if (st == DeviceState::engaged) cmd.flags |= kCommandEnable;
    // Host-caused faults (missed commands, a rejected frame) are cleared by the host.
    if (s.faults & (kFaultHostWatchdog | kFaultBadCommand)) cmd.flags |= kCommandClearFault;
    pack(cmd, out_buf_);
    libusb_fill_interrupt_transfer(out_, handle_, kEndpointOut, out_buf_, kCommandSize, &HapioDevice::out_callback,
                                   this, opt_.transfer_timeout_ms);
    const int slot = cmd.sequence % 64;
    sent_seq_[slot] = cmd.sequence;
    sent_at_[slot] = now();
    sent_open_[slot] = true;
    const int rc = libusb_submit_transfer(out_);
    out_active_ = rc == LIBUSB_SUCCESS;
    if (rc == LIBUSB_ERROR_NO_DEVICE) on_gone();
    else if (rc != LIBUSB_SUCCESS) set_fault(usb::fault_of_error(rc));
}

void HapioDevice::on_out(libusb_transfer* t) noexcept {
    out_active_ = false;
    if (stopping_ || gone_) return;
    switch (t->status) {
        case LIBUSB_TRANSFER_COMPLETED: counters_->commands.fetch_add(1); break;
        case LIBUSB_TRANSFER_NO_DEVICE: on_gone(); break;
        case LIBUSB_TRANSFER_CANCELLED: break;
        case LIBUSB_TRANSFER_STALL:
            counters_->stalls.fetch_add(1);
            set_fault(usb::fault_of_transfer(t->status));
            ctx_->post([this] {
                if (handle_ != nullptr && !stopping_ && !gone_ && libusb_clear_halt(handle_, kEndpointOut) == LIBUSB_ERROR_NO_DEVICE)
                    on_gone();
            });
            break;
        case LIBUSB_TRANSFER_TIMED_OUT: counters_->timeouts.fetch_add(1); set_fault(usb::fault_of_transfer(t->status)); break;
        default: counters_->transfer_errors.fetch_add(1); set_fault(usb::fault_of_transfer(t->status)); break;
    }
}

int HapioDevice::hotplug_callback(libusb_context*, libusb_device* dev, int event, void* user) {
    auto* self = static_cast<HapioDevice*>(user);
    if (event == LIBUSB_HOTPLUG_EVENT_DEVICE_LEFT) {
        if (dev == self->dev_) self->on_gone();
    } else if (event == LIBUSB_HOTPLUG_EVENT_DEVICE_ARRIVED && self->wanted_.load()) {
        // No synchronous I/O inside the callback: bring it up between rounds, after any pending
        // teardown of the handle that left (tasks run in order).
        self->ctx_->post([self] {
            if (!self->wanted_.load() || self->handle_ != nullptr) return;
            if (self->bring_up_with_retries()) self->counters_->reconnects.fetch_add(1);
        });
    }
    return 0;  // stay registered
}

}  // namespace contactlab::drivers::hapio
