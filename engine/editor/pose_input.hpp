// pose_input.hpp — the cursor as an input to a device: the UI thread publishes the finger pose the
// user points at (x_f and phi) and a device takes it (the mouse device reads it as the finger; the
// simulated CLD's hand takes it as where it intends the finger to be). Replay and USB devices
// take no pose: the recording or the user's real hand moves the finger.
#pragma once

#include "drivers/finger_sweep.hpp"
#include "haptics/vec2.hpp"

namespace contactlab::editor {

struct MousePose {
    Vec2 finger{0.0};  // x_f, m
    double phi = 0.0;  // rad
};

class PoseInput {
public:
    virtual ~PoseInput() = default;
    // UI thread; never blocks the servo (devices keep the pose in a seqlock).
    virtual void set_pose(const MousePose& p) noexcept = 0;
    // Seed 003's live trial (finger_script.hpp): the finger passes over the arc as `s` says, from
    // the device's next reading, until stop_sweep(). False where the device cannot take it: one
    // whose finger is the user's hand (the mouse's cursor, the CLD rig's grip); only a display
    // that tracks no finger, the wearable platform, can.
    virtual bool start_sweep(const drivers::FingerSweep& s) noexcept {
        (void)s;
        return false;
    }
    virtual void stop_sweep() noexcept {}
    // False where only the pose's angle is taken (a real device measuring no finger angle: the
    // user's hand places the finger, keyed_angle_device.hpp): the finger is then the device's.
    virtual bool takes_position() const noexcept { return true; }
};

}  // namespace contactlab::editor
