// cursor_wearable_device.hpp — "sim-wearable" in the editor: seed 003's platform in simulation
// (drivers/sim/sim_wearable_device.hpp) on a finger that is the cursor, as the mouse device's is:
// the wearable renders no force on the hand, so nothing moves the finger but the user. The servo
// loop turns the contact into a platform pose (haptics/wearable/contact_display.hpp); the frame
// draws the platform from platform_view(). In seed 003's live trial the finger is the trial's
// sweep instead (finger_script.hpp).
#pragma once

#include "drivers/sim/sim_wearable_device.hpp"
#include "engine/editor/finger_script.hpp"
#include "engine/editor/pose_input.hpp"

namespace contactlab::editor {

class CursorWearableDevice final : public drivers::Device, public PoseInput {
public:
    explicit CursorWearableDevice(const MousePose& start) : script_(start) {}

    // --- UI thread ---------------------------------------------------------------------------
    void set_pose(const MousePose& p) noexcept override { script_.set_pose(p); }
    bool start_sweep(const drivers::FingerSweep& s) noexcept override {
        script_.start_sweep(s);
        return true;
    }
    void stop_sweep() noexcept override { script_.stop_sweep(); }
    drivers::sim::WearablePlatformView platform_view() const noexcept { return inner_.platform_view(); }
    // The Wearable section's live gains, fit mode and FSR noise (parameter_edit.hpp checks them).
    void set_tuning(const wearable::RigTuning& t) noexcept { inner_.set_tuning(t); }
    wearable::RigTuning tuning() const noexcept { return inner_.tuning(); }

    // --- drivers::Device (servo thread, except open/close) ------------------------------------
    const char* name() const noexcept override { return "sim-wearable"; }
    drivers::DeviceCapabilities capabilities() const noexcept override { return inner_.capabilities(); }
    drivers::DeviceLimits limits() const noexcept override { return inner_.limits(); }
    bool open() override { return inner_.open(); }
    void close() override { inner_.close(); }
    drivers::DeviceState state() const noexcept override { return inner_.state(); }
    drivers::DeviceFault fault() const noexcept override { return inner_.fault(); }
    void set_engaged(bool on) noexcept override { inner_.set_engaged(on); }
    bool read(drivers::DeviceReading& out) noexcept override {
        const bool ok = inner_.read(out);
        script_.apply(out);
        return ok;
    }
    void write(const drivers::DeviceCommand& cmd) noexcept override { inner_.write(cmd); }
    void advance(double dt) noexcept override { inner_.advance(dt); }

private:
    drivers::sim::SimWearableDevice inner_;
    FingerScript script_;
};

}  // namespace contactlab::editor
