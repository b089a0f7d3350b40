// platform_finger_device.hpp — a USB device in the editor whose finger may need supplying: a
// hapio board is seed 000's CLD rig (model 1: its encoders measure the finger) or seed 003's
// wearable platform (model 2: it tracks no finger), and says which only once open. Everything
// passes through to the board; while it is a platform, the finger in each reading is the
// cursor's, or seed 003's live sweep (finger_script.hpp), as with `sim-wearable`.
#pragma once

#include "drivers/forwarding_device.hpp"
#include "engine/editor/finger_script.hpp"
#include "engine/editor/pose_input.hpp"

#include <memory>
#include <string>
#include <utility>

namespace contactlab::editor {

class PlatformFingerDevice final : public drivers::ForwardingDevice, public PoseInput {
public:
    PlatformFingerDevice(std::unique_ptr<drivers::Device> inner, const MousePose& start)
        : ForwardingDevice(std::move(inner)), script_(start) {}

    // --- UI thread ---------------------------------------------------------------------------
    void set_pose(const MousePose& p) noexcept override { script_.set_pose(p); }
    bool start_sweep(const drivers::FingerSweep& s) noexcept override {
        if (!inner_->capabilities().platform) return false;  // the CLD rig: the hand is real
        script_.start_sweep(s);
        return true;
    }
    void stop_sweep() noexcept override { script_.stop_sweep(); }

    // --- drivers::Device (the rest passes through) ---------------------------------------------
    bool read(drivers::DeviceReading& out) noexcept override {
        // Only a reading the board gave: the sweep's clock starts at the first one after it began.
        const bool ok = inner_->read(out);
        if (ok && inner_->capabilities().platform) script_.apply(out);
        return ok;
    }

private:
    FingerScript script_;
};

}  // namespace contactlab::editor
