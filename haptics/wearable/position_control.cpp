// position_control.cpp — seed 003 Fig. 6 (see position_control.hpp).
#include "haptics/wearable/position_control.hpp"

#include <cmath>
#include <numbers>

namespace contactlab::wearable {

ControlOutput PositionController::step(const Pose& reference, const Estimate& estimate, double dt) noexcept {
    ControlOutput out;
    auto fault = [&](ControlStatus s, int cable) {
        out.torque.setZero();
        out.status = s;
        out.cable = cable;
        reset();
        return out;
    };
    if (!(dt > 0.0) || !std::isfinite(def_.kp) || !std::isfinite(def_.kd) || !reference.allFinite())
        return fault(ControlStatus::fault_non_finite, -1);
    const IkResult ik = inverse_kinematics(platform_, reference);  // block IK of Fig. 6
    if (ik.status != IkStatus::ok) return fault(ControlStatus::fault_unreachable_pose, ik.cable);
    if (estimate.status != EstimateStatus::ok) return fault(ControlStatus::fault_estimate, estimate.cable);
    lr_ = ik.l;
    const Eigen::Vector3d err = estimate.length - lr_;  // l-hat - l_r (m)
    if (!primed_) {
        prev_ = err;
        rate_f_.setZero();
        primed_ = true;
    }
    const double alpha = 1.0 - std::exp(-2.0 * std::numbers::pi * def_.d_cutoff_hz * dt);
    rate_f_ += alpha * ((err - prev_) / dt - rate_f_);
    prev_ = err;
    for (int i = 0; i < 3; ++i) {
        const bool slack = estimate.tension(i) < slack_tension_;
        if (slack && err(i) <= 0.0) {
            out.torque(i) = 0.0;  // cannot see a slack cable's length: do not pay out further
            continue;
        }
        const double hold = def_.hold_tension ? holding_torque(motor_, estimate.tension(i)) : 0.0;
        const double tau = hold + def_.kp * err(i) + def_.kd * rate_f_(i);
        out.torque(i) = std::clamp(tau, -motor_.stall_torque, motor_.stall_torque);
        if (out.torque(i) != tau && out.status == ControlStatus::ok) {
            out.status = ControlStatus::saturated;
            out.cable = i;
        }
    }
    return out;
}

}  // namespace contactlab::wearable
