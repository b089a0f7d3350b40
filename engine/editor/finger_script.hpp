// finger_script.hpp — where the finger is for a device that cannot say: the wearable platform
// (simulated, or a hapio model 2 board) tracks no finger, so the editor supplies it. Normally
// that is the cursor (PoseInput::set_pose); during seed 003's live trial it is the trial's sweep
// (drivers/finger_sweep.hpp: the finger passing over the still arc, which is what it feels when
// the arc moves under the held finger). The UI thread publishes both through seqlocks; the servo
// thread applies them to each reading, timing the sweep from the first reading after it was
// published, on the device's own clock.
#pragma once

#include "drivers/device.hpp"
#include "drivers/finger_sweep.hpp"
#include "engine/editor/pose_input.hpp"
#include "haptics/servo_seqlock.hpp"

#include <cstdint>

namespace contactlab::editor {

class FingerScript {
public:
    explicit FingerScript(const MousePose& start = {}) { pose_.store(start); }

    // --- UI thread ---------------------------------------------------------------------------
    void set_pose(const MousePose& p) noexcept { pose_.store(p); }
    // Starts `s` afresh (a new sweep, or the same one again); stop_sweep() hands the finger back
    // to the cursor.
    void start_sweep(const drivers::FingerSweep& s) noexcept { sweep_.store({++generation_, true, s}); }
    void stop_sweep() noexcept { sweep_.store({++generation_, false, {}}); }

    // --- servo thread ------------------------------------------------------------------------
    void apply(drivers::DeviceReading& out) noexcept {
        const Command c = sweep_.load();
        if (!c.active) {
            const MousePose p = pose_.load();
            out.finger = p.finger;
            out.phi = p.phi;
            return;
        }
        if (c.generation != applied_) {  // a new sweep: it starts now
            applied_ = c.generation;
            t0_ = out.t;
        }
        out.finger = drivers::finger_sweep_at(c.sweep, out.t - t0_);
        out.phi = 0.0;  // the pad level: the platform tilts, not the finger
    }

private:
    struct Command {
        std::uint64_t generation = 0;
        bool active = false;
        drivers::FingerSweep sweep;
    };
    Seqlock<MousePose> pose_;
    Seqlock<Command> sweep_;
    std::uint64_t generation_ = 0;       // UI thread
    std::uint64_t applied_ = 0;          // servo thread: the sweep being played
    double t0_ = 0.0;                    // servo thread: its start, s of device time
};

}  // namespace contactlab::editor
