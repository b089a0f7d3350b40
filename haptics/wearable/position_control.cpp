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
    if (inverse_kinematics(platform_, reference).status != IkStatus::ok)
        return fault(ControlStatus::fault_unreachable_pose, inverse_kinematics(platform_, reference).cable);
    if (estimate.status != EstimateStatus::ok) return fault(ControlStatus::fault_estimate, estimate.cable);
    // Block IK of Fig. 6, on the actuated freedoms: p_x, p_y and gamma are the fingertip's (the
    // cables do not set them), so they are taken from the estimate, not the reference.
    Pose target = reference;
    if (def_.free_from_estimate) {
        target(0) = estimate.pose(0);
        target(1) = estimate.pose(1);
        target(5) = estimate.pose(5);
    }
    IkResult ik = inverse_kinematics(platform_, target);
    if (ik.status != IkStatus::ok) ik = inverse_kinematics(platform_, reference);
    lr_ = ik.l;
    const Eigen::Vector3d err = estimate.length - lr_;  // l-hat - l_r (m)
    if (!primed_) {
        prev_ = err;
        rate_f_.setZero();
        primed_ = true;
    }
    rate_f_ += low_pass_weight(def_.d_cutoff_hz, dt) * ((err - prev_) / dt - rate_f_);
    prev_ = err;
    for (int i = 0; i < 3; ++i) {
        const bool slack = estimate.tension(i) < slack_tension_;
        if (slack && err(i) <= 0.0) {
            out.torque(i) = 0.0;  // cannot see a slack cable's length: do not pay out further
            continue;
        }
        const double hold = def_.hold_tension ? holding_torque(motor_, estimate.tension(i)) : 0.0;
        set_clamped_torque(out, i, hold + def_.kp * err(i) + def_.kd * rate_f_(i), motor_.stall_torque);
    }
    return out;
}

}  // namespace contactlab::wearable
