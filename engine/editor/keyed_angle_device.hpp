// keyed_angle_device.hpp — a real device that measures no finger angle (the Novint Falcon, the
// Haply 2DIY) in the editor: its readings' position is the device's, and the finger angle phi is
// the one the editor holds (the `q`/`e` keys and the wheel turn it, as for the mouse), instead of
// staying at 0. The cursor's position is ignored: the user's hand on the device moves the finger.
#pragma once

#include "drivers/device.hpp"
#include "engine/editor/pose_input.hpp"

#include <atomic>
#include <memory>
#include <string>
#include <utility>

namespace contactlab::editor {

class KeyedAngleDevice final : public drivers::Device, public PoseInput {
public:
    KeyedAngleDevice(std::unique_ptr<drivers::Device> inner, const MousePose& start)
        : inner_(std::move(inner)), phi_(start.phi) {}

    // --- UI thread ---------------------------------------------------------------------------
    void set_pose(const MousePose& p) noexcept override { phi_.store(p.phi, std::memory_order_relaxed); }
    bool takes_position() const noexcept override { return false; }

    // --- drivers::Device ---------------------------------------------------------------------
    const char* name() const noexcept override { return inner_->name(); }
    drivers::DeviceCapabilities capabilities() const noexcept override {
        drivers::DeviceCapabilities c = inner_->capabilities();
        c.finger_angle = true;  // from the keys: the servo sees phi change, as with the mouse
        return c;
    }
    drivers::DeviceLimits limits() const noexcept override { return inner_->limits(); }
    std::string serial() const override { return inner_->serial(); }
    bool open() override { return inner_->open(); }
    void close() override { inner_->close(); }
    drivers::DeviceState state() const noexcept override { return inner_->state(); }
    drivers::DeviceFault fault() const noexcept override { return inner_->fault(); }
    void set_engaged(bool on) noexcept override { inner_->set_engaged(on); }
    bool read(drivers::DeviceReading& out) noexcept override {
        const bool ok = inner_->read(out);
        out.phi = phi_.load(std::memory_order_relaxed);  // rad
        return ok;
    }
    void write(const drivers::DeviceCommand& cmd) noexcept override { inner_->write(cmd); }
    void advance(double dt) noexcept override { inner_->advance(dt); }
    drivers::Device& inner() noexcept { return *inner_; }

private:
    std::unique_ptr<drivers::Device> inner_;
    std::atomic<double> phi_;  // rad, UI -> servo
};

}  // namespace contactlab::editor
