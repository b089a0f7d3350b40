// forwarding_device.hpp — a Device that wraps another and passes every call through: the base of
// the wrappers that change one thing about a device (the editor's finger angle from the keys for a
// device that measures none, a wearable platform's finger supplied by the cursor). A wrapper
// overrides only what it changes; the rest stays the inner device's, in one place.
#pragma once

#include "drivers/device.hpp"

#include <memory>
#include <string>
#include <utility>

namespace contactlab::drivers {

class ForwardingDevice : public Device {
public:
    explicit ForwardingDevice(std::unique_ptr<Device> inner) : inner_(std::move(inner)) {}

    const char* name() const noexcept override { return inner_->name(); }
    DeviceCapabilities capabilities() const noexcept override { return inner_->capabilities(); }
    DeviceLimits limits() const noexcept override { return inner_->limits(); }
    std::string serial() const override { return inner_->serial(); }
    bool open() override { return inner_->open(); }
    void close() override { inner_->close(); }
    DeviceState state() const noexcept override { return inner_->state(); }
    DeviceFault fault() const noexcept override { return inner_->fault(); }
    void set_engaged(bool on) noexcept override { inner_->set_engaged(on); }
    bool read(DeviceReading& out) noexcept override { return inner_->read(out); }
    void write(const DeviceCommand& cmd) noexcept override { inner_->write(cmd); }
    void advance(double dt) noexcept override { inner_->advance(dt); }

    Device& inner() noexcept { return *inner_; }

protected:
    std::unique_ptr<Device> inner_;
};

}  // namespace contactlab::drivers
