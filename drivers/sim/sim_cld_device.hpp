// sim_cld_device.hpp — "sim-cld": seed 000's hardware in simulation, held by a scripted hand.
//
// A 2-link force arm, a finger-angle encoder and the CLD roller, integrated at a sub-step of the
// servo period (at most `substep` seconds) with the commanded motor torques and roller voltage
// held between ticks (zero-order hold, as real amplifiers do). A device-side watchdog switches
// the motors off when no command arrives for `watchdog_timeout` of device time, like the
// amplifier enable line of a real device.
#pragma once

#include "drivers/device.hpp"
#include "drivers/sim/cld_roller.hpp"
#include "drivers/sim/planar_arm.hpp"
#include "drivers/sim/scripted_hand.hpp"

namespace contactlab::drivers::sim {

struct SimCldParams {
    PlanarArmParams arm;
    bool auto_base = true;          // place the arm's base below the hand path's bounding box
    RollerParams roller;
    HandParams hand;
    int angle_encoder_counts = 4096;  // per revolution
    double substep = 1e-4;          // s, longest integration step
    // Sub-steps per servo period at least, whatever the rate: the hold of the force over a period
    // is what makes a sampled spring active (K < 2b/T); integrating a period in one semi-implicit
    // Euler step would hide it (that step alone is passive for any K).
    int min_substeps = 10;
    double watchdog_timeout = 0.005; // s of device time without a command -> motors off
    double max_force = 1.5;         // N at the finger (seed 000)
};

class SimCldDevice final : public Device {
public:
    SimCldDevice(const SimCldParams& p, HandPath path);

    const char* name() const noexcept override { return "sim-cld"; }
    DeviceCapabilities capabilities() const noexcept override;
    DeviceLimits limits() const noexcept override { return limits_; }
    bool open() override;
    void close() override { state_ = DeviceState::disconnected; }
    DeviceState state() const noexcept override { return state_; }
    DeviceFault fault() const noexcept override { return fault_; }
    void set_engaged(bool on) noexcept override;
    bool read(DeviceReading& out) noexcept override;
    void write(const DeviceCommand& cmd) noexcept override;
    void advance(double dt) noexcept override;

    // Ground truth for tests and reports.
    double time() const { return t_; }
    const PlanarArm& arm() const { return arm_; }
    const CldRoller& roller() const { return roller_; }
    const ScriptedHand& hand() const { return hand_; }
    // The hand, to steer it tick by tick (a closed-loop hand); the arm's base and the limits stay
    // where the path given at construction put them.
    ScriptedHand& hand() { return hand_; }
    Vec2 applied_force() const { return motors_on_ ? arm_.applied_force() : Vec2{0.0}; }
    bool watchdog_tripped() const { return watchdog_trips_ > 0; }
    int watchdog_trips() const { return watchdog_trips_; }

private:
    SimCldParams p_;
    PlanarArm arm_;
    CldRoller roller_;
    ScriptedHand hand_;
    DeviceLimits limits_;
    DeviceState state_ = DeviceState::disconnected;
    DeviceFault fault_;
    double t_ = 0.0;               // s, device time
    double since_command_ = 0.0;   // s
    bool motors_on_ = false;
    int watchdog_trips_ = 0;
};

}  // namespace contactlab::drivers::sim
