// falcon_transport.cpp — FalconDevice's streaming on the event thread: one command out per reply
// in, replies reassembled from the FTDI stream, kinematics done here (not in the servo tick),
// unplug and hot-plug handled as for hapio (closing deferred out of callbacks).
#include "drivers/usb/falcon_device.hpp"
#include "drivers/usb/usb_status.hpp"

#include <libusb.h>

namespace contactlab::drivers::falcon {

void FalconDevice::in_callback(libusb_transfer* t) { static_cast<FalconDevice*>(t->user_data)->on_in(t); }
void FalconDevice::out_callback(libusb_transfer* t) { static_cast<FalconDevice*>(t->user_data)->on_out(t); }

void FalconDevice::on_in(libusb_transfer* t) noexcept {
    in_active_ = false;
    if (stopping_ || gone_) return;
    switch (t->status) {
        case LIBUSB_TRANSFER_COMPLETED: {
            const int got = parser_.feed(t->buffer, static_cast<std::size_t>(t->actual_length), [&](const State& s) {
                std::array<double, 3> th{};
                for (int i = 0; i < 3; ++i) th[i] = kin_.theta_of(i, s.encoder[i]);
                Vec3 p;
                const bool ok = kin_.forward(th, last_p_, p);
                if (ok) last_p_ = p;
                const Sample prev = latest_.load();
                latest_.store(Sample{s, ok ? p : last_p_, ok, now(), prev.count + 1});
                packets_.fetch_add(1);
            });
            malformed_.store(parser_.malformed());
            discarded_.store(parser_.discarded_bytes());
            if (got > 0 && state() == DeviceState::fault && status_.code.load() == DeviceFaultCode::timeout) {
                status_.code.store(DeviceFaultCode::none);
                status_.state.store(DeviceState::ready);
            }
            // A reply asks for the next command; a reply that never came is re-asked after 5 ms.
            if (got > 0 || now() - last_sent_ > 0.005) send_command();
            break;
        }
        case LIBUSB_TRANSFER_NO_DEVICE: on_gone(); return;
        case LIBUSB_TRANSFER_CANCELLED: return;
        case LIBUSB_TRANSFER_TIMED_OUT:
            timeouts_.fetch_add(1);
            set_fault(usb::fault_of_transfer(t->status));
            send_command();
            break;
        default: set_fault(usb::fault_of_transfer(t->status)); break;
    }
    const int rc = libusb_submit_transfer(in_);
    in_active_ = rc == LIBUSB_SUCCESS;
    if (rc == LIBUSB_ERROR_NO_DEVICE) on_gone();
    else if (rc != LIBUSB_SUCCESS) set_fault(usb::fault_of_error(rc));
}

void FalconDevice::send_command() noexcept {
    if (out_active_ || out_ == nullptr) return;
    Command c;
    const Sample s = latest_.load();
    const DeviceState st = state();
    if (st == DeviceState::engaged && s.p_ok && s.state.homed == 0x7) {
        const DeviceCommand cmd = command_.load();
        const Vec3 f = planar_force(opt_.planar, cmd.force, s.p.z);
        std::array<double, 3> tau{};
        if (kin_.torques(s.p, f, tau)) c.motor = motor_counts(opt_.planar, tau);
    }
    // Until homed the firmware runs its homing mode; the LED says what state we are in.
    c.flags = s.state.homed == 0x7 ? 0 : kHomingMode;
    c.flags |= st == DeviceState::engaged ? kLedGreen : st == DeviceState::fault ? kLedRed : kLedBlue;
    pack(c, out_buf_);
    libusb_fill_bulk_transfer(out_, handle_, kEndpointOut, out_buf_, kPacketSize, &FalconDevice::out_callback, this,
                              opt_.timeout_ms);
    last_sent_ = now();
    const int rc = libusb_submit_transfer(out_);
    out_active_ = rc == LIBUSB_SUCCESS;
    if (rc == LIBUSB_ERROR_NO_DEVICE) on_gone();
    else if (rc != LIBUSB_SUCCESS) set_fault(usb::fault_of_error(rc));
}

void FalconDevice::on_out(libusb_transfer* t) noexcept {
    out_active_ = false;
    if (stopping_ || gone_) return;
    if (t->status == LIBUSB_TRANSFER_COMPLETED) commands_.fetch_add(1);
    else if (t->status == LIBUSB_TRANSFER_NO_DEVICE) on_gone();
    else if (t->status != LIBUSB_TRANSFER_CANCELLED) set_fault(usb::fault_of_transfer(t->status));
}

void FalconDevice::on_gone() noexcept {
    if (gone_) return;
    gone_ = true;
    disconnects_.fetch_add(1);
    set_fault(DeviceFaultCode::disconnected, "Falcon unplugged (force zeroed; plug it back in to resume)");
    ctx_->post([this] { teardown(true); });
}

void FalconDevice::teardown(bool device_gone) {
    stopping_ = true;
    if (handle_ != nullptr) {
        if (in_active_) libusb_cancel_transfer(in_);
        if (out_active_) libusb_cancel_transfer(out_);
        for (int round = 0; round < 500 && (in_active_ || out_active_); ++round) {
            timeval tv{0, 2000};
            libusb_handle_events_timeout_completed(ctx_->raw(), &tv, nullptr);
        }
        if (!device_gone && !gone_) {
            // Leave the motors off: one zero command before letting go.
            std::uint8_t pkt[kPacketSize];
            pack(Command{}, pkt);
            int done = 0;
            libusb_bulk_transfer(handle_, kEndpointOut, pkt, kPacketSize, &done, opt_.timeout_ms);
            libusb_release_interface(handle_, 0);
        }
        libusb_close(handle_);
        handle_ = nullptr;
    }
    // Still in flight after the bounded wait: leak rather than free under libusb.
    if (in_ != nullptr && !in_active_) libusb_free_transfer(in_);
    if (out_ != nullptr && !out_active_) libusb_free_transfer(out_);
    in_ = out_ = nullptr;
    in_active_ = out_active_ = false;
    if (dev_ != nullptr) libusb_unref_device(dev_);
    dev_ = nullptr;
}

int FalconDevice::hotplug_callback(libusb_context*, libusb_device* dev, int event, void* user) {
    auto* self = static_cast<FalconDevice*>(user);
    if (event == LIBUSB_HOTPLUG_EVENT_DEVICE_LEFT) {
        if (dev == self->dev_) self->on_gone();
    } else if (event == LIBUSB_HOTPLUG_EVENT_DEVICE_ARRIVED && self->wanted_.load()) {
        self->ctx_->post([self] {
            if (!self->wanted_.load() || self->handle_ != nullptr) return;
            if (self->bring_up_with_retries()) self->reconnects_.fetch_add(1);
        });
    }
    return 0;
}

}  // namespace contactlab::drivers::falcon
