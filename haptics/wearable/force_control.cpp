// force_control.cpp — seed 003 Fig. 5 (see force_control.hpp).
#include "haptics/wearable/force_control.hpp"

#include <cmath>
#include <numbers>

namespace contactlab::wearable {

const char* to_string(ControlStatus s) noexcept {
    switch (s) {
        case ControlStatus::ok: return "ok";
        case ControlStatus::saturated: return "a motor torque is at the stall limit";
        case ControlStatus::reference_clamped: return "a negative cable force was raised to 0 (cables cannot push)";
        case ControlStatus::fault_above_stall: return "a cable force above the motors' stall limit: output zero";
        case ControlStatus::fault_non_finite: return "a non-finite reference or gain: output zero";
        case ControlStatus::fault_estimate: return "the force estimate is in fault: output zero";
        case ControlStatus::fault_unreachable_pose: return "the reference pose is outside the workspace: output zero";
    }
    return "?";
}

ControlOutput ForceController::step(const Eigen::Vector3d& reference, const Estimate& estimate, double dt) noexcept {
    ControlOutput out;
    auto fault = [&](ControlStatus s, int cable) {
        out.torque.setZero();
        out.status = s;
        out.cable = cable;
        reset();
        return out;
    };
    if (!(dt > 0.0) || !std::isfinite(def_.kp) || !std::isfinite(def_.kd)) return fault(ControlStatus::fault_non_finite, -1);
    const double limit = stall_cable_force(motor_);
    Eigen::Vector3d qr = reference;
    for (int i = 0; i < 3; ++i) {
        if (!std::isfinite(qr(i))) return fault(ControlStatus::fault_non_finite, i);
        if (qr(i) > limit) return fault(ControlStatus::fault_above_stall, i);
        if (qr(i) < 0.0) {
            qr(i) = 0.0;
            out.status = ControlStatus::reference_clamped;
            out.cable = i;
        }
    }
    if (estimate.status != EstimateStatus::ok) return fault(ControlStatus::fault_estimate, estimate.cable);
    const Eigen::Vector3d& q = estimate.tension;
    if (!primed_) {
        prev_ = q;
        rate_f_.setZero();
        primed_ = true;
    }
    rate_f_ += low_pass_weight(def_.d_cutoff_hz, dt) * ((q - prev_) / dt - rate_f_);
    prev_ = q;
    for (int i = 0; i < 3; ++i) {
        const double ff = def_.feedforward ? holding_torque(motor_, qr(i)) : 0.0;
        set_clamped_torque(out, i, ff + def_.kp * (qr(i) - q(i)) - def_.kd * rate_f_(i), motor_.stall_torque);
    }
    return out;
}

}  // namespace contactlab::wearable
