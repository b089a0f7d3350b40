// motor.cpp — the 0615S + 06/1 cable actuator (see motor.hpp).
#include "haptics/wearable/motor.hpp"

#include <algorithm>
#include <cmath>

namespace contactlab::wearable {

double stall_cable_force(const MotorDef& def) noexcept {
    const double output = std::min(def.stall_torque * def.gear_ratio * def.gear_efficiency, def.gear_max_torque);
    return output / def.spool_radius;
}

double holding_torque(const MotorDef& def, double tension) noexcept {
    return tension * def.spool_radius / (def.gear_ratio * def.gear_efficiency);
}

double cable_per_motor_radian(const MotorDef& def) noexcept { return def.spool_radius / def.gear_ratio; }

MotorState motor_step(const MotorDef& def, const MotorState& s, double torque_command, double tension,
                      double dt) noexcept {
    const double tau_m = std::isfinite(torque_command) ? std::clamp(torque_command, -def.stall_torque, def.stall_torque) : 0.0;
    const double load = holding_torque(def, std::isfinite(tension) ? std::max(tension, 0.0) : 0.0);
    const double back_emf = def.stall_torque / def.no_load_speed;  // N m s/rad
    const double drive = tau_m - back_emf * s.speed - load;        // all but friction (N m)
    MotorState out = s;
    if (s.speed == 0.0 && std::abs(drive) <= def.friction_torque) {
        out.speed = 0.0;  // stuck: static friction holds
        return out;
    }
    const double direction = s.speed != 0.0 ? (s.speed > 0.0 ? 1.0 : -1.0) : (drive > 0.0 ? 1.0 : -1.0);
    // Torques held over the step, the back-EMF's damping integrated exactly (J / b = 8.7 ms is
    // not small next to a 1 ms step): omega -> omega_inf + (omega - omega_inf) exp(-dt / tau).
    const double tau_mech = def.rotor_inertia / back_emf;  // s
    const double omega_inf = (tau_m - load - def.friction_torque * direction) / back_emf;
    double speed = omega_inf + (s.speed - omega_inf) * std::exp(-dt / tau_mech);
    const double max_change = def.max_acceleration * dt;  // Table 1's acceleration limit
    speed = std::clamp(speed, s.speed - max_change, s.speed + max_change);
    // Friction stops the shaft; it never reverses it within a step.
    if (speed * direction < 0.0 && std::abs(tau_m - load) <= def.friction_torque) speed = 0.0;
    out.speed = speed;
    out.angle = s.angle + 0.5 * (s.speed + speed) * dt;
    return out;
}

}  // namespace contactlab::wearable
