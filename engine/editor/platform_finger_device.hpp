// platform_finger_device.hpp — a USB device in the editor whose finger may need supplying: a
// hapio board is seed 000's CLD rig (model 1: its encoders measure the finger) or seed 003's
// wearable platform (model 2: it tracks no finger), and says which only once open. Everything
// passes through to the board; while it is a platform, the finger in each reading is the
// cursor's, or seed 003's live sweep (finger_script.hpp), as with `sim-wearable`.
#pragma once

#include "drivers/device.hpp"
#include "engine/editor/finger_script.hpp"
#include "engine/editor/pose_input.hpp"

#include <memory>
#include <string>
#include <utility>

namespace contactlab::editor {

class PlatformFingerDevice final : public drivers::Device, public PoseInput {
public:
    PlatformFingerDevice(std::unique_ptr<drivers::Device> inner, const MousePose& start)
        : inner_(std::move(inner)), script_(start) {}

    // --- UI thread ---------------------------------------------------------------------------
    void set_pose(const MousePose& p) noexcept override { script_.set_pose(p); }
    bool start_sweep(const drivers::FingerSweep& s) noexcept override {
        if (!inner_->capabilities().platform) return false;  // the CLD rig: the hand is real
        script_.start_sweep(s);
        return true;
    }
    void stop_sweep() noexcept override { script_.stop_sweep(); }

    // --- drivers::Device ---------------------------------------------------------------------
    const char* name() const noexcept override { return inner_->name(); }
    drivers::DeviceCapabilities capabilities() const noexcept override { return inner_->capabilities(); }
    drivers::DeviceLimits limits() const noexcept override { return inner_->limits(); }
    std::string serial() const override { return inner_->serial(); }
    bool open() override { return inner_->open(); }
    void close() override { inner_->close(); }
    drivers::DeviceState state() const noexcept override { return inner_->state(); }
    drivers::DeviceFault fault() const noexcept override { return inner_->fault(); }
    void set_engaged(bool on) noexcept override { inner_->set_engaged(on); }
    bool read(drivers::DeviceReading& out) noexcept override {
        // Only a reading the board gave: the sweep's clock starts at the first one after it began.
        const bool ok = inner_->read(out);
        if (ok && inner_->capabilities().platform) script_.apply(out);
        return ok;
    }
    void write(const drivers::DeviceCommand& cmd) noexcept override { inner_->write(cmd); }
    void advance(double dt) noexcept override { inner_->advance(dt); }

private:
    std::unique_ptr<drivers::Device> inner_;
    FingerScript script_;
};

}  // namespace contactlab::editor
