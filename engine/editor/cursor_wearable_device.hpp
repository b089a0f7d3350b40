// cursor_wearable_device.hpp — "sim-wearable" in the editor: seed 003's platform in simulation
// (drivers/sim/sim_wearable_device.hpp) on a finger that is the cursor, as the mouse device's is:
// the wearable renders no force on the hand, so nothing moves the finger but the user. The servo
// loop turns the contact into a platform pose (haptics/wearable/contact_display.hpp); the frame
// draws the platform from platform_view().
#pragma once

#include "drivers/sim/sim_wearable_device.hpp"
#include "engine/editor/pose_input.hpp"
#include "haptics/servo_seqlock.hpp"

namespace contactlab::editor {

class CursorWearableDevice final : public drivers::Device, public PoseInput {
public:
    explicit CursorWearableDevice(const MousePose& start) { pose_.store(start); }

    // --- UI thread ---------------------------------------------------------------------------
    void set_pose(const MousePose& p) noexcept override { pose_.store(p); }
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
        const MousePose p = pose_.load();
        out.finger = p.finger;
        out.phi = p.phi;
        return ok;
    }
    void write(const drivers::DeviceCommand& cmd) noexcept override { inner_.write(cmd); }
    void advance(double dt) noexcept override { inner_.advance(dt); }

private:
    drivers::sim::SimWearableDevice inner_;
    Seqlock<MousePose> pose_;
};

}  // namespace contactlab::editor
