// hapio_cld_model.cpp — channel mapping of the CLD rig (see hapio_cld_model.hpp).
#include "drivers/usb/hapio_cld_model.hpp"

#include <cmath>

namespace contactlab::drivers::hapio {

void CldModel::joints(const State& s, double& q1, double& q2) const noexcept {
    q1 = kTwoPi * s.encoder[kEncShoulder] / c_.joint_counts + c_.q1_offset;
    q2 = kTwoPi * s.encoder[kEncElbow] / c_.joint_counts + c_.q2_offset;
}

Vec2 CldModel::endpoint(double q1, double q2) const noexcept {
    // q2 is relative to the upper arm (as the elbow encoder measures it).
    return c_.base + Vec2{c_.l1 * std::cos(q1) + c_.l2 * std::cos(q1 + q2),
                          c_.l1 * std::sin(q1) + c_.l2 * std::sin(q1 + q2)};
}

void CldModel::to_reading(const State& s, DeviceReading& out) const noexcept {
    double q1 = 0.0, q2 = 0.0;
    joints(s, q1, q2);
    out.finger = endpoint(q1, q2);
    out.phi = kTwoPi * s.encoder[kEncFingerAngle] / c_.angle_counts;
    out.roller_l = s.encoder[kEncRoller] / c_.roller_counts_per_m;
    for (int i = 0; i < 3; ++i) out.sensors[i] = s.adc[i] * c_.adc_newton_per_count;
    out.valid = true;
}

void CldModel::to_command(const DeviceCommand& in, double q1, double q2, Command& cmd) const noexcept {
    cmd.motors = kCldMotors;
    cmd.motor = {};
    Vec2 f = in.force;
    if (!is_finite(f) || !std::isfinite(q1) || !std::isfinite(q2)) f = Vec2{0.0};
    const double m = glm::length(f);
    if (m > c_.max_force) f *= c_.max_force / m;  // magnitude clamp in N, direction kept
    // J^T F with J the endpoint Jacobian of (q1, q2).
    const double s1 = std::sin(q1), c1 = std::cos(q1), s12 = std::sin(q1 + q2), c12 = std::cos(q1 + q2);
    const double tau1 = (-c_.l1 * s1 - c_.l2 * s12) * f.x + (c_.l1 * c1 + c_.l2 * c12) * f.y;  // N m
    const double tau2 = -c_.l2 * s12 * f.x + c_.l2 * c12 * f.y;                                  // N m
    // Per-motor saturation happens in pack_motor (fractions beyond +-1 are held at full scale).
    cmd.motor[kMotorShoulder] = pack_motor(tau1 / c_.max_torque);
    cmd.motor[kMotorElbow] = pack_motor(tau2 / c_.max_torque);
    cmd.motor[kMotorRoller] = pack_motor(in.roller_drive / c_.roller_full_scale);
}

Vec2 CldModel::force_of(const Command& cmd, double q1, double q2) const noexcept {
    const double tau1 = unpack_motor(cmd.motor[kMotorShoulder]) * c_.max_torque;
    const double tau2 = unpack_motor(cmd.motor[kMotorElbow]) * c_.max_torque;
    // F = J^-T tau.
    const double s1 = std::sin(q1), c1 = std::cos(q1), s12 = std::sin(q1 + q2), c12 = std::cos(q1 + q2);
    const double a = -c_.l1 * s1 - c_.l2 * s12, b = c_.l1 * c1 + c_.l2 * c12;  // first row of J^T
    const double c = -c_.l2 * s12, d = c_.l2 * c12;                            // second row
    const double det = a * d - b * c;
    if (std::fabs(det) < 1e-12) return Vec2{0.0};
    return Vec2{(d * tau1 - b * tau2) / det, (-c * tau1 + a * tau2) / det};
}

DeviceLimits CldModel::limits() const noexcept {
    DeviceLimits l;
    l.max_force = c_.max_force;
    l.axis_max_force = Vec2{c_.max_force};
    const double reach = c_.l1 + c_.l2;
    l.workspace.lo = c_.base - Vec2{reach};
    l.workspace.hi = c_.base + Vec2{reach};
    l.roller_min = -0.010;
    l.roller_max = 0.010;
    l.native_rate = 1000.0;
    return l;
}

}  // namespace contactlab::drivers::hapio
