// rig.cpp — the simulated wearable device (see rig.hpp).
#include "haptics/wearable/rig.hpp"

#include <cmath>
#include <stdexcept>

namespace contactlab::wearable {

WearableRig::WearableRig(const RigDef& def)
    : def_(def),
      plant_(def.plant),
      force_(def.force, def.plant.motor),
      position_(def.position, def.plant.motor, def.plant.platform, def.estimator.slack_tension),
      pending_pose_(def.plant.platform.rest),
      active_pose_(def.plant.platform.rest),
      shaped_pose_(def.plant.platform.rest) {
    if (!(def.force.rate_hz > 0.0) || !(def.force.command_rate_hz > 0.0) || !(def.position.rate_hz > 0.0))
        throw std::invalid_argument("wearable rig: the control and link rates must be positive (Hz)");
    if (!(def.reference_time_constant >= 0.0) || !std::isfinite(def.reference_time_constant))
        throw std::invalid_argument("wearable rig: the reference time constant must be >= 0 (s)");
    estimate_.pose = def.plant.platform.rest;
    estimate_.length = inverse_kinematics(def.plant.platform, def.plant.platform.rest).l;
}

RigDef seed_fit_rig() {
    RigDef def;
    def.reference_time_constant = 1.0 / (2.0 * 3.141592653589793 * 3.5);  // s: the seed's 3.5 Hz
    return def;
}

void WearableRig::command_force(const Eigen::Vector3d& reference) noexcept {
    pending_mode_ = RigMode::force;
    pending_force_ = reference;
}

void WearableRig::command_pose(const Pose& reference) noexcept {
    pending_mode_ = RigMode::position;
    pending_pose_ = reference;
}

void WearableRig::tick(double dt) {
    if (time_ + 1e-12 >= next_link_) {  // a link tick: the host's latest reference arrives
        if (pending_mode_ != active_mode_) {
            force_.reset();
            position_.reset();
        }
        active_mode_ = pending_mode_;
        active_force_ = pending_force_;
        active_pose_ = pending_pose_;
        next_link_ += 1.0 / def_.force.command_rate_hz;
    }
    // Reference shaping (RigDef::reference_time_constant), exact first order. A reference the
    // controllers refuse (above stall, non-finite, a pose IK cannot reach) goes to them unshaped so
    // that they fault at once, and the shaping restarts from rest.
    const double a = def_.reference_time_constant > 0.0 ? 1.0 - std::exp(-dt / def_.reference_time_constant) : 1.0;
    Eigen::Vector3d force_ref = active_force_;
    if (active_force_.allFinite() && active_force_.maxCoeff() <= stall_cable_force(def_.plant.motor)) {
        shaped_force_ += a * (active_force_.cwiseMax(0.0) - shaped_force_);
        force_ref = shaped_force_;
    } else {
        shaped_force_.setZero();
    }
    Pose pose_ref = active_pose_;
    if (inverse_kinematics(def_.plant.platform, active_pose_).status == IkStatus::ok) {
        shaped_pose_ += a * (active_pose_ - shaped_pose_);
        pose_ref = shaped_pose_;
    } else {
        shaped_pose_ = def_.plant.platform.rest;
    }
    fsr_ = plant_.read_fsr();
    const Estimate e = wearable::estimate(def_.estimator, def_.plant.platform, def_.plant.stiffness, fsr_, estimate_.pose);
    // A fault keeps the last good pose for the next sample (estimate() returns the previous one).
    estimate_ = e;
    output_ = active_mode_ == RigMode::force ? force_.step(force_ref, estimate_, dt)
                                             : position_.step(pose_ref, estimate_, dt);
    plant_.step(output_.torque, dt);
    time_ += dt;
}

void WearableRig::advance(double dt) {
    if (!(dt > 0.0)) return;
    const double period = 1.0 / (active_mode_ == RigMode::force ? def_.force.rate_hz : def_.position.rate_hz);
    carry_ += dt;
    while (carry_ >= period - 1e-12) {
        tick(period);
        carry_ -= period;
    }
}

}  // namespace contactlab::wearable
