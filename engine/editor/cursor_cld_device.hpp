// cursor_cld_device.hpp — "sim-cld" in the editor: seed 000's hardware in simulation (drivers'
// 2-link planar force arm and CLD roller) held by a hand whose intended path is the mouse cursor.
//
// The hand is the scripted hand's impedance (drivers/sim/scripted_hand.hpp: a spring-damper from
// the intended position to the finger, the finger angle following through a first-order lag), but
// its intended position is the cursor, published by the UI through a seqlock, smoothed by a
// first-order lag (`cursor_lag`) so the 30-60 Hz steps of a mouse do not hit the finger as force
// steps. The finger is what the coupled simulation produces: pulled by the hand, pushed back by
// the rendered contact force, so it lags the cursor and stops at the surface while the cursor
// goes on into the solid. At rest in contact the hand spring and the wall are in series:
//   Ke (depth) = K_hand (cursor depth - depth)  ->  depth = K_hand d_c / (K_hand + Ke).
//
// Physics is integrated in advance(dt) with the servo's commanded force held over the period (zero
// order hold) in sub-steps of at most `substep`, at least `min_substeps` per period, as sim-cld
// does in `contactlab simulate`. Device time is the sum of the periods advanced (the simulation's
// own clock), so a late tick delays the simulation instead of making it jump.
#pragma once

#include "drivers/device.hpp"
#include "drivers/sim/cld_roller.hpp"
#include "drivers/sim/planar_arm.hpp"
#include "drivers/sim/scripted_hand.hpp"
#include "engine/editor/pose_input.hpp"
#include "haptics/servo_seqlock.hpp"

#include <atomic>

namespace contactlab::editor {

struct CursorCldParams {
    drivers::sim::PlanarArmParams arm;       // base placed `base_below` under the cursor at construction
    double base_below = 0.15;                // m, shoulder below the first cursor position
    drivers::sim::RollerParams roller;
    drivers::sim::HandParams hand;           // 300 N/m, 2 N s/m, phi lag 20 ms
    double cursor_lag = 0.02;                // s, time constant of the hand following the cursor
    int angle_encoder_counts = 4096;         // per revolution
    double substep = 1e-4;                   // s, longest integration step
    int min_substeps = 10;                   // per servo period, whatever the rate
    double max_force = 1.5;                  // N at the finger (seed 000)
};

class CursorCldDevice final : public drivers::Device, public PoseInput {
public:
    // `start`: the cursor pose when the device is created (places the arm's base below it).
    CursorCldDevice(const CursorCldParams& p, const MousePose& start);

    // --- UI thread ---------------------------------------------------------------------------
    void set_pose(const MousePose& p) noexcept override { cursor_.store(p); }

    // --- drivers::Device ---------------------------------------------------------------------
    const char* name() const noexcept override { return "sim-cld"; }
    drivers::DeviceCapabilities capabilities() const noexcept override;
    drivers::DeviceLimits limits() const noexcept override { return limits_; }
    // The first open places the arm under the cursor; later ones (a servo restarted at another
    // rate) leave it where it is.
    bool open() override;
    void close() override { state_.store(drivers::DeviceState::disconnected); }
    drivers::DeviceState state() const noexcept override { return state_.load(); }
    drivers::DeviceFault fault() const noexcept override { return fault_; }
    void set_engaged(bool on) noexcept override;
    bool read(drivers::DeviceReading& out) noexcept override;
    void write(const drivers::DeviceCommand& cmd) noexcept override;
    void advance(double dt) noexcept override;

    // Ground truth (servo thread, or after the servo stopped).
    const drivers::sim::PlanarArm& arm() const { return arm_; }
    Vec2 hand_target() const { return target_; }  // m, the smoothed cursor

private:
    CursorCldParams p_;
    drivers::sim::PlanarArm arm_;
    drivers::sim::CldRoller roller_;
    Seqlock<MousePose> cursor_;
    drivers::DeviceLimits limits_;
    std::atomic<drivers::DeviceState> state_{drivers::DeviceState::disconnected};
    drivers::DeviceFault fault_;
    double t_ = 0.0;        // s, device time
    Vec2 target_{0.0};      // m, the hand's intended finger position (cursor through the lag)
    double phi_ = 0.0;      // rad, the finger angle (driven by the hand)
    bool placed_ = false;   // the arm was placed under the cursor by the first open()
};

}  // namespace contactlab::editor
