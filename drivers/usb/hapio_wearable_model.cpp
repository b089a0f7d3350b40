// hapio_wearable_model.cpp — channel mapping and host-side loop of the wearable platform over
// hapio (see hapio_wearable_model.hpp).
#include "drivers/usb/hapio_wearable_model.hpp"

#include <cmath>

namespace contactlab::drivers::hapio {

using namespace contactlab::wearable;

WearableModel::WearableModel(const WearableCalibration& c)
    : c_(c),
      force_(c.force, c.motor),
      position_(c.position, c.motor, c.platform, c.estimator.slack_tension) {
    reset();
}

void WearableModel::reset() noexcept {
    force_.reset();
    position_.reset();
    estimate_ = Estimate{};
    estimate_.pose = c_.platform.rest;
    status_ = ControlStatus::ok;
}

void WearableModel::to_reading(const State& s, DeviceReading& out) const noexcept {
    out.valid = true;
    for (int i = 0; i < kWearableAnalog; ++i) {
        out.sensors[i] = s.adc[i] * c_.fsr_newton_per_count;
        if (s.adc[i] >= c_.adc_full_scale) out.valid = false;  // saturated: the force is unknown
    }
}

WearableLinkStatus WearableModel::to_command(const DeviceCommand& in, const State& s, double dt, Command& cmd) noexcept {
    cmd.motors = kWearableMotors;
    cmd.motor = {};
    DeviceReading r;
    to_reading(s, r);
    if (!r.valid) {
        force_.reset();
        position_.reset();
        status_ = ControlStatus::fault_estimate;
        return WearableLinkStatus::fsr_saturated;
    }
    const Eigen::Vector3d fsr(r.sensors[0], r.sensors[1], r.sensors[2]);
    const Estimate e = wearable::estimate(c_.estimator, c_.platform, c_.stiffness, fsr, estimate_.pose);
    estimate_ = e;  // a fault keeps the previous pose in e.pose
    const Eigen::Vector3d v(in.platform[0], in.platform[1], in.platform[2]);
    ControlOutput out;
    if (in.platform_mode == DeviceCommand::PlatformMode::pose) {
        Pose xi = c_.platform.rest;
        xi(2) += v(0);
        xi(3) += v(1);
        xi(4) += v(2);
        out = position_.step(xi, estimate_, dt);
    } else {
        const Eigen::Vector3d q = in.platform_mode == DeviceCommand::PlatformMode::wrench ? v : Eigen::Vector3d::Zero();
        out = force_.step(q, estimate_, dt);
    }
    status_ = out.status;
    if (is_fault(out.status)) return WearableLinkStatus::fault;  // cmd.motor stays zero
    for (int i = 0; i < kWearableMotors; ++i) cmd.motor[i] = pack_motor(out.torque(i) / c_.motor.stall_torque);
    return WearableLinkStatus::ok;
}

DeviceLimits WearableModel::limits() const noexcept {
    DeviceLimits l;
    const double stall = stall_cable_force(c_.motor);
    l.max_force = 3.0 * stall;
    l.axis_max_force = Vec2{3.0 * stall};
    l.roller_min = 0.0;
    l.roller_max = 0.0;
    l.native_rate = c_.force.command_rate_hz;
    return l;
}

}  // namespace contactlab::drivers::hapio
