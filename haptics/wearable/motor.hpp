// motor.hpp — one cable actuator of seed 003 (§2, Table 1): a Faulhaber 0615S DC motor with a
// 06/1 planetary gearhead (16:1) winding the cable on a spool.
//
// The motor is driven by PWM from the Arduino (a voltage drive), so its torque follows the
// straight torque-speed line of a DC motor from the stall torque at rest to zero at the no-load
// speed: tau = u tau_stall - (tau_stall / omega_0) omega, with u in [-1, 1] the duty. The
// controllers (Figs. 5-6) command the motor torque tau_m = u tau_stall of the figures; the
// back-EMF term is the motor's own damping. At the shaft:
//
//   J_r omega_dot = tau_m - (tau_stall / omega_0) omega - tau_f sgn(omega) - Q r / (N eta)
//
// with Coulomb friction tau_f that sticks while the other torques stay within it, the cable
// tension Q (N) acting on the spool radius r through the gearhead (ratio N, efficiency eta), and
// |omega_dot| limited to Table 1's maximum angular acceleration. Positive angle reels cable in.
#pragma once

namespace contactlab::wearable {

struct MotorDef {
    // Table 1 (0615S motor, 06/1 gearhead).
    double stall_torque = 0.24e-3;       // N m at the motor shaft
    double friction_torque = 0.02e-3;    // N m at the motor shaft
    double no_load_speed = 2094.395;     // rad/s (20000 rpm)
    double rotor_inertia = 1e-9;         // kg m^2 (0.01 g cm^2)
    double max_acceleration = 244e3;     // rad/s^2
    double gear_ratio = 16.0;            // 16:1
    double gear_max_torque = 25e-3;      // N m at the gearhead's output
    // Not in the seed: the 06/1 two-stage gearhead's catalogue efficiency, and the spool radius,
    // chosen so that the stall cable force (1.54 N) is a few times the seed's 0.3 N steps.
    double gear_efficiency = 0.8;        // dimensionless
    double spool_radius = 0.002;         // m
};

// The largest cable tension the motor holds (N): the stall torque through the gearhead, or the
// gearhead's own limit if lower.
double stall_cable_force(const MotorDef& def) noexcept;

// Motor torque (N m at the shaft) that balances tension Q (N) at rest, friction aside.
double holding_torque(const MotorDef& def, double tension) noexcept;

// Cable reeled in per motor radian (m/rad): r / N.
double cable_per_motor_radian(const MotorDef& def) noexcept;

struct MotorState {
    double angle = 0.0;   // rad at the motor shaft; positive reels cable in
    double speed = 0.0;   // rad/s
};

// One step of the shaft's dynamics over dt (s), the torques held and the back-EMF integrated
// exactly, under the commanded torque tau_m (N m,
// clamped to the stall torque: the duty cannot exceed 100 %) and cable tension Q (N). A
// non-finite command counts as zero.
MotorState motor_step(const MotorDef& def, const MotorState& s, double torque_command, double tension,
                      double dt) noexcept;

}  // namespace contactlab::wearable
