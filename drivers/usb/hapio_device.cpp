// hapio_device.cpp — the servo-facing half of HapioDevice: lock-free reads and writes, states,
// open/close (which hand the USB work to the event thread; see hapio_transport.cpp).
#include "drivers/usb/hapio_device.hpp"
#include "drivers/usb/hapio_counters.hpp"

#include <libusb.h>

#include <ctime>

namespace contactlab::drivers::hapio {

namespace {
double monotonic() noexcept {
    timespec ts{};
    clock_gettime(CLOCK_MONOTONIC, &ts);
    return static_cast<double>(ts.tv_sec) + 1e-9 * static_cast<double>(ts.tv_nsec);
}
}  // namespace

HapioDevice::HapioDevice(const HapioOptions& o, std::shared_ptr<usb::UsbContext> ctx)
    : opt_(o), model_(o.calibration), wearable_(o.wearable), ctx_(std::move(ctx)), epoch_(monotonic()),
      counters_(std::make_unique<Counters>()) {}

HapioDevice::~HapioDevice() { close(); }

double HapioDevice::now() const noexcept { return monotonic() - epoch_; }

DeviceCapabilities HapioDevice::capabilities() const noexcept {
    DeviceCapabilities c;
    if (is_wearable()) {
        c.platform = true;
        c.force_sensors = kWearableAnalog;
        return c;
    }
    c.planar_force = true;
    c.finger_angle = true;
    c.roller = true;
    return c;
}

DeviceFault HapioDevice::fault() const noexcept {
    return status_.fault();
}

DeviceFault HapioDevice::last_fault() const noexcept {
    return {last_fault_code_.load(std::memory_order_acquire), last_fault_detail_.load(std::memory_order_acquire)};
}

void HapioDevice::set_fault(DeviceFaultCode code, const char* detail) noexcept {
    last_fault_detail_.store(detail, std::memory_order_release);
    last_fault_code_.store(code, std::memory_order_release);
    counters_->faults.fetch_add(1, std::memory_order_acq_rel);
    status_.set_fault(code, detail);
}

void HapioDevice::clear_fault_to_ready() noexcept {
    status_.clear(DeviceState::ready);
}

void HapioDevice::set_engaged(bool on) noexcept {
    want_engaged_.store(on, std::memory_order_release);
    status_.engage(on);
}

bool HapioDevice::read(DeviceReading& out) noexcept {
    out = DeviceReading{};
    out.t = now();  // host clock: keeps running through unplugs, so the servo's timing stays sane
    if (!status_.readable()) return false;
    const Sample s = latest_.load();
    if (s.count == 0 || out.t - s.rx_time > opt_.stale_after) return false;
    if (is_wearable()) wearable_.to_reading(s.state, out);
    else model_.to_reading(s.state, out);
    out.t = now();
    return true;
}

void HapioDevice::write(const DeviceCommand& cmd) noexcept { command_.store(cmd); }

bool HapioDevice::open() {
    if (!ctx_) ctx_ = std::make_shared<usb::UsbContext>();
    if (!ctx_->ok()) {
        set_fault(DeviceFaultCode::not_found, "no USB subsystem (libusb_init failed): no device can be found");
        return false;
    }
    wanted_.store(true);
    hotplug_.watch(*ctx_, opt_.vendor_id, opt_.product_id, &HapioDevice::hotplug_callback, this);
    bool ok = false;
    ctx_->run([&] { ok = bring_up_with_retries(); });
    return ok;
}

void HapioDevice::close() {
    wanted_.store(false);
    if (!ctx_ || !ctx_->ok()) return;
    hotplug_.unwatch();
    ctx_->run([&] { teardown(false); });
    status_.clear(DeviceState::disconnected);
}

HapioStats HapioDevice::stats() const noexcept {
    const Counters& c = *counters_;
    HapioStats s;
    s.frames = c.frames.load();
    s.commands = c.commands.load();
    s.short_frames = c.short_frames.load();
    s.bad_magic = c.bad_magic.load();
    s.bad_version = c.bad_version.load();
    s.bad_crc = c.bad_crc.load();
    s.bad_counts = c.bad_counts.load();
    s.sequence_gaps = c.sequence_gaps.load();
    s.timeouts = c.timeouts.load();
    s.stalls = c.stalls.load();
    s.transfer_errors = c.transfer_errors.load();
    s.disconnects = c.disconnects.load();
    s.reconnects = c.reconnects.load();
    s.rtt_count = c.rtt_count.load();
    s.rtt_min = c.rtt_min.load();
    s.rtt_max = c.rtt_max.load();
    s.rtt_mean = s.rtt_count ? c.rtt_sum.load() / static_cast<double>(s.rtt_count) : 0.0;
    s.board_rejected_commands = c.board_rejected.load();
    s.faults = c.faults.load(std::memory_order_acquire);
    return s;
}

}  // namespace contactlab::drivers::hapio
