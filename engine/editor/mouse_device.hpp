// mouse_device.hpp — the editor's default device: the cursor is the finger. The UI thread sets
// the finger centre x_f (m) and angle phi (rad) through a seqlock; the servo thread reads them
// each tick with the real-time clock. A mouse renders no force, so the commanded force is only
// shown; the contact-location roller is simulated (drivers' CLD roller model, driven by the
// servo's roller PID) so l_d tracking and the roller gains can be watched live.
#pragma once

#include "drivers/device.hpp"
#include "drivers/sim/cld_roller.hpp"
#include "engine/editor/pose_input.hpp"
#include "haptics/servo_seqlock.hpp"

#include <atomic>
#include <chrono>

namespace contactlab::editor {

class MouseDevice final : public drivers::Device, public PoseInput {
public:
    MouseDevice();

    // --- UI thread ---------------------------------------------------------------------------
    void set_pose(const MousePose& p) noexcept override { pose_.store(p); }
    MousePose pose() const noexcept { return pose_.load(); }

    // --- drivers::Device (servo thread, except open/close) ------------------------------------
    const char* name() const noexcept override { return "mouse"; }
    drivers::DeviceCapabilities capabilities() const noexcept override;
    drivers::DeviceLimits limits() const noexcept override { return limits_; }
    bool open() override;
    void close() override { state_.store(drivers::DeviceState::disconnected); }
    drivers::DeviceState state() const noexcept override { return state_.load(); }
    drivers::DeviceFault fault() const noexcept override { return {}; }
    void set_engaged(bool on) noexcept override;
    bool read(drivers::DeviceReading& out) noexcept override;
    void write(const drivers::DeviceCommand& cmd) noexcept override;
    void advance(double dt) noexcept override;

private:
    Seqlock<MousePose> pose_;
    drivers::DeviceLimits limits_;
    drivers::sim::CldRoller roller_;
    std::atomic<drivers::DeviceState> state_{drivers::DeviceState::disconnected};
    std::chrono::steady_clock::time_point opened_;
};

}  // namespace contactlab::editor
