// sim_wearable_device.cpp — the simulated wearable platform as a Device (see sim_wearable_device.hpp).
#include "drivers/sim/sim_wearable_device.hpp"

#include <cmath>
#include <stdexcept>

namespace contactlab::drivers::sim {

using namespace contactlab::wearable;

SimWearableDevice::SimWearableDevice(const SimWearableParams& p) : p_(p) {
    const double stall = stall_cable_force(p_.rig.plant.motor);  // N per cable
    // Three cables at stall, nearly normal to the platform (cos(theta) ~ 0.9): the largest push.
    limits_.max_force = 3.0 * stall;
    limits_.axis_max_force = Vec2{3.0 * stall};
    limits_.native_rate = p_.rig.force.command_rate_hz;
    limits_.min_rate = 100.0;
    limits_.roller_min = 0.0;
    limits_.roller_max = 0.0;
}

SimWearableDevice::SimWearableDevice(const SimWearableParams& p, HandPath path) : SimWearableDevice(p) {
    t0_ = path.start();
    path_.emplace(std::move(path));
}

DeviceCapabilities SimWearableDevice::capabilities() const noexcept {
    DeviceCapabilities c;
    c.platform = true;
    c.force_sensors = 3;
    c.simulated = true;
    return c;
}

bool SimWearableDevice::open() {
    state_ = DeviceState::opening;
    try {
        rig_.emplace(p_.rig);
    } catch (const std::invalid_argument&) {
        rig_.reset();
        state_ = DeviceState::fault;
        fault_ = {DeviceFaultCode::open_failed, "the platform cannot be assembled (check_platform says why)"};
        return false;
    }
    fault_ = {};
    since_command_ = 0.0;
    state_ = DeviceState::ready;
    return true;
}

void SimWearableDevice::close() {
    rig_.reset();
    state_ = DeviceState::disconnected;
}

void SimWearableDevice::set_engaged(bool on) noexcept {
    if (state_ == DeviceState::ready && on) state_ = DeviceState::engaged;
    else if (state_ == DeviceState::engaged && !on) state_ = DeviceState::ready;
}

void SimWearableDevice::set_fault(DeviceFaultCode code, const char* detail) noexcept {
    if (rig_) rig_->command_force(Eigen::Vector3d::Zero());
    state_ = DeviceState::fault;
    fault_ = {code, detail};
}

bool SimWearableDevice::read(DeviceReading& out) noexcept {
    out = DeviceReading{};
    if (!rig_ || state_ == DeviceState::disconnected || state_ == DeviceState::opening) return false;
    out.t = t0_ + rig_->time();
    if (path_) {
        const PathPoint pp = path_->at(out.t);
        out.finger = pp.x;
        out.phi = pp.phi;
    }
    for (int i = 0; i < 3; ++i) out.sensors[i] = rig_->fsr()(i);
    out.valid = true;
    return true;
}

void SimWearableDevice::write(const DeviceCommand& cmd) noexcept {
    if (!rig_ || state_ == DeviceState::disconnected || state_ == DeviceState::opening) return;
    since_command_ = 0.0;
    const Eigen::Vector3d v(cmd.platform[0], cmd.platform[1], cmd.platform[2]);
    if (!v.allFinite()) return set_fault(DeviceFaultCode::non_finite_command, "non-finite platform command refused");
    switch (cmd.platform_mode) {
        case DeviceCommand::PlatformMode::none:
            rig_->command_force(Eigen::Vector3d::Zero());
            break;
        case DeviceCommand::PlatformMode::wrench:
            if (v.maxCoeff() > stall_cable_force(p_.rig.plant.motor))
                return set_fault(DeviceFaultCode::over_limit, "a cable force above the motors' stall limit");
            rig_->command_force(v.cwiseMax(0.0));
            break;
        case DeviceCommand::PlatformMode::pose: {
            Pose xi = p_.rig.plant.platform.rest;
            xi(2) += v(0);
            xi(3) += v(1);
            xi(4) += v(2);
            if (inverse_kinematics(p_.rig.plant.platform, xi).status != IkStatus::ok)
                return set_fault(DeviceFaultCode::over_limit, "a platform pose outside the workspace");
            rig_->command_pose(xi);
            break;
        }
    }
    if (state_ == DeviceState::fault) {  // a good command clears a fault, as sim-cld's amplifiers
        state_ = DeviceState::ready;
        fault_ = {};
    }
}

void SimWearableDevice::advance(double dt) noexcept {
    if (!rig_ || !(dt > 0.0) || state_ == DeviceState::disconnected) return;
    if (const std::uint64_t serial = tuning_serial_.load(std::memory_order_acquire); serial != tuning_applied_) {
        const RigTuning t = tuning_.load();
        apply_tuning(p_.rig, t);  // a later open() assembles the rig as tuned
        rig_->retune(t);
        tuning_applied_ = serial;
    }
    since_command_ += dt;
    if (since_command_ > p_.watchdog_timeout && state_ != DeviceState::fault)
        set_fault(DeviceFaultCode::watchdog, "no command within the watchdog timeout");
    rig_->advance(dt);
    WearablePlatformView v;
    v.valid = true;
    const Pose& xi = rig_->plant().pose();
    const Pose& rest = p_.rig.plant.platform.rest;
    v.roll = xi(3) - rest(3);
    v.press = xi(2) - rest(2);
    v.pitch = xi(4) - rest(4);
    v.tension_limit = stall_cable_force(p_.rig.plant.motor);
    v.control = rig_->output().status;
    v.position_mode = rig_->mode() == RigMode::position;
    for (int i = 0; i < 3; ++i) {
        v.tension[i] = rig_->plant().tension()(i);
        v.fsr[i] = rig_->fsr()(i);
    }
    view_.store(v);
    if (rig_->output().status == ControlStatus::fault_estimate && state_ != DeviceState::fault) {
        state_ = DeviceState::fault;  // the rig already outputs zero torque
        fault_ = {DeviceFaultCode::io_error, "an FSR reading is out of range (the estimate is in fault)"};
    }
}

}  // namespace contactlab::drivers::sim
