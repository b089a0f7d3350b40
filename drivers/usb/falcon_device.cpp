// falcon_device.cpp — the servo-facing half of FalconDevice (see falcon_device.hpp).
#include "drivers/usb/falcon_device.hpp"

#include <libusb.h>

#include <ctime>

namespace contactlab::drivers::falcon {

namespace {
double monotonic() noexcept {
    timespec ts{};
    clock_gettime(CLOCK_MONOTONIC, &ts);
    return static_cast<double>(ts.tv_sec) + 1e-9 * static_cast<double>(ts.tv_nsec);
}
}  // namespace

FalconDevice::FalconDevice(const FalconOptions& o, std::shared_ptr<usb::UsbContext> ctx)
    : opt_(o), kin_(o.geometry), ctx_(std::move(ctx)), epoch_(monotonic()) {
    last_p_ = {0.0, 0.0, opt_.planar.z0};
}

FalconDevice::~FalconDevice() { close(); }

double FalconDevice::now() const noexcept { return monotonic() - epoch_; }

DeviceCapabilities FalconDevice::capabilities() const noexcept {
    DeviceCapabilities c;
    c.planar_force = true;
    c.spatial_force = true;  // z is held by the restoring spring on the device side
    return c;
}

DeviceLimits FalconDevice::limits() const noexcept {
    DeviceLimits l;
    l.max_force = opt_.planar.max_force;
    l.axis_max_force = Vec2{opt_.planar.max_force};
    l.workspace.lo = opt_.planar.origin - Vec2{0.05};  // m: about the Falcon's 10 cm cube
    l.workspace.hi = opt_.planar.origin + Vec2{0.05};
    l.native_rate = 1000.0;
    l.mass = opt_.mass;
    return l;
}

DeviceFault FalconDevice::fault() const noexcept {
    return status_.fault();
}

void FalconDevice::set_fault(DeviceFaultCode code, const char* detail) noexcept {
    status_.set_fault(code, detail);
}

void FalconDevice::set_engaged(bool on) noexcept {
    status_.engage(on);
}

bool FalconDevice::read(DeviceReading& out) noexcept {
    out = DeviceReading{};
    out.t = now();
    if (!status_.readable()) return false;
    const Sample s = latest_.load();
    if (s.count == 0 || !s.p_ok || out.t - s.rx_time > opt_.stale_after) return false;
    if (s.state.homed != 0x7) return false;  // encoders are relative until every arm has homed
    out.finger = opt_.planar.origin + Vec2{s.p.x, s.p.y};
    out.z = s.p.z - opt_.planar.z0;
    out.valid = true;
    return true;
}

void FalconDevice::write(const DeviceCommand& cmd) noexcept { command_.store(cmd); }

bool FalconDevice::open() {
    if (!ctx_) ctx_ = std::make_shared<usb::UsbContext>();
    if (!ctx_->ok()) {
        set_fault(DeviceFaultCode::not_found, "no USB subsystem (libusb_init failed): no device can be found");
        return false;
    }
    wanted_.store(true);
    hotplug_.watch(*ctx_, kVendorId, kProductId, &FalconDevice::hotplug_callback, this);
    bool ok = false;
    ctx_->run([&] { ok = bring_up_with_retries(); });
    return ok;
}

void FalconDevice::close() {
    wanted_.store(false);
    if (!ctx_ || !ctx_->ok()) return;
    hotplug_.unwatch();
    ctx_->run([&] { teardown(false); });
    status_.clear(DeviceState::disconnected);
}

std::string FalconDevice::serial() const {
    const std::array<char, 64> s = serial_.load();
    return std::string(s.data());
}

FalconStats FalconDevice::stats() const noexcept {
    FalconStats s;
    s.packets = packets_.load();
    s.commands = commands_.load();
    s.malformed = malformed_.load();
    s.discarded_bytes = discarded_.load();
    s.timeouts = timeouts_.load();
    s.disconnects = disconnects_.load();
    s.reconnects = reconnects_.load();
    s.firmware_uploads = uploads_.load();
    return s;
}

}  // namespace contactlab::drivers::falcon
