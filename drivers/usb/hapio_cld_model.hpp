// hapio_cld_model.hpp — how a hapio board's channels become seed 000's CLD rig behind the Device
// interface: two arm joint encoders and motors (a planar force arm), the finger-angle encoder and
// the roller's motor encoder and drive (HAPIO.md §5 lists the channel assignment).
//
// Pure arithmetic on the servo/transport threads: no allocation, no I/O.
#pragma once

#include "drivers/device.hpp"
#include "drivers/usb/hapio_protocol.hpp"

namespace contactlab::drivers::hapio {

struct CldCalibration {
    Vec2 base{0.0, -0.25};          // m, shoulder joint in the world frame
    double l1 = 0.20, l2 = 0.20;    // m, upper arm and forearm
    double joint_counts = 65536;    // counts per joint revolution (after the capstan)
    double q1_offset = 0.0, q2_offset = 0.0;  // rad at count 0
    double angle_counts = 4096;     // finger-angle encoder, counts per revolution
    double roller_counts_per_m = 2048.0 / 0.002;  // motor encoder through a 2 mm lead screw
    double max_torque = 0.35;       // N m, joint motor full scale (continuous)
    double roller_full_scale = 12.0; // V, roller amplifier full scale
    double max_force = 1.5;         // N, magnitude clamp at the finger (seed 000)
    double adc_newton_per_count = 0.0;  // N per ADC count for analog sensors (0: unused)
};

// Channel assignment (HAPIO.md §5).
inline constexpr int kEncShoulder = 0, kEncElbow = 1, kEncFingerAngle = 2, kEncRoller = 3;
inline constexpr int kMotorShoulder = 0, kMotorElbow = 1, kMotorRoller = 2;
inline constexpr int kCldEncoders = 4, kCldMotors = 3;

class CldModel {
public:
    explicit CldModel(const CldCalibration& c = {}) : c_(c) {}
    const CldCalibration& calibration() const noexcept { return c_; }

    // Joint angles (rad) of a frame, and the finger reading they imply (t is left to the caller).
    void joints(const State& s, double& q1, double& q2) const noexcept;
    void to_reading(const State& s, DeviceReading& out) const noexcept;

    // Force (N) -> joint torques: |F| clamped to max_force (direction kept), tau = J^T F, then each
    // torque saturated to the motor's full scale; roller drive (V) saturated to its full scale.
    // Non-finite inputs give zero drive. Fills motor[0..2] of `cmd` and sets cmd.motors.
    void to_command(const DeviceCommand& in, double q1, double q2, Command& cmd) const noexcept;

    // Forward kinematics and the endpoint force the packed torques produce (tests, diagnostics).
    Vec2 endpoint(double q1, double q2) const noexcept;
    Vec2 force_of(const Command& cmd, double q1, double q2) const noexcept;
    DeviceLimits limits() const noexcept;

private:
    CldCalibration c_;
};

}  // namespace contactlab::drivers::hapio
