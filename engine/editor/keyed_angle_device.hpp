// keyed_angle_device.hpp — a real device that measures no finger angle (the Novint Falcon, the
// Haply 2DIY) in the editor: its readings' position is the device's, and the finger angle phi is
// the one the editor holds (the `q`/`e` keys and the wheel turn it, as for the mouse), instead of
// staying at 0. The cursor's position is ignored: the user's hand on the device moves the finger.
#pragma once

#include "drivers/forwarding_device.hpp"
#include "engine/editor/pose_input.hpp"

#include <atomic>
#include <memory>
#include <string>
#include <utility>

namespace contactlab::editor {

class KeyedAngleDevice final : public drivers::ForwardingDevice, public PoseInput {
public:
    KeyedAngleDevice(std::unique_ptr<drivers::Device> inner, const MousePose& start)
        : ForwardingDevice(std::move(inner)), phi_(start.phi) {}

    // --- UI thread ---------------------------------------------------------------------------
    void set_pose(const MousePose& p) noexcept override { phi_.store(p.phi, std::memory_order_relaxed); }
    bool takes_position() const noexcept override { return false; }

    // --- drivers::Device (the rest passes through) ---------------------------------------------
    drivers::DeviceCapabilities capabilities() const noexcept override {
        drivers::DeviceCapabilities c = inner_->capabilities();
        c.finger_angle = true;  // from the keys: the servo sees phi change, as with the mouse
        return c;
    }
    bool read(drivers::DeviceReading& out) noexcept override {
        const bool ok = inner_->read(out);
        out.phi = phi_.load(std::memory_order_relaxed);  // rad
        return ok;
    }

private:
    std::atomic<double> phi_;  // rad, UI -> servo
};

}  // namespace contactlab::editor
